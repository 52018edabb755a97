using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Native sleeping (drape_cloth_set_sleep / drape_cloth_wake, Stats.Sleeping).</summary>
    public class SleepTests
    {
        private const float Dt = 1f / 60f;

        /// <summary>A 12 x 12 cloth hanging from its two top corners, heavily air-damped so it settles
        /// within seconds, sleeping at 0.02 m/s for 0.5 s.</summary>
        private static NativeCloth Hanging(NativeWorld world)
        {
            NativeCloth cloth = TestScenes.FacingGrid(world, 12, 12);
            cloth.SetPins(new[] { new Pin(0, new Float3(-0.5f, 0.5f, 0f)), new Pin(11, new Float3(0.5f, 0.5f, 0f)) });
            Params p = NativeWorld.DefaultParams();
            p.AirDrag = 3f;
            cloth.SetParams(p);
            cloth.SetSleep(0.02f, 0.5f);
            return cloth;
        }

        private static int StepsUntilAsleep(NativeCloth cloth, ColliderDesc[] colliders = null)
        {
            for (int i = 1; i <= 1200; ++i)
            {
                if (colliders != null) cloth.SetColliders(colliders);
                cloth.Step(Dt);
                if (cloth.GetStats().Sleeping != 0) return i;
            }
            return -1;
        }

        [Test]
        public void HangingClothFallsAsleepStaysStillAndWakes()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = Hanging(world))
            {
                Assert.That(cloth.GetStats().Sleeping, Is.EqualTo(0u));
                int steps = StepsUntilAsleep(cloth);
                Assert.That(steps, Is.GreaterThan(30), "fell asleep before 0.5 s of stillness were possible");
                Assert.That(steps, Is.LessThan(1200), "did not fall asleep within 20 s");

                var before = new float[cloth.VertexCount * 3];
                var after = new float[before.Length];
                cloth.ReadPositions(before);
                for (int i = 0; i < 30; ++i) cloth.Step(Dt);
                cloth.ReadPositions(after);
                Assert.That(after, Is.EqualTo(before), "an asleep cloth moved");
                Assert.That(cloth.GetStats().Sleeping, Is.EqualTo(1u));

                cloth.Wake();
                cloth.Step(Dt);
                Assert.That(cloth.GetStats().Sleeping, Is.EqualTo(0u), "Wake did not wake it");
                Assert.That(StepsUntilAsleep(cloth), Is.GreaterThan(0), "did not fall asleep again");
            }
        }

        [Test]
        public void UnchangedCollidersResentEveryFrameLetItSleepAndAMovedOneWakesIt()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = Hanging(world))
            {
                // A sphere behind the cloth, out of its way: re-sent unchanged each frame as DrapeCloth does.
                var colliders = new[] { ColliderDesc.Sphere(3, new Float3(0f, 0f, -2f), 0.2f) };
                Assert.That(StepsUntilAsleep(cloth, colliders), Is.GreaterThan(0));
                colliders[0].Position.X = 0.1f;
                cloth.SetColliders(colliders);
                cloth.Step(Dt);
                Assert.That(cloth.GetStats().Sleeping, Is.EqualTo(0u), "moving a collider did not wake the cloth");
            }
        }

        [Test]
        public void ThresholdZeroNeverSleeps()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = Hanging(world))
            {
                cloth.SetSleep(0f, 0.5f);
                for (int i = 0; i < 600; ++i) cloth.Step(Dt);
                Assert.That(cloth.GetStats().Sleeping, Is.EqualTo(0u));
            }
        }

        [Test]
        public void BadSleepInputThrowsWithTheNativeMessage()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                var e = Assert.Throws<DrapeException>(() => cloth.SetSleep(-1f, 1f));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorInvalidArgument));
                Assert.That(e.NativeMessage, Is.Not.Empty);
                e = Assert.Throws<DrapeException>(() => cloth.SetSleep(0.01f, float.NaN));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorNotFinite));
                Assert.That(e.Function, Is.EqualTo("drape_cloth_set_sleep"));
            }
        }
    }
}
