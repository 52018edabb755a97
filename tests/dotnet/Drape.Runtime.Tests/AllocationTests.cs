using System;
using Drape.Core;
using NUnit.Framework;
using UnityEngine;

namespace Drape.Tests
{
    /// <summary>Zero managed allocation per frame, measured with GC.GetAllocatedBytesForCurrentThread
    /// around whole frames (Update, LateUpdate, OnGUI of every component) of a cloth with a sphere
    /// collider and a plane, a finger dragging it (legacy input) and the HUD. CoreCLR, not Unity's
    /// Mono or IL2CPP: our code avoids what allocates only there (number and enum ToString, string
    /// building), but the runtimes differ, so this is evidence, not proof for Unity.</summary>
    public sealed class AllocationTests : SceneFixture
    {
        private static DrapeCloth BusyScene(out DrapeHud hud)
        {
            DrapeCloth cloth = Scene.Grid(16, 16);
            var ball = new GameObject("ball");
            ball.transform.position = new Vector3(0f, -0.6f, 0.1f);
            var sphere = ball.AddComponent<SphereCollider>();
            sphere.radius = 0.2f;
            cloth.Colliders.Colliders.Add(sphere);
            var floor = new GameObject("floor");
            floor.transform.position = new Vector3(0f, -1.5f, 0f);
            cloth.Colliders.Planes.Add(floor.transform);
            cloth.gameObject.AddComponent<DrapeTouchDrag>();
            var cam = new GameObject("camera").AddComponent<Camera>();
            Camera.s_Main = cam;
            hud = new GameObject("hud").AddComponent<DrapeHud>();
            hud.Cloth = cloth;
            return cloth;
        }

        [Test]
        public void FramesAllocateNothing()
        {
            DrapeCloth cloth = BusyScene(out DrapeHud hud);
            hud.RefreshInterval = 2f;
            Input.s_TouchDown = true;
            for (int i = 0; i < 30; ++i) // warm up: delegates cached, first HUD text made, JIT done
            {
                Input.s_TouchPosition = new Vector2(400f + i, 300f);
                StandInHooks.Frame(i % 3 == 0 ? 1f / 30f : 1f / 144f);
            }
            Assert.That(hud.Text, Does.Contain("vertices 256"));
            hud.Cloth = cloth; // refresh now: the next refresh (2 s) falls after the measured frames
            StandInHooks.Frame(1f / 144f);
            long before = GC.GetAllocatedBytesForCurrentThread();
            for (int i = 0; i < 100; ++i) // ~1.6 s of frames at 144 and 30 Hz: 0, 1 and 2 steps per frame
            {
                Input.s_TouchPosition = new Vector2(430f + i, 300f + (i & 7));
                cloth.Colliders.Colliders[0].transform.position = new Vector3(0.001f * i, -0.6f, 0.1f);
                StandInHooks.Frame(i % 3 == 0 ? 1f / 30f : 1f / 144f);
            }
            long allocated = GC.GetAllocatedBytesForCurrentThread() - before;
            Scene.AssertNoErrors();
            Assert.That(cloth.LastStats.Substeps, Is.GreaterThan(0u), "the cloth stepped");
            Assert.That(allocated, Is.EqualTo(0L));
        }

        [Test]
        public void AHudRefreshAllocatesOnlyItsString()
        {
            DrapeCloth cloth = BusyScene(out DrapeHud hud);
            hud.RefreshInterval = 0.05f;
            Scene.Frames(10);
            string shown = hud.Text;
            long before = GC.GetAllocatedBytesForCurrentThread();
            Scene.Frames(4, 0.06f); // a refresh every frame
            long allocated = GC.GetAllocatedBytesForCurrentThread() - before;
            // At most one string per refresh: 4 x (header + 2 bytes per char), rounded up generously.
            Assert.That(allocated, Is.LessThanOrEqualTo(4L * (32 + 2 * 512)));
            Assert.That(hud.Text, Does.Contain("step"));
        }

        [Test]
        public void HudNumbersWithoutToString()
        {
            var t = new DrapeHudText(64);
            t.Append(3.14159f, 2).Append(' ').Append(0.005f, 2).Append(' ').Append(-12.5f, 1).Append(' ').Append(1234567L);
            Assert.That(t.ToString(), Is.EqualTo("3.14 0.01 -12.5 1234567"));
            Assert.That(DrapeHudText.BackendName(Backend.Gles), Is.EqualTo("GPU (GLES)"));
        }
    }
}
