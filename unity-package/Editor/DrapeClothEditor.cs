using Drape.Core;
using UnityEditor;
using UnityEngine;
using UnityEngine.Rendering;

namespace Drape.Editing
{
    /// <summary>Inspector for <see cref="DrapeCloth"/>: the serialized fields with stiffness sliders in
    /// the active model's units and range, fabric presets, Scene-view pin picking (with Undo), warnings
    /// about settings that will misbehave, which backend runs and why, and live statistics in Play
    /// mode (repainted four times a second, not every frame).</summary>
    [CustomEditor(typeof(DrapeCloth))]
    [CanEditMultipleObjects]
    public sealed class DrapeClothEditor : UnityEditor.Editor
    {
        private static readonly string[] s_customDrawn =
            { "m_Script", "_structuralStiffness", "_shearStiffness", "_bendStiffness", "_pbdStiffness" };
        private static readonly GUIContent s_structural = new GUIContent("Structural Stiffness", "Stretch springs/constraints.");
        private static readonly GUIContent s_shear = new GUIContent("Shear Stiffness", "Shear springs (grid diagonals).");
        private static readonly GUIContent s_bend = new GUIContent("Bend Stiffness", "Bend springs (two apart / across an edge).");
        private const double RepaintInterval = 0.25;

        private double _nextRepaint;
        private bool _editingPins;
        private Vector3[] _pickPositions;

        private void OnEnable() => EditorApplication.update += ThrottledRepaint;

        private void OnDisable() => EditorApplication.update -= ThrottledRepaint;

        public override bool RequiresConstantRepaint() => false;

        private void ThrottledRepaint()
        {
            if (!EditorApplication.isPlaying || EditorApplication.timeSinceStartup < _nextRepaint) return;
            _nextRepaint = EditorApplication.timeSinceStartup + RepaintInterval;
            Repaint();
        }

        public override void OnInspectorGUI()
        {
            serializedObject.Update();
            DrawPropertiesExcluding(serializedObject, s_customDrawn);
            DrawStiffness();
            serializedObject.ApplyModifiedProperties();

            var cloth = (DrapeCloth)target;
            DrawPresets(cloth);
            DrawPinEditing(cloth);
            foreach (string warning in Warnings(cloth))
                EditorGUILayout.HelpBox(warning, MessageType.Warning);
            string backend = BackendExplanation(cloth);
            if (backend.Length > 0) EditorGUILayout.HelpBox(backend, MessageType.Info);

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
            }
        }

        /// <summary>Stiffness sliders in the active model's range: N/m per spring (mass-spring, XPBD)
        /// or PBD's fraction per iteration; each model keeps its own values.</summary>
        private void DrawStiffness()
        {
            var model = (Model)(uint)serializedObject.FindProperty("_model").intValue;
            if (model == Model.Pbd)
            {
                SerializedProperty pbd = serializedObject.FindProperty("_pbdStiffness");
                EditorGUILayout.Slider(pbd.FindPropertyRelative("x"), 0f, 1f, s_structural);
                EditorGUILayout.Slider(pbd.FindPropertyRelative("y"), 0f, 1f, s_shear);
                EditorGUILayout.Slider(pbd.FindPropertyRelative("z"), 0f, 1f, s_bend);
                return;
            }
            float max = DrapeCloth.MaxStiffness(model) * 0.2f; // slider to 20000 N/m; scripts may go to the limit
            EditorGUILayout.Slider(serializedObject.FindProperty("_structuralStiffness"), 0f, max, s_structural);
            EditorGUILayout.Slider(serializedObject.FindProperty("_shearStiffness"), 0f, max, s_shear);
            EditorGUILayout.Slider(serializedObject.FindProperty("_bendStiffness"), 0f, max, s_bend);
        }

        private void DrawPresets(DrapeCloth cloth)
        {
            EditorGUILayout.LabelField("Fabric presets (XPBD, physical units)", EditorStyles.boldLabel);
            foreach (DrapeFabric fabric in DrapeFabric.Presets)
            {
                if (!GUILayout.Button(fabric.Name + ": " + (fabric.ArealDensity * 1000f).ToString("F0") + " g/m^2, stretch " +
                                      fabric.StretchStiffness.ToString("F0") + " N/m")) continue;
                foreach (Object t in targets)
                {
                    var c = (DrapeCloth)t;
                    Undo.RecordObject(c, "Apply fabric " + fabric.Name);
                    c.ApplyFabric(fabric);
                    EditorUtility.SetDirty(c);
                }
            }
        }

