using Drape.Core;
using UnityEditor;
using UnityEngine;
using UnityEngine.Rendering;

namespace Drape.Editing
{
    /// <summary>Inspector for <see cref="DrapeCloth"/>: the serialized fields plus warnings about
    /// settings that will misbehave, and live statistics in Play mode.</summary>
    [CustomEditor(typeof(DrapeCloth))]
    [CanEditMultipleObjects]
    public sealed class DrapeClothEditor : UnityEditor.Editor
    {
        public override void OnInspectorGUI()
        {
            serializedObject.Update();
            DrawDefaultInspector();
            serializedObject.ApplyModifiedProperties();

            var cloth = (DrapeCloth)target;
            foreach (string warning in Warnings(cloth))
                EditorGUILayout.HelpBox(warning, MessageType.Warning);

            if (Application.isPlaying && cloth.NativeCloth != null)
            {
                Stats s = cloth.LastStats;
                EditorGUILayout.LabelField("Live", EditorStyles.boldLabel);
                EditorGUILayout.LabelField("Backend", cloth.ActiveBackend.ToString());
                EditorGUILayout.LabelField("Vertices / particles",
                                           cloth.NativeCloth.Info.VertexCount + " / " + cloth.NativeCloth.Info.ParticleCount);
                EditorGUILayout.LabelField("Step", s.StepMs.ToString("F3") + " ms, " + s.Substeps + " substeps x " +
                                                       s.Iterations + " iterations");
                EditorGUILayout.LabelField("Strain max / rms", (s.MaxStrain * 100f).ToString("F2") + " % / " +
                                                                   (s.RmsStrain * 100f).ToString("F2") + " %");
                EditorGUILayout.LabelField("Rolled-back steps", s.UnstableSteps.ToString());
                if (cloth.IsAsleep) EditorGUILayout.HelpBox("Asleep (came to rest; steps cost nothing until something changes).", MessageType.Info);
                Repaint();
            }
        }

        /// <summary>Problems with the current settings, in words (empty when none).</summary>
        public static System.Collections.Generic.List<string> Warnings(DrapeCloth cloth)
        {
            var list = new System.Collections.Generic.List<string>();
            float dt = cloth.StepMode == DrapeStepMode.FixedUpdate ? Time.fixedDeltaTime : cloth.FixedStep;
            int vertexCount = cloth.Source == DrapeShapeSource.GeneratedGrid ? cloth.Columns * cloth.Rows : MeshVertexCount(cloth);

            if (cloth.Model == Model.MassSpring && vertexCount > 0 && dt > 0f)
            {
                long needed = MassSpringSubstepsNeeded(cloth, dt);
                if (cloth.Substeps > 0 && cloth.Substeps < needed)
                    list.Add("Mass-spring at this stiffness and mass is unstable with " + cloth.Substeps +
                             " substeps at dt = " + dt.ToString("F4") + " s: it needs about " + needed +
                             " (h * omega_max < 2). Raise Substeps, set 0 (automatic), lower stiffness or use XPBD.");
                else if (cloth.Substeps == 0 && needed > 16)
                    list.Add("Mass-spring needs about " + needed + " substeps per step here (chosen automatically); " +
                             "XPBD gives the same stiffness at a fraction of the cost.");
            }
            if (cloth.Model == Model.Pbd &&
                (cloth.StructuralStiffness > 1f || cloth.ShearStiffness > 1f || cloth.BendStiffness > 1f))
                list.Add("PBD stiffness is a fraction per iteration in [0, 1]; values above 1 are refused by the native library.");
            if (cloth.Backend == DrapeBackendChoice.Gpu && cloth.SimulationSpace == DrapeSimulationSpace.World)
                list.Add("The GPU backend simulates in Local space only; with World space the cloth runs on the CPU.");
            else if (cloth.Backend == DrapeBackendChoice.Gpu && SystemInfo.graphicsDeviceType != GraphicsDeviceType.OpenGLES3)
                list.Add("The GPU backend needs the OpenGL ES 3 graphics API (this editor uses " + SystemInfo.graphicsDeviceType +
                         "); the cloth runs on the CPU here and on the GPU on a GLES3 device.");
            if (cloth.Colliders.Colliders.Count + cloth.Colliders.Planes.Count > NativeCloth.MaxColliders)
                list.Add("More than " + NativeCloth.MaxColliders + " colliders and planes are listed; the rest are ignored.");
            foreach (UnityEngine.Collider c in cloth.Colliders.Colliders)
                if (c != null && !(c is SphereCollider) && !(c is CapsuleCollider) && !(c is BoxCollider))
                    list.Add("Collider '" + c.name + "' is not a Sphere, Capsule or Box collider and is ignored.");
            if (cloth.SimulationSpace == DrapeSimulationSpace.Local && cloth.Colliders.Colliders.Count > 0)
            {
                Vector3 sc = cloth.transform.lossyScale;
                if (Mathf.Abs(sc.x - sc.y) > 1e-3f * Mathf.Abs(sc.x) || Mathf.Abs(sc.x - sc.z) > 1e-3f * Mathf.Abs(sc.x))
                    list.Add("Non-uniform scale on the cloth: colliders are sized by its mean scale in Local space.");
            }
            if (cloth.Backend == DrapeBackendChoice.Gpu && cloth.SleepThreshold > 0f)
                list.Add("Sleeping, grabs and World space are CPU-only; the GPU backend ignores the sleep threshold.");
            if (cloth.SelfCollision && cloth.Backend == DrapeBackendChoice.Gpu)
                list.Add("Self-collision is CPU-only: the GPU backend refuses it (Auto picks the CPU while it is on).");
            if (cloth.SelfCollision && cloth.Source == DrapeShapeSource.GeneratedGrid && cloth.Columns > 1 && cloth.Rows > 1)
            {
                float spacing = Mathf.Min(cloth.Size.x / (cloth.Columns - 1), cloth.Size.y / (cloth.Rows - 1));
                if (cloth.SelfCollisionThickness < 0.5f * spacing)
                    list.Add("Self-collision thickness " + cloth.SelfCollisionThickness.ToString("F3") + " m is under half the particle spacing (" +
                             spacing.ToString("F3") + " m): layers can slip through each other. Use about the spacing.");
                else if (cloth.SelfCollisionThickness > 3f * spacing)
                    list.Add("Self-collision thickness " + cloth.SelfCollisionThickness.ToString("F3") + " m is several particle spacings (" +
                             spacing.ToString("F3") + " m): folds will puff up. Use about the spacing.");
            }
            if (cloth.Source == DrapeShapeSource.MeshFilterMesh)
            {
                var filter = cloth.GetComponent<MeshFilter>();
                Mesh mesh = filter != null ? filter.sharedMesh : null;
                if (mesh == null) list.Add("No mesh on the MeshFilter: a grid will be generated.");
                else if (!mesh.isReadable) list.Add("Mesh '" + mesh.name + "' is not readable: enable Read/Write in its import settings.");
            }
            if (cloth.PinMode == DrapePinMode.None)
                list.Add("No pins: the cloth will fall freely.");
            return list;
        }

