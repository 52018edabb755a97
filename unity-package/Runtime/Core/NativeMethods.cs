// Every P/Invoke of Drape in one place. Keep in sync with plugin-native/include/drape/drape.h.
// The library name, chosen here only:
//  - "__Internal" where IL2CPP compiles the native sources (unity-package/Plugins/Source, enabled for
//    Android and iOS in its .meta) into the player: iOS players, and Android players built with
//    IL2CPP unless the project defines DRAPE_ANDROID_PREBUILT (then the prebuilt arm64 .so is used
//    and the sources are excluded by their defineConstraints);
//  - "drape" everywhere else (libdrape.so / drape.dll / libdrape.dylib): the Editor, desktop
//    players, Android with Mono or DRAPE_ANDROID_PREBUILT. tvOS and WebGL compile no Drape sources,
//    so a call there fails with DllNotFoundException rather than breaking the player's link.
using System;
using System.Runtime.InteropServices;

namespace Drape.Core
{
    internal static class NativeMethods
    {
#if !UNITY_EDITOR && (UNITY_IOS || (UNITY_ANDROID && ENABLE_IL2CPP && !DRAPE_ANDROID_PREBUILT))
        internal const string Library = "__Internal";
#else
        internal const string Library = "drape";
#endif
        private const CallingConvention Cdecl = CallingConvention.Cdecl;

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern uint drape_abi_version();

        /// <summary>const char*, thread-local, never NULL; read with <see cref="LastError"/>.</summary>
        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern IntPtr drape_last_error();

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_backend_available(Backend backend, out uint available);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_params_default(out Params parameters);

        // Exactly one of grid and mesh: the overloads pass the other as IntPtr.Zero.
        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_estimate_stability(ref ClothDesc desc, ref GridDesc grid, IntPtr mesh,
                                                               ref Params parameters, float dt,
                                                               ref StabilityEstimate estimate);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_estimate_stability(ref ClothDesc desc, IntPtr grid, ref MeshDesc mesh,
                                                               ref Params parameters, float dt,
                                                               ref StabilityEstimate estimate);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_world_create(ref WorldDesc desc, out IntPtr world);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_world_destroy(IntPtr world);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_world_step(WorldHandle world, float dt);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_create_grid(WorldHandle world, ref ClothDesc desc, ref GridDesc grid,
                                                              out IntPtr cloth);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_create_mesh(WorldHandle world, ref ClothDesc desc, ref MeshDesc mesh,
                                                              out IntPtr cloth);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_destroy(IntPtr cloth);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_set_params(ClothHandle cloth, ref Params parameters);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_get_params(ClothHandle cloth, out Params parameters);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_set_inverse_masses(ClothHandle cloth, float* inverseMasses,
                                                                            uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_set_pins(ClothHandle cloth, Pin* pins, uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_release_pins(ClothHandle cloth, uint* vertices, uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_set_positions(ClothHandle cloth, float* positions, uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_set_velocities(ClothHandle cloth, float* velocities,
                                                                        uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_step(ClothHandle cloth, float dt);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_read(ClothHandle cloth, ref VertexLayout layout, void* dst,
                                                              UIntPtr dstSize);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_get_info(ClothHandle cloth, out ClothInfo info);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_get_stats(ClothHandle cloth, ref Stats stats);

        // ---- GLES backend and Unity render event ----

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_set_output_buffer(ClothHandle cloth, uint glBuffer, ref VertexLayout layout);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_readback(ClothHandle cloth);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_gles_context_lost();

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_unity_render_event(out IntPtr callback, out int eventId);

        // ---- Colliders, sleeping, touch drag, owner transform ----

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_set_colliders(ClothHandle cloth, ColliderDesc* colliders, uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_set_sleep(ClothHandle cloth, ref SleepDesc desc);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_wake(ClothHandle cloth);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_touch_default(out TouchPoint touch);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern unsafe Status drape_cloth_drag(ClothHandle cloth, ref View view, TouchPoint* touches, uint count);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_grab(ClothHandle cloth, ref View view, uint touchId, ref Float2 position,
                                                       float pickRadius, out uint vertex);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_grab_move(ClothHandle cloth, ref View view, uint touchId,
                                                            ref Float2 position);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_grab_release(ClothHandle cloth, uint touchId);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_owner_default(out Owner owner);

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_set_owner(ClothHandle cloth, ref Owner owner);

        // ---- Self-collision ----

        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_set_self_collision(ClothHandle cloth, ref SelfCollisionDesc desc);

        /// <summary>desc.StructSize must be set (the native side refuses 0).</summary>
        [DllImport(Library, CallingConvention = Cdecl)]
        internal static extern Status drape_cloth_get_self_collision(ClothHandle cloth, ref SelfCollisionDesc desc);

        /// <summary>The native message for the last failure on this thread ("" if none).</summary>
        internal static string LastError()
        {
            IntPtr p = drape_last_error();
            return p == IntPtr.Zero ? string.Empty : Marshal.PtrToStringAnsi(p) ?? string.Empty;
        }

        /// <summary>Throws a <see cref="DrapeException"/> carrying drape_last_error() unless OK.
        /// Call it right after the native call, on the same thread (the message is thread-local).</summary>
        internal static void Check(Status status, string function)
        {
            if (status != Status.Ok) throw new DrapeException(status, function, LastError());
        }
    }
}
