using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    public class ParamsTests
    {
        [Test]
        public void DefaultsAreTheDocumentedOnes()
        {
            // drape.h: XPBD, stiffness 2000/1000/200, damping 0.05, gravity (0,-9.81,0), wind 0,
            // air drag 0.1, substeps 0 (automatic: 16 small steps), 1 iteration, tethers at 10% stretch.
            Params p = NativeWorld.DefaultParams();
            Assert.That(p.StructSize, Is.EqualTo(SizeOf.Params));
            Assert.That(p.Model, Is.EqualTo(Model.Xpbd));
            Assert.That(p.Stiffness.Structural, Is.EqualTo(2000f));
            Assert.That(p.Stiffness.Shear, Is.EqualTo(1000f));
            Assert.That(p.Stiffness.Bend, Is.EqualTo(200f));
            Assert.That(p.Damping, Is.EqualTo(0.05f));
            Assert.That(p.Gravity, Is.EqualTo(new Float3(0f, -9.81f, 0f)));
            Assert.That(p.Wind, Is.EqualTo(new Float3(0f, 0f, 0f)));
            Assert.That(p.AirDrag, Is.EqualTo(0.1f));
            Assert.That(p.Substeps, Is.EqualTo(0u));
            Assert.That(p.Iterations, Is.EqualTo(1u));
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
                Assert.That(actual.Model, Is.EqualTo(expected.Model));
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
        public void MassSpringSubstepEstimateMatchesHandComputation()
        {
            // k = 1000/500/100 N/m, m = 0.001 kg: sum k = 4*(1600) = 6400 N/m,
            // omega_max = sqrt(2*6400/0.001) = sqrt(1.28e7) = 3577.7 rad/s.
            // dt = 1/60 s: n >= dt*omega/(2*0.9) = 59.63/1.8 = 33.13 -> 34 substeps.
            var k = new GroupValues(1000f, 500f, 100f);
            Assert.That(Stability.MassSpringOmegaMax(k, 0.001f), Is.EqualTo(3577.7).Within(0.1));
            Assert.That(Stability.MassSpringSubstepsNeeded(k, 0.001f, 1f / 60f), Is.EqualTo(34));
            // Soft and heavy: one substep is enough.
            Assert.That(Stability.MassSpringSubstepsNeeded(new GroupValues(1f, 0f, 0f), 1f, 1f / 60f), Is.EqualTo(1));
        }
    }
}
