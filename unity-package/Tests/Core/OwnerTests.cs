using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Owner transform (drape_cloth_set_owner) through the bindings.</summary>
    public class OwnerTests
    {
        private const float Dt = 1f / 60f;

        private static NativeCloth Weightless(NativeWorld world)
        {
            NativeCloth cloth = TestScenes.FacingGrid(world, 8, 8);
            cloth.SetPins(new[] { new Pin(0, new Float3(-0.5f, 0.5f, 0f)), new Pin(7, new Float3(0.5f, 0.5f, 0f)) });
            Params p = NativeWorld.DefaultParams();
            p.Gravity = new Float3(0f, 0f, 0f);
            p.AirDrag = 0f;
            cloth.SetParams(p);
            return cloth;
        }

        [Test]
        public void DefaultsAreTheDocumentedOnes()
        {
            Owner o = Owner.Default();
            Assert.That(o.StructSize, Is.EqualTo(SizeOf.Owner));
            Assert.That(o.Rotation.W, Is.EqualTo(1f));
            Assert.That(o.LinearInertia, Is.EqualTo(1f));
            Assert.That(o.AngularInertia, Is.EqualTo(1f));
            Assert.That(o.TeleportDistance, Is.EqualTo(1f));
        }

        [Test]
        public void WithoutInertiaTheWholeClothMovesWithTheOwner()
        {
            // Linear inertia 0: the cloth is carried fully (local space). The owner moves 0.3 m along
            // x: pins and free vertices all move by 0.3 m, shape unchanged.
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = Weightless(world))
            {
                var before = new float[cloth.VertexCount * 3];
                var after = new float[before.Length];
                cloth.ReadPositions(before);
                Owner o = Owner.Default();
                o.LinearInertia = 0f;
                o.AngularInertia = 0f;
                cloth.SetOwner(o);
                o.Position = new Float3(0.3f, 0f, 0f);
                cloth.SetOwner(o);
                cloth.Step(Dt);
                cloth.ReadPositions(after);
                for (int v = 0; v < cloth.VertexCount; ++v)
                {
                    Assert.That(after[3 * v] - before[3 * v], Is.EqualTo(0.3f).Within(1e-3f), "x of vertex " + v);
                    Assert.That(after[3 * v + 1] - before[3 * v + 1], Is.EqualTo(0f).Within(1e-3f), "y of vertex " + v);
                }
            }
        }

        [Test]
        public void WithInertiaPinsFollowAndTheClothLags()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = Weightless(world))
            {
                var before = new float[cloth.VertexCount * 3];
                var after = new float[before.Length];
                cloth.ReadPositions(before);
                Owner o = Owner.Default(); // inertia 1: world space
                cloth.SetOwner(o);
                o.Position = new Float3(0.3f, 0f, 0f);
                cloth.SetOwner(o);
                cloth.Step(Dt);
                cloth.ReadPositions(after);
                Assert.That(after[0] - before[0], Is.EqualTo(0.3f).Within(1e-4f), "pin 0 follows the owner");
                Assert.That(after[3 * 7] - before[3 * 7], Is.EqualTo(0.3f).Within(1e-4f), "pin 7 follows the owner");
                int bottom = 7 * 8 + 3;
                Assert.That(after[3 * bottom] - before[3 * bottom], Is.LessThan(0.2f), "the free bottom edge lags");
            }
        }

        [Test]
        public void BadOwnerInputThrowsWithTheNativeMessage()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = Weightless(world))
            {
                Owner o = Owner.Default();
                o.LinearInertia = 1.5f;
                var e = Assert.Throws<DrapeException>(() => cloth.SetOwner(o));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorInvalidArgument));
                Assert.That(e.NativeMessage, Is.Not.Empty);
                Assert.That(e.Function, Is.EqualTo("drape_cloth_set_owner"));
                o = Owner.Default();
                o.Position.Z = float.PositiveInfinity;
                e = Assert.Throws<DrapeException>(() => cloth.SetOwner(o));
                Assert.That(e.Status, Is.EqualTo(Status.ErrorNotFinite));
            }
        }
    }
}
