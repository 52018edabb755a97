using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    public class LifecycleTests
    {
        [Test]
        public void AbiVersionMatchesBindings()
        {
            Assert.That(NativeWorld.AbiVersion, Is.EqualTo(NativeWorld.ExpectedAbiVersion));
        }

        [Test]
        public void CpuBackendsAreAvailable()
        {
            Assert.That(NativeWorld.IsBackendAvailable(Backend.Cpu), Is.True);
            Assert.That(NativeWorld.IsBackendAvailable(Backend.CpuThreaded), Is.True);
        }

        [Test]
        public void CreateAndDisposeWorldAndCloth()
        {
            var world = new NativeWorld(1);
            NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 3);
            Assert.That(cloth.IsDisposed, Is.False);
            cloth.Dispose();
            Assert.That(cloth.IsDisposed, Is.True);
            cloth.Dispose(); // twice is harmless
            world.Dispose();
            Assert.That(world.IsDisposed, Is.True);
            world.Dispose();
        }

        [Test]
        public void GridInfoCountsTheStencil()
        {
            // 10 x 8 vertices. Structural: 9*8 along rows + 10*7 along columns = 142.
            // Shear: two diagonals per cell, 9*7*2 = 126. Bend (two apart): 8*8 + 10*6 = 124.
            // Triangles: two per cell = 126.
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 10, 8))
            {
                ClothInfo info = cloth.Info;
                Assert.That(info.VertexCount, Is.EqualTo(80u));
                Assert.That(info.ParticleCount, Is.EqualTo(80u));
                Assert.That(info.SpringCount.Structural, Is.EqualTo(142u));
                Assert.That(info.SpringCount.Shear, Is.EqualTo(126u));
                Assert.That(info.SpringCount.Bend, Is.EqualTo(124u));
                Assert.That(info.TriangleCount, Is.EqualTo(126u));
                Assert.That(info.Backend, Is.EqualTo(Backend.Cpu));
                Assert.That(cloth.VertexCount, Is.EqualTo(80));
            }
        }

        [Test]
        public void MeshSeamVerticesAreWelded()
        {
            // A unit quad as two triangles whose shared edge is split (as Unity splits UV seams):
            // 6 caller vertices, 4 distinct positions, so 4 particles.
            float[] positions =
            {
                0, 0, 0, 1, 0, 0, 1, 0, 1, // triangle 1
                0, 0, 0, 1, 0, 1, 0, 0, 1, // triangle 2 (copies of vertex 0 and 2)
            };
            int[] indices = { 0, 2, 1, 3, 5, 4 };
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = NativeCloth.CreateMesh(world, new ClothDesc { TotalMass = 1f }, positions, indices, 0f))
            {
                Assert.That(cloth.Info.VertexCount, Is.EqualTo(6u));
                Assert.That(cloth.Info.ParticleCount, Is.EqualTo(4u));
                Assert.That(cloth.Info.TriangleCount, Is.EqualTo(2u));
            }
        }

        [Test]
        public void ClothKeepsItsWorldAliveAfterWorldDispose()
        {
            var world = new NativeWorld(1);
            NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4);
            world.Dispose();
            // The native world is destroyed only when its last cloth goes; until then the cloth works.
            Assert.DoesNotThrow(() => cloth.Step(1f / 60f));
            cloth.Dispose();
            Assert.That(cloth.IsDisposed, Is.True);
        }

        [Test]
        public void UseAfterDisposeThrowsObjectDisposed()
        {
            var world = new NativeWorld(1);
            NativeCloth cloth = TestScenes.HorizontalGrid(world, 4, 4);
            cloth.Dispose();
            Assert.Throws<ObjectDisposedException>(() => cloth.Step(0.01f));
            world.Dispose();
            Assert.Throws<ObjectDisposedException>(() => world.Step(0.01f));
        }

        [Test]
        public void LeakedHandlesAreReleasedByTheFinalizer()
        {
            WeakReference leaked = LeakWorldAndCloth();
            for (int i = 0; i < 3 && leaked.IsAlive; ++i)
            {
                GC.Collect();
                GC.WaitForPendingFinalizers();
            }
            Assert.That(leaked.IsAlive, Is.False, "the cloth handle was not finalized");
            // The library is still usable afterwards (no double free, no stale handle).
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 3, 3))
            {
                cloth.Step(0.01f);
            }
        }

        private static WeakReference LeakWorldAndCloth()
        {
            var world = new NativeWorld(1);
            NativeCloth cloth = TestScenes.HorizontalGrid(world, 3, 3);
            cloth.Step(0.01f);
            return new WeakReference(cloth.Handle);
        }
    }
}
