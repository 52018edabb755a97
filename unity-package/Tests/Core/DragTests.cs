using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Touch drag (paper eq. 9, drape_cloth_drag) and pick-and-hold grabs through the bindings.</summary>
    public class DragTests
    {
        private const float Dt = 1f / 60f;
        private const uint Columns = 21;
        private const uint Center = 10 * Columns + 10;    // (0, 0, 0)
        private const uint Corner = 20 * Columns + 20;    // (0.5, -0.5, 0)

        /// <summary>A 21 x 21 facing cloth with no springs, gravity or air: each vertex moves exactly
        /// by what the touch gives it (as in tests/native/test_drag.cpp).</summary>
        private static NativeCloth FreeCloth(NativeWorld world)
        {
            NativeCloth cloth = TestScenes.FacingGrid(world, Columns, Columns);
            Params p = NativeWorld.DefaultParams();
            p.Stiffness = new GroupValues(0f, 0f, 0f);
            p.Gravity = new Float3(0f, 0f, 0f);
            p.AirDrag = 0f;
            p.Damping = 0f;
            p.MaxStretch = 0f;
            cloth.SetParams(p);
            return cloth;
        }

        private static Float3 Vertex(float[] xyz, uint v) => new Float3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);

        [Test]
        public void DragMovesVerticesNearTheTouchAndNotFarOnes()
        {
            // Camera 1.5 m in front of the cloth, 60 degree fov over 300 px: the cloth plane is seen at
            // 150 px / (1.5 tan 30 deg) = 173.2 px/m. Touch on the centre vertex, finger moves 20 px
            // right: with c = min(1, 200 exp(-r^2/600)) = 1 at r = 0 the centre moves 20/173.2 =
            // 0.1155 m along +x. The corner is 0.707 m = 122 px away: c = 200 exp(-24.9) ~ 3e-9.
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = FreeCloth(world))
            {
                View view = TestScenes.PerspectiveView(1.5f);
                var xyz = new float[cloth.VertexCount * 3];
                cloth.ReadPositions(xyz);
                Float3 center0 = Vertex(xyz, Center), corner0 = Vertex(xyz, Corner);
                Float2 touch = TestScenes.Project(view, center0.X, center0.Y, center0.Z);
                Assert.That(touch.X, Is.EqualTo(200f).Within(0.01f), "test's projection");

                cloth.Drag(view, touch, new Float2(20f, 0f));
                cloth.Step(Dt);
                cloth.ReadPositions(xyz);
                Float3 center1 = Vertex(xyz, Center), corner1 = Vertex(xyz, Corner);

                Assert.That(center1.X - center0.X, Is.EqualTo(20f / 173.2f).Within(0.005f), "centre x");
                Assert.That(center1.Y - center0.Y, Is.EqualTo(0f).Within(1e-3f), "centre y");
                Assert.That(center1.Z - center0.Z, Is.EqualTo(0f).Within(1e-3f), "centre stays at its depth");
                Assert.That(corner1.X - corner0.X, Is.EqualTo(0f).Within(1e-5f), "far corner moved");
                Assert.That(corner1.Y - corner0.Y, Is.EqualTo(0f).Within(1e-5f), "far corner moved");
            }
        }

        [Test]
        public void DragThroughASimulationToWorldMatrix()
        {
            // The cloth simulates in a local space shifted by (-0.2, 0, 0) from the world, as a
            // DrapeCloth on a moved GameObject does: View.World carries that. Touching where the
            // local (0.2, 0, 0) vertex appears on screen (world x = 0) must move that vertex.
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = FreeCloth(world))
            {
                View view = TestScenes.PerspectiveView(1.5f);
                view.World.M03 = -0.2f;
                const uint v = 10 * Columns + 14; // local (0.2, 0, 0)
                var xyz = new float[cloth.VertexCount * 3];
                cloth.ReadPositions(xyz);
                Float3 p0 = Vertex(xyz, v);
                Assert.That(p0.X, Is.EqualTo(0.2f).Within(1e-5f));
                Float2 touch = TestScenes.Project(view, p0.X, p0.Y, p0.Z);
                Assert.That(touch.X, Is.EqualTo(200f).Within(0.01f), "the vertex is seen at the centre");
                cloth.Drag(view, touch, new Float2(0f, 20f));
                cloth.Step(Dt);
                cloth.ReadPositions(xyz);
                Assert.That(Vertex(xyz, v).Y - p0.Y, Is.EqualTo(20f / 173.2f).Within(0.005f));
            }
        }

        [Test]
        public void GrabHoldsTheNearestVertexUnderTheFinger()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = FreeCloth(world))
            {
                View view = TestScenes.PerspectiveView(1.5f);
                var xyz = new float[cloth.VertexCount * 3];
                cloth.ReadPositions(xyz);
                Float3 c0 = Vertex(xyz, Center);
                Float2 at = TestScenes.Project(view, c0.X, c0.Y, c0.Z);

                Assert.That(cloth.Grab(view, 4, new Float2(at.X + 1f, at.Y - 1f), 10f), Is.EqualTo(Center));
                cloth.GrabMove(view, 4, new Float2(at.X, at.Y + 34.64f)); // 0.2 m up
                cloth.Step(Dt);
                cloth.ReadPositions(xyz);
                Assert.That(Vertex(xyz, Center).Y, Is.EqualTo(0.2f).Within(0.002f));
                Assert.That(Vertex(xyz, Center).Z, Is.EqualTo(0f).Within(0.002f), "held at its depth");
                cloth.GrabRelease(4);
                cloth.GrabRelease(12345); // unknown id: fine

                Assert.That(cloth.Grab(view, 5, new Float2(5f, 5f), 10f), Is.EqualTo(NativeCloth.NoVertex),
                            "nothing is near the screen corner");
            }
        }

        [Test]
        public void BadDragInputThrowsWithTheNativeMessage()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = FreeCloth(world))
            {
                View view = TestScenes.PerspectiveView();
                View flat = view;
                flat.Viewport = new Float2(0f, 300f);
                var e = Assert.Throws<DrapeException>(() => cloth.Drag(flat, new Float2(1f, 1f), new Float2(1f, 0f)));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorInvalidArgument));
                Assert.That(e.NativeMessage, Is.Not.Empty);
                Assert.That(e.Function, Is.EqualTo("drape_cloth_drag"));

                e = Assert.Throws<DrapeException>(() => cloth.Drag(view, new Float2(float.NaN, 1f), new Float2(1f, 0f)));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorNotFinite));

                e = Assert.Throws<DrapeException>(() => cloth.Drag(view, new TouchPoint[17]));
                Assert.That(e.NativeMessage, Is.Not.Empty);

                e = Assert.Throws<DrapeException>(() => cloth.GrabMove(view, 99, new Float2(1f, 1f)));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorInvalidArgument), "moving a grab that holds nothing");
                Assert.That(e.NativeMessage, Is.Not.Empty);
            }
        }

        [Test]
        public void TouchDefaultsAreTheDocumentedOnes()
        {
            TouchPoint t = TouchPoint.Default();
            Assert.That(t.StructSize, Is.EqualTo(SizeOf.TouchPoint));
            Assert.That(t.Amplitude, Is.EqualTo(200f));
            Assert.That(t.Sigma, Is.EqualTo(300f));
        }
    }
}
