using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using Drape.Core;
using Unity.Collections;
using Unity.Collections.LowLevel.Unsafe;
using UnityEngine;
using UnityEngine.Rendering;

namespace Drape
{
    /// <summary>Where the cloth's shape comes from.</summary>
    public enum DrapeShapeSource
    {
        /// <summary>The MeshFilter's mesh (must be Read/Write enabled).</summary>
        MeshFilterMesh = 0,
        /// <summary>A grid generated in the local XY plane, rows going down (-Y): a curtain.</summary>
        GeneratedGrid = 1,
    }

    /// <summary>Which solver runs the cloth.</summary>
    public enum DrapeBackendChoice
    {
        /// <summary>GPU where available, else threaded CPU for large cloths, else CPU.</summary>
        Auto = 0,
        Cpu = 1,
        CpuThreaded = 2,
        /// <summary>OpenGL ES 3 transform feedback writing straight into the mesh's vertex buffer
        /// (OpenGLES3 graphics device only, Local simulation space; else falls back to the CPU).</summary>
        Gpu = 3,
    }

    /// <summary>The space the cloth is simulated in.</summary>
    public enum DrapeSimulationSpace
    {
        /// <summary>The GameObject's local space: moving the object carries the cloth rigidly (no inertia).</summary>
        Local = 0,
        /// <summary>World space with the GameObject as the cloth's owner (drape_owner): pins follow it,
        /// the rest of the cloth lags and swings by the inertia settings. CPU backends only.</summary>
        World = 1,
    }

    /// <summary>Which vertices are pinned.</summary>
    public enum DrapePinMode
    {
        None = 0,
        /// <summary>Grid: row 0. Mesh: the vertices at the top (highest local Y).</summary>
        TopEdge = 1,
        /// <summary>The two ends of the top edge.</summary>
        Corners = 2,
        /// <summary>The vertex indices listed in Pinned Vertices.</summary>
        VertexList = 3,
        /// <summary>Vertices whose colour's red channel is above the threshold.</summary>
        VertexColor = 4,
    }

    /// <summary>When the cloth steps.</summary>
    public enum DrapeStepMode
    {
        /// <summary>One step of Time.fixedDeltaTime per FixedUpdate.</summary>
        FixedUpdate = 0,
        /// <summary>In Update, as many fixed steps as the frame time holds (accumulator).</summary>
        FixedStepPerFrame = 1,
    }

    /// <summary>The vertex the native side writes into the mesh's stream 0. Keep in sync with the
    /// VertexAttributeDescriptor list in <see cref="DrapeCloth"/> and VertexLayout(24, 0, 12).</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct DrapeVertex
    {
        public Vector3 Position;
        public Vector3 Normal;
    }

    /// <summary>Simulates this GameObject's mesh (or a generated grid) as cloth with Drape's native
    /// solver and renders the result through the MeshFilter. In Local simulation space gravity and
    /// wind are turned into the GameObject's space every step, so moving the object carries the cloth
    /// (and its pins) along rigidly; in World space the GameObject is the cloth's owner transform and
    /// the cloth reacts to its motion with inertia. Colliders are pushed once per frame in one call.</summary>
    [DisallowMultipleComponent]
    [RequireComponent(typeof(MeshFilter))]
    [AddComponentMenu("Drape/Drape Cloth")]
    public sealed class DrapeCloth : MonoBehaviour
    {
        [Header("Shape")]
        [Tooltip("Use the MeshFilter's mesh (Read/Write enabled) or generate a grid.")]
        public DrapeShapeSource Source = DrapeShapeSource.GeneratedGrid;

        [Tooltip("Grid vertices per row.")]
        [Range(2, 256)] public int Columns = 32;

        [Tooltip("Grid rows.")]
        [Range(2, 256)] public int Rows = 32;

        [Tooltip("Grid width (local X) and height (local -Y), metres.")]
        public Vector2 Size = new Vector2(1f, 1f);

        [Tooltip("Mesh vertices closer than this (m) are simulated as one: Unity splits vertices at UV seams.")]
        [Range(0f, 0.01f)] public float WeldDistance = 0.0001f;

        [Header("Solver")]
        [Tooltip("Auto: GPU where available, else CPU (threaded for large cloths).")]
        public DrapeBackendChoice Backend = DrapeBackendChoice.Auto;

        [Tooltip("XPBD: accurate, stiffness in N/m, independent of step and iterations (default). " +
                 "PBD: the paper's position-based model, stiffness is a fraction per iteration. " +
                 "Mass-spring: the paper's explicit springs; needs substeps when stiff.")]
        public Model Model = Model.Xpbd;

