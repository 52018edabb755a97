using System.Collections.Generic;
using Drape.Core;
using NUnit.Framework;
using UnityEngine;

namespace Drape.Tests
{
    /// <summary>DrapeCloth's settings take effect while it runs, in a player too (no OnValidate).</summary>
    public sealed class LifecycleTests : SceneFixture
    {
        [Test]
        public void PinsOfAReleasedClothAreForgotten()
        {
            // 8 top-edge pins (indices 0..7); rebuilt as 2 x 2 (4 vertices), keeping them would ask
            // the native cloth to release pins 4..7, which it refuses.
            DrapeCloth cloth = Scene.Grid(8, 8);
            Assert.That(cloth.ActivePins.Length, Is.EqualTo(8));
            cloth.enabled = false;
            Assert.That(cloth.ActivePins.Length, Is.EqualTo(0));
            cloth.Columns = 2;
            cloth.Rows = 2;
            cloth.enabled = true;
            Scene.AssertNoErrors();
            Assert.That(cloth.enabled, Is.True);
            Assert.That(cloth.ActivePins.Length, Is.EqualTo(2));
        }

        [Test]
        public void PinEditsApplyAtTheNextStep()
        {
            DrapeCloth cloth = Scene.Grid(6, 6);
            Scene.Frames(2);
            cloth.PinMode = DrapePinMode.Corners;
            Scene.Frames(1);
            Assert.That(cloth.ActivePins.ToArray(), Is.EquivalentTo(new uint[] { 0, 5 }));
            cloth.PinMode = DrapePinMode.VertexList;
            cloth.SetPinnedVertices(new[] { 3, 3, 7, 99 }); // duplicates and out-of-range indices are dropped
            cloth.AddPinnedVertex(10);
            Scene.Frames(1);
            Assert.That(cloth.ActivePins.ToArray(), Is.EquivalentTo(new uint[] { 3, 7, 10 }));
            Assert.That(cloth.TogglePinnedVertex(7), Is.False);
            Scene.Frames(1);
            Assert.That(cloth.ActivePins.ToArray(), Is.EquivalentTo(new uint[] { 3, 10 }));
            Scene.AssertNoErrors();
        }

        [Test]
        public void ParameterEditsReachTheNativeCloth()
        {
            DrapeCloth cloth = Scene.Grid(6, 6);
            cloth.Damping = 0.5f;
            cloth.Substeps = 7;
            cloth.StructuralStiffness = 1234f;
            Scene.Frames(1);
            Params p = cloth.NativeCloth.GetParams();
            Assert.That(p.Damping, Is.EqualTo(0.5f));
            Assert.That(p.Substeps, Is.EqualTo(7u));
            Assert.That(p.Stiffness.Structural, Is.EqualTo(1234f));
        }

        [Test]
        public void BuildSettingEditsScheduleARebuild()
        {
            DrapeCloth cloth = Scene.Grid(6, 6);
            NativeCloth before = cloth.NativeCloth;
            cloth.Columns = 10;
            Assert.That(cloth.RebuildPending, Is.True);
            Assert.That(cloth.NativeCloth, Is.SameAs(before), "no rebuild inside a setter");
            Scene.Frames(1);
            Assert.That(cloth.RebuildPending, Is.False);
            Assert.That(cloth.NativeCloth, Is.Not.SameAs(before));
            Assert.That(cloth.VertexCount, Is.EqualTo(60));
            Assert.That(cloth.ActivePins.Length, Is.EqualTo(10));
            cloth.TotalMass = 2f;
            Assert.That(cloth.RebuildPending, Is.True, "mass is cooked into the cloth");
            Scene.Frames(1);
            Scene.AssertNoErrors();
        }

        [Test]
        public void EachModelKeepsStiffnessInItsOwnUnits()
        {
            DrapeCloth cloth = Scene.Grid(6, 6);
            cloth.Model = Model.Pbd; // the PBD defaults are fractions in [0, 1]: accepted natively
            Scene.Frames(2);
            Scene.AssertNoErrors();
            Assert.That(cloth.enabled, Is.True);
            Params p = cloth.NativeCloth.GetParams();
            Assert.That(p.Model, Is.EqualTo(Model.Pbd));
            Assert.That(p.Stiffness.Structural, Is.EqualTo(1f));
            Assert.That(p.Stiffness.Bend, Is.EqualTo(0.3f).Within(1e-6f));
            cloth.StructuralStiffness = 5f; // clamped to PBD's range
            Assert.That(cloth.StructuralStiffness, Is.EqualTo(1f));
            cloth.Model = Model.Xpbd;
            Assert.That(cloth.StructuralStiffness, Is.EqualTo(2000f), "XPBD's N/m value is kept");
            Assert.That(DrapeCloth.MaxStiffness(Model.Pbd), Is.EqualTo(1f));
        }

