// Stand-in for UnityEngine (2022.3 .. 6000.x), for compile checks and for the component tests in
// tests/dotnet. Every public type and member here exists in Unity with this exact signature
// (checked against Unity's C# reference source by ../unity_api.py, evidence in
// ../unity-api-evidence.tsv). Behaviour: members on the component's frame path do the minimum
// Unity documents (values are stored, vector and matrix maths, NativeArray memory, component
// lifecycle messages on AddComponent/enabled/Destroy, a mesh that stores its vertex streams);
// everything else throws. It is NOT Unity: what a test proves against it is our own logic, not
// Unity's behaviour. Test hooks are internal (StandInHooks), so they cannot leak into the checked
// public surface.
using System;
using System.Collections;
using System.Collections.Generic;
using System.Diagnostics;
using System.Reflection;
using System.Runtime.InteropServices;

[assembly: System.Runtime.CompilerServices.InternalsVisibleTo("Drape.Runtime.Tests")]

namespace UnityEngine
{
    internal static class StandIn
    {
        public static Exception No => new NotSupportedException("Unity stand-in: not emulated");
    }

    /// <summary>Test hooks: what Unity's engine would set (time, device, input) and what it would show (logs).</summary>
    internal static class StandInHooks
    {
        public static float DeltaTime = 1f / 60f, FixedDeltaTime = 0.02f, UnscaledTime, Time;
        public static int FrameCount;
        public static Rendering.GraphicsDeviceType Device = Rendering.GraphicsDeviceType.Null;
        public static float Dpi;
        public static readonly List<string> Warnings = new List<string>();
        public static readonly List<Exception> Exceptions = new List<Exception>();
        public static readonly List<Object> Live = new List<Object>();
        private static int s_nextId = 1;

        internal static int NextId() => s_nextId++;

        private static readonly Dictionary<(object, string), Action> s_messages = new Dictionary<(object, string), Action>();

        /// <summary>Calls a Unity message (Awake, OnEnable, Update, LateUpdate, ...) if the behaviour has
        /// it, through a delegate cached per object and message (no allocation once cached).</summary>
        public static void Send(object target, string message)
        {
            if (!s_messages.TryGetValue((target, message), out Action call))
            {
                MethodInfo m = target.GetType().GetMethod(message, BindingFlags.Instance | BindingFlags.Public | BindingFlags.NonPublic,
                                                          null, Type.EmptyTypes, null);
                call = m == null ? null : (Action)Delegate.CreateDelegate(typeof(Action), target, m);
                s_messages[(target, message)] = call;
            }
            call?.Invoke();
        }

        /// <summary>One frame: Update then LateUpdate of every enabled behaviour, then OnGUI.</summary>
        public static void Frame(float dt)
        {
            DeltaTime = dt;
            UnscaledTime += dt;
            Time += dt;
            FrameCount++;
            foreach (string message in s_frameMessages)
                for (int i = 0; i < Live.Count; ++i)
                    if (Live[i] is Behaviour b && b.enabled && !b.m_Destroyed) Send(b, message);
        }

        private static readonly string[] s_frameMessages = { "Update", "LateUpdate", "OnGUI" };

        public static void Reset()
        {
            foreach (Object o in Live.ToArray()) Object.DestroyImmediate(o);
            Live.Clear();
            Warnings.Clear();
            Exceptions.Clear();
            s_messages.Clear();
            Device = Rendering.GraphicsDeviceType.Null;
            Dpi = 0f;
            Input.s_TouchDown = false;
            Camera.s_Main = null;
            DeltaTime = 1f / 60f;
        }
    }

    public class Object
    {
        internal bool m_Destroyed;
        internal readonly int m_Id = StandInHooks.NextId();
        private string m_Name = string.Empty;

        public string name { get => m_Name; set => m_Name = value; }
        public static void Destroy(Object obj) => DestroyImmediate(obj);
        public static void DestroyImmediate(Object obj)
        {
            if (IsNull(obj)) return;
            if (obj is GameObject go)
            {
                foreach (Component c in go.m_Components.ToArray()) DestroyImmediate(c);
            }
            else if (obj is Behaviour b)
            {
                if (b.m_Enabled && b.m_Awake) StandInHooks.Send(b, "OnDisable");
                StandInHooks.Send(b, "OnDestroy");
            }
            if (obj is Component comp && comp.m_GameObject != null) comp.m_GameObject.m_Components.Remove(comp);
            obj.m_Destroyed = true;
            StandInHooks.Live.Remove(obj);
        }
#if UNITY_2023_1_OR_NEWER
        [Obsolete("stand-in: obsolete from 2023.1", false)]
#endif
        public static T FindObjectOfType<T>() where T : Object => FindAnyObjectByType<T>();
        public static T FindAnyObjectByType<T>() where T : Object
        {
            foreach (Object o in StandInHooks.Live)
                if (o is T t && !o.m_Destroyed) return t;
            return null;
        }
#if UNITY_6000_5_OR_NEWER
        [Obsolete("stand-in: obsolete as an error from 6000.5", true)]
#elif UNITY_6000_4_OR_NEWER
        [Obsolete("stand-in: obsolete from 6000.4", false)]
#endif
        public int GetInstanceID() => m_Id;
#if UNITY_6000_2_OR_NEWER
        public EntityId GetEntityId() => new EntityId { m_Raw = (ulong)(uint)m_Id | (1ul << 32) };
#endif
        private static bool IsNull(Object o) => ReferenceEquals(o, null) || o.m_Destroyed;
        public static bool operator ==(Object a, Object b) => IsNull(a) ? IsNull(b) : !IsNull(b) && ReferenceEquals(a, b);
        public static bool operator !=(Object a, Object b) => !(a == b);
        public static implicit operator bool(Object exists) => !IsNull(exists);
        public override bool Equals(object other) => ReferenceEquals(this, other);
        public override int GetHashCode() => m_Id;
    }

#if UNITY_6000_2_OR_NEWER
    public struct EntityId
    {
        internal ulong m_Raw;
#if UNITY_6000_4_OR_NEWER
        public static ulong ToULong(EntityId entityId) => entityId.m_Raw;
#endif
    }
#endif

