using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Colliders (drape_cloth_set_colliders) through the C# bindings.</summary>
    public class ColliderTests
    {
        private const float Dt = 1f / 60f;

        [Test]
        public void ClothFallsOntoASphereAndStaysAboveIt()
        {
            // A free 1 m x 1 m horizontal cloth (x in [0, 1], z in [-1, 0]) dropped from y = 1.5 onto a
            // sphere of radius 0.25 centred under its middle at (0.5, 0.5, -0.5). Without the sphere
            // it would fall 0.5 g t^2 = 44 m in 3 s; with it the middle must rest on top of the
            // sphere (y ~ 0.75 + margin) and no vertex may be inside it, while the free edges hang down.
            // 3 s: the impact (0.4 s) flings the corners up to the sphere's top, and they come to rest
            // by about 2.5 s (at 2 s a corner was still at 0.68 m on its way down).
            const float radius = 0.25f, margin = 0.005f;
            var center = new Float3(0.5f, 0.5f, -0.5f);
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 21, 21, 1.5f))
            {
                var colliders = new[] { ColliderDesc.Sphere(7, center, radius, margin, 0.5f) };
                var xyz = new float[cloth.VertexCount * 3];
                for (int i = 0; i < 180; ++i)
                {
                    cloth.SetColliders(colliders); // every frame, like DrapeCloth does
                    cloth.Step(Dt);
                }
                cloth.ReadPositions(xyz);
                float minDistance = float.MaxValue;
                for (int v = 0; v < cloth.VertexCount; ++v)
                {
                    float dx = xyz[3 * v] - center.X, dy = xyz[3 * v + 1] - center.Y, dz = xyz[3 * v + 2] - center.Z;
                    minDistance = Math.Min(minDistance, (float)Math.Sqrt(dx * dx + dy * dy + dz * dz));
                }
                int middle = 10 * 21 + 10;
                Assert.That(minDistance, Is.GreaterThan(radius - 0.01f), "a vertex went into the sphere");
                Assert.That(xyz[3 * middle + 1], Is.EqualTo(center.Y + radius + margin).Within(0.03f),
                            "the middle of the cloth does not rest on top of the sphere");
                Assert.That(xyz[1], Is.LessThan(center.Y + radius - 0.1f), "the corner did not drape down");
                Assert.That(cloth.GetStats().NonFinite, Is.EqualTo(0u));
            }
        }

        [Test]
        public void WithoutTheColliderTheClothFallsThrough()
        {
            // Control for the test above: same scene, colliders removed (empty span).
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 21, 21, 1.5f))
            {
                cloth.SetColliders(new[] { ColliderDesc.Sphere(7, new Float3(0.5f, 0.5f, -0.5f), 0.25f) });
                cloth.SetColliders(Span<ColliderDesc>.Empty);
                for (int i = 0; i < 60; ++i) cloth.Step(Dt);
                var xyz = new float[cloth.VertexCount * 3];
                cloth.ReadPositions(xyz);
                Assert.That(xyz[3 * (10 * 21 + 10) + 1], Is.LessThan(0f));
            }
        }

        [Test]
        public void ClothRestsOnAPlane()
        {
            // Ground plane y = 0 (identity rotation: +y is the free side).
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 9, 9, 0.3f))
            {
                var colliders = new[] { ColliderDesc.Plane(1, new Float3(0f, 0f, 0f), Float4.IdentityRotation, 0.01f) };
                for (int i = 0; i < 90; ++i)
                {
                    cloth.SetColliders(colliders);
                    cloth.Step(Dt);
                }
                var xyz = new float[cloth.VertexCount * 3];
                cloth.ReadPositions(xyz);
                for (int v = 0; v < cloth.VertexCount; ++v)
                    Assert.That(xyz[3 * v + 1], Is.EqualTo(0.01f).Within(0.01f), "vertex " + v);
            }
        }

        private static DrapeException Refused(NativeCloth cloth, ColliderDesc[] colliders, Status expected)
        {
            var e = Assert.Throws<DrapeException>(() => cloth.SetColliders(colliders));
            Assert.That(e.Status, Is.EqualTo(expected));
            Assert.That(e.Function, Is.EqualTo("drape_cloth_set_colliders"));
            Assert.That(e.NativeMessage, Is.Not.Empty, "the native message is missing");
            Assert.That(e.Message, Does.Contain(e.NativeMessage));
            return e;
        }

        [Test]
        public void BadColliderInputThrowsWithTheNativeMessage()
        {
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4))
            {
                var good = ColliderDesc.Sphere(1, new Float3(0f, 0f, 0f), 0.5f);

                ColliderDesc c = good;
                c.Size.X = -1f;
                Refused(cloth, new[] { c }, Status.ErrorInvalidArgument);

                c = good;
                c.Position.Y = float.NaN;
                Refused(cloth, new[] { c }, Status.ErrorNotFinite);

                c = good;
                c.Shape = (ColliderShape)99;
                Refused(cloth, new[] { c }, Status.ErrorInvalidEnum);

                c = good;
                c.Rotation = new Float4(0f, 0f, 0f, 2f);
                Refused(cloth, new[] { c }, Status.ErrorInvalidArgument);

                c = good;
                c.Friction = -0.1f;
                Refused(cloth, new[] { c }, Status.ErrorInvalidArgument);

                Refused(cloth, new[] { good, good }, Status.ErrorInvalidArgument); // duplicate id

                var tooMany = new ColliderDesc[NativeCloth.MaxColliders + 1];
                for (int k = 0; k < tooMany.Length; ++k)
                    tooMany[k] = ColliderDesc.Sphere((uint)k, new Float3(k, 0f, 0f), 0.1f);
                Refused(cloth, tooMany, Status.ErrorInvalidArgument);

                // The cloth still works and takes good input after the refusals.
                cloth.SetColliders(new[] { good });
                cloth.Step(Dt);
            }
        }
    }
}
