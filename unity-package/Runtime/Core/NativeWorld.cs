using System;

namespace Drape.Core
{
    /// <summary>A set of cloths stepped together (drape_world). Dispose it when done; disposing
    /// with cloths still alive defers the native destroy until the last cloth is disposed.</summary>
    public sealed class NativeWorld : IDisposable
    {
        /// <summary>The drape.h DRAPE_ABI_VERSION these bindings were written against.</summary>
        public const uint ExpectedAbiVersion = 1;

        private readonly WorldHandle _handle;

        /// <param name="threadCount">Workers for CpuThreaded including the caller; 0 = hardware count.</param>
        public NativeWorld(uint threadCount = 0)
        {
            CheckAbi();
            var desc = new WorldDesc { StructSize = SizeOf.WorldDesc, ThreadCount = threadCount };
            NativeMethods.Check(NativeMethods.drape_world_create(ref desc, out IntPtr world), "drape_world_create");
            _handle = new WorldHandle(world);
        }

        public WorldHandle Handle => _handle;
        public bool IsDisposed => _handle.IsClosed;

        /// <summary>The native library's DRAPE_ABI_VERSION.</summary>
        public static uint AbiVersion => NativeMethods.drape_abi_version();

        /// <summary>Throws if the loaded native library is not the ABI these bindings expect.</summary>
        public static void CheckAbi()
        {
            uint abi = NativeMethods.drape_abi_version();
            if (abi != ExpectedAbiVersion)
                throw new DrapeException(Status.ErrorStructSize, "drape_abi_version",
                                         "native library has ABI " + abi + ", the C# bindings expect " +
                                             ExpectedAbiVersion);
        }

        /// <summary>True if cloths with this backend can be created now (on this thread).</summary>
        public static bool IsBackendAvailable(Backend backend)
        {
            NativeMethods.Check(NativeMethods.drape_backend_available(backend, out uint available),
                                "drape_backend_available");
            return available != 0;
        }

        /// <summary>The library's default parameters (StructSize set).</summary>
        public static Params DefaultParams()
        {
            NativeMethods.Check(NativeMethods.drape_params_default(out Params p), "drape_params_default");
            p.StructSize = SizeOf.Params;
            return p;
        }

        /// <summary>The native render-event callback for Unity's GL.IssuePluginEvent /
        /// CommandBuffer.IssuePluginEvent, and the event id to pass with it. The event runs every GLES
        /// cloth's recorded GL work on Unity's render thread. Fetch once and keep.</summary>
        public static void GetUnityRenderEvent(out IntPtr callback, out int eventId)
        {
            NativeMethods.Check(NativeMethods.drape_unity_render_event(out callback, out eventId),
                                "drape_unity_render_event");
        }

        /// <summary>The GL context of the GLES cloths is gone: every GLES cloth forgets its GL objects
        /// (without deleting them) and rebuilds them on its next GL work in a new context, resuming
        /// from its CPU copy (the state of its last readback). See drape_gles_context_lost.</summary>
        public static void GlesContextLost()
        {
            NativeMethods.Check(NativeMethods.drape_gles_context_lost(), "drape_gles_context_lost");
        }

        /// <summary>Steps every cloth of the world by dt seconds (0 &lt; dt &lt;= 1). Throws on the
        /// first failure; the other cloths were still stepped. Allocates nothing unless it throws.</summary>
        public void Step(float dt)
        {
            Status s;
            lock (_handle.Sync)
            {
                s = NativeMethods.drape_world_step(_handle, dt);
                if (s != Status.Ok) NativeMethods.Check(s, "drape_world_step");
            }
        }

        public void Dispose()
        {
            _handle.Dispose();
        }
    }
}