    public class Component : Object
    {
        internal GameObject m_GameObject;
        public Transform transform => m_GameObject.transform;
        public GameObject gameObject => m_GameObject;
        public T GetComponent<T>() => m_GameObject.GetComponent<T>();
    }

    public class Behaviour : Component
    {
        internal bool m_Enabled = true;
        internal bool m_Awake;

        public bool enabled
        {
            get => m_Enabled;
            set
            {
                if (m_Enabled == value) return;
                m_Enabled = value;
                if (!m_Awake || m_Destroyed) return;
                StandInHooks.Send(this, value ? "OnEnable" : "OnDisable");
            }
        }
    }

    public class MonoBehaviour : Behaviour
    {
        private bool m_UseGUILayout = true;
        public bool useGUILayout { get => m_UseGUILayout; set => m_UseGUILayout = value; }
    }

    public sealed class GameObject : Object
    {
        internal readonly List<Component> m_Components = new List<Component>();
        private readonly Transform m_Transform;
        private bool m_Active = true;

        public GameObject(string name)
        {
            this.name = name;
            m_Transform = new Transform { m_GameObject = this };
            m_Components.Add(m_Transform);
            StandInHooks.Live.Add(this);
        }

        /// <summary>As Unity: adds [RequireComponent] types first, then the component; a behaviour on an
        /// active object gets Awake and, if enabled, OnEnable at once.</summary>
        public T AddComponent<T>() where T : Component => (T)AddComponent(typeof(T));

        private Component AddComponent(Type type)
        {
            foreach (RequireComponent r in type.GetCustomAttributes(typeof(RequireComponent), true))
                if (FindComponent(r.m_Type) == null) AddComponent(r.m_Type);
            var c = (Component)Activator.CreateInstance(type, true);
            c.m_GameObject = this;
            c.name = name;
            m_Components.Add(c);
            StandInHooks.Live.Add(c);
            if (c is Behaviour b && m_Active)
            {
                b.m_Awake = true;
                StandInHooks.Send(b, "Awake");
                if (b.m_Enabled && !b.m_Destroyed) StandInHooks.Send(b, "OnEnable");
            }
            return c;
        }

        private Component FindComponent(Type type)
        {
            foreach (Component c in m_Components)
                if (type.IsInstanceOfType(c)) return c;
            return null;
        }

        public Transform transform => m_Transform;
        public bool activeInHierarchy => m_Active;
        public string tag { get => throw StandIn.No; set => throw StandIn.No; }
        public void SetActive(bool value) => m_Active = value;
        public static GameObject CreatePrimitive(PrimitiveType type) => throw StandIn.No;
        public T GetComponent<T>()
        {
            foreach (Component c in m_Components)
                if (c is T t) return t;
            return default;
        }
    }

    /// <summary>A root transform (no parent): position, rotation, scale.</summary>
    public class Transform : Component, IEnumerable
    {
        private Vector3 m_Position;
        private Quaternion m_Rotation = new Quaternion(0f, 0f, 0f, 1f);
        private Vector3 m_Scale = new Vector3(1f, 1f, 1f);
        private bool m_HasChanged = true;

        public bool hasChanged { get => m_HasChanged; set => m_HasChanged = value; }
        public Vector3 position { get => m_Position; set { m_Position = value; m_HasChanged = true; } }
        public Quaternion rotation { get => m_Rotation; set { m_Rotation = value; m_HasChanged = true; } }
        public Vector3 lossyScale => m_Scale;
        public Vector3 localScale { get => m_Scale; set { m_Scale = value; m_HasChanged = true; } }
        public void LookAt(Vector3 worldPosition) => throw StandIn.No;
        public Vector3 up { get => m_Rotation * new Vector3(0f, 1f, 0f); set => throw StandIn.No; }
        public Matrix4x4 worldToLocalMatrix => Matrix4x4.InverseTRS(m_Position, m_Rotation, m_Scale);
        public Matrix4x4 localToWorldMatrix => Matrix4x4.TRS(m_Position, m_Rotation, m_Scale);
        public Vector3 TransformPoint(Vector3 position) => localToWorldMatrix.MultiplyPoint3x4(position);
        public Vector3 TransformDirection(Vector3 direction) => m_Rotation * direction;
        public Vector3 InverseTransformDirection(Vector3 direction) => Quaternion.Inverse(m_Rotation) * direction;
        public IEnumerator GetEnumerator() => throw StandIn.No;
    }