        [Tooltip("Stretch springs/constraints (grid neighbours, mesh edges). N/m per spring; PBD: 0..1.")]
        [Range(0f, 20000f)] public float StructuralStiffness = 2000f;

        [Tooltip("Shear springs (grid diagonals). N/m per spring; PBD: 0..1.")]
        [Range(0f, 20000f)] public float ShearStiffness = 1000f;

        [Tooltip("Bend springs (two apart / across an edge). N/m per spring; PBD: 0..1.")]
        [Range(0f, 20000f)] public float BendStiffness = 200f;

        [Tooltip("Damping along each spring, N*s/m (paper eq. 2).")]
        [Range(0f, 10f)] public float Damping = 0.05f;

        [Tooltip("Mass of the whole cloth, kg, spread over the vertices by area.")]
        [Range(0.001f, 100f)] public float TotalMass = 0.5f;

        [Tooltip("Use Physics.gravity instead of the value below.")]
        public bool UseUnityGravity = true;

        [Tooltip("Gravity in world space, m/s^2.")]
        public Vector3 Gravity = new Vector3(0f, -9.81f, 0f);

        [Tooltip("Air velocity in world space, m/s.")]
        public Vector3 Wind = Vector3.zero;

        [Tooltip("How fast the cloth takes on the wind's velocity, 1/s.")]
        [Range(0f, 10f)] public float AirDrag = 0.1f;

        [Tooltip("Substeps per step. 0 = automatic (mass-spring: from the stability bound; PBD/XPBD: 16).")]
        [Range(0, 64)] public int Substeps = 0;

        [Tooltip("Solver iterations per substep (PBD, XPBD). More substeps beat more iterations at equal cost.")]
        [Range(1, 32)] public int Iterations = 1;

        [Tooltip("Tethers: no vertex gets further than (1 + this) times its rest distance along the cloth from " +
                 "the nearest pin. Stops fine cloth from stretching like rubber. 0 = off.")]
        [Range(0f, 1f)] public float MaxStretch = 0.1f;

        [Header("Pins")]
        [Tooltip("Which vertices are held in place (in the GameObject's local space).")]
        public DrapePinMode PinMode = DrapePinMode.TopEdge;

        [Tooltip("Vertex indices pinned in Vertex List mode.")]
        public List<int> PinnedVertices = new List<int>();

        [Tooltip("Vertex Color mode: vertices whose red channel is above this are pinned.")]
        [Range(0f, 1f)] public float PinColorThreshold = 0.5f;

        [Header("Timing")]
        [Tooltip("FixedUpdate: one step per physics tick. Fixed Step Per Frame: fixed steps in Update from an accumulator.")]
        public DrapeStepMode StepMode = DrapeStepMode.FixedUpdate;

        [Tooltip("Step length for Fixed Step Per Frame, seconds.")]
        [Range(0.001f, 0.05f)] public float FixedStep = 1f / 60f;

        [Tooltip("Most steps one frame may take (Fixed Step Per Frame); the rest of the time is dropped.")]
        [Range(1, 8)] public int MaxStepsPerFrame = 3;

        [Tooltip("Stop stepping while no camera renders the cloth (shadows and Scene view count).")]
        public bool PauseWhenInvisible = true;

        [Tooltip("Sleep (stop stepping, no cost) when the fastest vertex stays below this speed, m/s, for Sleep Time; " +
                 "0 = never. Moving colliders, pins, drag, the owner or parameter changes wake it. CPU backends only.")]
        [Range(0f, 0.5f)] public float SleepThreshold = 0.01f;

        [Tooltip("Seconds the motion must stay below the sleep threshold before the cloth sleeps.")]
        [Range(0f, 10f)] public float SleepTime = 1f;

        [Header("Space and owner")]
        [Tooltip("Local: the cloth lives in this GameObject's space and moves rigidly with it. " +
                 "World: the GameObject is the cloth's owner; pins follow it and the cloth swings with inertia (CPU only).")]
        public DrapeSimulationSpace SimulationSpace = DrapeSimulationSpace.Local;

        [Tooltip("World space: how much of the owner's linear motion the free cloth resists (1 = fully world space, 0 = carried along).")]
        [Range(0f, 1f)] public float LinearInertia = 1f;

        [Tooltip("World space: the same for the owner's rotation.")]
        [Range(0f, 1f)] public float AngularInertia = 1f;

