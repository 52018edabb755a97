using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>The per-frame path (set params, pin, step, read, stats) allocates no managed memory.</summary>
    public class AllocationTests
    {
        /// <summary>The counter must work on this runtime, or the tests below would pass vacuously.</summary>
        private static void RequireAllocationCounter()
        {
            long probeBefore = GC.GetAllocatedBytesForCurrentThread();
            object probe = new byte[1024];
            long probeAfter = GC.GetAllocatedBytesForCurrentThread();
            GC.KeepAlive(probe);
            if (probeAfter - probeBefore < 1024)
                Assert.Ignore("GC.GetAllocatedBytesForCurrentThread does not count allocations on this runtime");
        }

        [Test]
        public unsafe void SteadyStateFrameAllocatesNothing()
        {
            RequireAllocationCounter();
            long probeBefore = 0;

            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 16, 16))
            {
                var pins = new Pin[2];
                var layout = new VertexLayout(24, 0, 12); // position + normal, like a Unity vertex stream
                byte[] vertices = new byte[24 * cloth.VertexCount];
                Params p = NativeWorld.DefaultParams();

                for (int frame = 0; frame < 200; ++frame)
                {
                    if (frame == 100) probeBefore = GC.GetAllocatedBytesForCurrentThread();
                    p.Wind = new Float3(frame % 7, 0f, 0f);
                    cloth.SetParams(p);
                    pins[0] = new Pin(0, new Float3(0f, 1f, 0f));
                    pins[1] = new Pin(15, new Float3(1f, 1f, 0f));
                    cloth.SetPins(pins);
                    world.Step(1f / 60f);
                    cloth.Step(1f / 120f);
                    fixed (byte* dst = vertices)
                    {
                        cloth.Read(layout, dst, vertices.Length);
                    }
                    Stats stats = cloth.GetStats();
                    if (stats.NonFinite != 0) Assert.Fail("non-finite state at frame " + frame);
                }
                long allocated = GC.GetAllocatedBytesForCurrentThread() - probeBefore;
                Assert.That(allocated, Is.EqualTo(0), "bytes allocated over 100 steady-state frames");
            }
        }
    
        [Test]
        public void FrameWithCollidersDragOwnerAndSleepAllocatesNothing()
        {
            // What DrapeCloth and DrapeTouchDrag do each frame: push every collider transform in one
            // call from a preallocated array, drag, move the owner, step the world, read the stats.
            RequireAllocationCounter();
            using (var world = new NativeWorld(1))
            using (NativeCloth cloth = TestScenes.HorizontalGrid(world, 16, 16))
            {
                var colliders = new ColliderDesc[NativeCloth.MaxColliders];
                View view = TestScenes.PerspectiveView();
                var touches = new TouchPoint[1];
                Owner owner = Owner.Default();
                var xyz = new float[cloth.VertexCount * 3];
                cloth.SetSleep(0.01f, 1f);
                long before = 0;
                for (int frame = 0; frame < 200; ++frame)
                {
                    if (frame == 100) before = GC.GetAllocatedBytesForCurrentThread();
                    float t = frame * (1f / 60f);
                    colliders[0] = ColliderDesc.Sphere(1, new Float3(0.5f, 0.5f + 0.1f * t, -0.5f), 0.3f);
                    colliders[1] = ColliderDesc.Plane(2, new Float3(0f, -0.5f, 0f), Float4.IdentityRotation);
                    colliders[2] = new ColliderDesc
                    {
                        Shape = ColliderShape.Capsule, Id = 3, Position = new Float3(2f, 0f, 0f),
                        Rotation = Float4.IdentityRotation, Size = new Float3(0.1f, 0.3f, 0f), Margin = 0.005f,
                    };
                    colliders[3] = new ColliderDesc
                    {
                        Shape = ColliderShape.Box, Id = 4, Position = new Float3(-2f, 0f, 0f),
                        Rotation = Float4.IdentityRotation, Size = new Float3(0.1f, 0.2f, 0.3f), Margin = 0.005f,
                    };
                    cloth.SetColliders(new Span<ColliderDesc>(colliders, 0, 4));
                    touches[0] = new TouchPoint { Position = new Float2(200f, 150f), Motion = new Float2(1f, 0f),
                                             Amplitude = 200f, Sigma = 300f };
                    cloth.Drag(view, touches);
                    owner.Position = new Float3(0.001f * frame, 0f, 0f);
                    cloth.SetOwner(owner);
                    world.Step(1f / 60f);
                    Stats stats = cloth.GetStats();
                    if (stats.NonFinite != 0) Assert.Fail("non-finite state at frame " + frame);
                    cloth.ReadPositions(xyz);
                }
                long allocated = GC.GetAllocatedBytesForCurrentThread() - before;
                Assert.That(allocated, Is.EqualTo(0), "bytes allocated over 100 steady-state frames");
            }
        }
    }
}
