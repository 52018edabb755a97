using System;
using Drape.Core;
using UnityEngine;

namespace Drape
{
    /// <summary>The one native world every <see cref="DrapeCloth"/> lives in (its CpuThreaded
    /// worker pool is shared). Created by the first enabled cloth, disposed with the last one, and
    /// reset before a scene loads when domain reload is off.</summary>
    public static class DrapeSimulation
    {
        private static NativeWorld s_world;
        private static int s_users;
        private static IntPtr s_renderCallback;
        private static int s_renderEventId;
        private static int s_renderEventFrame = -1;

        /// <summary>Issues the native render event (drape_unity_render_event) through
        /// GL.IssuePluginEvent, once per frame unless <paramref name="force"/>: it runs every GLES
        /// cloth's recorded GL work (steps, output into the mesh buffers, releases) on the render
        /// thread. The callback is fetched once.</summary>
        public static void IssueRenderEvent(bool force = false)
        {
            int frame = Time.frameCount;
            if (!force && frame == s_renderEventFrame) return;
            if (s_renderCallback == IntPtr.Zero)
            {
                NativeWorld.GetUnityRenderEvent(out s_renderCallback, out s_renderEventId);
                if (s_renderCallback == IntPtr.Zero) return; // GL.IssuePluginEvent throws on a null callback
            }
            s_renderEventFrame = frame;
            GL.IssuePluginEvent(s_renderCallback, s_renderEventId);
        }

        /// <summary>Takes a reference on the shared world (creating it if needed).</summary>
        public static NativeWorld Acquire()
        {
            if (s_world == null || s_world.IsDisposed) s_world = new NativeWorld(0);
            s_users++;
            return s_world;
        }

        /// <summary>Gives back a reference taken by <see cref="Acquire"/>.</summary>
        public static void Release()
        {
            if (s_users > 0) s_users--;
            if (s_users == 0 && s_world != null)
            {
                s_world.Dispose(); // native destroy waits for any cloth handle still open
                s_world = null;
            }
        }

        [RuntimeInitializeOnLoadMethod(RuntimeInitializeLoadType.SubsystemRegistration)]
        private static void ResetStatics()
        {
            // With "Enter Play Mode Options" and no domain reload, statics survive: start clean.
            if (s_world != null) s_world.Dispose();
            s_world = null;
            s_users = 0;
            s_renderEventFrame = -1; // the callback pointer stays valid: native libraries are not unloaded
        }

#if UNITY_EDITOR
        [UnityEditor.InitializeOnLoadMethod]
        private static void HookAssemblyReload()
        {
            // Native memory survives a domain reload; free it before the managed side goes away.
            UnityEditor.AssemblyReloadEvents.beforeAssemblyReload += ResetStatics;
        }
#endif
    }
}