        [Tooltip("World space: a jump of the owner further than this (m) moves the cloth rigidly instead of stretching it.")]
        [Range(0.01f, 100f)] public float TeleportDistance = 1f;

        [Header("Self-collision")]
        [Tooltip("Keep the cloth from passing through itself where it folds or piles up. Costs extra work per " +
                 "step while on (off: none). CPU backends only: Auto then picks the CPU, the GPU backend refuses it.")]
        public bool SelfCollision = false;

        [Tooltip("Distance (m) kept between parts of the cloth that are not neighbours. Use about the particle " +
                 "spacing (generated grid: Size / (Columns - 1)): well below it, particles slip through the gaps " +
                 "between another layer's particles; well above it, folds puff up. At most a quarter of the cloth's diagonal.")]
        [Range(0.001f, 0.2f)] public float SelfCollisionThickness = 0.03f;

        [Tooltip("Friction between layers of the cloth sliding on each other (Coulomb coefficient); 0 = frictionless. " +
                 "Typical 0.1-0.5.")]
        [Range(0f, 2f)] public float SelfCollisionFriction = 0.2f;

        [Header("Colliders")]
        [Tooltip("Unity colliders and planes the cloth collides with; their transforms are pushed every frame.")]
        public DrapeColliderSet Colliders = new DrapeColliderSet();

        // Native objects and buffers.
        private NativeWorld _world;
        private NativeCloth _cloth;
        private Mesh _mesh;
        private Mesh _originalMesh;
        private NativeArray<DrapeVertex> _vertices;
        private Drape.Core.Pin[] _pins = new Drape.Core.Pin[0];
        private uint[] _pinnedIndices = new uint[0];
        private int _pinCount;
        private Vector3[] _restPositions;
        private Color[] _restColors;
        private MeshRenderer _renderer;

        private float _accumulator;
        private bool _paramsDirty = true;
        private bool _pinsDirty = true;
        private bool _sleepDirty = true;
        private bool _worldSpace;
        private int _sentColliders;
        private bool _collidersUnsupported;
        private bool _warnedTruncated;
        private Stats _lastStats;
        private SelfCollisionDesc _sentSelfCollision;    // what the native cloth has (a new cloth: off)
        private SelfCollisionDesc _refusedSelfCollision; // the last setting refused (warned once)
        private bool _selfCollisionRefused;

        // GPU path: the GL buffer name of stream 0, fetched once at init.
        private uint _glBuffer;

        private static readonly VertexLayout s_layout = new VertexLayout(24, 0, 12);

        /// <summary>The native cloth, or null while disabled.</summary>
        public NativeCloth NativeCloth => _cloth;

        /// <summary>Statistics of the last step.</summary>
        public Stats LastStats => _lastStats;

        /// <summary>Vertices of the simulated mesh (0 while disabled).</summary>
        public int VertexCount => _cloth != null ? _cloth.VertexCount : 0;

        /// <summary>The backend the cloth actually runs on.</summary>
        public Drape.Core.Backend ActiveBackend { get; private set; }

        /// <summary>True while the native cloth sleeps (came to rest; steps do no work).</summary>
        public bool IsAsleep => _lastStats.Sleeping != 0;

        /// <summary>Simulation space -&gt; world: the matrix touch drag passes as drape_view.world.</summary>
        public Matrix4x4 SimulationToWorld => _worldSpace ? Matrix4x4.identity : transform.localToWorldMatrix;

        /// <summary>Pinned vertex indices in use (valid while enabled).</summary>
        public ReadOnlySpan<uint> ActivePins => new ReadOnlySpan<uint>(_pinnedIndices, 0, _pinCount);

        /// <summary>Rest positions (local) of the simulated mesh, for gizmos.</summary>
        public Vector3[] RestPositions => _restPositions;

        private void OnEnable()
        {
            try
            {
                Build();
            }
            catch (Exception e)
            {
                Debug.LogException(e, this);
                Release();
                enabled = false;
            }
        }

        private void OnDisable() => Release();

        private void OnDestroy() => Release();

        private void OnValidate()
        {
            // May run off the main thread: only flag; the next step applies the change.
            _paramsDirty = true;
            _pinsDirty = true;
            _sleepDirty = true;
        }

        private void FixedUpdate()
        {
            if (StepMode == DrapeStepMode.FixedUpdate) Simulate(Time.fixedDeltaTime, 1);
        }

