using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using Drape.Core;
using Unity.Collections;
using Unity.Collections.LowLevel.Unsafe;
using UnityEngine;
using UnityEngine.Rendering;
using UnityEngine.Serialization;

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
        /// <summary>One step of Time.fixedDeltaTime per FixedUpdate, no interpolation (judders when the
        /// frame rate and the physics rate differ; colliders animated in Update are read a frame late).</summary>
        FixedUpdate = 0,
        /// <summary>In Update, as many fixed steps as the frame time holds (accumulator), no interpolation.</summary>
        FixedStepPerFrame = 1,
        /// <summary>In LateUpdate (after animation and scripts moved the colliders), as many fixed steps as
        /// the frame time holds; the mesh shows the state interpolated between the last two steps, so
        /// motion is smooth at any frame rate (CPU backends; the GPU backend shows the latest step).
        /// The default.</summary>
        LateUpdateInterpolated = 2,
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
    /// the cloth reacts to its motion with inertia. Colliders are pushed once per frame in one call.
    /// Every setting is a property: a change made while the cloth runs (from a script, or from the
    /// inspector in Play mode) is applied at the next step, and settings the native cloth is built
    /// from (shape, mass, backend, space) schedule a rebuild.</summary>
    [DisallowMultipleComponent]
    [RequireComponent(typeof(MeshFilter))]
    [AddComponentMenu("Drape/Drape Cloth")]
    [HelpURL(HelpUrl)]
    [DefaultExecutionOrder(ExecutionOrder)]
    public sealed class DrapeCloth : MonoBehaviour
    {
        /// <summary>The component's page of the package documentation (see <see cref="DrapeDocs"/>).</summary>
        public const string HelpUrl = DrapeDocs.Manual + "#drapecloth";

        /// <summary>After default-order scripts: their Update and LateUpdate have moved colliders,
        /// pins and the owner before the cloth steps in LateUpdate.</summary>
        public const int ExecutionOrder = 1000;

        /// <summary>Stiffness limits per model: mass-spring, XPBD and implicit in N/m per spring,
        /// PBD a fraction per iteration.</summary>
        public static float MaxStiffness(Model model) => model == Model.Pbd ? 1f : 100000f;

        // ---------------------------------------------------------------- serialized state
        [Header("Shape")]
        [Tooltip("Use the MeshFilter's mesh (Read/Write enabled) or generate a grid.")]
        [SerializeField, FormerlySerializedAs("Source")] private DrapeShapeSource _source = DrapeShapeSource.GeneratedGrid;
        [Tooltip("Grid vertices per row.")]
        [SerializeField, FormerlySerializedAs("Columns"), Range(2, 256)] private int _columns = 32;
        [Tooltip("Grid rows.")]
        [SerializeField, FormerlySerializedAs("Rows"), Range(2, 256)] private int _rows = 32;
        [Tooltip("Grid width (local X) and height (local -Y), metres.")]
        [SerializeField, FormerlySerializedAs("Size")] private Vector2 _size = new Vector2(1f, 1f);
        [Tooltip("Mesh vertices closer than this (m) are simulated as one: Unity splits vertices at UV seams.")]
        [SerializeField, FormerlySerializedAs("WeldDistance"), Range(0f, 0.01f)] private float _weldDistance = 0.0001f;

        [Header("Solver")]
        [Tooltip("Auto: the GPU (OpenGL ES 3) where it can run this cloth, else the CPU (threaded for large cloths). " +
                 "The inspector says which one runs and why.")]
        [SerializeField, FormerlySerializedAs("Backend")] private DrapeBackendChoice _backend = DrapeBackendChoice.Auto;
        [Tooltip("Auto (default): the model that rests where its springs balance gravity: implicit, on the CPU and the GPU. " +
                 "XPBD: stiffness in N/m, independent of step and iterations; rests softer than its springs. " +
                 "PBD: the paper's position-based model, stiffness is a fraction per iteration (0..1). " +
                 "Mass-spring: the paper's explicit springs; needs substeps when stiff. " +
                 "Implicit: implicit Euler on the same springs (N/m), rests exactly at their equilibrium, stable at any " +
                 "stiffness (the GPU stretches more in motion than the CPU, and lags more when stiff).")]
        [SerializeField, FormerlySerializedAs("Model")] private Model _model = Model.Auto;
        [Tooltip("Mass-spring, XPBD and implicit: stretch springs (grid neighbours, mesh edges), N/m per spring.")]
        [SerializeField, FormerlySerializedAs("StructuralStiffness")] private float _structuralStiffness = 2000f;
        [Tooltip("Mass-spring, XPBD and implicit: shear springs (grid diagonals), N/m per spring.")]
        [SerializeField, FormerlySerializedAs("ShearStiffness")] private float _shearStiffness = 1000f;
        [Tooltip("Mass-spring, XPBD and implicit: bend springs (two apart / across an edge), N/m per spring.")]
        [SerializeField, FormerlySerializedAs("BendStiffness")] private float _bendStiffness = 200f;
        [Tooltip("PBD: stiffness per group (structural, shear, bend) as a fraction per iteration, 0..1.")]
        [SerializeField] private Vector3 _pbdStiffness = new Vector3(1f, 0.8f, 0.3f);
        [Tooltip("Damping along each spring, N*s/m (paper eq. 2).")]
        [SerializeField, FormerlySerializedAs("Damping"), Range(0f, 10f)] private float _damping = 0.05f;
        [Tooltip("Mass of the whole cloth, kg, spread over the vertices by area.")]
        [SerializeField, FormerlySerializedAs("TotalMass"), Range(0.001f, 100f)] private float _totalMass = 0.5f;
        [Tooltip("Use Physics.gravity instead of the value below.")]
        [SerializeField, FormerlySerializedAs("UseUnityGravity")] private bool _useUnityGravity = true;
        [Tooltip("Gravity in world space, m/s^2.")]
        [SerializeField, FormerlySerializedAs("Gravity")] private Vector3 _gravity = new Vector3(0f, -9.81f, 0f);
        [Tooltip("Air velocity in world space, m/s.")]
        [SerializeField, FormerlySerializedAs("Wind")] private Vector3 _wind = Vector3.zero;
        [Tooltip("How fast the cloth takes on the wind's velocity, 1/s.")]
        [SerializeField, FormerlySerializedAs("AirDrag"), Range(0f, 10f)] private float _airDrag = 0.1f;
        [Tooltip("Substeps per step. 0 = automatic (mass-spring: from the stability bound; PBD/XPBD: 16; implicit: 2, on the GPU one per 1/960 s).")]
        [SerializeField, FormerlySerializedAs("Substeps"), Range(0, 64)] private int _substeps = 0;
        [Tooltip("Solver iterations per substep (PBD, XPBD, implicit). 0 = automatic (implicit: 4, on the GPU 3; PBD, XPBD: 1). " +
                 "More substeps beat more iterations at equal cost.")]
        [SerializeField, FormerlySerializedAs("Iterations"), Range(0, 32)] private int _iterations = 0;
        [Tooltip("Tethers: no vertex gets further than (1 + this) times its rest distance along the cloth from " +
                 "the nearest pin. Stops fine cloth from stretching like rubber. 0 = off.")]
        [SerializeField, FormerlySerializedAs("MaxStretch"), Range(0f, 1f)] private float _maxStretch = 0.1f;

        [Header("Pins")]
        [Tooltip("Which vertices are held in place (in the GameObject's local space).")]
        [SerializeField, FormerlySerializedAs("PinMode")] private DrapePinMode _pinMode = DrapePinMode.TopEdge;
        [Tooltip("Vertex indices pinned in Vertex List mode (pick them in the Scene view: Edit Pins in the inspector).")]
        [SerializeField, FormerlySerializedAs("PinnedVertices")] private List<int> _pinnedVertices = new List<int>();
        [Tooltip("Vertex Color mode: vertices whose red channel is above this are pinned.")]
        [SerializeField, FormerlySerializedAs("PinColorThreshold"), Range(0f, 1f)] private float _pinColorThreshold = 0.5f;

        [Header("Timing")]
        [Tooltip("Late Update Interpolated (default): fixed steps in LateUpdate, drawn interpolated. Fixed Update: one " +
                 "step per physics tick. Fixed Step Per Frame: fixed steps in Update.")]
        [SerializeField, FormerlySerializedAs("StepMode")] private DrapeStepMode _stepMode = DrapeStepMode.LateUpdateInterpolated;
        [Tooltip("Step length for the per-frame modes, seconds.")]
        [SerializeField, FormerlySerializedAs("FixedStep"), Range(0.001f, 0.05f)] private float _fixedStep = 1f / 60f;
        [Tooltip("Most steps one frame may take (per-frame modes); the rest of the time is dropped.")]
        [SerializeField, FormerlySerializedAs("MaxStepsPerFrame"), Range(1, 8)] private int _maxStepsPerFrame = 3;
        [Tooltip("Stop stepping while no camera renders the cloth (shadows and Scene view count).")]
        [SerializeField, FormerlySerializedAs("PauseWhenInvisible")] private bool _pauseWhenInvisible = true;
        [Tooltip("Sleep (stop stepping, no cost) when the fastest vertex stays below this speed, m/s, for Sleep Time; " +
                 "0 = never. Moving colliders, pins, drag, the owner or parameter changes wake it.")]
        [SerializeField, FormerlySerializedAs("SleepThreshold"), Range(0f, 0.5f)] private float _sleepThreshold = 0.01f;
        [Tooltip("Seconds the motion must stay below the sleep threshold before the cloth sleeps.")]
        [SerializeField, FormerlySerializedAs("SleepTime"), Range(0f, 10f)] private float _sleepTime = 1f;

        [Header("Space and owner")]
        [Tooltip("Local: the cloth lives in this GameObject's space and moves rigidly with it. " +
                 "World: the GameObject is the cloth's owner; pins follow it and the cloth swings with inertia (CPU only).")]
        [SerializeField, FormerlySerializedAs("SimulationSpace")] private DrapeSimulationSpace _simulationSpace = DrapeSimulationSpace.Local;
        [Tooltip("World space: how much of the owner's linear motion the free cloth resists (1 = fully world space, 0 = carried along).")]
        [SerializeField, FormerlySerializedAs("LinearInertia"), Range(0f, 1f)] private float _linearInertia = 1f;
        [Tooltip("World space: the same for the owner's rotation.")]
        [SerializeField, FormerlySerializedAs("AngularInertia"), Range(0f, 1f)] private float _angularInertia = 1f;
        [Tooltip("World space: a jump of the owner further than this (m) moves the cloth rigidly instead of stretching it.")]
        [SerializeField, FormerlySerializedAs("TeleportDistance"), Range(0.01f, 100f)] private float _teleportDistance = 1f;

        [Header("Self-collision")]
        [Tooltip("Keep the cloth from passing through itself where it folds or piles up. Costs extra work per " +
                 "step while on (off: none). CPU backends only: Auto then picks the CPU, the GPU backend refuses it.")]
        [SerializeField, FormerlySerializedAs("SelfCollision")] private bool _selfCollision = false;
        [Tooltip("Distance (m) kept between parts of the cloth that are not neighbours. Use about the particle " +
                 "spacing (generated grid: Size / (Columns - 1)). At most a quarter of the cloth's diagonal.")]
        [SerializeField, FormerlySerializedAs("SelfCollisionThickness"), Range(0.001f, 0.2f)] private float _selfCollisionThickness = 0.03f;
        [Tooltip("Friction between layers of the cloth sliding on each other (Coulomb coefficient); 0 = frictionless.")]
        [SerializeField, FormerlySerializedAs("SelfCollisionFriction"), Range(0f, 2f)] private float _selfCollisionFriction = 0.2f;

        [Header("Colliders")]
        [Tooltip("Unity colliders and planes the cloth collides with; their transforms are pushed every frame.")]
        [SerializeField, FormerlySerializedAs("Colliders")] private DrapeColliderSet _colliders = new DrapeColliderSet();

        // ---------------------------------------------------------------- properties
        public DrapeShapeSource Source { get => _source; set => SetRebuild(ref _source, value); }
        public int Columns { get => _columns; set => SetRebuild(ref _columns, Mathf.Clamp(value, 2, 256)); }
        public int Rows { get => _rows; set => SetRebuild(ref _rows, Mathf.Clamp(value, 2, 256)); }
        public Vector2 Size { get => _size; set => SetRebuild(ref _size, value); }
        public float WeldDistance { get => _weldDistance; set => SetRebuild(ref _weldDistance, Mathf.Clamp(value, 0f, 0.01f)); }
        public DrapeBackendChoice Backend { get => _backend; set => SetRebuild(ref _backend, value); }
        /// <summary>Kilograms, the whole cloth; a change rebuilds the cloth.</summary>
        public float TotalMass { get => _totalMass; set => SetRebuild(ref _totalMass, Mathf.Clamp(value, 0.001f, 100f)); }
        public DrapeSimulationSpace SimulationSpace { get => _simulationSpace; set => SetRebuild(ref _simulationSpace, value); }

        /// <summary>The model; each keeps its own stiffness values (N/m, or PBD's 0..1 fractions).</summary>
        public Model Model { get => _model; set => SetParams(ref _model, value); }
        /// <summary>The active model's structural stiffness: N/m per spring (mass-spring, XPBD) or PBD's fraction in [0, 1].</summary>
        public float StructuralStiffness { get => Stiffness(0); set => SetStiffness(0, value); }
        public float ShearStiffness { get => Stiffness(1); set => SetStiffness(1, value); }
        public float BendStiffness { get => Stiffness(2); set => SetStiffness(2, value); }
        public float Damping { get => _damping; set => SetParams(ref _damping, Mathf.Clamp(value, 0f, 10f)); }
        public bool UseUnityGravity { get => _useUnityGravity; set => SetParams(ref _useUnityGravity, value); }
        public Vector3 Gravity { get => _gravity; set => SetParams(ref _gravity, value); }
        public Vector3 Wind { get => _wind; set => SetParams(ref _wind, value); }
        public float AirDrag { get => _airDrag; set => SetParams(ref _airDrag, Mathf.Clamp(value, 0f, 10f)); }
        public int Substeps { get => _substeps; set => SetParams(ref _substeps, Mathf.Clamp(value, 0, 64)); }
        public int Iterations { get => _iterations; set => SetParams(ref _iterations, Mathf.Clamp(value, 0, 32)); }
        public float MaxStretch { get => _maxStretch; set => SetParams(ref _maxStretch, Mathf.Clamp(value, 0f, 1f)); }

        public DrapePinMode PinMode { get => _pinMode; set => SetPins(ref _pinMode, value); }
        public float PinColorThreshold { get => _pinColorThreshold; set => SetPins(ref _pinColorThreshold, Mathf.Clamp01(value)); }
        /// <summary>Vertex indices pinned in Vertex List mode. Change them with <see cref="SetPinnedVertices"/>,
        /// <see cref="AddPinnedVertex"/> or <see cref="TogglePinnedVertex"/> (applied at the next step).</summary>
        public IReadOnlyList<int> PinnedVertices => _pinnedVertices;

        public DrapeStepMode StepMode { get => _stepMode; set { _stepMode = value; _clock = 0f; } }
        public float FixedStep { get => _fixedStep; set => _fixedStep = Mathf.Clamp(value, 0.001f, 0.05f); }
        public int MaxStepsPerFrame { get => _maxStepsPerFrame; set => _maxStepsPerFrame = Mathf.Clamp(value, 1, 8); }
        public bool PauseWhenInvisible { get => _pauseWhenInvisible; set => _pauseWhenInvisible = value; }
        public float SleepThreshold { get => _sleepThreshold; set => SetSleep(ref _sleepThreshold, Mathf.Clamp(value, 0f, 0.5f)); }
        public float SleepTime { get => _sleepTime; set => SetSleep(ref _sleepTime, Mathf.Clamp(value, 0f, 10f)); }

        public float LinearInertia { get => _linearInertia; set => _linearInertia = Mathf.Clamp01(value); }
        public float AngularInertia { get => _angularInertia; set => _angularInertia = Mathf.Clamp01(value); }
        public float TeleportDistance { get => _teleportDistance; set => _teleportDistance = Mathf.Clamp(value, 0.01f, 100f); }

        public bool SelfCollision { get => _selfCollision; set => _selfCollision = value; }
        public float SelfCollisionThickness { get => _selfCollisionThickness; set => _selfCollisionThickness = Mathf.Clamp(value, 0.001f, 0.2f); }
        public float SelfCollisionFriction { get => _selfCollisionFriction; set => _selfCollisionFriction = Mathf.Clamp(value, 0f, 2f); }

        /// <summary>The colliders and planes; their lists and margins are read at every step.</summary>
        public DrapeColliderSet Colliders => _colliders;

        // ---------------------------------------------------------------- run-time state
        private NativeWorld _world;
        private NativeCloth _cloth;
        private Mesh _mesh;
        private Mesh _originalMesh;
        private NativeArray<DrapeVertex> _vertices;  // what the mesh shows
        private NativeArray<DrapeVertex> _previous;  // interpolation: the state one step back
        private NativeArray<DrapeVertex> _current;   // interpolation: the latest step
        private bool _haveCurrent;
        private Drape.Core.Pin[] _pins = new Drape.Core.Pin[0];
        private uint[] _pinnedIndices = new uint[0];
        private int _pinCount;
        private Vector3[] _restPositions;
        private Color[] _restColors;
        private MeshRenderer _renderer;
        private int _gridColumns; // the columns the native grid was built with (0: a mesh)

        private float _clock;
        private bool _paramsDirty = true;
        private bool _pinsDirty = true;
        private bool _sleepDirty = true;
        private bool _rebuildPending;
        private BuildKey _built;
        private bool _worldSpace;
        private int _sentColliders;
        private bool _collidersUnsupported;
        private bool _warnedTruncated;
        private bool _warnedUnstable;
        private int _unstableEvents;
        private Stats _lastStats;
        private SelfCollisionDesc _sentSelfCollision;    // what the native cloth has (a new cloth: off)
        private SelfCollisionDesc _refusedSelfCollision; // the last setting refused (warned once)
        private bool _selfCollisionRefused;

        // GPU path: the GL buffer name of stream 0; fetched again after the app resumes (an Android
        // GL context loss recreates Unity's buffers under new names).
        private uint _glBuffer;
        private bool _glRebindPending;

        private static readonly VertexLayout s_layout = new VertexLayout(24, 0, 12);

        /// <summary>The settings the native cloth is built from; a difference schedules a rebuild.</summary>
        private struct BuildKey
        {
            public DrapeShapeSource Source;
            public int Columns, Rows;
            public Vector2 Size;
            public float WeldDistance, TotalMass;
            public DrapeBackendChoice Backend;
            public DrapeSimulationSpace Space;

            public bool Same(in BuildKey o) =>
                Source == o.Source && Columns == o.Columns && Rows == o.Rows && Size == o.Size &&
                WeldDistance == o.WeldDistance && TotalMass == o.TotalMass && Backend == o.Backend && Space == o.Space;
        }

        /// <summary>The native cloth, or null while disabled.</summary>
        public NativeCloth NativeCloth => _cloth;

        /// <summary>Statistics of the last step (GPU backend: StepMs is the main thread's recording time per
        /// step, Substeps the setting (0 = automatic); strain and energy stay 0: the GPU state is not read back).</summary>
        public Stats LastStats => _lastStats;

        /// <summary>Vertices of the simulated mesh (0 while disabled).</summary>
        public int VertexCount => _cloth != null ? _cloth.VertexCount : 0;

        /// <summary>The backend the cloth actually runs on.</summary>
        public Drape.Core.Backend ActiveBackend { get; private set; }

        /// <summary>Why <see cref="ActiveBackend"/> is not the GPU (empty when it is, or when the CPU was asked for).</summary>
        public string BackendReason { get; private set; } = string.Empty;

        /// <summary>True while the native cloth sleeps (came to rest; steps do no work).</summary>
        public bool IsAsleep => _lastStats.Sleeping != 0;

        /// <summary>Times a step was rolled back as unstable since the cloth was built (logged once).</summary>
        public int UnstableEvents => _unstableEvents;

        /// <summary>True while a settings change waits for the rebuild at the next step.</summary>
        public bool RebuildPending => _rebuildPending;

        /// <summary>Simulation space -&gt; world: the matrix touch drag passes as drape_view.world.</summary>
        public Matrix4x4 SimulationToWorld => _worldSpace ? Matrix4x4.identity : transform.localToWorldMatrix;

        /// <summary>Pinned vertex indices in use (valid while enabled).</summary>
        public ReadOnlySpan<uint> ActivePins => new ReadOnlySpan<uint>(_pinnedIndices, 0, _pinCount);

        /// <summary>Rest positions (local) of the simulated mesh, for gizmos and pin picking.</summary>
        public Vector3[] RestPositions => _restPositions;

        /// <summary>Local vertex positions for pin authoring: the rest shape while the cloth runs, else
        /// the MeshFilter mesh's vertices (readable mesh source) or the grid's. Allocates: editor use.</summary>
        public Vector3[] AuthoringPositions()
        {
            if (_cloth != null && _restPositions != null) return _restPositions;
            var filter = GetComponent<MeshFilter>();
            Mesh mesh = filter != null ? filter.sharedMesh : null;
            if (_source == DrapeShapeSource.MeshFilterMesh && mesh != null && mesh.isReadable) return mesh.vertices;
            MakeGrid(_columns, _rows, _size, out Vector3[] positions, out _, out _);
            return positions;
        }

        // ---------------------------------------------------------------- setters
        private void SetRebuild<T>(ref T field, T value)
        {
            if (EqualityComparer<T>.Default.Equals(field, value)) return;
            field = value;
            if (_cloth != null) _rebuildPending = true;
        }

        private void SetParams<T>(ref T field, T value)
        {
            if (EqualityComparer<T>.Default.Equals(field, value)) return;
            field = value;
            _paramsDirty = true;
        }

        private void SetPins<T>(ref T field, T value)
        {
            if (EqualityComparer<T>.Default.Equals(field, value)) return;
            field = value;
            _pinsDirty = true;
        }

        private void SetSleep(ref float field, float value)
        {
            if (field == value) return;
            field = value;
            _sleepDirty = true;
        }

        private float Stiffness(int group)
        {
            if (_model == Model.Pbd) return _pbdStiffness[group];
            return group == 0 ? _structuralStiffness : group == 1 ? _shearStiffness : _bendStiffness;
        }

        private void SetStiffness(int group, float value)
        {
            value = Mathf.Clamp(value, 0f, MaxStiffness(_model));
            if (Stiffness(group) == value) return;
            if (_model == Model.Pbd) _pbdStiffness[group] = value;
            else if (group == 0) _structuralStiffness = value;
            else if (group == 1) _shearStiffness = value;
            else _bendStiffness = value;
            _paramsDirty = true;
        }

        /// <summary>Replaces the Vertex List pins (applied at the next step).</summary>
        public void SetPinnedVertices(IEnumerable<int> vertices)
        {
            _pinnedVertices.Clear();
            if (vertices != null) _pinnedVertices.AddRange(vertices);
            _pinsDirty = true;
        }

        /// <summary>Adds one Vertex List pin (no duplicate).</summary>
        public void AddPinnedVertex(int vertex)
        {
            if (vertex < 0 || _pinnedVertices.Contains(vertex)) return;
            _pinnedVertices.Add(vertex);
            _pinsDirty = true;
        }

        /// <summary>Pins the vertex if it is not in the Vertex List, else unpins it; returns true if it is pinned now.</summary>
        public bool TogglePinnedVertex(int vertex)
        {
            _pinsDirty = true;
            if (_pinnedVertices.Remove(vertex)) return false;
            if (vertex >= 0) _pinnedVertices.Add(vertex);
            return vertex >= 0;
        }

        /// <summary>Applies a fabric: mass from its areal density and the cloth's area, XPBD stiffness
        /// from its moduli (see <see cref="DrapeFabric"/>). Rebuilds if the mass changes.</summary>
        public void ApplyFabric(in DrapeFabric fabric)
        {
            float area = Source == DrapeShapeSource.GeneratedGrid || _restPositions == null
                ? Size.x * Size.y
                : DrapeFabric.MeshArea(_restPositions, _originalMesh != null && _originalMesh.isReadable ? _originalMesh.triangles : null);
            float spacing = Source == DrapeShapeSource.GeneratedGrid
                ? Mathf.Max(1e-4f, Mathf.Min(Size.x / Mathf.Max(1, Columns - 1), Size.y / Mathf.Max(1, Rows - 1)))
                : Mathf.Max(1e-4f, Mathf.Sqrt(area / Mathf.Max(1, _restPositions != null ? _restPositions.Length : Columns * Rows)));
            Model = Model.Xpbd;
            TotalMass = fabric.ArealDensity * Mathf.Max(1e-6f, area);
            StructuralStiffness = fabric.StretchStiffness;
            ShearStiffness = fabric.ShearStiffness;
            BendStiffness = fabric.BendSpringStiffness(spacing);
            Damping = fabric.Damping;
        }

        // ---------------------------------------------------------------- Unity messages
        private void Reset()
        {
            // Added to an object that already shows a readable mesh: simulate that mesh, not a grid.
            var filter = GetComponent<MeshFilter>();
            Mesh mesh = filter != null ? filter.sharedMesh : null;
            _source = mesh != null && mesh.isReadable ? DrapeShapeSource.MeshFilterMesh : DrapeShapeSource.GeneratedGrid;
        }

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
            // Editor only, may run off the main thread: only flag. The next step applies the change
            // (and rebuilds if a build setting differs from what the cloth was built with).
            _paramsDirty = true;
            _pinsDirty = true;
            _sleepDirty = true;
        }

        private void OnApplicationPause(bool paused)
        {
            if (!paused) _glRebindPending = true;
        }

        private void OnApplicationFocus(bool focused)
        {
            if (focused) _glRebindPending = true;
        }

        private void FixedUpdate()
        {
            if (_stepMode == DrapeStepMode.FixedUpdate) Simulate(Time.fixedDeltaTime, 1, false);
        }

        private void Update()
        {
            if (_stepMode != DrapeStepMode.FixedStepPerFrame) return;
            int steps = Advance(Time.deltaTime);
            if (steps > 0) Simulate(_fixedStep, steps, false);
        }

        private void LateUpdate()
        {
            if (_stepMode == DrapeStepMode.LateUpdateInterpolated)
            {
                int steps = Advance(Time.deltaTime);
                Simulate(_fixedStep, steps, true);
            }
            // One render event per frame runs every GLES cloth's recorded GL work on the render thread.
            if (_cloth != null && ActiveBackend == Drape.Core.Backend.Gles) DrapeSimulation.IssueRenderEvent();
        }

        /// <summary>The fixed-step accumulator of the per-frame modes: steps to take for a frame of
        /// <paramref name="frameDt"/> seconds; a backlog beyond MaxStepsPerFrame is dropped.</summary>
        internal int Advance(float frameDt)
        {
            return AdvanceClock(ref _clock, frameDt, _fixedStep, _maxStepsPerFrame);
        }

        /// <summary>Pure accumulator step (see <see cref="Advance"/>); afterwards clock / step is the
        /// interpolation fraction in [0, 1).</summary>
        internal static int AdvanceClock(ref float clock, float frameDt, float step, int maxSteps)
        {
            if (!(step > 0f)) return 0;
            if (frameDt > 0f) clock += frameDt;
            int steps = (int)(clock / step);
            if (steps > maxSteps)
            {
                steps = maxSteps;
                clock = 0f; // drop the backlog rather than spiral
            }
            else
            {
                clock -= steps * step;
                if (clock < 0f) clock = 0f;
            }
            return steps;
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

        private BuildKey CurrentBuildKey()
        {
            return new BuildKey
            {
                Source = _source, Columns = _columns, Rows = _rows, Size = _size, WeldDistance = _weldDistance,
                TotalMass = _totalMass, Backend = _backend, Space = _simulationSpace,
            };
        }

        private void Simulate(float dt, int steps, bool interpolate)
        {
            if (_cloth == null) return;
            if (_rebuildPending || (_paramsDirty && !CurrentBuildKey().Same(_built)))
            {
                // A build setting changed (setter, or the inspector in Play mode): rebuild now, between steps.
                Release();
                OnEnable();
                if (_cloth == null) return;
            }
            if (_pauseWhenInvisible && _renderer != null && !_renderer.isVisible) return;
            bool gpu = ActiveBackend == Drape.Core.Backend.Gles;
            interpolate = interpolate && _previous.IsCreated; // buffers exist if the cloth was built for it
            try
            {
                if (transform.hasChanged)
                {
                    transform.hasChanged = false;
                    if (!_worldSpace) _paramsDirty = true; // gravity and wind are re-expressed in local space
                }
                if (gpu && _glRebindPending) RebindGpuOutput();
                if (steps > 0)
                {
                    if (_pinsDirty) ApplyPins();
                    if (_paramsDirty) ApplyParams();
                    if (_sleepDirty) ApplySleep();
                    ApplySelfCollision();
                    if (_worldSpace) PushOwner();
                    PushColliders();

                    bool wasAsleep = _lastStats.Sleeping != 0;
                    if (gpu)
                    {
                        // drape_cloth_get_stats would read the GPU state back (and needs the render
                        // thread's context): report the main thread's recording time instead.
                        long t0 = System.Diagnostics.Stopwatch.GetTimestamp();
                        for (int i = 0; i < steps; ++i) _cloth.Step(dt);
                        long t1 = System.Diagnostics.Stopwatch.GetTimestamp();
                        _lastStats.StepMs = (float)((t1 - t0) * 1000.0 / System.Diagnostics.Stopwatch.Frequency / steps);
                        _lastStats.Substeps = (uint)Mathf.Max(0, _substeps);
                        _lastStats.Iterations = (uint)Mathf.Max(0, _iterations);
                        return; // the GPU writes the mesh's vertex buffer at the render event; nothing to read back
                    }
                    if (!interpolate)
                    {
                        for (int i = 0; i < steps; ++i) _cloth.Step(dt);
                        _lastStats = _cloth.GetStats();
                        if (wasAsleep && _lastStats.Sleeping != 0) return; // nothing moved: the mesh is current
                        ReadState(_vertices);
                        ShowVertices();
                        return;
                    }
                    // Interpolated: keep the states before and after the frame's last step.
                    for (int i = 0; i < steps - 1; ++i) _cloth.Step(dt);
                    if (steps > 1 || !_haveCurrent) ReadState(_previous);
                    else Swap(ref _previous, ref _current);
                    _cloth.Step(dt);
                    _lastStats = _cloth.GetStats();
                    ReadState(_current);
                    _haveCurrent = true;
                }
                if (interpolate && !gpu && _haveCurrent)
                {
                    float alpha = _fixedStep > 0f ? Mathf.Clamp01(_clock / _fixedStep) : 1f;
                    Interpolate(_previous, _current, _vertices, alpha);
                    ShowVertices();
                }
            }
            catch (DrapeException e) when (e.Status == Status.ErrorUnstable)
            {
                // The native side restored the last good state; keep going and say so, once.
                _unstableEvents++;
                if (!_warnedUnstable)
                {
                    _warnedUnstable = true;
                    Debug.LogWarning("Drape: " + name + ": " + e.NativeMessage + " (state rolled back; further " +
                                     "roll-backs are counted in UnstableEvents, not logged). Raise substeps or lower stiffness.", this);
                }
            }
            catch (Exception e)
            {
                Debug.LogException(e, this);
                enabled = false;
            }
        }

        private static void Swap(ref NativeArray<DrapeVertex> a, ref NativeArray<DrapeVertex> b)
        {
            NativeArray<DrapeVertex> t = a;
            a = b;
            b = t;
        }

        /// <summary>Positions lerped, normals lerped and renormalised: the state <paramref name="alpha"/>
        /// of the way from <paramref name="from"/> to <paramref name="to"/>.</summary>
        internal static void Interpolate(NativeArray<DrapeVertex> from, NativeArray<DrapeVertex> to,
                                         NativeArray<DrapeVertex> result, float alpha)
        {
            float beta = 1f - alpha;
            int n = result.Length;
            for (int i = 0; i < n; ++i)
            {
                DrapeVertex a = from[i], b = to[i];
                Vector3 normal = a.Normal * beta + b.Normal * alpha;
                float len = Mathf.Sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
                result[i] = new DrapeVertex
                {
                    Position = a.Position * beta + b.Position * alpha,
                    Normal = len > 1e-12f ? normal * (1f / len) : b.Normal,
                };
            }
        }

        private void ApplySleep()
        {
            _sleepDirty = false;
            _cloth.SetSleep(Mathf.Max(0f, _sleepThreshold), Mathf.Max(0f, _sleepTime));
        }

        /// <summary>Sends the self-collision fields when they changed (cheap when they did not, so
        /// edits from the inspector or from scripts apply at the next step). In Local space the cloth
        /// is simulated in the GameObject's units: the thickness (m) is divided by its mean scale. A
        /// refused setting (thickness above a quarter of the cloth's diagonal, GPU backend) is
        /// warned about once and leaves the previous one in place.</summary>
        private void ApplySelfCollision()
        {
            float thickness = Mathf.Max(0f, _selfCollisionThickness);
            if (!_worldSpace)
            {
                Vector3 sc = transform.lossyScale;
                thickness *= 3f / Mathf.Max(1e-6f, Mathf.Abs(sc.x) + Mathf.Abs(sc.y) + Mathf.Abs(sc.z));
            }
            var desc = new SelfCollisionDesc(_selfCollision, thickness, Mathf.Min(10f, Mathf.Max(0f, _selfCollisionFriction)));
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
                Debug.LogWarning("Drape: " + name + ": self-collision not applied: " + e.NativeMessage, this);
            }
        }

        private static bool SameSelfCollision(SelfCollisionDesc a, SelfCollisionDesc b) =>
            a.Enabled == b.Enabled && a.Thickness == b.Thickness && a.Friction == b.Friction;

        private void PushOwner()
        {
            Owner o = Owner.Default();
            o.Position = DrapeConvert.ToDrape(transform.position);
            o.Rotation = DrapeConvert.ToDrape(transform.rotation);
            o.LinearInertia = Mathf.Clamp01(_linearInertia);
            o.AngularInertia = Mathf.Clamp01(_angularInertia);
            o.TeleportDistance = Mathf.Max(0.001f, _teleportDistance);
            _cloth.SetOwner(o);
        }

        /// <summary>Every listed collider's current transform, in one native call (no allocation).</summary>
        private void PushColliders()
        {
            if (_collidersUnsupported) return;
            _colliders.Gather(_worldSpace ? null : transform);
            if (_colliders.Truncated && !_warnedTruncated)
            {
                _warnedTruncated = true;
                Debug.LogWarning("Drape: " + name + " lists more than " + NativeCloth.MaxColliders + " colliders; the rest are ignored.", this);
            }
            if (_colliders.Count == 0 && _sentColliders == 0) return;
            try
            {
                _cloth.SetColliders(_colliders.Records);
                _sentColliders = _colliders.Count;
            }
            catch (DrapeException e) when (e.Status == Status.ErrorBackendUnavailable)
            {
                _collidersUnsupported = true;
                Debug.LogWarning("Drape: " + name + ": colliders are not supported on backend " + ActiveBackend + ": " +
                                 e.NativeMessage, this);
            }
        }

        private unsafe void ReadState(NativeArray<DrapeVertex> into)
        {
            _cloth.Read(s_layout, NativeArrayUnsafeUtility.GetUnsafePtr(into), (long)into.Length * 24);
            if (!_worldSpace) return;
            // Simulated in world space; the renderer draws in the GameObject's space.
            Matrix4x4 toLocal = transform.worldToLocalMatrix;
            int count = into.Length;
            for (int i = 0; i < count; ++i)
            {
                DrapeVertex v = into[i];
                v.Position = toLocal.MultiplyPoint3x4(v.Position);
                v.Normal = toLocal.MultiplyVector(v.Normal).normalized;
                into[i] = v;
            }
        }

        private void ShowVertices()
        {
            int count = _vertices.Length;
            // Bounds from the shown positions (the renderer culls with them).
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

        /// <summary>True if the GLES backend can run this cloth here (see <see cref="ExplainBackend"/>).</summary>
        public bool GpuUsable() => ExplainGpu(SimulationSpace, SystemInfo.graphicsDeviceType, GlesInLibrary()) == null;

        private static bool GlesInLibrary()
        {
            try
            {
                return NativeWorld.IsBackendAvailable(Drape.Core.Backend.Gles);
            }
            catch (DrapeException)
            {
                return false;
            }
            catch (DllNotFoundException)
            {
                return false;
            }
        }

        /// <summary>Why the GLES backend cannot run a cloth with these settings on this device, in words;
        /// null if it can.</summary>
        public static string ExplainGpu(DrapeSimulationSpace space, GraphicsDeviceType device, bool glesInLibrary)
        {
            if (space != DrapeSimulationSpace.Local) return "World simulation space runs on the CPU only.";
            if (device != GraphicsDeviceType.OpenGLES3)
                return "the active graphics API is " + DeviceName(device) + ", not OpenGLES3. On Android, Unity lists Vulkan " +
                       "before OpenGLES3 by default: to run cloth on the GPU, put OpenGLES3 first (Player Settings > Other " +
                       "Settings > Graphics APIs) or uncheck Auto Graphics API.";
            if (!glesInLibrary) return "this build of the native library has no GLES backend.";
            return null;
        }

        private static string DeviceName(GraphicsDeviceType device)
        {
            switch (device)
            {
                case GraphicsDeviceType.Vulkan: return "Vulkan";
                case GraphicsDeviceType.Metal: return "Metal";
                case GraphicsDeviceType.Direct3D11: return "Direct3D11";
                case GraphicsDeviceType.Direct3D12: return "Direct3D12";
                case GraphicsDeviceType.OpenGLCore: return "OpenGLCore";
                case GraphicsDeviceType.OpenGLES3: return "OpenGLES3";
                case GraphicsDeviceType.Null: return "Null (batch mode)";
                default: return "graphics device " + (int)device;
            }
        }

        /// <summary>The backend a choice resolves to, and why it is not the GPU (empty when it is, or
        /// when the CPU was asked for).</summary>
        public static Drape.Core.Backend ResolveBackend(DrapeBackendChoice choice, int vertexCount, string gpuProblem,
                                                        out string reason)
        {
            Drape.Core.Backend cpu = vertexCount >= 2048 ? Drape.Core.Backend.CpuThreaded : Drape.Core.Backend.Cpu;
            reason = string.Empty;
            switch (choice)
            {
                case DrapeBackendChoice.Cpu:
                    return Drape.Core.Backend.Cpu;
                case DrapeBackendChoice.CpuThreaded:
                    return Drape.Core.Backend.CpuThreaded;
                default:
                    if (gpuProblem == null) return Drape.Core.Backend.Gles;
                    reason = (choice == DrapeBackendChoice.Gpu ? "GPU asked for, running on the CPU: " : "Auto chose the CPU: ") + gpuProblem;
                    return cpu;
            }
        }

        private Drape.Core.Backend ChooseBackend(int vertexCount)
        {
            string problem = _backend == DrapeBackendChoice.Cpu || _backend == DrapeBackendChoice.CpuThreaded
                ? null
                : ExplainGpu(_simulationSpace, SystemInfo.graphicsDeviceType, GlesInLibrary());
            Drape.Core.Backend b = ResolveBackend(_backend, vertexCount, problem, out string reason);
            BackendReason = reason;
            if (_backend == DrapeBackendChoice.Gpu && reason.Length > 0) Debug.LogWarning("Drape: " + name + ": " + reason, this);
            return b;
        }

        private void Build()
        {
            var filter = GetComponent<MeshFilter>();
            _renderer = GetComponent<MeshRenderer>();
            _originalMesh = filter.sharedMesh;

            bool grid = _source == DrapeShapeSource.GeneratedGrid || _originalMesh == null;
            Vector3[] positions;
            int[] simTriangles;
            if (grid)
            {
                MakeGrid(_columns, _rows, _size, out positions, out _, out simTriangles);
                _restColors = null;
            }
            else
            {
                if (!_originalMesh.isReadable)
                    throw new InvalidOperationException("Drape: mesh '" + _originalMesh.name +
                                                        "' is not readable; enable Read/Write in its import settings.");
                positions = _originalMesh.vertices;
                simTriangles = TriangleIndices(_originalMesh);
                _restColors = _originalMesh.colors;
            }
            _restPositions = positions;
            _gridColumns = grid ? _columns : 0;
            _worldSpace = _simulationSpace == DrapeSimulationSpace.World;
            Matrix4x4 toSim = _worldSpace ? transform.localToWorldMatrix : Matrix4x4.identity;

            _world = DrapeSimulation.Acquire();
            ActiveBackend = ChooseBackend(positions.Length);
            var desc = new ClothDesc { Backend = ActiveBackend, TotalMass = _totalMass };
            if (grid)
            {
                // The native grid path: the paper's 12-neighbour stencil (structural, shear, bend),
                // same vertex order as MakeGrid (r * columns + c).
                // In world space the grid's corner and edges are the transformed local ones.
                Vector3 u = toSim.MultiplyVector(new Vector3(_size.x, 0f, 0f));
                Vector3 v = toSim.MultiplyVector(new Vector3(0f, -_size.y, 0f));
                var gridDesc = new GridDesc
                {
                    Columns = (uint)_columns,
                    Rows = (uint)_rows,
                    Width = u.magnitude,
                    Height = v.magnitude,
                    Origin = DrapeConvert.ToDrape(toSim.MultiplyPoint3x4(new Vector3(-0.5f * _size.x, 0f, 0f))),
                    AxisU = DrapeConvert.ToDrape(u.normalized),
                    AxisV = DrapeConvert.ToDrape(v.normalized),
                };
                _cloth = NativeCloth.CreateGrid(_world, desc, gridDesc);
                _mesh = DrapeMeshBuilder.ForGrid(name, _columns, _rows, _size);
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
                _cloth = NativeCloth.CreateMesh(_world, desc, flat, simTriangles, _weldDistance);
                _mesh = DrapeMeshBuilder.CopyWithDynamicStream0(name, _originalMesh);
            }
            filter.sharedMesh = _mesh;

            _vertices = new NativeArray<DrapeVertex>(positions.Length, Allocator.Persistent);
            bool interpolated = _stepMode == DrapeStepMode.LateUpdateInterpolated && ActiveBackend != Drape.Core.Backend.Gles;
            if (interpolated)
            {
                _previous = new NativeArray<DrapeVertex>(positions.Length, Allocator.Persistent);
                _current = new NativeArray<DrapeVertex>(positions.Length, Allocator.Persistent);
            }
            _haveCurrent = false;
            _built = CurrentBuildKey();
            _rebuildPending = false;
            _paramsDirty = true;
            _pinsDirty = true;
            _sleepDirty = true;
            _sentColliders = 0;
            _collidersUnsupported = false;
            _warnedTruncated = false;
            _warnedUnstable = false;
            _unstableEvents = 0;
            _lastStats = default;
            _sentSelfCollision = default;
            _selfCollisionRefused = false;
            _clock = 0f;
            transform.hasChanged = false;
            ApplyPins();
            ApplyParams();
            ApplySelfCollision();
            ApplySleep();
            if (ActiveBackend == Drape.Core.Backend.Gles)
            {
                InitGpuOutput(positions);
            }
            else
            {
                if (_worldSpace) PushOwner(); // the first call only records the owner's pose
                ReadState(_vertices);
                if (interpolated)
                {
                    NativeArray<DrapeVertex>.Copy(_vertices, _current);
                    _haveCurrent = true;
                }
                ShowVertices();
            }
        }

        /// <summary>Every triangle-topology submesh's indices (base vertex applied), for the solver.</summary>
        private static int[] TriangleIndices(Mesh mesh)
        {
            int total = 0;
            for (int s = 0; s < mesh.subMeshCount; ++s)
                if (mesh.GetTopology(s) == MeshTopology.Triangles) total += (int)mesh.GetIndexCount(s);
            var all = new int[total];
            int at = 0;
            for (int s = 0; s < mesh.subMeshCount; ++s)
            {
                if (mesh.GetTopology(s) != MeshTopology.Triangles) continue;
                int[] t = mesh.GetTriangles(s);
                Array.Copy(t, 0, all, at, t.Length);
                at += t.Length;
            }
            return all;
        }

        /// <summary>GPU path (compile-checked against the Unity stand-ins only; not run in Unity yet).
        /// Stream 0's layout is fixed (position + normal, Float32, 24 bytes) and the mesh is dynamic;
        /// the rest shape is uploaded once, and the native side writes that buffer at every render
        /// event. The buffer name is fetched here and again after the application resumes.</summary>
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
            _glBuffer = 0;
            RebindGpuOutput();
        }

        /// <summary>Asks Unity for stream 0's GL buffer name and gives it to the native side if it
        /// changed (a lost GL context on Android recreates the buffer under a new name).</summary>
        private void RebindGpuOutput()
        {
            _glRebindPending = false;
            uint name = (uint)(ulong)_mesh.GetNativeVertexBufferPtr(0).ToInt64();
            if (name == _glBuffer) return;
            _glBuffer = name;
            _cloth.SetOutputBuffer(_glBuffer, s_layout);
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
            if (_previous.IsCreated) _previous.Dispose();
            if (_current.IsCreated) _current.Dispose();
            _haveCurrent = false;
            _pinCount = 0; // the pins belonged to the released cloth (a rebuilt one may have fewer vertices)
            _rebuildPending = false;
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
            p.Model = _model;
            p.Stiffness = new GroupValues(StructuralStiffness, ShearStiffness, BendStiffness);
            p.Damping = _damping;
            Vector3 g = _useUnityGravity ? Physics.gravity : _gravity;
            Vector3 w = _wind;
            if (!_worldSpace)
            {
                g = transform.InverseTransformDirection(g);
                w = transform.InverseTransformDirection(w);
            }
            p.Gravity = new Float3(g.x, g.y, g.z);
            p.Wind = new Float3(w.x, w.y, w.z);
            p.AirDrag = _airDrag;
            p.Substeps = (uint)Mathf.Max(0, _substeps);
            p.Iterations = (uint)Mathf.Max(0, _iterations);
            p.MaxStretch = Mathf.Max(0f, _maxStretch);
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
            _pinCount = SelectPins(_pinMode, _restPositions, _restColors, _gridColumns, _pinnedVertices, _pinColorThreshold,
                                   _pinnedIndices);
            // World space: pins at the rest shape as the owner holds it now; the owner moves them later.
            Matrix4x4 toSim = _worldSpace ? transform.localToWorldMatrix : Matrix4x4.identity;
            for (int k = 0; k < _pinCount; ++k)
            {
                Vector3 p = toSim.MultiplyPoint3x4(_restPositions[_pinnedIndices[k]]);
                _pins[k] = new Drape.Core.Pin(_pinnedIndices[k], new Float3(p.x, p.y, p.z));
            }
            if (_pinCount > 0) _cloth.SetPins(new Span<Drape.Core.Pin>(_pins, 0, _pinCount));
        }

        /// <summary>The pinned vertices for a mode, written to <paramref name="into"/> (length at least
        /// the vertex count); returns how many. <paramref name="gridColumns"/> &gt; 0: a generated grid.</summary>
        internal static int SelectPins(DrapePinMode mode, Vector3[] rest, Color[] colors, int gridColumns,
                                       List<int> list, float colorThreshold, uint[] into)
        {
            int n = rest.Length, count = 0;
            switch (mode)
            {
                case DrapePinMode.TopEdge:
                case DrapePinMode.Corners:
                {
                    if (gridColumns > 0 && mode == DrapePinMode.TopEdge)
                    {
                        for (int c = 0; c < gridColumns && c < n; ++c) into[count++] = (uint)c;
                        break;
                    }
                    float top = float.MinValue, bottom = float.MaxValue;
                    for (int i = 0; i < n; ++i)
                    {
                        top = Mathf.Max(top, rest[i].y);
                        bottom = Mathf.Min(bottom, rest[i].y);
                    }
                    float eps = Mathf.Max(1e-5f, (top - bottom) * 1e-3f);
                    int left = -1, right = -1;
                    for (int i = 0; i < n; ++i)
                    {
                        if (rest[i].y < top - eps) continue;
                        if (mode == DrapePinMode.TopEdge) into[count++] = (uint)i;
                        if (left < 0 || rest[i].x < rest[left].x) left = i;
                        if (right < 0 || rest[i].x > rest[right].x) right = i;
                    }
                    if (mode == DrapePinMode.Corners && left >= 0)
                    {
                        into[count++] = (uint)left;
                        if (right != left) into[count++] = (uint)right;
                    }
                    break;
                }
                case DrapePinMode.VertexList:
                    for (int k = 0; k < list.Count && count < n; ++k)
                    {
                        int v = list[k];
                        if (v < 0 || v >= n) continue;
                        bool seen = false;
                        for (int j = 0; j < count && !seen; ++j) seen = into[j] == (uint)v;
                        if (!seen) into[count++] = (uint)v;
                    }
                    break;
                case DrapePinMode.VertexColor:
                    if (colors != null && colors.Length == n)
                        for (int i = 0; i < n; ++i)
                            if (colors[i].r > colorThreshold) into[count++] = (uint)i;
                    break;
            }
            return count;
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
