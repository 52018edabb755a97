using System;

namespace Drape.Core
{
    /// <summary>One simulated cloth (drape_cloth) in a <see cref="World"/>. Every method forwards to
    /// one C call; failures throw <see cref="DrapeException"/> with the native message. Step, Read,
    /// SetParams, SetPins and GetStats allocate nothing on success (steady state).</summary>
    public sealed class Cloth : IDisposable
    {
        private readonly ClothHandle _handle;
        private readonly object _sync;

        private Cloth(World world, IntPtr cloth)
        {
            _handle = new ClothHandle(world.Handle, cloth);
            _sync = world.Handle.Sync;
            NativeMethods.Check(NativeMethods.drape_cloth_get_info(_handle, out ClothInfo info), "drape_cloth_get_info");
            Info = info;
        }

        public ClothHandle Handle => _handle;
        public bool IsDisposed => _handle.IsClosed;

        /// <summary>Topology counts, read once at creation (they never change).</summary>
        public ClothInfo Info { get; }

        /// <summary>Caller vertices (before welding): the length every per-vertex array must have.</summary>
        public int VertexCount => (int)Info.VertexCount;

        /// <summary>Creates a rectangular grid cloth. StructSize fields are set here.</summary>
        public static Cloth CreateGrid(World world, ClothDesc desc, GridDesc grid)
        {
            if (world == null) throw new ArgumentNullException(nameof(world));
            desc.StructSize = SizeOf.ClothDesc;
            grid.StructSize = SizeOf.GridDesc;
            IntPtr cloth;
            lock (world.Handle.Sync)
            {
                NativeMethods.Check(NativeMethods.drape_cloth_create_grid(world.Handle, ref desc, ref grid, out cloth),
                                    "drape_cloth_create_grid");
            }
            return new Cloth(world, cloth);
        }

        /// <summary>Creates a cloth from a triangle mesh: positions (xyz per vertex) and a triangle
        /// list. The native side copies both.</summary>
        public static unsafe Cloth CreateMesh(World world, ClothDesc desc, ReadOnlySpan<float> positions,
                                              ReadOnlySpan<int> indices, float weldDistance)
        {
            if (world == null) throw new ArgumentNullException(nameof(world));
            if (positions.Length % 3 != 0)
                throw new ArgumentException("positions holds xyz triples; length " + positions.Length +
                                            " is not a multiple of 3", nameof(positions));
            desc.StructSize = SizeOf.ClothDesc;
            IntPtr cloth;
            fixed (float* p = positions)
            fixed (int* i = indices)
            {
                var mesh = new MeshDesc
                {
                    StructSize = SizeOf.MeshDesc,
                    VertexCount = (uint)(positions.Length / 3),
                    Positions = (IntPtr)p,
                    IndexCount = (uint)indices.Length,
                    // Unity's int indices are reinterpreted as uint32: a negative one becomes huge and
                    // is refused natively with ErrorIndexOutOfRange.
                    Indices = (IntPtr)i,
                    WeldDistance = weldDistance,
                };
                lock (world.Handle.Sync)
                {
                    NativeMethods.Check(NativeMethods.drape_cloth_create_mesh(world.Handle, ref desc, ref mesh,
                                                                              out cloth),
                                        "drape_cloth_create_mesh");
                }
            }
            return new Cloth(world, cloth);
        }

        /// <summary>Sets every parameter (StructSize is set here). Takes effect at the next step.</summary>
        public void SetParams(Params parameters)
        {
            parameters.StructSize = SizeOf.Params;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_set_params(_handle, ref parameters);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_params");
            }
        }

        public Params GetParams()
        {
            lock (_sync)
            {
                NativeMethods.Check(NativeMethods.drape_cloth_get_params(_handle, out Params p), "drape_cloth_get_params");
                return p;
            }
        }

        /// <summary>Per vertex, &gt;= 0 and finite; 0 pins the vertex where it is.</summary>
        public unsafe void SetInverseMasses(ReadOnlySpan<float> inverseMasses)
        {
            fixed (float* p = inverseMasses)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_set_inverse_masses(_handle, p, (uint)inverseMasses.Length);
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_inverse_masses");
                }
            }
        }

        /// <summary>Pins (or moves already pinned) vertices. StructSize of each pin is set here.</summary>
        public unsafe void SetPins(Span<Pin> pins)
        {
            uint size = SizeOf.Pin;
            for (int k = 0; k < pins.Length; ++k) pins[k].StructSize = size;
            fixed (Pin* p = pins)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_set_pins(_handle, p, (uint)pins.Length);
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_pins");
                }
            }
        }

        /// <summary>Releases pins: the vertices get back the inverse mass they had before pinning.</summary>
        public unsafe void ReleasePins(ReadOnlySpan<uint> vertices)
        {
            fixed (uint* p = vertices)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_release_pins(_handle, p, (uint)vertices.Length);
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_release_pins");
                }
            }
        }

        /// <summary>Teleports every vertex (xyz per vertex) and zeroes velocities.</summary>
        public unsafe void SetPositions(ReadOnlySpan<float> positions)
        {
            fixed (float* p = positions)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_set_positions(_handle, p, (uint)(positions.Length / 3));
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_positions");
                }
            }
        }

        /// <summary>Sets every vertex velocity (xyz per vertex, m/s).</summary>
        public unsafe void SetVelocities(ReadOnlySpan<float> velocities)
        {
            fixed (float* p = velocities)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_set_velocities(_handle, p, (uint)(velocities.Length / 3));
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_velocities");
                }
            }
        }

        /// <summary>Steps this cloth alone by dt seconds (0 &lt; dt &lt;= 1). ErrorUnstable: the state
        /// was rolled back to the last good one.</summary>
        public void Step(float dt)
        {
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_step(_handle, dt);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_step");
            }
        }

        /// <summary>Writes positions and/or normals of every vertex into dst (dstSize bytes), laid out
        /// by <paramref name="layout"/>. This is the path Unity's Mesh.SetVertexBufferData uses: dst is
        /// a NativeArray's unsafe pointer, so no managed copy is made.</summary>
        public unsafe void Read(VertexLayout layout, void* dst, long dstSize)
        {
            if (dstSize < 0) throw new ArgumentOutOfRangeException(nameof(dstSize));
            layout.StructSize = SizeOf.VertexLayout;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_read(_handle, ref layout, dst, (UIntPtr)(ulong)dstSize);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_read");
            }
        }

        /// <summary>Reads positions, tightly packed (xyz per vertex), into a managed buffer.</summary>
        public unsafe void ReadPositions(Span<float> xyz)
        {
            fixed (float* p = xyz)
            {
                Read(new VertexLayout(12, 0, -1), p, (long)xyz.Length * sizeof(float));
            }
        }

        /// <summary>Reads normals, tightly packed (xyz per vertex), into a managed buffer.</summary>
        public unsafe void ReadNormals(Span<float> xyz)
        {
            fixed (float* p = xyz)
            {
                Read(new VertexLayout(12, -1, 0), p, (long)xyz.Length * sizeof(float));
            }
        }

        /// <summary>Measurements of the last step.</summary>
        public Stats GetStats()
        {
            lock (_sync)
            {
                // drape_cloth_get_stats honours out_stats->struct_size (the struct grew after ABI 1).
                var stats = new Stats { StructSize = SizeOf.Stats };
                Status s = NativeMethods.drape_cloth_get_stats(_handle, ref stats);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_get_stats");
                return stats;
            }
        }

        public void Dispose()
        {
            _handle.Dispose();
        }
    }
}