        private void Update()
        {
            if (StepMode != DrapeStepMode.FixedStepPerFrame) return;
            _accumulator += Time.deltaTime;
            int steps = (int)(_accumulator / FixedStep);
            if (steps > MaxStepsPerFrame)
            {
                steps = MaxStepsPerFrame;
                _accumulator = 0f; // drop the backlog rather than spiral
            }
            else
            {
                _accumulator -= steps * FixedStep;
            }
            if (steps > 0) Simulate(FixedStep, steps);
        }

        /// <summary>Wakes a sleeping cloth. Rarely needed: colliders, pins, drag, the owner and
        /// parameter changes wake it natively.</summary>
        public void WakeUp()
        {
            if (_cloth != null && ActiveBackend != Drape.Core.Backend.Gles) _cloth.Wake();
        }

        /// <summary>Marks parameters as changed: they are pushed before the next step.</summary>
        public void MarkParamsDirty()
        {
            _paramsDirty = true;
            WakeUp();
        }

        private void Simulate(float dt, int steps)
        {
            if (_cloth == null) return;
            if (PauseWhenInvisible && _renderer != null && !_renderer.isVisible) return;
            bool gpu = ActiveBackend == Drape.Core.Backend.Gles;
            try
            {
                if (transform.hasChanged)
                {
                    transform.hasChanged = false;
                    if (!_worldSpace) _paramsDirty = true; // gravity and wind are re-expressed in local space
                }
                if (_pinsDirty) ApplyPins();
                if (_paramsDirty) ApplyParams();
                if (_sleepDirty && !gpu) ApplySleep();
                ApplySelfCollision();
                if (_worldSpace) PushOwner();
                PushColliders();

                bool wasAsleep = _lastStats.Sleeping != 0;
                for (int i = 0; i < steps; ++i) _cloth.Step(dt);
                if (gpu) return; // the GPU wrote the mesh's vertex buffer; nothing to read back
                _lastStats = _cloth.GetStats();
                if (wasAsleep && _lastStats.Sleeping != 0) return; // nothing moved: the mesh is current
                WriteMesh();
            }
            catch (DrapeException e) when (e.Status == Status.ErrorUnstable)
            {
                // The native side restored the last good state; keep going and say so.
                Debug.LogWarning("Drape: " + name + ": " + e.NativeMessage + " (state rolled back). Raise substeps or lower stiffness.", this);
            }
            catch (Exception e)
            {
                Debug.LogException(e, this);
                enabled = false;
            }
        }

        private void ApplySleep()
        {
            _sleepDirty = false;
            _cloth.SetSleep(Mathf.Max(0f, SleepThreshold), Mathf.Max(0f, SleepTime));
        }

        /// <summary>Sends the self-collision fields when they changed (cheap when they did not, so
        /// edits from the inspector or from scripts apply at the next step). In Local space the cloth
        /// is simulated in the GameObject's units: the thickness (m) is divided by its mean scale. A
        /// refused setting (thickness above a quarter of the cloth's diagonal, GPU backend) is
        /// warned about once and leaves the previous one in place.</summary>
        private void ApplySelfCollision()
        {
            float thickness = Mathf.Max(0f, SelfCollisionThickness);
            if (!_worldSpace)
            {
                Vector3 sc = transform.lossyScale;
                thickness *= 3f / Mathf.Max(1e-6f, Mathf.Abs(sc.x) + Mathf.Abs(sc.y) + Mathf.Abs(sc.z));
            }
            var desc = new SelfCollisionDesc(SelfCollision, thickness, Mathf.Min(10f, Mathf.Max(0f, SelfCollisionFriction)));
            if (!desc.IsEnabled && !_sentSelfCollision.IsEnabled) return; // off either way: nothing to change
            if (SameSelfCollision(desc, _sentSelfCollision) || (_selfCollisionRefused && SameSelfCollision(desc, _refusedSelfCollision))) return;
            try
            {
                _cloth.SetSelfCollision(desc);
                _sentSelfCollision = desc;
                _selfCollisionRefused = false;
            }
            catch (DrapeException e)
            {
                _refusedSelfCollision = desc;
                _selfCollisionRefused = true;
                string hint = e.Status == Status.ErrorBackendUnavailable
                    ? " Self-collision runs on the CPU backends only: set Backend to Auto or CPU and re-enable the component."
                    : "";
                Debug.LogWarning("Drape: " + name + ": self-collision not applied: " + e.NativeMessage + hint, this);
            }
        }

