// One SafeHandle per native object. A cloth handle holds a reference on its world handle, so
// the world (drape_world_destroy frees every cloth still in it) is destroyed only after its last
// cloth, even when both are left to the finalizer. Release takes the world's lock: a finalizer
// never destroys a cloth while another thread steps the world.
using System;
using Microsoft.Win32.SafeHandles;

namespace Drape.Core
{
    /// <summary>Owns a drape_world*.</summary>
    public sealed class WorldHandle : SafeHandleZeroOrMinusOneIsInvalid
    {
        /// <summary>Serialises every call on this world and its cloths (drape.h: one thread at a time).</summary>
        internal readonly object Sync = new object();

        public WorldHandle() : base(true) { }

        internal WorldHandle(IntPtr world) : base(true)
        {
            SetHandle(world);
        }

        protected override bool ReleaseHandle()
        {
            lock (Sync)
            {
                return NativeMethods.drape_world_destroy(handle) == Status.Ok;
            }
        }
    }

    /// <summary>Owns a drape_cloth*; keeps its world alive.</summary>
    public sealed class ClothHandle : SafeHandleZeroOrMinusOneIsInvalid
    {
        private readonly WorldHandle _world;
        private bool _worldRefAdded;

        public ClothHandle() : base(true) { }

        internal ClothHandle(WorldHandle world, IntPtr cloth) : base(true)
        {
            _world = world;
            // Taken before the handle is set, so ReleaseHandle always has a reference to give back.
            world.DangerousAddRef(ref _worldRefAdded);
            SetHandle(cloth);
        }

        internal WorldHandle World => _world;

        protected override bool ReleaseHandle()
        {
            if (_world == null) return NativeMethods.drape_cloth_destroy(handle) == Status.Ok;
            bool ok;
            lock (_world.Sync)
            {
                ok = NativeMethods.drape_cloth_destroy(handle) == Status.Ok;
            }
            if (_worldRefAdded) _world.DangerousRelease();
            return ok;
        }
    }
}