    public sealed class MeshFilter : Component
    {
        private Mesh m_Mesh;
        public Mesh sharedMesh { get => m_Mesh; set => m_Mesh = value; }
    }

    public class Renderer : Component
    {
        internal bool m_Visible = true;
        public bool isVisible => m_Visible;
        public Material sharedMaterial { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public sealed class MeshRenderer : Renderer { }

    public class Material : Object { }

    public class ScriptableObject : Object { }

    public sealed class GUILayoutOption { }

    public enum PrimitiveType { Sphere = 0, Capsule = 1, Cylinder = 2, Cube = 3, Plane = 4, Quad = 5 }

    public enum LightType { Spot = 0, Directional = 1, Point = 2 }

    public sealed class Light : Behaviour
    {
        public LightType type { get => throw StandIn.No; set => throw StandIn.No; }
    }

    public class Collider : Component
    {
        private bool m_Enabled = true;
        public bool enabled { get => m_Enabled; set => m_Enabled = value; }
        public Bounds bounds => throw StandIn.No;
    }

    public sealed class SphereCollider : Collider
    {
        private Vector3 m_Center;
        private float m_Radius = 0.5f;
        public Vector3 center { get => m_Center; set => m_Center = value; }
        public float radius { get => m_Radius; set => m_Radius = value; }
    }

    public sealed class CapsuleCollider : Collider
    {
        private Vector3 m_Center;
        private float m_Radius = 0.5f, m_Height = 2f;
        private int m_Direction = 1;
        public Vector3 center { get => m_Center; set => m_Center = value; }
        public float radius { get => m_Radius; set => m_Radius = value; }
        public float height { get => m_Height; set => m_Height = value; }
        public int direction { get => m_Direction; set => m_Direction = value; }
    }

    public sealed class BoxCollider : Collider
    {
        private Vector3 m_Center, m_Size = new Vector3(1f, 1f, 1f);
        public Vector3 center { get => m_Center; set => m_Center = value; }
        public Vector3 size { get => m_Size; set => m_Size = value; }
    }

    public enum MeshTopology { Triangles = 0, Quads = 2, Lines = 3, LineStrip = 4, Points = 5 }

    /// <summary>Stores vertex streams as bytes. The classic setters (vertices, uv, colors, triangles)
    /// lay out stream 0 as Position, Normal?, Color, TexCoord0 in Float32 (Unity picks its own
    /// layout; code must read it through GetVertexAttributes / offsets / strides, as ours does).</summary>
    public sealed class Mesh : Object
    {
        internal bool m_Readable = true;
        private int m_VertexCount;
        private Rendering.VertexAttributeDescriptor[] m_Layout = new Rendering.VertexAttributeDescriptor[0];
        private byte[][] m_Streams = new byte[0][];
        private int[] m_Indices = new int[0];
        private Rendering.SubMeshDescriptor[] m_SubMeshes = new Rendering.SubMeshDescriptor[0];
        private Vector3[] m_Vertices;
        private Vector2[] m_Uv;
        private Color[] m_Colors;
        private Bounds m_Bounds;

        public Mesh() { }
        public bool isReadable => m_Readable;
        public int vertexCount => m_VertexCount;
        public int subMeshCount
        {
            get => m_SubMeshes.Length;
            set => Array.Resize(ref m_SubMeshes, value);
        }
        public Bounds bounds { get => m_Bounds; set => m_Bounds = value; }
        public Vector3[] vertices
        {
            get => ReadChannel<Vector3>(Rendering.VertexAttribute.Position);
            set { m_Vertices = value; m_VertexCount = value.Length; RebuildClassic(); }
        }
        public Vector2[] uv { get => ReadChannel<Vector2>(Rendering.VertexAttribute.TexCoord0); set { m_Uv = value; RebuildClassic(); } }
        public Color[] colors { get => ReadChannel<Color>(Rendering.VertexAttribute.Color); set { m_Colors = value; RebuildClassic(); } }
        public int[] triangles
        {
            get => (int[])m_Indices.Clone();
            set
            {
                m_Indices = (int[])value.Clone();
                m_SubMeshes = new[] { new Rendering.SubMeshDescriptor(0, value.Length) };
            }
        }
        public void SetTriangles(int[] triangles, int submesh)
        {
            int start = 0;
            for (int s = 0; s < submesh; ++s) start += m_SubMeshes[s].indexCount;
            var all = new List<int>(m_Indices);
            all.RemoveRange(start, Math.Min(m_SubMeshes[submesh].indexCount, all.Count - start));
            all.InsertRange(start, triangles);
            m_Indices = all.ToArray();
            m_SubMeshes[submesh] = new Rendering.SubMeshDescriptor(start, triangles.Length);
            for (int s = submesh + 1, at = start + triangles.Length; s < m_SubMeshes.Length; ++s)
            {
                m_SubMeshes[s] = new Rendering.SubMeshDescriptor(at, m_SubMeshes[s].indexCount, m_SubMeshes[s].topology);
                at += m_SubMeshes[s].indexCount;
            }
        }
        public void MarkDynamic() { }
        public void MarkModified() { }
        public void UploadMeshData(bool markNoLongerReadable) => m_Readable = !markNoLongerReadable;
        public void SetVertexBufferParams(int vertexCount, params Rendering.VertexAttributeDescriptor[] attributes)
        {
            m_VertexCount = vertexCount;
            m_Layout = (Rendering.VertexAttributeDescriptor[])attributes.Clone();
            int streams = 0;
            foreach (var a in m_Layout) streams = Math.Max(streams, a.stream + 1);
            m_Streams = new byte[streams][];
            for (int s = 0; s < streams; ++s) m_Streams[s] = new byte[vertexCount * GetVertexBufferStride(s)];
        }
        public void SetVertexBufferData<T>(Unity.Collections.NativeArray<T> data, int dataStart, int meshBufferStart, int count, int stream = 0, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct
            => CopyInto(data.m_Array, dataStart, meshBufferStart, count, stream);
        public void SetVertexBufferData<T>(T[] data, int dataStart, int meshBufferStart, int count, int stream = 0, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct
            => CopyInto(data, dataStart, meshBufferStart, count, stream);
        private void CopyInto<T>(T[] data, int dataStart, int meshBufferStart, int count, int stream) where T : struct
        {
            ReadOnlySpan<byte> bytes = MemoryMarshal.AsBytes(new ReadOnlySpan<T>(data, dataStart, count));
            int size = Marshal.SizeOf<T>();
            bytes.CopyTo(new Span<byte>(m_Streams[stream], meshBufferStart * size, count * size));
        }
        public void SetIndexBufferParams(int indexCount, Rendering.IndexFormat format) => m_Indices = new int[indexCount];
        public void SetIndexBufferData<T>(T[] data, int dataStart, int meshBufferStart, int count, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct
        {
            for (int i = 0; i < count; ++i) m_Indices[meshBufferStart + i] = Convert.ToInt32(data[dataStart + i]);
        }
        public void SetSubMesh(int index, Rendering.SubMeshDescriptor desc, Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) => m_SubMeshes[index] = desc;
        public IntPtr GetNativeVertexBufferPtr(int index) => throw StandIn.No;
        public Rendering.VertexAttributeDescriptor[] GetVertexAttributes() => (Rendering.VertexAttributeDescriptor[])m_Layout.Clone();
        public int GetVertexAttributeStream(Rendering.VertexAttribute attr)
        {
            foreach (var a in m_Layout)
                if (a.attribute == attr) return a.stream;
            return -1;
        }
        public int GetVertexAttributeOffset(Rendering.VertexAttribute attr)
        {
            int stream = GetVertexAttributeStream(attr), offset = 0;
            foreach (var a in m_Layout)
            {
                if (a.stream != stream) continue;
                if (a.attribute == attr) return offset;
                offset += Size(a);
            }
            return -1;
        }
        public int GetVertexBufferStride(int stream)
        {
            int stride = 0;
            foreach (var a in m_Layout)
                if (a.stream == stream) stride += Size(a);
            return stride;
        }
        private static int Size(Rendering.VertexAttributeDescriptor a)
        {
            switch (a.format)
            {
                case Rendering.VertexAttributeFormat.Float32:
                case Rendering.VertexAttributeFormat.UInt32:
                case Rendering.VertexAttributeFormat.SInt32: return 4 * a.dimension;
                case Rendering.VertexAttributeFormat.UNorm8:
                case Rendering.VertexAttributeFormat.SNorm8:
                case Rendering.VertexAttributeFormat.UInt8:
                case Rendering.VertexAttributeFormat.SInt8: return a.dimension;
                default: return 2 * a.dimension;
            }
        }
        public uint GetIndexCount(int submesh) => (uint)m_SubMeshes[submesh].indexCount;
        public int[] GetIndices(int submesh, bool applyBaseVertex)
        {
            var d = m_SubMeshes[submesh];
            var r = new int[d.indexCount];
            Array.Copy(m_Indices, d.indexStart, r, 0, d.indexCount);
            return r;
        }
        public int[] GetTriangles(int submesh) => GetIndices(submesh, true);
        public MeshTopology GetTopology(int submesh) => m_SubMeshes[submesh].topology;
        public static MeshDataArray AcquireReadOnlyMeshData(Mesh mesh) => new MeshDataArray { m_Mesh = mesh };

        private void RebuildClassic()
        {
            var layout = new List<Rendering.VertexAttributeDescriptor>
            {
                new Rendering.VertexAttributeDescriptor(Rendering.VertexAttribute.Position, Rendering.VertexAttributeFormat.Float32, 3, 0),
            };
            if (m_Colors != null) layout.Add(new Rendering.VertexAttributeDescriptor(Rendering.VertexAttribute.Color, Rendering.VertexAttributeFormat.Float32, 4, 0));
            if (m_Uv != null) layout.Add(new Rendering.VertexAttributeDescriptor(Rendering.VertexAttribute.TexCoord0, Rendering.VertexAttributeFormat.Float32, 2, 0));
            SetVertexBufferParams(m_VertexCount, layout.ToArray());
            WriteChannel(Rendering.VertexAttribute.Position, m_Vertices);
            if (m_Colors != null) WriteChannel(Rendering.VertexAttribute.Color, m_Colors);
            if (m_Uv != null) WriteChannel(Rendering.VertexAttribute.TexCoord0, m_Uv);
        }

        private void WriteChannel<T>(Rendering.VertexAttribute attr, T[] values) where T : struct
        {
            int stream = GetVertexAttributeStream(attr), offset = GetVertexAttributeOffset(attr), stride = GetVertexBufferStride(stream);
            int size = Marshal.SizeOf<T>();
            for (int v = 0; v < m_VertexCount && v < values.Length; ++v)
                MemoryMarshal.AsBytes(new ReadOnlySpan<T>(values, v, 1)).CopyTo(new Span<byte>(m_Streams[stream], v * stride + offset, size));
        }

        private T[] ReadChannel<T>(Rendering.VertexAttribute attr) where T : struct
        {
            int stream = GetVertexAttributeStream(attr);
            var values = new T[stream < 0 ? 0 : m_VertexCount];
            if (stream < 0) return values;
            int offset = GetVertexAttributeOffset(attr), stride = GetVertexBufferStride(stream);
            int size = Marshal.SizeOf<T>();
            for (int v = 0; v < m_VertexCount; ++v)
                new ReadOnlySpan<byte>(m_Streams[stream], v * stride + offset, size).CopyTo(MemoryMarshal.AsBytes(new Span<T>(values, v, 1)));
            return values;
        }

        public struct MeshDataArray : IDisposable
        {
            internal Mesh m_Mesh;
            public int Length => 1;
            public MeshData this[int index] => new MeshData { m_Mesh = m_Mesh };
            public void Dispose() { }
        }

        public struct MeshData
        {
            internal Mesh m_Mesh;
            public Unity.Collections.NativeArray<T> GetVertexData<T>(int stream = 0) where T : struct
            {
                byte[] bytes = m_Mesh.m_Streams[stream];
                var copy = new T[bytes.Length / Marshal.SizeOf<T>()];
                new ReadOnlySpan<byte>(bytes).CopyTo(MemoryMarshal.AsBytes(new Span<T>(copy)));
                return new Unity.Collections.NativeArray<T>(copy);
            }
        }
    }

    public struct Vector2 : IEquatable<Vector2>
    {
        public float x, y;
        public float sqrMagnitude => x * x + y * y;
        public Vector2(float x, float y) { this.x = x; this.y = y; }
        public static Vector2 zero => default;
        public static Vector2 operator -(Vector2 a, Vector2 b) => new Vector2(a.x - b.x, a.y - b.y);
        public static bool operator ==(Vector2 a, Vector2 b) => a.x == b.x && a.y == b.y;
        public static bool operator !=(Vector2 a, Vector2 b) => !(a == b);
        public static implicit operator Vector2(Vector3 v) => new Vector2(v.x, v.y);
        public override bool Equals(object other) => other is Vector2 v && Equals(v);
        public bool Equals(Vector2 other) => x == other.x && y == other.y;
        public override int GetHashCode() => x.GetHashCode() ^ (y.GetHashCode() << 2);
    }

    public struct Vector3 : IEquatable<Vector3>
    {
        public float x, y, z;
        public Vector3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public static Vector3 zero => default;
        public static Vector3 one => new Vector3(1f, 1f, 1f);
        public static Vector3 up => new Vector3(0f, 1f, 0f);
        public static Vector3 right => new Vector3(1f, 0f, 0f);
        public static Vector3 forward => new Vector3(0f, 0f, 1f);
        public Vector3 normalized { get { float m = magnitude; return m > 1e-5f ? this * (1f / m) : zero; } }
        public float magnitude => (float)Math.Sqrt(x * x + y * y + z * z);
        public float this[int index]
        {
            get => index == 0 ? x : index == 1 ? y : index == 2 ? z : throw new IndexOutOfRangeException();
            set { if (index == 0) x = value; else if (index == 1) y = value; else if (index == 2) z = value; else throw new IndexOutOfRangeException(); }
        }
        public static Vector3 Min(Vector3 a, Vector3 b) => new Vector3(Math.Min(a.x, b.x), Math.Min(a.y, b.y), Math.Min(a.z, b.z));
        public static Vector3 Max(Vector3 a, Vector3 b) => new Vector3(Math.Max(a.x, b.x), Math.Max(a.y, b.y), Math.Max(a.z, b.z));
        public static Vector3 Scale(Vector3 a, Vector3 b) => new Vector3(a.x * b.x, a.y * b.y, a.z * b.z);
        public static float Distance(Vector3 a, Vector3 b) => (a - b).magnitude;
        public static Vector3 operator +(Vector3 a, Vector3 b) => new Vector3(a.x + b.x, a.y + b.y, a.z + b.z);
        public static Vector3 operator -(Vector3 a, Vector3 b) => new Vector3(a.x - b.x, a.y - b.y, a.z - b.z);
        public static Vector3 operator *(Vector3 a, float d) => new Vector3(a.x * d, a.y * d, a.z * d);
        public static Vector3 operator *(float d, Vector3 a) => a * d;
        public static bool operator ==(Vector3 a, Vector3 b) => (a - b).magnitude < 1e-5f;
        public static bool operator !=(Vector3 a, Vector3 b) => !(a == b);
        public override bool Equals(object other) => other is Vector3 v && Equals(v);
        public bool Equals(Vector3 other) => x == other.x && y == other.y && z == other.z;
        public override int GetHashCode() => x.GetHashCode() ^ (y.GetHashCode() << 2) ^ (z.GetHashCode() >> 2);
    }

    public struct Quaternion
    {
        public float x, y, z, w;
        public Quaternion(float x, float y, float z, float w) { this.x = x; this.y = y; this.z = z; this.w = w; }
        public static Quaternion identity => new Quaternion(0f, 0f, 0f, 1f);
        public static Quaternion Inverse(Quaternion rotation) => new Quaternion(-rotation.x, -rotation.y, -rotation.z, rotation.w);
        /// <summary>Unity's order: z, then x, then y (degrees).</summary>
        public static Quaternion Euler(float x, float y, float z)
        {
            Quaternion Axis(float deg, float ax, float ay, float az)
            {
                double h = deg * Math.PI / 360.0;
                float s = (float)Math.Sin(h);
                return new Quaternion(ax * s, ay * s, az * s, (float)Math.Cos(h));
            }
            return Axis(y, 0, 1, 0) * Axis(x, 1, 0, 0) * Axis(z, 0, 0, 1);
        }
        public static Quaternion operator *(Quaternion a, Quaternion b) => new Quaternion(
            a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y + a.y * b.w + a.z * b.x - a.x * b.z,
            a.w * b.z + a.z * b.w + a.x * b.y - a.y * b.x,
            a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z);
        public static Vector3 operator *(Quaternion rotation, Vector3 point)
        {
            Matrix4x4 m = Matrix4x4.TRS(Vector3.zero, rotation, Vector3.one);
            return m.MultiplyVector(point);
        }
    }

    public struct Matrix4x4
    {
        public float m00, m10, m20, m30, m01, m11, m21, m31, m02, m12, m22, m32, m03, m13, m23, m33;
        public static Matrix4x4 identity => new Matrix4x4 { m00 = 1f, m11 = 1f, m22 = 1f, m33 = 1f };
        public static Matrix4x4 TRS(Vector3 pos, Quaternion q, Vector3 s)
        {
            float x = q.x, y = q.y, z = q.z, w = q.w;
            return new Matrix4x4
            {
                m00 = (1 - 2 * (y * y + z * z)) * s.x, m01 = 2 * (x * y - z * w) * s.y, m02 = 2 * (x * z + y * w) * s.z, m03 = pos.x,
                m10 = 2 * (x * y + z * w) * s.x, m11 = (1 - 2 * (x * x + z * z)) * s.y, m12 = 2 * (y * z - x * w) * s.z, m13 = pos.y,
                m20 = 2 * (x * z - y * w) * s.x, m21 = 2 * (y * z + x * w) * s.y, m22 = (1 - 2 * (x * x + y * y)) * s.z, m23 = pos.z,
                m33 = 1f,
            };
        }
        internal static Matrix4x4 InverseTRS(Vector3 pos, Quaternion q, Vector3 s)
        {
            Matrix4x4 r = TRS(Vector3.zero, Quaternion.Inverse(q), Vector3.one);
            var inv = new Vector3(1f / s.x, 1f / s.y, 1f / s.z);
            Matrix4x4 m = new Matrix4x4
            {
                m00 = r.m00 * inv.x, m01 = r.m01 * inv.x, m02 = r.m02 * inv.x,
                m10 = r.m10 * inv.y, m11 = r.m11 * inv.y, m12 = r.m12 * inv.y,
                m20 = r.m20 * inv.z, m21 = r.m21 * inv.z, m22 = r.m22 * inv.z, m33 = 1f,
            };
            Vector3 t = m.MultiplyVector(pos);
            m.m03 = -t.x;
            m.m13 = -t.y;
            m.m23 = -t.z;
            return m;
        }
        public Vector3 MultiplyPoint3x4(Vector3 point) => new Vector3(
            m00 * point.x + m01 * point.y + m02 * point.z + m03,
            m10 * point.x + m11 * point.y + m12 * point.z + m13,
            m20 * point.x + m21 * point.y + m22 * point.z + m23);
        public Vector3 MultiplyVector(Vector3 vector) => new Vector3(
            m00 * vector.x + m01 * vector.y + m02 * vector.z,
            m10 * vector.x + m11 * vector.y + m12 * vector.z,
            m20 * vector.x + m21 * vector.y + m22 * vector.z);
    }

    public struct Color
    {
        public float r, g, b, a;
        public Color(float r, float g, float b) { this.r = r; this.g = g; this.b = b; a = 1f; }
        public Color(float r, float g, float b, float a) { this.r = r; this.g = g; this.b = b; this.a = a; }
    }

    public struct Bounds
    {
        private Vector3 m_Center, m_Size;
        public Vector3 center { get => m_Center; set => m_Center = value; }
        public Vector3 size { get => m_Size; set => m_Size = value; }
        public void SetMinMax(Vector3 min, Vector3 max)
        {
            m_Size = max - min;
            m_Center = min + m_Size * 0.5f;
        }
    }

    public struct Rect
    {
        private float m_X, m_Y, m_Width, m_Height;
        public Rect(float x, float y, float width, float height) { m_X = x; m_Y = y; m_Width = width; m_Height = height; }
        public float x { get => m_X; set => m_X = value; }
        public float y { get => m_Y; set => m_Y = value; }
        public float width { get => m_Width; set => m_Width = value; }
        public float height { get => m_Height; set => m_Height = value; }
    }

    public sealed class Camera : Behaviour
    {
        internal static Camera s_Main;
        private Rect m_PixelRect = new Rect(0f, 0f, 800f, 600f);
        private Matrix4x4 m_View = Matrix4x4.identity, m_Projection = Matrix4x4.identity;
        public static Camera main => s_Main;
        public Rect pixelRect { get => m_PixelRect; set => m_PixelRect = value; }
        public Matrix4x4 worldToCameraMatrix { get => m_View; set => m_View = value; }
        public Matrix4x4 projectionMatrix { get => m_Projection; set => m_Projection = value; }
    }

    public sealed class SystemInfo
    {
        public static Rendering.GraphicsDeviceType graphicsDeviceType => StandInHooks.Device;
    }

    public sealed class GL
    {
        public static void IssuePluginEvent(IntPtr callback, int eventID) => throw StandIn.No;
    }

    public class Physics
    {
        private static Vector3 s_Gravity = new Vector3(0f, -9.81f, 0f);
        public static Vector3 gravity { get => s_Gravity; set => s_Gravity = value; }
    }

    public class Time
    {
        public static float deltaTime => StandInHooks.DeltaTime;
        public static float fixedDeltaTime { get => StandInHooks.FixedDeltaTime; set => StandInHooks.FixedDeltaTime = value; }
        public static float unscaledTime => StandInHooks.UnscaledTime;
        public static float time => StandInHooks.Time;
        public static int frameCount => StandInHooks.FrameCount;
    }

    public class Application
    {
        public static bool isPlaying => true;
    }

    public class Debug
    {
        public static void Log(object message) { }
        public static void LogWarning(object message, Object context) => StandInHooks.Warnings.Add(message.ToString());
        public static void LogException(Exception exception, Object context) => StandInHooks.Exceptions.Add(exception);
    }

    public struct Mathf
    {
        public static float Max(float a, float b) => a > b ? a : b;
        public static int Max(int a, int b) => a > b ? a : b;
        public static float Min(float a, float b) => a < b ? a : b;
        public static float Abs(float f) => Math.Abs(f);
        public static float Lerp(float a, float b, float t) => a + (b - a) * Clamp01(t);
        public static float Sqrt(float f) => (float)Math.Sqrt(f);
        public static float PerlinNoise(float x, float y) => throw StandIn.No;
        public static float Clamp01(float value) => value < 0f ? 0f : value > 1f ? 1f : value;
        public static float Clamp(float value, float min, float max) => value < min ? min : value > max ? max : value;
        public static int Clamp(int value, int min, int max) => value < min ? min : value > max ? max : value;
    }

    public enum TouchPhase { Began = 0, Moved = 1, Stationary = 2, Ended = 3, Canceled = 4 }

    public struct Touch
    {
        internal Vector2 m_Position;
        public int fingerId => 0;
        public Vector2 position => m_Position;
        public Vector2 deltaPosition => throw StandIn.No;
        public TouchPhase phase => throw StandIn.No;
    }

    /// <summary>Legacy input: one touch at StandInHooks-set position when TouchDown.</summary>
    public class Input
    {
        internal static bool s_TouchDown;
        internal static Vector2 s_TouchPosition;
        public static int touchCount => s_TouchDown ? 1 : 0;
        public static Touch GetTouch(int index) => new Touch { m_Position = s_TouchPosition };
        public static bool mousePresent => false;
        public static Vector3 mousePosition => default;
        public static bool GetMouseButton(int button) => false;
    }

    public class GUIContent
    {
        internal string m_Text;
        public GUIContent(string text, string tooltip) => m_Text = text;
        public static GUIContent none = new GUIContent("", "");
    }

    public class GUIStyle { }

    public enum FocusType { Keyboard = 1, Passive = 2 }

    public enum EventType { MouseDown = 0, MouseUp = 1, MouseMove = 2, MouseDrag = 3, KeyDown = 4, KeyUp = 5, ScrollWheel = 6, Repaint = 7, Layout = 8 }

    public sealed class Event
    {
        public static Event current { get => throw StandIn.No; set => throw StandIn.No; }
        public EventType type { get => throw StandIn.No; set => throw StandIn.No; }
        public int button { get => throw StandIn.No; set => throw StandIn.No; }
        public Vector2 mousePosition { get => throw StandIn.No; set => throw StandIn.No; }
        public bool alt { get => throw StandIn.No; set => throw StandIn.No; }
        public void Use() => throw StandIn.No;
    }

    public class GUIUtility
    {
        public static int GetControlID(FocusType focus) => throw StandIn.No;
    }

    public class GUILayout
    {
        public static bool Button(string text, params GUILayoutOption[] options) => throw StandIn.No;
    }

    public class GUI
    {
        public static void Box(Rect position, GUIContent content) { }
        public static void Label(Rect position, string text) { }
    }

    public sealed class Gizmos
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
    public sealed class RequireComponent : Attribute
    {
        internal readonly Type m_Type;
        public RequireComponent(Type requiredComponent) => m_Type = requiredComponent;
    }

    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public sealed class SerializeField : Attribute { }

    [AttributeUsage(AttributeTargets.Class, AllowMultiple = false)]
    public class HelpURLAttribute : Attribute { public HelpURLAttribute(string url) { } }

    [AttributeUsage(AttributeTargets.Class)]
    public class DefaultExecutionOrder : Attribute { public DefaultExecutionOrder(int order) { } }

    public sealed class Screen
    {
        public static float dpi => StandInHooks.Dpi;
        public static int width => throw StandIn.No;
        public static int height => throw StandIn.No;
    }

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
                                         int stream = 0)
        {
            m_Attribute = attribute;
            m_Format = format;
            m_Dimension = dimension;
            m_Stream = stream;
        }
        private VertexAttribute m_Attribute;
        private VertexAttributeFormat m_Format;
        private int m_Dimension, m_Stream;
        public VertexAttribute attribute { get => m_Attribute; set => m_Attribute = value; }
        public VertexAttributeFormat format { get => m_Format; set => m_Format = value; }
        public int dimension { get => m_Dimension; set => m_Dimension = value; }
        public int stream { get => m_Stream; set => m_Stream = value; }
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
        public SubMeshDescriptor(int indexStart, int indexCount, MeshTopology topology = MeshTopology.Triangles)
        {
            m_IndexStart = indexStart;
            m_IndexCount = indexCount;
            m_Topology = topology;
        }
        private int m_IndexStart, m_IndexCount;
        private MeshTopology m_Topology;
        public int indexStart { get => m_IndexStart; set => m_IndexStart = value; }
        public int indexCount { get => m_IndexCount; set => m_IndexCount = value; }
        public MeshTopology topology { get => m_Topology; set => m_Topology = value; }
    }
}


namespace Unity.Collections
{
    public enum Allocator { Invalid = 0, None = 1, Temp = 2, TempJob = 3, Persistent = 4 }

    public enum NativeArrayOptions { UninitializedMemory = 0, ClearMemory = 1 }

    /// <summary>A pinned managed array stands for Unity's native memory (same indexing, a stable pointer).</summary>
    public struct NativeArray<T> : IDisposable where T : struct
    {
        internal T[] m_Array;
        internal System.Runtime.InteropServices.GCHandle m_Pin;

        public NativeArray(int length, Allocator allocator, NativeArrayOptions options = NativeArrayOptions.ClearMemory)
            : this(new T[length]) { }

        internal NativeArray(T[] array)
        {
            m_Array = array;
            m_Pin = System.Runtime.InteropServices.GCHandle.Alloc(array, System.Runtime.InteropServices.GCHandleType.Pinned);
        }

        public int Length => m_Array.Length;
        public bool IsCreated => m_Array != null && m_Pin.IsAllocated;
        public T this[int index] { get => m_Array[index]; set => m_Array[index] = value; }
        public void Dispose()
        {
            if (m_Pin.IsAllocated) m_Pin.Free();
            m_Array = null;
        }
        public static void Copy(NativeArray<T> src, NativeArray<T> dst) => Array.Copy(src.m_Array, dst.m_Array, src.Length);
    }
}

namespace Unity.Collections.LowLevel.Unsafe
{
    public static class NativeArrayUnsafeUtility
    {
        public static unsafe void* GetUnsafePtr<T>(this NativeArray<T> nativeArray) where T : struct =>
            (void*)nativeArray.m_Pin.AddrOfPinnedObject();
    }
}

namespace UnityEngine.Serialization
{
    [AttributeUsage(AttributeTargets.Field, AllowMultiple = true, Inherited = false)]
    public class FormerlySerializedAsAttribute : Attribute { public FormerlySerializedAsAttribute(string oldName) { } }
}