        private void DrawPinEditing(DrapeCloth cloth)
        {
            string label = _editingPins ? "Stop editing pins" : "Edit pins in the Scene view (click vertices)";
            if (GUILayout.Button(label))
            {
                _editingPins = !_editingPins;
                _pickPositions = _editingPins ? cloth.AuthoringPositions() : null;
                SceneView.RepaintAll();
            }
            if (_editingPins)
                EditorGUILayout.HelpBox("Click a vertex to pin or unpin it (Undo works). Pin Mode becomes Vertex List; " +
                                        "the pins in use are kept as its starting list.", MessageType.Info);
        }

        /// <summary>Scene view: while editing pins, draws every vertex (pinned ones larger) and toggles
        /// the one nearest the click (within 12 px) in the Vertex List, with Undo.</summary>
        private void OnSceneGUI()
        {
            if (!_editingPins || _pickPositions == null) return;
            var cloth = (DrapeCloth)target;
            Event e = Event.current;
            int control = GUIUtility.GetControlID(FocusType.Passive);
            if (e.type == EventType.Layout) HandleUtility.AddDefaultControl(control);
            Matrix4x4 toWorld = cloth.transform.localToWorldMatrix;
            if (e.type == EventType.Repaint)
            {
                for (int i = 0; i < _pickPositions.Length; ++i)
                {
                    Vector3 p = toWorld.MultiplyPoint3x4(_pickPositions[i]);
                    bool pinned = IsPinned(cloth, i);
                    Handles.color = pinned ? new Color(1f, 0.4f, 0.1f) : new Color(0.6f, 0.8f, 1f, 0.6f);
                    Handles.DotHandleCap(0, p, Quaternion.identity, HandleUtility.GetHandleSize(p) * (pinned ? 0.04f : 0.02f), EventType.Repaint);
                }
                return;
            }
            if (e.type != EventType.MouseDown || e.button != 0 || e.alt) return;
            int nearest = -1;
            float best = 12f * 12f;
            for (int i = 0; i < _pickPositions.Length; ++i)
            {
                float d = (HandleUtility.WorldToGUIPoint(toWorld.MultiplyPoint3x4(_pickPositions[i])) - e.mousePosition).sqrMagnitude;
                if (d < best)
                {
                    best = d;
                    nearest = i;
                }
            }
            if (nearest < 0) return;
            Undo.RecordObject(cloth, "Toggle Drape pin");
            if (cloth.PinMode != DrapePinMode.VertexList)
            {
                cloth.SetPinnedVertices(CurrentPins(cloth));
                cloth.PinMode = DrapePinMode.VertexList;
            }
            cloth.TogglePinnedVertex(nearest);
            EditorUtility.SetDirty(cloth);
            e.Use();
        }

        private static bool IsPinned(DrapeCloth cloth, int vertex)
        {
            if (cloth.PinMode == DrapePinMode.VertexList)
            {
                for (int k = 0; k < cloth.PinnedVertices.Count; ++k)
                    if (cloth.PinnedVertices[k] == vertex) return true;
                return false;
            }
            System.ReadOnlySpan<uint> pins = cloth.ActivePins;
            for (int k = 0; k < pins.Length; ++k)
                if (pins[k] == (uint)vertex) return true;
            return false;
        }

        private static System.Collections.Generic.List<int> CurrentPins(DrapeCloth cloth)
        {
            var list = new System.Collections.Generic.List<int>();
            System.ReadOnlySpan<uint> pins = cloth.ActivePins;
            for (int k = 0; k < pins.Length; ++k) list.Add((int)pins[k]);
            return list;
        }

        /// <summary>Which backend runs (or would run here) and why not the GPU; empty for an explicit CPU choice.</summary>
        private static string BackendExplanation(DrapeCloth cloth)
        {
            if (cloth.Backend == DrapeBackendChoice.Cpu || cloth.Backend == DrapeBackendChoice.CpuThreaded) return "";
            if (Application.isPlaying && cloth.NativeCloth != null)
                return cloth.BackendReason.Length > 0 ? cloth.BackendReason : "Running on the GPU (OpenGL ES 3).";
            string problem = DrapeCloth.ExplainGpu(cloth.SimulationSpace, SystemInfo.graphicsDeviceType, true);
            return problem == null
                ? "Backend " + cloth.Backend + ": the GPU (OpenGL ES 3) will run this cloth here."
                : "Backend " + cloth.Backend + ": in this editor the CPU runs the cloth: " + problem +
                  " On a device whose active graphics API is OpenGL ES 3 the GPU runs it.";
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
