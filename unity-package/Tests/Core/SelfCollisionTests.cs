using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Self-collision (drape_cloth_set_self_collision / drape_cloth_get_self_collision).</summary>
    public class SelfCollisionTests
    {
        private const float Dt = 1f / 60f;

        // The fold scene of tests/native/test_self_collision.cpp, narrowed to a few columns: a cloth of
        // Cols x 33 vertices, 1 m along z (row spacing 1/32 m, column spacing 3 cm), pinned along its
        // middle row at y = 1. Half A (rows 0-15) starts horizontal towards +z, half B (rows 17-32)
        // tilted 30 degrees down towards -z; both swing down and meet under the pin line.
        private const uint Cols = 6, Rows = 33, PinRow = 16;
        private const float ColSpacing = 0.03f, RowSpacing = 1f / 32f, PinY = 1f;
        private const float Thickness = 0.03f; // about the particle spacing
        private const int FoldFrames = 120;

        private static NativeCloth FoldCloth(NativeWorld world)
        {
            var desc = new ClothDesc { Backend = Backend.Cpu, TotalMass = 0.3f };
            var grid = new GridDesc
            {
                Columns = Cols,
                Rows = Rows,
                Width = ColSpacing * (Cols - 1),
                Height = 1f,
                Origin = new Float3(0f, PinY, 0.5f), // default axes: columns +x, rows -z
            };
            NativeCloth cloth = NativeCloth.CreateGrid(world, desc, grid);
            var x = new float[cloth.VertexCount * 3];
            cloth.ReadPositions(x);
            double tilt = 30.0 * Math.PI / 180.0;
            for (uint r = PinRow + 1; r < Rows; ++r)
            for (uint c = 0; c < Cols; ++c)
            {
                float rho = (r - PinRow) * RowSpacing;
                uint v = r * Cols + c;
                x[3 * v + 1] = PinY - rho * (float)Math.Sin(tilt);
                x[3 * v + 2] = -rho * (float)Math.Cos(tilt);
            }
            cloth.SetPositions(x);
            var pins = new Pin[Cols];
            for (uint c = 0; c < Cols; ++c)
            {
                uint v = PinRow * Cols + c;
                pins[c] = new Pin(v, new Float3(x[3 * v], x[3 * v + 1], x[3 * v + 2]));
            }
            cloth.SetPins(pins);
            return cloth;
        }

        /// <summary>Pairs the library is asked to keep apart: not joined by a spring of the grid's
        /// 12-neighbour stencil and at least 1.5 thickness apart in the rest grid.</summary>
        private static bool NonNeighbours(uint i, uint j)
        {
            int dc = Math.Abs((int)(i % Cols) - (int)(j % Cols)), dr = Math.Abs((int)(i / Cols) - (int)(j / Cols));
            if ((dc <= 1 && dr <= 1) || (dc == 2 && dr == 0) || (dc == 0 && dr == 2)) return false;
            float dx = ColSpacing * dc, dz = RowSpacing * dr;
            return dx * dx + dz * dz >= (1.5f * Thickness) * (1.5f * Thickness);
        }

        /// <summary>Smallest distance between non-neighbour particles, and how many such pairs are
        /// closer than <paramref name="limit"/>.</summary>
        private static float MinNonNeighbourDistance(float[] x, float limit, out int closer)
        {
            float min = float.MaxValue;
            closer = 0;
            uint n = (uint)(x.Length / 3);
            for (uint i = 0; i < n; ++i)
            for (uint j = i + 1; j < n; ++j)
            {
                if (!NonNeighbours(i, j)) continue;
                float dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1], dz = x[3 * i + 2] - x[3 * j + 2];
                float d = (float)Math.Sqrt(dx * dx + dy * dy + dz * dz);
                if (d < min) min = d;
                if (d < limit) ++closer;
            }
            return min;
        }

        /// <summary>Folds the cloth for <see cref="FoldFrames"/> frames; returns the end positions and the
        /// most non-neighbour pairs closer than thickness/2 seen at any sampled frame.</summary>
        private static float[] Fold(bool selfCollision, out int worstCloser)
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = FoldCloth(world))
            {
                if (selfCollision) cloth.SetSelfCollision(true, Thickness, 0.2f);
                var x = new float[cloth.VertexCount * 3];
                worstCloser = 0;
                for (int f = 0; f < FoldFrames; ++f)
                {
                    cloth.Step(Dt);
                    if (f % 10 != 9) continue;
                    cloth.ReadPositions(x);
                    MinNonNeighbourDistance(x, 0.5f * Thickness, out int closer);
                    worstCloser = Math.Max(worstCloser, closer);
                }
                cloth.ReadPositions(x);
                Assert.That(cloth.GetStats().MaxStrain, Is.LessThan(0.2f), "the contact tore the cloth");
                return x;
            }
        }

        [Test]
        public void NewClothHasSelfCollisionOff()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                SelfCollisionDesc d = cloth.GetSelfCollision();
                Assert.That(d.Enabled, Is.EqualTo(0u));
                Assert.That(d.IsEnabled, Is.False);
                Assert.That(d.Thickness, Is.EqualTo(0f));
                Assert.That(d.Friction, Is.EqualTo(0f));
                Assert.That(d.StructSize, Is.EqualTo(SizeOf.SelfCollisionDesc));
            }
        }

        [Test]
        public void SettingRoundTrips()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 8, 8))
            {
                // StructSize left 0 on purpose: the wrapper sets it.
                cloth.SetSelfCollision(new SelfCollisionDesc { Enabled = 1, Thickness = 0.05f, Friction = 0.3f });
                SelfCollisionDesc d = cloth.GetSelfCollision();
                Assert.That(d.Enabled, Is.EqualTo(1u));
                Assert.That(d.Thickness, Is.EqualTo(0.05f));
                Assert.That(d.Friction, Is.EqualTo(0.3f));

                cloth.SetSelfCollision(false, 0.04f, 0.1f);
                d = cloth.GetSelfCollision();
                Assert.That(d.IsEnabled, Is.False);
                Assert.That(d.Thickness, Is.EqualTo(0.04f));
                Assert.That(d.Friction, Is.EqualTo(0.1f));

                // Edge values: off with thickness 0; friction 10.
                cloth.SetSelfCollision(false, 0f);
                cloth.SetSelfCollision(true, 0.1f, 10f);
                Assert.That(cloth.GetSelfCollision().Friction, Is.EqualTo(10f));
                cloth.Step(Dt);
            }
        }

        [Test]
        public void BadInputThrowsWithTheNativeMessageAndChangesNothing()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 8, 8)) // rest diagonal 1.41 m: thickness <= 0.35 m
            {
                cloth.SetSelfCollision(true, 0.05f, 0.25f);
                var cases = new[]
                {
                    (new SelfCollisionDesc { Enabled = 2, Thickness = 0.05f }, Status.ErrorInvalidArgument),
                    (new SelfCollisionDesc(true, float.NaN), Status.ErrorNotFinite),
                    (new SelfCollisionDesc(true, 0.05f, float.PositiveInfinity), Status.ErrorNotFinite),
                    (new SelfCollisionDesc(true, -0.01f), Status.ErrorInvalidArgument),
                    (new SelfCollisionDesc(false, -0.01f), Status.ErrorInvalidArgument),
                    (new SelfCollisionDesc(true, 0f), Status.ErrorInvalidArgument),
                    (new SelfCollisionDesc(true, 0.5f), Status.ErrorInvalidArgument), // above a quarter of the diagonal
                    (new SelfCollisionDesc(true, 0.05f, -0.1f), Status.ErrorInvalidArgument),
                    (new SelfCollisionDesc(true, 0.05f, 11f), Status.ErrorInvalidArgument),
                };
                foreach ((SelfCollisionDesc desc, Status expected) in cases)
                {
                    string what = "enabled " + desc.Enabled + ", thickness " + desc.Thickness + ", friction " + desc.Friction;
                    var e = Assert.Throws<DrapeException>(() => cloth.SetSelfCollision(desc), what);
                    Assert.That(e.Status, Is.EqualTo(expected), what);
                    Assert.That(e.Function, Is.EqualTo("drape_cloth_set_self_collision"), what);
                    Assert.That(e.NativeMessage, Is.Not.Empty, what);
                    Assert.That(e.Message, Does.Contain(e.NativeMessage), what);
                    SelfCollisionDesc got = cloth.GetSelfCollision();
                    Assert.That(got.Enabled, Is.EqualTo(1u), what);
                    Assert.That(got.Thickness, Is.EqualTo(0.05f), what);
                    Assert.That(got.Friction, Is.EqualTo(0.25f), what);
                }
            }
        }

        [Test]
        public void DisposedClothThrowsObjectDisposed()
        {
            using (var world = new NativeWorld(1))
            {
                NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4);
                cloth.Dispose();
                Assert.Throws<ObjectDisposedException>(() => cloth.SetSelfCollision(true, 0.05f));
                Assert.Throws<ObjectDisposedException>(() => cloth.GetSelfCollision());
            }
        }

        [Test]
        public void GlesRefusesToEnable()
        {
            if (!NativeWorld.IsBackendAvailable(Backend.Gles)) Assert.Ignore("GLES is not available here");
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 8, 8, backend: Backend.Gles))
            {
                var e = Assert.Throws<DrapeException>(() => cloth.SetSelfCollision(true, 0.05f));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorBackendUnavailable));
                Assert.That(e.NativeMessage, Is.Not.Empty);
                cloth.SetSelfCollision(false, 0.05f); // turning it off is accepted
                Assert.That(cloth.GetSelfCollision().IsEnabled, Is.False);
            }
        }

        /// <summary>The fold: without self-collision the halves swing through each other (the control
        /// shows the measure sees it); with it no two non-neighbour particles are closer than half the
        /// thickness, at the end nor at any sampled frame.</summary>
        [Test]
        public void FoldingClothKeepsItsLayersApart()
        {
            float[] off = Fold(false, out int offCloser);
            Assert.That(offCloser, Is.GreaterThan(0), "control: without self-collision the halves should meet");

            float[] on = Fold(true, out int onCloser);
            float min = MinNonNeighbourDistance(on, 0.5f * Thickness, out int endCloser);
            float offMin = MinNonNeighbourDistance(off, 0.5f * Thickness, out int offEnd);
            TestContext.Out.WriteLine("[ measured ] fold " + Cols + "x" + Rows + ": without self-collision " + offCloser +
                                      " pairs < t/2 (max over frames), " + offEnd + " at the end, min " + offMin +
                                      " m; with: " + onCloser + ", " + endCloser + ", min " + min + " m (t = " + Thickness + ")");
            Assert.That(endCloser, Is.EqualTo(0), "pairs closer than thickness/2 at the end (min " + min + " m)");
            Assert.That(min, Is.GreaterThanOrEqualTo(0.5f * Thickness));
            Assert.That(onCloser, Is.EqualTo(0), "pairs closer than thickness/2 during the fold");
            Assert.That(on, Is.Not.EqualTo(off), "self-collision made no difference");
        }
    }
}
