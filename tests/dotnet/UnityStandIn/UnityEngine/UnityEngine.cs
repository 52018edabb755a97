// COMPILE CHECK ONLY. Signature-only stand-in for UnityEngine 2022.3: no behaviour, every member
// throws. Never reference this from anything that runs.
using System;
using System.Collections;
using System.Diagnostics;

namespace UnityEngine
{
    internal static class StandIn
    {
        public static Exception No => new NotSupportedException("Unity stand-in: compile check only");
    }

    public class Object
    {
        public string name { get => throw StandIn.No; set => throw StandIn.No; }
        public static void Destroy(Object obj) => throw StandIn.No;
        public static void DestroyImmediate(Object obj) => throw StandIn.No;
        public static T FindObjectOfType<T>() where T : Object => throw StandIn.No;
        public int GetInstanceID() => throw StandIn.No;
        public static bool operator ==(Object a, Object b) => ReferenceEquals(a, b);
        public static bool operator !=(Object a, Object b) => !ReferenceEquals(a, b);
        public static implicit operator bool(Object exists) => !ReferenceEquals(exists, null);
    }

    public class Component : Object
    {
        public Transform transform => throw StandIn.No;
        public GameObject gameObject => throw StandIn.No;
        public T GetComponent<T>() => throw StandIn.No;
    }

