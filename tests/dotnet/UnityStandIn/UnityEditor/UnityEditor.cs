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
        public void Update() => throw StandIn.No;
        public bool ApplyModifiedProperties() => throw StandIn.No;
    }

    public class Editor : ScriptableObjectStandIn
    {
        public SerializedObject serializedObject => throw StandIn.No;
        public UnityEngine.Object target { get => throw StandIn.No; set => throw StandIn.No; }
        public virtual void OnInspectorGUI() => throw StandIn.No;
        public bool DrawDefaultInspector() => throw StandIn.No;
        public void Repaint() => throw StandIn.No;
    }

    /// <summary>Stands for UnityEngine.ScriptableObject in the Editor's base chain.</summary>
    public class ScriptableObjectStandIn : UnityEngine.Object { }

    [AttributeUsage(AttributeTargets.Class, AllowMultiple = false, Inherited = true)]
    public sealed class CustomEditor : Attribute { public CustomEditor(Type inspectedType) { } }

    [AttributeUsage(AttributeTargets.Class)]
    public sealed class CanEditMultipleObjects : Attribute { }

    public enum MessageType { None = 0, Info = 1, Warning = 2, Error = 3 }

    public static class EditorGUILayout
    {
        public static void HelpBox(string message, MessageType type) => throw StandIn.No;
        public static void LabelField(string label, GUIStyle style, params GUILayoutOption[] options) => throw StandIn.No;
        public static void LabelField(string label, string label2, params GUILayoutOption[] options) => throw StandIn.No;
    }

    public sealed class GUILayoutOption { }

    public static class EditorStyles
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
