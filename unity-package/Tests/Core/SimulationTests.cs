using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Step a cloth and read back positions that physics predicts.</summary>
    public class SimulationTests
    {
        private const float Dt = 1f / 60f;

        private static float[] Positions(NativeCloth cloth)
        {
            var xyz = new float[cloth.VertexCount * 3];
            cloth.ReadPositions(xyz);
            return xyz;
        }

        [Test]
        public void ReadBackTheGridAsDescribed()
        {
            // drape.h: vertex (c, r) = origin + axis_u*width*c/(columns-1) + axis_v*height*r/(rows-1),
            // default axes +x and -z. 5 x 3 vertices, 2 m x 1 m, origin (1, 2, 3).
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = NativeCloth.CreateGrid(world, new ClothDesc { TotalMass = 1f },
                                                  new GridDesc { Columns = 5, Rows = 3, Width = 2f, Height = 1f,
                                                                 Origin = new Float3(1f, 2f, 3f) }))
            {
                float[] p = Positions(cloth);
                int v = 2 * 5 + 4; // c = 4, r = 2
                Assert.That(p[3 * v + 0], Is.EqualTo(3f).Within(1e-5f));
                Assert.That(p[3 * v + 1], Is.EqualTo(2f).Within(1e-5f));
                Assert.That(p[3 * v + 2], Is.EqualTo(2f).Within(1e-5f));
            }
        }

        [TestCase(Model.Xpbd, Backend.Cpu)]
        [TestCase(Model.Pbd, Backend.Cpu)]
        [TestCase(Model.MassSpring, Backend.Cpu)]
        [TestCase(Model.Xpbd, Backend.CpuThreaded)]
        public void UnpinnedClothFallsFreely(Model model, Backend backend)
        {
            // No air drag: every particle accelerates at g, so after t = 0.5 s the cloth has dropped
            // g t^2 / 2 = 1.226 m and kept its shape (springs stay at rest length).
            using (var world = new NativeWorld(2))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 8, 8, 10f, backend))
            {
                Params p = NativeWorld.DefaultParams();
                p.Model = model;
                if (model == Model.Pbd) p.Stiffness = new GroupValues(1f, 1f, 0.5f);
                p.AirDrag = 0f;
                cloth.SetParams(p);
                for (int i = 0; i < 30; ++i) cloth.Step(Dt);

                float[] xyz = Positions(cloth);
                float expectedY = 10f - 0.5f * 9.81f * 0.25f;
                for (int v = 0; v < cloth.VertexCount; ++v)
                    Assert.That(xyz[3 * v + 1], Is.EqualTo(expectedY).Within(0.03f), "vertex " + v);
                Assert.That(cloth.GetStats().MaxStrain, Is.LessThan(0.01f));
            }
        }

        [TestCase(Model.Xpbd)]
        [TestCase(Model.Pbd)]
        [TestCase(Model.MassSpring)]
        public void ClothPinnedAtTwoCornersSwingsDownButHangs(Model model)
        {
            // A 1 m x 1 m horizontal cloth at y = 1 pinned at the two corners of its first row,
            // 1 s of simulated time. Like a plate hinged on that edge it swings down (a stiff cloth
            // may swing back up: a rigid pendulum of 1 m has a period of about 1.6 s), so over the
            // run the far edge must get well below its start; the pins must not move; and no vertex
            // may get further below the pins than the cloth reaches (1 m, allowing 100% stretch).
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 11, 11, 1f))
            {
                Params p = NativeWorld.DefaultParams();
                p.Model = model;
                if (model == Model.Pbd) p.Stiffness = new GroupValues(1f, 1f, 0.5f);
                cloth.SetParams(p);
                var inverseMasses = new float[cloth.VertexCount];
                for (int v = 0; v < inverseMasses.Length; ++v) inverseMasses[v] = 1f;
                inverseMasses[0] = 0f;
                inverseMasses[10] = 0f;
                cloth.SetInverseMasses(inverseMasses);

                const int farCorner = 120; // (10, 10)
                float lowestFar = float.MaxValue;
                float lowest = float.MaxValue;
                var xyz = new float[cloth.VertexCount * 3];
                for (int i = 0; i < 60; ++i)
                {
                    cloth.Step(Dt);
                    cloth.ReadPositions(xyz);
                    for (int k = 0; k < xyz.Length; ++k)
                        Assert.That(float.IsNaN(xyz[k]) || float.IsInfinity(xyz[k]), Is.False, "non-finite output");
                    for (int v = 0; v < cloth.VertexCount; ++v) lowest = Math.Min(lowest, xyz[3 * v + 1]);
                    lowestFar = Math.Min(lowestFar, xyz[3 * farCorner + 1]);
                    Assert.That(xyz[1], Is.EqualTo(1f).Within(1e-5f), "pinned corner 0 moved");
                    Assert.That(xyz[3 * 10 + 0], Is.EqualTo(1f).Within(1e-5f), "pinned corner 10 moved");
                    Assert.That(xyz[3 * 10 + 1], Is.EqualTo(1f).Within(1e-5f), "pinned corner 10 moved");
                }
                Assert.That(lowestFar, Is.LessThan(0.5f), "the free edge did not swing down");
                Assert.That(lowest, Is.GreaterThan(1f - 2f), "fell further than the cloth reaches");
                Stats stats = cloth.GetStats();
                Assert.That(stats.NonFinite, Is.EqualTo(0u));
                Assert.That(stats.UnstableSteps, Is.EqualTo(0u));
            }
        }

        [Test]
        public void MovingAPinMovesTheVertex()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 5, 5, 1f))
            {
                var pins = new[] { new Pin(0, new Float3(0f, 1f, 0f)) };
                cloth.SetPins(pins);
                pins[0].Position = new Float3(0.2f, 1.5f, 0f);
                cloth.SetPins(pins);
                cloth.Step(Dt);
                float[] xyz = Positions(cloth);
                Assert.That(xyz[0], Is.EqualTo(0.2f).Within(1e-4f));
                Assert.That(xyz[1], Is.EqualTo(1.5f).Within(1e-4f));

                // Hold it there (a pinned vertex that is not moved has no velocity) until the cloth
                // hangs still below it, then let go: gravity and the cloth below pull it down. The
                // 0.5 m jump in one step throws the cloth up past the pin (MASS_SPRING's rises to
                // y = 3); released 10 steps after the jump, the vertex went up with it (1.51 m with
                // IMPLICIT's coarse space, which no longer damps that swing as the old one did).
                for (int i = 0; i < 180; ++i) cloth.Step(Dt);
                Assert.That(Positions(cloth)[1], Is.EqualTo(1.5f).Within(1e-4f));
                cloth.ReleasePins(new uint[] { 0 });
                for (int i = 0; i < 10; ++i) cloth.Step(Dt);
                Assert.That(Positions(cloth)[1], Is.LessThan(1.5f), "released vertex should fall");
            }
        }

        [Test]
        public void NormalsOfAFlatGridAreUnitAndVertical()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                var n = new float[cloth.VertexCount * 3];
                cloth.ReadNormals(n);
                for (int v = 0; v < cloth.VertexCount; ++v)
                {
                    Assert.That(Math.Abs(n[3 * v + 1]), Is.EqualTo(1f).Within(1e-4f), "vertex " + v);
                    Assert.That(n[3 * v + 0], Is.EqualTo(0f).Within(1e-4f));
                    Assert.That(n[3 * v + 2], Is.EqualTo(0f).Within(1e-4f));
                }
            }
        }

        [Test]
        public void WorldStepMatchesClothStepOnTheCpu()
        {
            // Cpu is deterministic: stepping through the world or the cloth gives the same bits.
            using (var world1 = new NativeWorld(1))
            using (var world2 = new NativeWorld(1))
            using (NativeCloth a = TestScenes.HorizontalGrid(world1, 6, 6))
            using (NativeCloth b = TestScenes.HorizontalGrid(world2, 6, 6))
            {
                var inv = new float[36];
                for (int v = 0; v < 36; ++v) inv[v] = v < 6 ? 0f : 1f;
                a.SetInverseMasses(inv);
                b.SetInverseMasses(inv);
                for (int i = 0; i < 20; ++i)
                {
                    world1.Step(Dt);
                    b.Step(Dt);
                }
                Assert.That(Positions(a), Is.EqualTo(Positions(b)));
            }
        }
    }
}