    public class Behaviour : Component
    {
        public bool enabled { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public class MonoBehaviour : Behaviour { }

    public sealed class GameObject : Object
    {
        public GameObject(string name) => throw StandIn.No;
        public T AddComponent<T>() where T : Component => throw StandIn.No;
        public Transform transform => throw StandIn.No;
        public bool activeInHierarchy => throw StandIn.No;
        public string tag { get => throw StandIn.No; set => throw StandIn.No; }
        public void SetActive(bool value) => throw StandIn.No;
        public static GameObject CreatePrimitive(PrimitiveType type) => throw StandIn.No;
        public T GetComponent<T>() => throw StandIn.No;
    }

    public class Transform : Component, IEnumerable
    {
        public bool hasChanged { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector3 position { get => throw StandIn.No; set => throw StandIn.No; }
        public Quaternion rotation { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector3 lossyScale => throw StandIn.No;
        public Vector3 localScale { get => throw StandIn.No; set => throw StandIn.No; }
        public void LookAt(Vector3 worldPosition) => throw StandIn.No;
        public Vector3 up { get => throw StandIn.No; set => throw StandIn.No; }
        public Matrix4x4 worldToLocalMatrix => throw StandIn.No;
        public Matrix4x4 localToWorldMatrix => throw StandIn.No;
        public Vector3 TransformPoint(Vector3 position) => throw StandIn.No;
        public Vector3 TransformDirection(Vector3 direction) => throw StandIn.No;
        public Vector3 InverseTransformDirection(Vector3 direction) => throw StandIn.No;
        public IEnumerator GetEnumerator() => throw StandIn.No;
    }

    public sealed class MeshFilter : Component
    {
        public Mesh sharedMesh { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public class Renderer : Component
    {
        public bool isVisible => throw StandIn.No;
        public Material sharedMaterial { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public sealed class MeshRenderer : Renderer { }

    public class Material : Object { }

    public enum PrimitiveType { Sphere = 0, Capsule = 1, Cylinder = 2, Cube = 3, Plane = 4, Quad = 5 }

    public enum LightType { Spot = 0, Directional = 1, Point = 2 }

    public sealed class Light : Behaviour
    {
        public LightType type { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public class Collider : Component
    {
        public bool enabled { get => throw StandIn.No; set => throw StandIn.No; }
        public Bounds bounds => throw StandIn.No;
    }

    public sealed class SphereCollider : Collider
    {
        public Vector3 center { get => throw StandIn.No; set => throw StandIn.No; }
        public float radius { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public sealed class CapsuleCollider : Collider
    {
        public Vector3 center { get => throw StandIn.No; set => throw StandIn.No; }
        public float radius { get => throw StandIn.No; set => throw StandIn.No; }
        public float height { get => throw StandIn.No; set => throw StandIn.No; }
        public int direction { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public sealed class BoxCollider : Collider
    {
        public Vector3 center { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector3 size { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public enum MeshTopology { Triangles = 0, Quads = 2, Lines = 3, LineStrip = 4, Points = 5 }

    public sealed class Mesh : Object
    {
        public Mesh() => throw StandIn.No;
        public bool isReadable => throw StandIn.No;
        public int vertexCount => throw StandIn.No;
        public int subMeshCount { get => throw StandIn.No; set => throw StandIn.No; }
        public Bounds bounds { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector3[] vertices { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector2[] uv { get => throw StandIn.No; set => throw StandIn.No; }
        public Color[] colors { get => throw StandIn.No; set => throw StandIn.No; }
        public int[] triangles { get => throw StandIn.No; set => throw StandIn.No; }
        public void MarkDynamic() => throw StandIn.No;
        public void MarkModified() => throw StandIn.No;
        public void UploadMeshData(bool markNoLongerReadable) => throw StandIn.No;
        public void SetVertexBufferParams(int vertexCount, params Rendering.VertexAttributeDescriptor[] attributes) => throw StandIn.No;
        public void SetVertexBufferData<T>(Unity.Collections.NativeArray<T> data, int dataStart, int meshBufferStart, int count, int stream = 0, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct => throw StandIn.No;
        public void SetVertexBufferData<T>(T[] data, int dataStart, int meshBufferStart, int count, int stream = 0, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct => throw StandIn.No;
        public void SetIndexBufferParams(int indexCount, Rendering.IndexFormat format) => throw StandIn.No;
        public void SetIndexBufferData<T>(T[] data, int dataStart, int meshBufferStart, int count, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct => throw StandIn.No;
        public void SetSubMesh(int index, Rendering.SubMeshDescriptor desc, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) => throw StandIn.No;
        public IntPtr GetNativeVertexBufferPtr(int index) => throw StandIn.No;
    }

    public struct Vector2
    {
        public float x, y;
        public Vector2(float x, float y) { this.x = x; this.y = y; }
        public static Vector2 zero => default;
        public static Vector2 operator -(Vector2 a, Vector2 b) => throw StandIn.No;
        public static bool operator ==(Vector2 a, Vector2 b) => throw StandIn.No;
        public static bool operator !=(Vector2 a, Vector2 b) => throw StandIn.No;
        public static implicit operator Vector2(Vector3 v) => throw StandIn.No;
        public override bool Equals(object other) => throw StandIn.No;
        public override int GetHashCode() => throw StandIn.No;
    }

    public struct Vector3
    {
        public float x, y, z;
        public Vector3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public static Vector3 zero => default;
        public static Vector3 one => throw StandIn.No;
        public static Vector3 up => throw StandIn.No;
        public static Vector3 right => throw StandIn.No;
        public static Vector3 forward => throw StandIn.No;
        public Vector3 normalized => throw StandIn.No;
        public float magnitude => throw StandIn.No;
        public static Vector3 Min(Vector3 a, Vector3 b) => throw StandIn.No;
        public static Vector3 Max(Vector3 a, Vector3 b) => throw StandIn.No;
        public static Vector3 Scale(Vector3 a, Vector3 b) => throw StandIn.No;
        public static float Distance(Vector3 a, Vector3 b) => throw StandIn.No;
        public static Vector3 operator +(Vector3 a, Vector3 b) => throw StandIn.No;
        public static Vector3 operator -(Vector3 a, Vector3 b) => throw StandIn.No;
        public static Vector3 operator *(Vector3 a, float d) => throw StandIn.No;
        public static Vector3 operator *(float d, Vector3 a) => throw StandIn.No;
        public static bool operator ==(Vector3 a, Vector3 b) => throw StandIn.No;
        public static bool operator !=(Vector3 a, Vector3 b) => throw StandIn.No;
        public override bool Equals(object other) => throw StandIn.No;
        public override int GetHashCode() => throw StandIn.No;
    }

    public struct Quaternion
    {
        public float x, y, z, w;
        public Quaternion(float x, float y, float z, float w) { this.x = x; this.y = y; this.z = z; this.w = w; }
        public static Quaternion identity => throw StandIn.No;
        public static Quaternion Inverse(Quaternion rotation) => throw StandIn.No;
        public static Quaternion Euler(float x, float y, float z) => throw StandIn.No;
        public static Quaternion operator *(Quaternion a, Quaternion b) => throw StandIn.No;
    }

    public struct Matrix4x4
    {
        public float m00, m10, m20, m30, m01, m11, m21, m31, m02, m12, m22, m32, m03, m13, m23, m33;
        public static Matrix4x4 identity => throw StandIn.No;
        public static Matrix4x4 TRS(Vector3 pos, Quaternion q, Vector3 s) => throw StandIn.No;
        public Vector3 MultiplyPoint3x4(Vector3 point) => throw StandIn.No;
        public Vector3 MultiplyVector(Vector3 vector) => throw StandIn.No;
    }

    public struct Color
    {
        public float r, g, b, a;
        public Color(float r, float g, float b) { this.r = r; this.g = g; this.b = b; a = 1f; }
        public Color(float r, float g, float b, float a) { this.r = r; this.g = g; this.b = b; this.a = a; }
    }

    public struct Bounds
    {
        public Vector3 center { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector3 size { get => throw StandIn.No; set => throw StandIn.No; }
        public void SetMinMax(Vector3 min, Vector3 max) => throw StandIn.No;
    }

    public struct Rect
    {
        public Rect(float x, float y, float width, float height) => throw StandIn.No;
        public float x { get => throw StandIn.No; set => throw StandIn.No; }
        public float y { get => throw StandIn.No; set => throw StandIn.No; }
        public float width { get => throw StandIn.No; set => throw StandIn.No; }
        public float height { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public sealed class Camera : Behaviour
    {
        public static Camera main => throw StandIn.No;
        public Rect pixelRect { get => throw StandIn.No; set => throw StandIn.No; }
        public Matrix4x4 worldToCameraMatrix { get => throw StandIn.No; set => throw StandIn.No; }
        public Matrix4x4 projectionMatrix { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public static class SystemInfo
    {
        public static Rendering.GraphicsDeviceType graphicsDeviceType => throw StandIn.No;
    }

    public static class GL
    {
        public static void IssuePluginEvent(IntPtr callback, int eventID) => throw StandIn.No;
    }

    public static class Physics
    {
        public static Vector3 gravity { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public static class Time
    {
        public static float deltaTime => throw StandIn.No;
        public static float fixedDeltaTime { get => throw StandIn.No; set => throw StandIn.No; }
        public static float unscaledTime => throw StandIn.No;
        public static float time => throw StandIn.No;
        public static int frameCount => throw StandIn.No;
    }

    public static class Application
    {
        public static bool isPlaying => throw StandIn.No;
    }

    public static class Debug
    {
        public static void Log(object message) => throw StandIn.No;
        public static void LogWarning(object message, Object context) => throw StandIn.No;
        public static void LogException(Exception exception, Object context) => throw StandIn.No;
    }

    public static class Mathf
    {
        public static float Max(float a, float b) => throw StandIn.No;
        public static int Max(int a, int b) => throw StandIn.No;
        public static float Min(float a, float b) => throw StandIn.No;
        public static float Abs(float f) => throw StandIn.No;
        public static float Lerp(float a, float b, float t) => throw StandIn.No;
        public static float Sqrt(float f) => throw StandIn.No;
        public static float PerlinNoise(float x, float y) => throw StandIn.No;
        public static float Clamp01(float value) => throw StandIn.No;
    }

    public enum TouchPhase { Began = 0, Moved = 1, Stationary = 2, Ended = 3, Canceled = 4 }

    public struct Touch
    {
        public int fingerId => throw StandIn.No;
        public Vector2 position => throw StandIn.No;
        public Vector2 deltaPosition => throw StandIn.No;
        public TouchPhase phase => throw StandIn.No;
    }

    public static class Input
    {
        public static int touchCount => throw StandIn.No;
        public static Touch GetTouch(int index) => throw StandIn.No;
        public static bool mousePresent => throw StandIn.No;
        public static Vector3 mousePosition => throw StandIn.No;
        public static bool GetMouseButton(int button) => throw StandIn.No;
    }

    public class GUIContent
    {
        public static GUIContent none => throw StandIn.No;
    }

    public class GUIStyle { }

    public static class GUI
    {
        public static void Box(Rect position, GUIContent content) => throw StandIn.No;
        public static void Label(Rect position, string text) => throw StandIn.No;
    }

    public static class Gizmos
    {
        public static Color color { get => throw StandIn.No; set => throw StandIn.No; }
        public static Matrix4x4 matrix { get => throw StandIn.No; set => throw StandIn.No; }
        public static void DrawSphere(Vector3 center, float radius) => throw StandIn.No;
        public static void DrawWireCube(Vector3 center, Vector3 size) => throw StandIn.No;
        public static void DrawLine(Vector3 from, Vector3 to) => throw StandIn.No;
    }

    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public class TooltipAttribute : Attribute { public TooltipAttribute(string tooltip) { } }

    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public sealed class RangeAttribute : Attribute
    {
        public RangeAttribute(float min, float max) { }
    }

    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = true)]
    public class HeaderAttribute : Attribute { public HeaderAttribute(string header) { } }

    [AttributeUsage(AttributeTargets.Class, Inherited = false)]
    public sealed class DisallowMultipleComponent : Attribute { }

    [AttributeUsage(AttributeTargets.Class, AllowMultiple = true)]
    public sealed class RequireComponent : Attribute { public RequireComponent(Type requiredComponent) { } }

    public sealed class AddComponentMenu : Attribute { public AddComponentMenu(string menuName) { } }

    public enum RuntimeInitializeLoadType
    {
        AfterSceneLoad = 0, BeforeSceneLoad = 1, AfterAssembliesLoaded = 2, BeforeSplashScreen = 3, SubsystemRegistration = 4,
    }

    [AttributeUsage(AttributeTargets.Method, AllowMultiple = false)]
    public class RuntimeInitializeOnLoadMethodAttribute : Attribute
    {
        public RuntimeInitializeOnLoadMethodAttribute() { }
        public RuntimeInitializeOnLoadMethodAttribute(RuntimeInitializeLoadType loadType) { }
    }

    public class YieldInstruction { }
    public sealed class WaitForFixedUpdate : YieldInstruction { }
}

namespace UnityEngine.Rendering
{
    public enum VertexAttribute
    {
        Position = 0, Normal, Tangent, Color, TexCoord0, TexCoord1, TexCoord2, TexCoord3, TexCoord4, TexCoord5,
        TexCoord6, TexCoord7, BlendWeight, BlendIndices,
    }

    public enum VertexAttributeFormat
    {
        Float32 = 0, Float16 = 1, UNorm8 = 2, SNorm8 = 3, UNorm16 = 4, SNorm16 = 5, UInt8 = 6, SInt8 = 7, UInt16 = 8,
        SInt16 = 9, UInt32 = 10, SInt32 = 11,
    }

    public struct VertexAttributeDescriptor
    {
        public VertexAttributeDescriptor(VertexAttribute attribute = VertexAttribute.Position,
                                         VertexAttributeFormat format = VertexAttributeFormat.Float32, int dimension = 3,
                                         int stream = 0) => throw StandIn.No;
    }

    [Flags]
    public enum MeshUpdateFlags
    {
        Default = 0, DontValidateIndices = 1, DontResetBoneBounds = 2, DontNotifyMeshUsers = 4, DontRecalculateBounds = 8,
    }

    public enum IndexFormat { UInt16 = 0, UInt32 = 1 }

    public enum GraphicsDeviceType
    {
        Direct3D11 = 2, Null = 4, OpenGLES2 = 8, OpenGLES3 = 11, Metal = 16, OpenGLCore = 17, Direct3D12 = 18, Vulkan = 21,
    }

    public struct SubMeshDescriptor
    {
        public SubMeshDescriptor(int indexStart, int indexCount, MeshTopology topology = MeshTopology.Triangles) => throw StandIn.No;
    }
}

namespace UnityEngine.TestTools
{
    [AttributeUsage(AttributeTargets.Method)]
    public class UnityTestAttribute : Attribute { }
}

namespace Unity.Collections
{
    public enum Allocator { Invalid = 0, None = 1, Temp = 2, TempJob = 3, Persistent = 4 }

    public enum NativeArrayOptions { UninitializedMemory = 0, ClearMemory = 1 }

    public struct NativeArray<T> : IDisposable where T : struct
    {
        public NativeArray(int length, Allocator allocator, NativeArrayOptions options = NativeArrayOptions.ClearMemory) => throw UnityEngine.StandIn.No;
        public int Length => throw UnityEngine.StandIn.No;
        public bool IsCreated => throw UnityEngine.StandIn.No;
        public T this[int index] { get => throw UnityEngine.StandIn.No; set => throw UnityEngine.StandIn.No; }
        public void Dispose() => throw UnityEngine.StandIn.No;
    }
}

namespace Unity.Collections.LowLevel.Unsafe
{
    public static class NativeArrayUnsafeUtility
    {
        public static unsafe void* GetUnsafePtr<T>(this NativeArray<T> nativeArray) where T : struct => throw UnityEngine.StandIn.No;
    }
}