        private static bool SameSelfCollision(SelfCollisionDesc a, SelfCollisionDesc b) =>
            a.Enabled == b.Enabled && a.Thickness == b.Thickness && a.Friction == b.Friction;

        private void PushOwner()
        {
            Owner o = Owner.Default();
            o.Position = DrapeConvert.ToDrape(transform.position);
            o.Rotation = DrapeConvert.ToDrape(transform.rotation);
            o.LinearInertia = Mathf.Clamp01(LinearInertia);
            o.AngularInertia = Mathf.Clamp01(AngularInertia);
            o.TeleportDistance = Mathf.Max(0.001f, TeleportDistance);
            _cloth.SetOwner(o);
        }

        /// <summary>Every listed collider's current transform, in one native call (no allocation).</summary>
        private void PushColliders()
        {
            if (_collidersUnsupported) return;
            Colliders.Gather(_worldSpace ? null : transform);
            if (Colliders.Truncated && !_warnedTruncated)
            {
                _warnedTruncated = true;
                Debug.LogWarning("Drape: " + name + " lists more than " + NativeCloth.MaxColliders + " colliders; the rest are ignored.", this);
            }
            if (Colliders.Count == 0 && _sentColliders == 0) return;
            try
            {
                _cloth.SetColliders(Colliders.Records);
                _sentColliders = Colliders.Count;
            }
            catch (DrapeException e) when (e.Status == Status.ErrorBackendUnavailable)
            {
                _collidersUnsupported = true;
                Debug.LogWarning("Drape: " + name + ": colliders are not supported on backend " + ActiveBackend + ": " +
                                 e.NativeMessage, this);
            }
        }

        private unsafe void WriteMesh()
        {
            int count = _vertices.Length;
            _cloth.Read(s_layout, NativeArrayUnsafeUtility.GetUnsafePtr(_vertices), (long)count * 24);
            if (_worldSpace)
            {
                // Simulated in world space; the renderer draws in the GameObject's space.
                Matrix4x4 toLocal = transform.worldToLocalMatrix;
                for (int i = 0; i < count; ++i)
                {
                    DrapeVertex v = _vertices[i];
                    v.Position = toLocal.MultiplyPoint3x4(v.Position);
                    v.Normal = toLocal.MultiplyVector(v.Normal).normalized;
                    _vertices[i] = v;
                }
            }
            // Bounds from the simulated positions (the renderer culls with them).
            Vector3 min = _vertices[0].Position, max = min;
            for (int i = 1; i < count; ++i)
            {
                Vector3 p = _vertices[i].Position;
                min = Vector3.Min(min, p);
                max = Vector3.Max(max, p);
            }
            const MeshUpdateFlags flags = MeshUpdateFlags.DontValidateIndices | MeshUpdateFlags.DontRecalculateBounds;
            _mesh.SetVertexBufferData(_vertices, 0, 0, count, 0, flags);
            var bounds = new Bounds();
            bounds.SetMinMax(min, max);
            _mesh.bounds = bounds;
        }

        /// <summary>True if the GLES backend can run this cloth here: an OpenGL ES 3 device (the
        /// native plug-in records on the main thread and runs GL at the render event), the library
        /// reports the backend available, and the cloth simulates in local space.</summary>
        public bool GpuUsable()
        {
            if (SimulationSpace != DrapeSimulationSpace.Local) return false;
            if (SystemInfo.graphicsDeviceType != GraphicsDeviceType.OpenGLES3) return false;
            try
            {
                return NativeWorld.IsBackendAvailable(Drape.Core.Backend.Gles);
            }
            catch (DrapeException)
            {
                return false;
            }
        }

        private Drape.Core.Backend ChooseBackend(int vertexCount)
        {
            Drape.Core.Backend cpu = vertexCount >= 2048 ? Drape.Core.Backend.CpuThreaded : Drape.Core.Backend.Cpu;
            switch (Backend)
            {
                case DrapeBackendChoice.Cpu:
                    return Drape.Core.Backend.Cpu;
                case DrapeBackendChoice.CpuThreaded:
                    return Drape.Core.Backend.CpuThreaded;
                case DrapeBackendChoice.Gpu:
                    if (GpuUsable()) return Drape.Core.Backend.Gles;
                    Debug.LogWarning("Drape: " + name + ": the GPU backend needs an OpenGL ES 3 device, a library built " +
                                     "with GLES and Local simulation space; running on the CPU.", this);
                    return cpu;
                default:
                    // Self-collision is CPU-only: with it on, Auto stays on the CPU.
                    return !SelfCollision && GpuUsable() ? Drape.Core.Backend.Gles : cpu;
            }
        }

