using Drape.Core;
using NUnit.Framework;
using UnityEngine;

namespace Drape.Tests
{
    /// <summary>Builds tiny scenes on the Unity stand-in and runs frames (Update, LateUpdate, OnGUI).</summary>
    internal static class Scene
    {
        public static DrapeCloth Grid(int columns, int rows, DrapePinMode pins = DrapePinMode.TopEdge)
        {
            var go = new GameObject("cloth");
            var cloth = go.AddComponent<DrapeCloth>(); // Awake + OnEnable: built with the defaults
            cloth.enabled = false;
            cloth.Backend = DrapeBackendChoice.Cpu;
            cloth.Columns = columns;
            cloth.Rows = rows;
            cloth.PinMode = pins;
            cloth.PauseWhenInvisible = false;
            cloth.enabled = true;
            Assert.That(cloth.NativeCloth, Is.Not.Null, "the cloth builds");
            return cloth;
        }

        public static void Frames(int count, float dt = 1f / 60f)
        {
            for (int i = 0; i < count; ++i) StandInHooks.Frame(dt);
        }

        public static void AssertNoErrors()
        {
            Assert.That(StandInHooks.Exceptions, Is.Empty, StandInHooks.Exceptions.Count > 0 ? StandInHooks.Exceptions[0].ToString() : "");
        }
    }

    public abstract class SceneFixture
    {
        [SetUp]
        public void CleanScene() => StandInHooks.Reset();

        [TearDown]
        public void DestroyScene() => StandInHooks.Reset();
    }
}
