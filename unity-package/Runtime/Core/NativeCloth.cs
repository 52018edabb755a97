using System;

namespace Drape.Core
{
    /// <summary>One simulated cloth (drape_cloth) in a <see cref="NativeWorld"/>. Every method forwards to
    /// one C call; failures throw <see cref="DrapeException"/> with the native message. Step, Read,
    /// SetParams, SetPins and GetStats allocate nothing on success (steady state).</summary>
    public sealed class NativeCloth : IDisposable
    {
        private readonly ClothHandle _handle;
        private readonly object _sync;

        private NativeCloth(NativeWorld world, IntPtr cloth)
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
        public static NativeCloth CreateGrid(NativeWorld world, ClothDesc desc, GridDesc grid)
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
            return new NativeCloth(world, cloth);
        }

        /// <summary>Creates a cloth from a triangle mesh: positions (xyz per vertex) and a triangle
        /// list. The native side copies both.</summary>
        public static unsafe NativeCloth CreateMesh(NativeWorld world, ClothDesc desc, ReadOnlySpan<float> positions,
                                              ReadOnlySpan<int> indices, float weldDistance)
        {
            if (world == null) throw new ArgumentNullException(nameof(world));
            desc.StructSize = SizeOf.ClothDesc;
            IntPtr cloth;
            fixed (float* p = positions)
            fixed (int* i = indices)
            {
                var mesh = MeshDesc.Pinned(p, positions.Length, i, indices.Length, weldDistance);
                lock (world.Handle.Sync)
                {
                    NativeMethods.Check(NativeMethods.drape_cloth_create_mesh(world.Handle, ref desc, ref mesh,
                                                                              out cloth),
                                        "drape_cloth_create_mesh");
                }
            }
            return new NativeCloth(world, cloth);
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

        /// <summary>Most colliders one cloth takes (DRAPE_MAX_COLLIDERS).</summary>
        public const int MaxColliders = 64;

        /// <summary>Returned by <see cref="Grab"/> when no vertex was within the pick radius (UINT32_MAX).</summary>
        public const uint NoVertex = uint.MaxValue;

        /// <summary>Returned by <see cref="Grab"/> on a GPU (GLES) cloth (DRAPE_GRAB_ON_GPU): the vertex is
        /// picked on the GPU at the next step and is not known here. The touch id holds the grab until
        /// released, whether or not a vertex was within the radius (<see cref="GrabMove"/> then moves nothing).</summary>
        public const uint GrabOnGpu = 0xFFFFFFFEu;

        /// <summary>Replaces the cloth's colliders (call once per frame with the current transforms;
        /// empty removes them all). StructSize of each element is set here. A collider keeps its Id
        /// from call to call so that its motion is swept across the next step. Allocates nothing.</summary>
        public unsafe void SetColliders(Span<ColliderDesc> colliders)
        {
            uint size = SizeOf.ColliderDesc;
            for (int k = 0; k < colliders.Length; ++k) colliders[k].StructSize = size;
            fixed (ColliderDesc* p = colliders)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_set_colliders(_handle, p, (uint)colliders.Length);
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_colliders");
                }
            }
        }

        /// <summary>Lets the cloth fall asleep when its fastest particle stays below
        /// <paramref name="threshold"/> m/s for <paramref name="time"/> s (threshold 0: never). An
        /// asleep cloth's steps do no work; any change (colliders, pins, drag, owner, parameters,
        /// positions) wakes it. See <see cref="Stats.Sleeping"/>.</summary>
        public void SetSleep(float threshold, float time)
        {
            var desc = new SleepDesc { StructSize = SizeOf.SleepDesc, Threshold = threshold, Time = time };
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_set_sleep(_handle, ref desc);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_sleep");
            }
        }

        /// <summary>Wakes the cloth (it may fall asleep again after the sleep time of stillness).</summary>
        public void Wake()
        {
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_wake(_handle);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_wake");
            }
        }

        /// <summary>Drags the cloth with up to 16 touches seen through <paramref name="view"/> (paper
        /// eq. 9); the displacement is spread over the next step. Calls before a step add up.
        /// StructSize of the view and of each touch is set here. Allocates nothing.</summary>
        public unsafe void Drag(in View view, Span<TouchPoint> touches)
        {
            View v = view;
            v.StructSize = SizeOf.View;
            uint size = SizeOf.TouchPoint;
            for (int k = 0; k < touches.Length; ++k) touches[k].StructSize = size;
            fixed (TouchPoint* p = touches)
            {
                lock (_sync)
                {
                    Status s = NativeMethods.drape_cloth_drag(_handle, ref v, p, (uint)touches.Length);
                    if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_drag");
                }
            }
        }

        /// <summary>Drags the cloth with one touch: the finger was at <paramref name="position"/> (px,
        /// origin bottom-left of the viewport) and moved by <paramref name="motion"/> px.</summary>
        public unsafe void Drag(in View view, Float2 position, Float2 motion, float amplitude = 200f, float sigma = 300f)
        {
            TouchPoint* touch = stackalloc TouchPoint[1];
            touch[0] = new TouchPoint { Position = position, Motion = motion, Amplitude = amplitude, Sigma = sigma };
            Drag(view, new Span<TouchPoint>(touch, 1));
        }

        /// <summary>Pick-and-hold: grabs the free vertex nearest on screen to <paramref name="position"/>
        /// (px) within <paramref name="pickRadius"/> px and holds it at its depth under the finger.
        /// Returns the vertex, or <see cref="NoVertex"/> if none was within the radius (a GPU cloth:
        /// <see cref="GrabOnGpu"/>). At most 16 grabs at once; grabbing with a live
        /// <paramref name="touchId"/> releases the old one first.</summary>
        public uint Grab(in View view, uint touchId, Float2 position, float pickRadius)
        {
            View v = view;
            v.StructSize = SizeOf.View;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_grab(_handle, ref v, touchId, ref position, pickRadius, out uint vertex);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_grab");
                return vertex;
            }
        }

        /// <summary>Moves the vertex held by <paramref name="touchId"/> under the finger at
        /// <paramref name="position"/> (px); the move is spread over the next step.</summary>
        public void GrabMove(in View view, uint touchId, Float2 position)
        {
            View v = view;
            v.StructSize = SizeOf.View;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_grab_move(_handle, ref v, touchId, ref position);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_grab_move");
            }
        }

        /// <summary>Releases a grab (unknown ids are fine): the vertex keeps its velocity.</summary>
        public void GrabRelease(uint touchId)
        {
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_grab_release(_handle, touchId);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_grab_release");
            }
        }

        /// <summary>Sets this frame's owner transform (in simulation space). The first call only
        /// records it; later calls move pins (rigidly) and free vertices (by 1 - inertia) by the
        /// change. StructSize is set here. Allocates nothing.</summary>
        public void SetOwner(Owner owner)
        {
            owner.StructSize = SizeOf.Owner;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_set_owner(_handle, ref owner);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_owner");
            }
        }

        /// <summary>Turns self-collision on or off (see <see cref="SelfCollisionDesc"/>); takes effect at
        /// the next step and wakes a sleeping cloth. StructSize is set here. Bad input (Enabled not 0/1,
        /// thickness or friction out of range or not finite) throws and leaves the setting unchanged;
        /// enabling it on a GLES cloth throws with ErrorBackendUnavailable (turning it off is accepted).
        /// Allocates nothing.</summary>
        public void SetSelfCollision(SelfCollisionDesc desc)
        {
            desc.StructSize = SizeOf.SelfCollisionDesc;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_set_self_collision(_handle, ref desc);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_self_collision");
            }
        }

        /// <summary>Turns self-collision on or off: non-neighbour particles are kept
        /// <paramref name="thickness"/> m apart (&gt; 0 when enabled; the particle spacing is a good
        /// value), with Coulomb <paramref name="friction"/> in [0, 10] between layers.</summary>
        public void SetSelfCollision(bool enabled, float thickness, float friction = 0f) =>
            SetSelfCollision(new SelfCollisionDesc(enabled, thickness, friction));

        /// <summary>The current self-collision setting. A new cloth: off, thickness 0, friction 0.</summary>
        public SelfCollisionDesc GetSelfCollision()
        {
            lock (_sync)
            {
                var desc = new SelfCollisionDesc { StructSize = SizeOf.SelfCollisionDesc };
                Status s = NativeMethods.drape_cloth_get_self_collision(_handle, ref desc);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_get_self_collision");
                return desc;
            }
        }

        /// <summary>GLES cloths: after every step the GPU writes positions and/or normals of every vertex
        /// into GL buffer <paramref name="glBuffer"/> (Unity: the name Mesh.GetNativeVertexBufferPtr
        /// returns on OpenGL ES), laid out by <paramref name="layout"/>; 0 stops writing. In Unity the
        /// GL work runs at the render event (<see cref="NativeWorld.GetUnityRenderEvent"/>).</summary>
        public void SetOutputBuffer(uint glBuffer, VertexLayout layout)
        {
            layout.StructSize = SizeOf.VertexLayout;
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_set_output_buffer(_handle, glBuffer, ref layout);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_set_output_buffer");
            }
        }

        /// <summary>GLES cloths: copies the GPU state to the CPU copy (Unity: at the next render event).
        /// No-op for CPU cloths.</summary>
        public void Readback()
        {
            lock (_sync)
            {
                Status s = NativeMethods.drape_cloth_readback(_handle);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_cloth_readback");
            }
        }

        public void Dispose()
        {
            _handle.Dispose();
        }
    }
}
