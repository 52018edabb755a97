// COMPILE CHECK ONLY. Signature-only stand-in for UnityEditor 2022.3: no behaviour.
using System;
using UnityEngine;

namespace UnityEditor
{
    internal static class StandIn
    {
        public static Exception No => new NotSupportedException("Unity stand-in: compile check only");
    }

    public sealed class SerializedObject
    {
        public SerializedProperty FindProperty(string propertyPath) => throw StandIn.No;
        public void Update() => throw StandIn.No;
        public bool ApplyModifiedProperties() => throw StandIn.No;
    }

    public class Editor : ScriptableObject
    {
        public SerializedObject serializedObject => throw StandIn.No;
        public UnityEngine.Object target { get => throw StandIn.No; set => throw StandIn.No; }
        public UnityEngine.Object[] targets => throw StandIn.No;
        public virtual void OnInspectorGUI() => throw StandIn.No;
        public bool DrawDefaultInspector() => throw StandIn.No;
        public void Repaint() => throw StandIn.No;
        public virtual bool RequiresConstantRepaint() => throw StandIn.No;
        protected internal static void DrawPropertiesExcluding(SerializedObject obj, params string[] propertyToExclude) => throw StandIn.No;
    }

    [AttributeUsage(AttributeTargets.Class, AllowMultiple = false, Inherited = true)]
    public sealed class CustomEditor : Attribute { public CustomEditor(Type inspectedType) { } }

    [AttributeUsage(AttributeTargets.Class)]
    public sealed class CanEditMultipleObjects : Attribute { }

    public enum MessageType { None = 0, Info = 1, Warning = 2, Error = 3 }

    public class SerializedProperty
    {
        public int intValue { get => throw StandIn.No; set => throw StandIn.No; }
        public float floatValue { get => throw StandIn.No; set => throw StandIn.No; }
        public SerializedProperty FindPropertyRelative(string relativePropertyPath) => throw StandIn.No;
    }

    public sealed class EditorApplication
    {
        public delegate void CallbackFunction();
        public static CallbackFunction update;
        public static bool isPlaying { get => throw StandIn.No; set => throw StandIn.No; }
        public static double timeSinceStartup => throw StandIn.No;
    }

    public class Undo
    {
        public static void RecordObject(UnityEngine.Object objectToUndo, string name) => throw StandIn.No;
    }

    public class EditorUtility
    {
        public static void SetDirty(UnityEngine.Object target) => throw StandIn.No;
    }

    public sealed class Handles
    {
        public static Color color { get => throw StandIn.No; set => throw StandIn.No; }
        public static Matrix4x4 matrix { get => throw StandIn.No; set => throw StandIn.No; }
        public static void DotHandleCap(int controlID, Vector3 position, Quaternion rotation, float size, EventType eventType) => throw StandIn.No;
    }

    public sealed class HandleUtility
    {
        public static float GetHandleSize(Vector3 position) => throw StandIn.No;
        public static Vector2 WorldToGUIPoint(Vector3 world) => throw StandIn.No;
        public static void AddDefaultControl(int controlId) => throw StandIn.No;
    }

    public class SceneView
    {
        public static void RepaintAll() => throw StandIn.No;
    }

    public class EditorGUILayout
    {
        public static void HelpBox(string message, MessageType type) => throw StandIn.No;
        public static void Slider(SerializedProperty property, float leftValue, float rightValue, GUIContent label, params GUILayoutOption[] options) => throw StandIn.No;
        public static void LabelField(string label, params GUILayoutOption[] options) => throw StandIn.No;
        public static void Space() => throw StandIn.No;
        public static void LabelField(string label, GUIStyle style, params GUILayoutOption[] options) => throw StandIn.No;
        public static void LabelField(string label, string label2, params GUILayoutOption[] options) => throw StandIn.No;
    }

    public sealed class EditorStyles
    {
        public static GUIStyle boldLabel => throw StandIn.No;
    }

    [Flags]
    public enum GizmoType
    {
        Pickable = 1, NotInSelectionHierarchy = 2, NonSelected = 32, Selected = 4, Active = 8, InSelectionHierarchy = 16,
    }

    [AttributeUsage(AttributeTargets.Method)]
    public sealed class DrawGizmo : Attribute { public DrawGizmo(GizmoType gizmo) { } }

    [AttributeUsage(AttributeTargets.Method)]
    public class InitializeOnLoadMethodAttribute : Attribute { }

    public static class AssemblyReloadEvents
    {
        public delegate void AssemblyReloadCallback();
        public static event AssemblyReloadCallback beforeAssemblyReload { add => throw StandIn.No; remove => throw StandIn.No; }
    }
}
