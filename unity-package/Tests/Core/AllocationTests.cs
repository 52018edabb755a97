using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>The per-frame path (set params, pin, step, read, stats) allocates no managed memory.</summary>
    public class AllocationTests
    {
        [Test]
        public unsafe void SteadyStateFrameAllocatesNothing()
        {
            // The counter must work on this runtime, or the test below would pass vacuously.
            long probeBefore = GC.GetAllocatedBytesForCurrentThread();
            object probe = new byte[1024];
            long probeAfter = GC.GetAllocatedBytesForCurrentThread();
            GC.KeepAlive(probe);
            if (probeAfter - probeBefore < 1024)
                Assert.Ignore("GC.GetAllocatedBytesForCurrentThread does not count allocations on this runtime");

            using (var world = new World(1))
            using (Cloth cloth = TestScenes.HorizontalGrid(world, 16, 16))
            {
                var pins = new Pin[2];
                var layout = new VertexLayout(24, 0, 12); // position + normal, like a Unity vertex stream
                byte[] vertices = new byte[24 * cloth.VertexCount];
                Params p = World.DefaultParams();

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
    }
}
