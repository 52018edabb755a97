using NUnit.Framework;
using Unity.Collections;
using UnityEngine;

namespace Drape.Tests
{
    /// <summary>LateUpdate stepping: a fixed-step accumulator and the drawn state interpolated
    /// between the last two steps.</summary>
    public sealed class InterpolationTests : SceneFixture
    {
        [Test]
        public void TheClockTakesWholeStepsAndKeepsTheRemainder()
        {
            float clock = 0f;
            // 144 Hz frames, 60 Hz steps: 0, 1, 0 ... steps; the remainder stays below one step.
            int total = 0;
            for (int i = 0; i < 144; ++i)
            {
                total += DrapeCloth.AdvanceClock(ref clock, 1f / 144f, 1f / 60f, 3);
                Assert.That(clock, Is.InRange(0f, 1f / 60f));
            }
            Assert.That(total, Is.InRange(59, 60), "one second of frames holds 60 steps");
            clock = 0f;
            Assert.That(DrapeCloth.AdvanceClock(ref clock, 1f, 1f / 60f, 3), Is.EqualTo(3), "a long frame is capped");
            Assert.That(clock, Is.EqualTo(0f), "and its backlog dropped");
        }

        [Test]
        public void TheDrawnStateLiesBetweenTheLastTwoSteps()
        {
            var a = new NativeArray<DrapeVertex>(1, Allocator.Persistent);
            var b = new NativeArray<DrapeVertex>(1, Allocator.Persistent);
            var r = new NativeArray<DrapeVertex>(1, Allocator.Persistent);
            a[0] = new DrapeVertex { Position = new Vector3(0f, 0f, 0f), Normal = new Vector3(1f, 0f, 0f) };
            b[0] = new DrapeVertex { Position = new Vector3(2f, 4f, 0f), Normal = new Vector3(0f, 1f, 0f) };
            DrapeCloth.Interpolate(a, b, r, 0.25f);
            Assert.That(r[0].Position.x, Is.EqualTo(0.5f).Within(1e-6f));
            Assert.That(r[0].Position.y, Is.EqualTo(1f).Within(1e-6f));
            Assert.That(r[0].Normal.magnitude, Is.EqualTo(1f).Within(1e-5f), "normals renormalised");
            a.Dispose();
            b.Dispose();
            r.Dispose();
        }

        [Test]
        public void FramesFasterThanTheStepStillMoveTheMesh()
        {
            DrapeCloth cloth = Scene.Grid(8, 8, DrapePinMode.TopEdge);
            cloth.Model = Drape.Core.Model.Xpbd; // still swinging after 30 frames (implicit has come to rest by then)
            Assert.That(cloth.StepMode, Is.EqualTo(DrapeStepMode.LateUpdateInterpolated), "the default");
            Mesh mesh = cloth.GetComponent<MeshFilter>().sharedMesh;
            Scene.Frames(30);
            float y0 = mesh.vertices[63].y;
            Scene.Frames(1, 1f / 240f); // no step this frame: the drawn state still advances
            float y1 = mesh.vertices[63].y;
            Assert.That(y1, Is.Not.EqualTo(y0));
            Scene.AssertNoErrors();
        }
    }
}