        private void Build()
        {
            var filter = GetComponent<MeshFilter>();
            _renderer = GetComponent<MeshRenderer>();
            _originalMesh = filter.sharedMesh;

            Vector3[] positions;
            Vector2[] uvs;
            int[] triangles;
            if (Source == DrapeShapeSource.GeneratedGrid || _originalMesh == null)
            {
                MakeGrid(Columns, Rows, Size, out positions, out uvs, out triangles);
                _restColors = null;
            }
            else
            {
                if (!_originalMesh.isReadable)
                    throw new InvalidOperationException("Drape: mesh '" + _originalMesh.name +
                                                        "' is not readable; enable Read/Write in its import settings.");
                positions = _originalMesh.vertices;
                uvs = _originalMesh.uv;
                triangles = _originalMesh.triangles;
                _restColors = _originalMesh.colors;
            }
            _restPositions = positions;
            _worldSpace = SimulationSpace == DrapeSimulationSpace.World;
            Matrix4x4 toSim = _worldSpace ? transform.localToWorldMatrix : Matrix4x4.identity;

            _world = DrapeSimulation.Acquire();
            ActiveBackend = ChooseBackend(positions.Length);
            var desc = new ClothDesc { Backend = ActiveBackend, TotalMass = TotalMass };
            if (Source == DrapeShapeSource.GeneratedGrid || _originalMesh == null)
            {
                // The native grid path: the paper's 12-neighbour stencil (structural, shear, bend),
                // same vertex order as MakeGrid (r * columns + c).
                // In world space the grid's corner and edges are the transformed local ones.
                Vector3 u = toSim.MultiplyVector(new Vector3(Size.x, 0f, 0f));
                Vector3 v = toSim.MultiplyVector(new Vector3(0f, -Size.y, 0f));
                var grid = new GridDesc
                {
                    Columns = (uint)Columns,
                    Rows = (uint)Rows,
                    Width = u.magnitude,
                    Height = v.magnitude,
                    Origin = DrapeConvert.ToDrape(toSim.MultiplyPoint3x4(new Vector3(-0.5f * Size.x, 0f, 0f))),
                    AxisU = DrapeConvert.ToDrape(u.normalized),
                    AxisV = DrapeConvert.ToDrape(v.normalized),
                };
                _cloth = NativeCloth.CreateGrid(_world, desc, grid);
            }
            else
            {
                var flat = new float[positions.Length * 3];
                for (int i = 0; i < positions.Length; ++i)
                {
                    Vector3 p = toSim.MultiplyPoint3x4(positions[i]);
                    flat[3 * i] = p.x;
                    flat[3 * i + 1] = p.y;
                    flat[3 * i + 2] = p.z;
                }
                _cloth = NativeCloth.CreateMesh(_world, desc, flat, triangles, WeldDistance);
            }

            // Output mesh: stream 0 = position + normal (written by the native side every step),
            // stream 1 = UV (static).
            _mesh = new Mesh { name = "Drape " + name };
            _mesh.MarkDynamic();
            _mesh.SetVertexBufferParams(positions.Length,
                new VertexAttributeDescriptor(VertexAttribute.Position, VertexAttributeFormat.Float32, 3, 0),
                new VertexAttributeDescriptor(VertexAttribute.Normal, VertexAttributeFormat.Float32, 3, 0),
                new VertexAttributeDescriptor(VertexAttribute.TexCoord0, VertexAttributeFormat.Float32, 2, 1));
            if (uvs == null || uvs.Length != positions.Length) uvs = new Vector2[positions.Length];
            _mesh.SetVertexBufferData(uvs, 0, 0, uvs.Length, 1);
            _mesh.SetIndexBufferParams(triangles.Length, IndexFormat.UInt32);
            _mesh.SetIndexBufferData(triangles, 0, 0, triangles.Length);
            _mesh.subMeshCount = 1;
            _mesh.SetSubMesh(0, new SubMeshDescriptor(0, triangles.Length));
            filter.sharedMesh = _mesh;

            _vertices = new NativeArray<DrapeVertex>(positions.Length, Allocator.Persistent);
            _paramsDirty = true;
            _pinsDirty = true;
            _sleepDirty = true;
            _sentColliders = 0;
            _collidersUnsupported = false;
            _warnedTruncated = false;
            _lastStats = default;
            _sentSelfCollision = default;
            _selfCollisionRefused = false;
            transform.hasChanged = false;
            ApplyPins();
            ApplyParams();
            ApplySelfCollision();
            if (ActiveBackend == Drape.Core.Backend.Gles)
            {
                InitGpuOutput(positions);
            }
            else
            {
                ApplySleep();
                if (_worldSpace) PushOwner(); // the first call only records the owner's pose
                WriteMesh();
            }
        }

