using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    public class ParamsTests
    {
        [Test]
        public void DefaultsAreTheDocumentedOnes()
        {
            // drape.h: AUTO, stiffness 2000/1000/200, damping 0.05, gravity (0,-9.81,0), wind 0,
            // air drag 0.1, substeps 0 (automatic: 16 small steps), 1 iteration, tethers at 10% stretch.
            Params p = NativeWorld.DefaultParams();
            Assert.That(p.StructSize, Is.EqualTo(SizeOf.Params));
            Assert.That(p.Model, Is.EqualTo(Model.Auto));
            Assert.That(p.Stiffness.Structural, Is.EqualTo(2000f));
            Assert.That(p.Stiffness.Shear, Is.EqualTo(1000f));
            Assert.That(p.Stiffness.Bend, Is.EqualTo(200f));
            Assert.That(p.Damping, Is.EqualTo(0.05f));
            Assert.That(p.Gravity, Is.EqualTo(new Float3(0f, -9.81f, 0f)));
            Assert.That(p.Wind, Is.EqualTo(new Float3(0f, 0f, 0f)));
            Assert.That(p.AirDrag, Is.EqualTo(0.1f));
            Assert.That(p.Substeps, Is.EqualTo(0u));
            Assert.That(p.Iterations, Is.EqualTo(0u)); // automatic (drape.h: per model)
            Assert.That(p.MaxStretch, Is.EqualTo(0.1f).Within(1e-7f));
        }

        [Test]
        public void NewClothStartsWithTheDefaults()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                Params expected = NativeWorld.DefaultParams();
                Params actual = cloth.GetParams();
                Assert.That(expected.Model, Is.EqualTo(Model.Auto));
                Assert.That(actual.Model, Is.EqualTo(Model.Implicit)); // what AUTO resolves to on the CPU
                Assert.That(actual.Stiffness.Structural, Is.EqualTo(expected.Stiffness.Structural));
                Assert.That(actual.Iterations, Is.EqualTo(expected.Iterations));
            }
        }

        [TestCase(Model.MassSpring)]
        [TestCase(Model.Pbd)]
        [TestCase(Model.Xpbd)]
        public void SetParamsRoundTrips(Model model)
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                Params p = NativeWorld.DefaultParams();
                p.Model = model;
                p.Stiffness = model == Model.Pbd ? new GroupValues(0.9f, 0.5f, 0.1f) : new GroupValues(500f, 250f, 50f);
                p.Damping = 0.25f;
                p.Gravity = new Float3(0f, -3f, 1f);
                p.Wind = new Float3(2f, 0f, -1f);
                p.AirDrag = 0.3f;
                p.Substeps = 3;
                p.Iterations = 7;
                p.MaxStretch = 0.25f;
                p.StructSize = 0; // the wrapper sets it
                cloth.SetParams(p);

                Params back = cloth.GetParams();
                Assert.That(back.Model, Is.EqualTo(model));
                Assert.That(back.Stiffness.Structural, Is.EqualTo(p.Stiffness.Structural));
                Assert.That(back.Stiffness.Shear, Is.EqualTo(p.Stiffness.Shear));
                Assert.That(back.Stiffness.Bend, Is.EqualTo(p.Stiffness.Bend));
                Assert.That(back.Damping, Is.EqualTo(0.25f));
                Assert.That(back.Gravity, Is.EqualTo(new Float3(0f, -3f, 1f)));
                Assert.That(back.Wind, Is.EqualTo(new Float3(2f, 0f, -1f)));
                Assert.That(back.AirDrag, Is.EqualTo(0.3f));
                Assert.That(back.Substeps, Is.EqualTo(3u));
                Assert.That(back.Iterations, Is.EqualTo(7u));
                Assert.That(back.MaxStretch, Is.EqualTo(0.25f));
            }
        }

        [Test]
        public void FixedSubstepsAreUsedByTheStep()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                Params p = NativeWorld.DefaultParams();
                p.Substeps = 5;
                p.Iterations = 2;
                cloth.SetParams(p);
                cloth.Step(1f / 60f);
                Stats stats = cloth.GetStats();
                Assert.That(stats.Substeps, Is.EqualTo(5u));
                Assert.That(stats.Iterations, Is.EqualTo(2u));
            }
        }

        [Test]
        public void StabilityEstimateMatchesHandComputationAndTheStep()
        {
            // A chain: 1 column x 11 rows, 1 m long, 0.011 kg -> 11 particles of 0.001 kg (a chain's
            // mass is uniform). Bend springs off, so an inner particle has 2 structural springs of
            // k = 1000 N/m: omega_max^2 <= 2 * sum k / m = 2 * 2000 / 0.001 = 4e6, omega_max = 2000 rad/s.
            // No damping: h <= 2 * 0.9 / omega_max = 9e-4 s; dt = 1/60 s -> ceil(16.667 / 0.9) = 19 substeps.
            var grid = new GridDesc { Columns = 1, Rows = 11, Width = 1f, Height = 1f };
            Params p = NativeWorld.DefaultParams();
            p.Model = Model.MassSpring;
            p.Stiffness = new GroupValues(1000f, 0f, 0f);
            p.Damping = 0f;
            StabilityEstimate e = Stability.ForGrid(grid, 0.011f, p, 1f / 60f);
            Assert.That(e.StructSize, Is.EqualTo(SizeOf.StabilityEstimate));
            Assert.That(e.MaxStableSubstep, Is.EqualTo(9e-4f).Within(1e-8f));
            Assert.That(e.StableSubsteps, Is.EqualTo(19u));
            Assert.That(e.Substeps, Is.EqualTo(19u));  // automatic: the bound
            Assert.That(e.Stable, Is.EqualTo(1u));

            // The estimate is what the library does: a cloth built the same way steps with 19.
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = NativeCloth.CreateGrid(world, new ClothDesc { Backend = Backend.Cpu, TotalMass = 0.011f }, grid))
            {
                cloth.SetParams(p);
                cloth.Step(1f / 60f);
                Assert.That(cloth.GetStats().Substeps, Is.EqualTo(e.Substeps));
            }

            // Four times stiffer: omega doubles, so about twice the substeps; 5 given is flagged unstable.
            p.Stiffness = new GroupValues(4000f, 0f, 0f);
            p.Substeps = 5;
            e = Stability.ForGrid(grid, 0.011f, p, 1f / 60f);
            Assert.That(e.StableSubsteps, Is.EqualTo(38u));  // ceil(16.667 / 0.45)
            Assert.That(e.Substeps, Is.EqualTo(5u));
            Assert.That(e.Stable, Is.EqualTo(0u));

            // Position-based models have no explicit bound; automatic substeps are 16 small steps.
            p.Model = Model.Xpbd;
            p.Substeps = 0;
            e = Stability.ForGrid(grid, 0.011f, p, 1f / 60f);
            Assert.That(e.Substeps, Is.EqualTo(16u));
            Assert.That(e.StableSubsteps, Is.EqualTo(1u));
            Assert.That(e.MaxStableSubstep, Is.EqualTo(0f));

            // Bad input is refused like creation refuses it.
            var ex = Assert.Throws<DrapeException>(() => Stability.ForGrid(grid, 0.011f, p, 0f));
            Assert.That(ex.Status, Is.EqualTo(Status.ErrorInvalidArgument));
            ex = Assert.Throws<DrapeException>(() => Stability.ForGrid(grid, -1f, p, 1f / 60f));
            Assert.That(ex.Status, Is.EqualTo(Status.ErrorInvalidArgument));
        }

        [Test]
        public void StabilityEstimateForAMesh()
        {
            // Two triangles (a unit quad), XPBD defaults: 16 automatic substeps, no explicit bound.
            float[] positions = { 0f, 0f, 0f, 1f, 0f, 0f, 1f, 0f, 1f, 0f, 0f, 1f };
            int[] indices = { 0, 1, 2, 0, 2, 3 };
            Params xpbd = NativeWorld.DefaultParams();
            xpbd.Model = Model.Xpbd;
            StabilityEstimate e = Stability.ForMesh(positions, indices, 0f, 1f, xpbd, 1f / 60f);
            Assert.That(e.Substeps, Is.EqualTo(16u));
            Assert.That(e.Stable, Is.EqualTo(1u));
            int[] bad = { 0, 1, 9 };
            var ex = Assert.Throws<DrapeException>(() => Stability.ForMesh(positions, bad, 0f, 1f, NativeWorld.DefaultParams(), 1f / 60f));
            Assert.That(ex.Status, Is.EqualTo(Status.ErrorIndexOutOfRange));
        }
    }
}