        [Test]
        public void AnUnstableClothWarnsOnce()
        {
            DrapeCloth cloth = Scene.Grid(8, 8);
            cloth.Model = Model.MassSpring;
            cloth.Substeps = 1;
            cloth.StructuralStiffness = 100000f;
            cloth.ShearStiffness = 100000f;
            cloth.BendStiffness = 100000f;
            cloth.FixedStep = 0.05f;
            Scene.Frames(30, 0.05f);
            Assert.That(cloth.UnstableEvents, Is.GreaterThan(1), "explicit springs this stiff at one substep of 50 ms blow up");
            int warnings = 0;
            foreach (string w in StandInHooks.Warnings)
                if (w.Contains("rolled back")) warnings++;
            Assert.That(warnings, Is.EqualTo(1));
            Assert.That(cloth.enabled, Is.True, "the cloth keeps running from its last good state");
        }

        [Test]
        public void ResetKeepsAReadableMesh()
        {
            var go = new GameObject("shirt");
            MeshFilter filter = go.AddComponent<MeshFilter>();
            filter.sharedMesh = new Mesh { vertices = new Vector3[3], triangles = new[] { 0, 1, 2 } };
            var cloth = go.AddComponent<DrapeCloth>();
            cloth.enabled = false;
            StandInHooks.Send(cloth, "Reset"); // what the editor does when the component is added
            Assert.That(cloth.Source, Is.EqualTo(DrapeShapeSource.MeshFilterMesh));
            filter.sharedMesh.m_Readable = false;
            StandInHooks.Send(cloth, "Reset");
            Assert.That(cloth.Source, Is.EqualTo(DrapeShapeSource.GeneratedGrid));
        }

        [Test]
        public void AutoSaysWhyNotTheGpu()
        {
            StandInHooks.Device = UnityEngine.Rendering.GraphicsDeviceType.Vulkan;
            DrapeCloth cloth = Scene.Grid(4, 4);
            cloth.Backend = DrapeBackendChoice.Auto;
            Scene.Frames(1);
            Assert.That(cloth.ActiveBackend, Is.Not.EqualTo(Backend.Gles));
            Assert.That(cloth.BackendReason, Does.Contain("Vulkan"));
            Assert.That(cloth.BackendReason, Does.Contain("OpenGLES3 first"));

            Assert.That(DrapeCloth.ExplainGpu(DrapeSimulationSpace.Local, UnityEngine.Rendering.GraphicsDeviceType.OpenGLES3, true), Is.Null);
            Assert.That(DrapeCloth.ExplainGpu(DrapeSimulationSpace.World, UnityEngine.Rendering.GraphicsDeviceType.OpenGLES3, true), Does.Contain("World"));
            Assert.That(DrapeCloth.ExplainGpu(DrapeSimulationSpace.Local, UnityEngine.Rendering.GraphicsDeviceType.OpenGLES3, false), Does.Contain("no GLES"));
            Assert.That(DrapeCloth.ResolveBackend(DrapeBackendChoice.Auto, 100, null, out string none), Is.EqualTo(Backend.Gles));
            Assert.That(none, Is.Empty);
            Assert.That(DrapeCloth.ResolveBackend(DrapeBackendChoice.Auto, 4096, "x", out string why), Is.EqualTo(Backend.CpuThreaded));
            Assert.That(why, Does.StartWith("Auto chose the CPU"));
        }

        [Test]
        public void TouchRadiusFollowsScreenDensity()
        {
            Assert.That(DrapeTouchDrag.DensityScale(0f), Is.EqualTo(1f), "unknown density: pixels as given");
            Assert.That(DrapeTouchDrag.DensityScale(96f), Is.EqualTo(1f));
            Assert.That(DrapeTouchDrag.DensityScale(480f), Is.EqualTo(5f));
        }

        [Test]
        public void CollidersKeepIdsAcrossFrames()
        {
            var ball = new GameObject("ball");
            var sphere = ball.AddComponent<SphereCollider>();
            var set = new DrapeColliderSet();
            set.Colliders.Add(sphere);
            set.Colliders.Add(sphere); // a duplicate is skipped
            set.Gather(null);
            Assert.That(set.Count, Is.EqualTo(1));
            uint id = set.Records[0].Id;
            ball.transform.position = new Vector3(1f, 2f, 3f);
            set.Gather(null);
            Assert.That(set.Records[0].Id, Is.EqualTo(id));
            Assert.That(set.Records[0].Position.Y, Is.EqualTo(2f));
        }
    }
}