        /// <summary>GPU path (compile-checked against the Unity stand-ins only; not run in Unity yet).
        /// Stream 0's layout is fixed above (position + normal, Float32, 24 bytes) and the mesh is
        /// dynamic; the rest shape is uploaded once, the GL buffer name fetched once (it syncs with the
        /// render thread), and the native side writes that buffer at every render event.</summary>
        private void InitGpuOutput(Vector3[] positions)
        {
            for (int i = 0; i < positions.Length; ++i)
                _vertices[i] = new DrapeVertex { Position = positions[i], Normal = new Vector3(0f, 0f, 1f) };
            _mesh.SetVertexBufferData(_vertices, 0, 0, positions.Length, 0,
                                      MeshUpdateFlags.DontValidateIndices | MeshUpdateFlags.DontRecalculateBounds);
            // GPU writes are invisible to Unity's bounds: cover every pose the cloth can reach
            // (its rest box grown by its own diagonal on each side).
            Vector3 min = positions[0], max = min;
            for (int i = 1; i < positions.Length; ++i)
            {
                min = Vector3.Min(min, positions[i]);
                max = Vector3.Max(max, positions[i]);
            }
            var bounds = new Bounds();
            bounds.SetMinMax(min, max);
            float reach = bounds.size.magnitude;
            bounds.SetMinMax(min - Vector3.one * reach, max + Vector3.one * reach);
            _mesh.bounds = bounds;
            // Make sure the GPU buffer exists before asking for its name (defensive; see unity-notes §1).
            _mesh.UploadMeshData(false);
            _glBuffer = (uint)(ulong)_mesh.GetNativeVertexBufferPtr(0).ToInt64();
            _cloth.SetOutputBuffer(_glBuffer, s_layout);
        }

        private void LateUpdate()
        {
            // One render event per frame runs every GLES cloth's recorded GL work on the render thread.
            if (_cloth != null && ActiveBackend == Drape.Core.Backend.Gles) DrapeSimulation.IssueRenderEvent();
        }

        private void Release()
        {
            if (_cloth != null)
            {
                if (_glBuffer != 0)
                {
                    // Stop writing the mesh's buffer before the mesh goes: both are recorded, and the
                    // render event issued here runs them on the render thread ahead of the mesh's
                    // destruction (Unity keeps render-thread commands in order).
                    try
                    {
                        _cloth.SetOutputBuffer(0, s_layout);
                    }
                    catch (DrapeException e)
                    {
                        Debug.LogException(e, this);
                    }
                }
                _cloth.Dispose();
                _cloth = null;
                if (_glBuffer != 0) DrapeSimulation.IssueRenderEvent(force: true);
                _glBuffer = 0;
            }
            if (_world != null)
            {
                _world = null;
                DrapeSimulation.Release();
            }
            if (_vertices.IsCreated) _vertices.Dispose();
            if (_mesh != null)
            {
                var filter = GetComponent<MeshFilter>();
                if (filter != null && filter.sharedMesh == _mesh) filter.sharedMesh = _originalMesh;
                if (Application.isPlaying) Destroy(_mesh);
                else DestroyImmediate(_mesh);
                _mesh = null;
            }
        }

        private void ApplyParams()
        {
            _paramsDirty = false;
            Params p = NativeWorld.DefaultParams();
            p.Model = Model;
            p.Stiffness = new GroupValues(StructuralStiffness, ShearStiffness, BendStiffness);
            p.Damping = Damping;
            Vector3 g = UseUnityGravity ? Physics.gravity : Gravity;
            Vector3 w = Wind;
            if (!_worldSpace)
            {
                g = transform.InverseTransformDirection(g);
                w = transform.InverseTransformDirection(w);
            }
            p.Gravity = new Float3(g.x, g.y, g.z);
            p.Wind = new Float3(w.x, w.y, w.z);
            p.AirDrag = AirDrag;
            p.Substeps = (uint)Mathf.Max(0, Substeps);
            p.Iterations = (uint)Mathf.Max(1, Iterations);
            p.MaxStretch = Mathf.Max(0f, MaxStretch);
            _cloth.SetParams(p);
        }