        /// <summary>Fewest substeps within the explicit stability bound, from the native library (the
        /// computation the cloth itself runs); 0 if the shape or settings are refused.</summary>
        private static long MassSpringSubstepsNeeded(DrapeCloth cloth, float dt)
        {
            Params p = NativeWorld.DefaultParams();
            p.Model = Model.MassSpring;
            p.Stiffness = new GroupValues(cloth.StructuralStiffness, cloth.ShearStiffness, cloth.BendStiffness);
            p.Damping = cloth.Damping;
            try
            {
                if (cloth.Source == DrapeShapeSource.GeneratedGrid)
                {
                    var grid = new GridDesc { Columns = (uint)cloth.Columns, Rows = (uint)cloth.Rows,
                                              Width = cloth.Size.x, Height = cloth.Size.y };
                    return Stability.ForGrid(grid, cloth.TotalMass, p, dt).StableSubsteps;
                }
                var filter = cloth.GetComponent<MeshFilter>();
                Mesh mesh = filter != null ? filter.sharedMesh : null;
                if (mesh == null) return 0;
                Vector3[] v = mesh.vertices;
                var flat = new float[v.Length * 3];
                for (int i = 0; i < v.Length; ++i)
                {
                    flat[3 * i] = v[i].x;
                    flat[3 * i + 1] = v[i].y;
                    flat[3 * i + 2] = v[i].z;
                }
                return Stability.ForMesh(flat, mesh.triangles, cloth.WeldDistance, cloth.TotalMass, p, dt).StableSubsteps;
            }
            catch (DrapeException)
            {
                return 0;  // invalid settings: other warnings and the inspector's ranges say why
            }
        }

        private static int MeshVertexCount(DrapeCloth cloth)
        {
            var filter = cloth.GetComponent<MeshFilter>();
            return filter != null && filter.sharedMesh != null ? filter.sharedMesh.vertexCount : 0;
        }
    }

    /// <summary>Scene-view gizmos: pinned vertices and the registered colliders.</summary>
    internal static class DrapeClothGizmos
    {
        [DrawGizmo(GizmoType.Selected | GizmoType.Active)]
        private static void Draw(DrapeCloth cloth, GizmoType type)
        {
            Vector3[] rest = cloth.RestPositions;
            Gizmos.color = new Color(1f, 0.4f, 0.1f);
            Gizmos.matrix = cloth.transform.localToWorldMatrix;
            if (rest != null)
            {
                System.ReadOnlySpan<uint> pins = cloth.ActivePins;
                for (int i = 0; i < pins.Length; ++i)
                    if (pins[i] < rest.Length) Gizmos.DrawSphere(rest[pins[i]], 0.01f);
            }
            Gizmos.matrix = Matrix4x4.identity;
            Gizmos.color = new Color(0.2f, 0.8f, 1f);
            foreach (UnityEngine.Collider c in cloth.Colliders.Colliders)
            {
                if (c == null) continue;
                Bounds b = c.bounds;
                Gizmos.DrawWireCube(b.center, b.size);
            }
            foreach (Transform plane in cloth.Colliders.Planes)
            {
                if (plane == null) continue;
                Gizmos.DrawLine(plane.position, plane.position + plane.up * 0.5f);
                Gizmos.matrix = Matrix4x4.TRS(plane.position, plane.rotation, Vector3.one);
                Gizmos.DrawWireCube(Vector3.zero, new Vector3(2f, 0f, 2f));
                Gizmos.matrix = Matrix4x4.identity;
            }
        }
    }
}