        private void ApplyPins()
        {
            _pinsDirty = false;
            if (_pinCount > 0) _cloth.ReleasePins(new ReadOnlySpan<uint>(_pinnedIndices, 0, _pinCount));
            _pinCount = 0;
            int n = _restPositions.Length;
            if (_pinnedIndices.Length < n)
            {
                _pinnedIndices = new uint[n];
                _pins = new Drape.Core.Pin[n];
            }
            SelectPins();
            // World space: pins at the rest shape as the owner holds it now; the owner moves them later.
            Matrix4x4 toSim = _worldSpace ? transform.localToWorldMatrix : Matrix4x4.identity;
            for (int k = 0; k < _pinCount; ++k)
            {
                Vector3 p = toSim.MultiplyPoint3x4(_restPositions[_pinnedIndices[k]]);
                _pins[k] = new Drape.Core.Pin(_pinnedIndices[k], new Float3(p.x, p.y, p.z));
            }
            if (_pinCount > 0) _cloth.SetPins(new Span<Drape.Core.Pin>(_pins, 0, _pinCount));
        }

        private void SelectPins()
        {
            int n = _restPositions.Length;
            bool grid = Source == DrapeShapeSource.GeneratedGrid || _originalMesh == null;
            switch (PinMode)
            {
                case DrapePinMode.TopEdge:
                case DrapePinMode.Corners:
                {
                    float top = float.MinValue, bottom = float.MaxValue;
                    for (int i = 0; i < n; ++i)
                    {
                        top = Mathf.Max(top, _restPositions[i].y);
                        bottom = Mathf.Min(bottom, _restPositions[i].y);
                    }
                    float eps = Mathf.Max(1e-5f, (top - bottom) * 1e-3f);
                    if (grid && PinMode == DrapePinMode.TopEdge)
                    {
                        for (int c = 0; c < Columns; ++c) _pinnedIndices[_pinCount++] = (uint)c;
                        break;
                    }
                    int left = -1, right = -1;
                    for (int i = 0; i < n; ++i)
                    {
                        if (_restPositions[i].y < top - eps) continue;
                        if (PinMode == DrapePinMode.TopEdge) _pinnedIndices[_pinCount++] = (uint)i;
                        if (left < 0 || _restPositions[i].x < _restPositions[left].x) left = i;
                        if (right < 0 || _restPositions[i].x > _restPositions[right].x) right = i;
                    }
                    if (PinMode == DrapePinMode.Corners && left >= 0)
                    {
                        _pinnedIndices[_pinCount++] = (uint)left;
                        if (right != left) _pinnedIndices[_pinCount++] = (uint)right;
                    }
                    break;
                }
                case DrapePinMode.VertexList:
                    for (int k = 0; k < PinnedVertices.Count && _pinCount < n; ++k)
                    {
                        int v = PinnedVertices[k];
                        if (v >= 0 && v < n) _pinnedIndices[_pinCount++] = (uint)v;
                    }
                    break;
                case DrapePinMode.VertexColor:
                    if (_restColors != null && _restColors.Length == n)
                        for (int i = 0; i < n; ++i)
                            if (_restColors[i].r > PinColorThreshold) _pinnedIndices[_pinCount++] = (uint)i;
                    break;
            }
        }

        /// <summary>A Columns x Rows grid in the local XY plane, centred on X, hanging from y = 0
        /// down to y = -Size.y; two triangles per cell.</summary>
        internal static void MakeGrid(int columns, int rows, Vector2 size, out Vector3[] positions, out Vector2[] uvs,
                                      out int[] triangles)
        {
            positions = new Vector3[columns * rows];
            uvs = new Vector2[columns * rows];
            for (int r = 0; r < rows; ++r)
            for (int c = 0; c < columns; ++c)
            {
                float u = c / (float)(columns - 1), v = r / (float)(rows - 1);
                positions[r * columns + c] = new Vector3((u - 0.5f) * size.x, -v * size.y, 0f);
                uvs[r * columns + c] = new Vector2(u, 1f - v);
            }
            triangles = new int[(columns - 1) * (rows - 1) * 6];
            int t = 0;
            for (int r = 0; r + 1 < rows; ++r)
            for (int c = 0; c + 1 < columns; ++c)
            {
                int i = r * columns + c;
                triangles[t++] = i;
                triangles[t++] = i + 1;
                triangles[t++] = i + columns;
                triangles[t++] = i + 1;
                triangles[t++] = i + columns + 1;
                triangles[t++] = i + columns;
            }
        }
    }
}
