// Blittable twins of the structs in plugin-native/include/drape/drape.h. Keep in sync with drape.h:
// same fields, same order, same types (tests/dotnet compares sizes and field offsets with the C
// compiler's). StructSize is set by the wrappers (World, Cloth) before every call; code using
// NativeMethods directly must set it from the matching SizeOf constant.
using System;
using System.Runtime.InteropServices;

namespace Drape.Core
{
    /// <summary>Three floats (C: float[3]). Units depend on the field.</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct Float3 : IEquatable<Float3>
    {
        public float X;
        public float Y;
        public float Z;

        public Float3(float x, float y, float z)
        {
            X = x;
            Y = y;
            Z = z;
        }

        public bool Equals(Float3 other) => X == other.X && Y == other.Y && Z == other.Z;
        public override bool Equals(object obj) => obj is Float3 other && Equals(other);
        public override int GetHashCode() => X.GetHashCode() ^ (Y.GetHashCode() << 2) ^ (Z.GetHashCode() >> 2);
        public override string ToString() => "(" + X + ", " + Y + ", " + Z + ")";
    }

    /// <summary>Two floats (C: float[2]): screen pixels or a viewport size.</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct Float2
    {
        public float X;
        public float Y;

        public Float2(float x, float y)
        {
            X = x;
            Y = y;
        }
    }

    /// <summary>Four floats (C: float[4]): a rotation quaternion x, y, z, w.</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct Float4
    {
        public float X;
        public float Y;
        public float Z;
        public float W;

        public Float4(float x, float y, float z, float w)
        {
            X = x;
            Y = y;
            Z = z;
            W = w;
        }

        /// <summary>The identity rotation (0, 0, 0, 1).</summary>
        public static Float4 IdentityRotation => new Float4(0f, 0f, 0f, 1f);
    }

    /// <summary>A 4x4 matrix (C: float[16]) in column-major memory order, as drape.h, OpenGL and
    /// Unity's Matrix4x4 store it: field Mrc is row r, column c, at index c*4 + r. Unity's
    /// Matrix4x4 has the same fields (m00, m10, m20, m30, m01, ...) in the same order.</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct Float4x4
    {
        public float M00, M10, M20, M30;
        public float M01, M11, M21, M31;
        public float M02, M12, M22, M32;
        public float M03, M13, M23, M33;

        public static Float4x4 Identity => new Float4x4 { M00 = 1f, M11 = 1f, M22 = 1f, M33 = 1f };

        /// <summary>Element at row <paramref name="row"/>, column <paramref name="column"/> (0..3).</summary>
        public unsafe float this[int row, int column]
        {
            get
            {
                if ((uint)row > 3 || (uint)column > 3) throw new ArgumentOutOfRangeException(nameof(row));
                fixed (float* m = &M00) return m[column * 4 + row];
            }
            set
            {
                if ((uint)row > 3 || (uint)column > 3) throw new ArgumentOutOfRangeException(nameof(row));
                fixed (float* m = &M00) m[column * 4 + row] = value;
            }
        }
    }

    /// <summary>One float per <see cref="Group"/> (C: float[DRAPE_GROUP_COUNT]).</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct GroupValues
    {
        public float Structural;
        public float Shear;
        public float Bend;

        public GroupValues(float structural, float shear, float bend)
        {
            Structural = structural;
            Shear = shear;
            Bend = bend;
        }
    }

    /// <summary>One count per <see cref="Group"/> (C: uint32_t[DRAPE_GROUP_COUNT]).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct GroupCounts
    {
        public uint Structural;
        public uint Shear;
        public uint Bend;
    }

    /// <summary>C twin: drape_world_desc.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct WorldDesc
    {
        public uint StructSize;
        /// <summary>Workers for CpuThreaded including the caller; 0 = hardware count.</summary>
        public uint ThreadCount;
    }

    /// <summary>C twin: drape_cloth_desc. Common to grid and mesh creation.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ClothDesc
    {
        public uint StructSize;
        public Backend Backend;
        /// <summary>kg, &gt; 0; spread over vertices by area.</summary>
        public float TotalMass;
    }

    /// <summary>C twin: drape_grid_desc. Vertex (c, r) is at Origin + AxisU*Width*c/(Columns-1)
    /// + AxisV*Height*r/(Rows-1); vertex index = r*Columns + c.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct GridDesc
    {
        public uint StructSize;
        /// <summary>Vertices per row, &gt;= 1 (Columns*Rows &gt;= 2).</summary>
        public uint Columns;
        /// <summary>&gt;= 1.</summary>
        public uint Rows;
        /// <summary>m, &gt; 0.</summary>
        public float Width;
        /// <summary>m, &gt; 0.</summary>
        public float Height;
        /// <summary>m, position of vertex (0,0).</summary>
        public Float3 Origin;
        /// <summary>Unit direction of increasing column; all zero = +x.</summary>
        public Float3 AxisU;
        /// <summary>Unit direction of increasing row; all zero = -z.</summary>
        public Float3 AxisV;
    }

    /// <summary>C twin: drape_mesh_desc. The pointers must stay valid for the duration of the
    /// create call only (the native side copies).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct MeshDesc
    {
        public uint StructSize;
        /// <summary>&gt;= 3.</summary>
        public uint VertexCount;
        /// <summary>const float*: VertexCount * 3 floats.</summary>
        public IntPtr Positions;
        /// <summary>Multiple of 3, &gt;= 3.</summary>
        public uint IndexCount;
        /// <summary>const uint32_t*: triangle list.</summary>
        public IntPtr Indices;
        /// <summary>m, &gt;= 0; 0 welds only bit-identical positions.</summary>
        public float WeldDistance;
    }

    /// <summary>C twin: drape_params. Settable at any time; <see cref="NativeWorld.DefaultParams"/> fills
    /// the library defaults.</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct Params
    {
        public uint StructSize;
        /// <summary>Default Xpbd.</summary>
        public Model Model;
        /// <summary>Per group. MassSpring, Xpbd: N/m per spring (0 = group off); Pbd: fraction in
        /// [0,1] per iteration. Default 2000, 1000, 200.</summary>
        public GroupValues Stiffness;
        /// <summary>N*s/m along each spring (eq. 2; Xpbd: constraint damping). Default 0.05.</summary>
        public float Damping;
        /// <summary>m/s^2. Default (0,-9.81,0).</summary>
        public Float3 Gravity;
        /// <summary>m/s, air velocity. Default 0.</summary>
        public Float3 Wind;
        /// <summary>1/s, a += AirDrag*(Wind - v). Default 0.1.</summary>
        public float AirDrag;
        /// <summary>Per step; 0 = automatic (MassSpring: from the stability bound; Pbd, Xpbd: 16).</summary>
        public uint Substeps;
        /// <summary>Solver iterations per substep (Pbd, Xpbd), &gt;= 1. Default 1.</summary>
        public uint Iterations;
        /// <summary>Tethers: every particle stays within (1 + MaxStretch) x its rest distance along the
        /// cloth to the nearest pinned particle. &gt;= 0; 0 = off. Default 0.1.</summary>
        public float MaxStretch;
    }

    /// <summary>C twin: drape_vertex_layout. Output goes to dst + i*Stride + offset for vertex i.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct VertexLayout
    {
        public uint StructSize;
        /// <summary>Bytes between vertices, &gt;= 12, multiple of 4.</summary>
        public uint Stride;
        /// <summary>Bytes, multiple of 4, or -1 = do not write.</summary>
        public int PositionOffset;
        /// <summary>Bytes, multiple of 4, or -1 = do not write.</summary>
        public int NormalOffset;

        public VertexLayout(uint stride, int positionOffset, int normalOffset)
        {
            StructSize = SizeOf.VertexLayout;
            Stride = stride;
            PositionOffset = positionOffset;
            NormalOffset = normalOffset;
        }
    }

    /// <summary>C twin: drape_pin. Pins a vertex (inverse mass 0) at a target; pinning again moves it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Pin
    {
        public uint StructSize;
        public uint Vertex;
        public Float3 Position;

        public Pin(uint vertex, Float3 position)
        {
            StructSize = SizeOf.Pin;
            Vertex = vertex;
            Position = position;
        }
    }

    /// <summary>C twin: drape_cloth_info.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ClothInfo
    {
        public uint StructSize;
        /// <summary>Caller vertices (before welding).</summary>
        public uint VertexCount;
        /// <summary>Simulated particles (after welding).</summary>
        public uint ParticleCount;
        /// <summary>Springs / constraints per group.</summary>
        public GroupCounts SpringCount;
        /// <summary>0 for a grid with a single row or column.</summary>
        public uint TriangleCount;
        public Backend Backend;
    }

    /// <summary>C twin: drape_stats. Describes the last step.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Stats
    {
        public uint StructSize;
        /// <summary>Wall time of the last step, ms.</summary>
        public float StepMs;
        public uint Substeps;
        public uint Iterations;
        /// <summary>Max over structural+shear springs of |l/L0 - 1|.</summary>
        public float MaxStrain;
        public float RmsStrain;
        /// <summary>J.</summary>
        public float KineticEnergy;
        /// <summary>J, gravity relative to y = 0.</summary>
        public float PotentialEnergy;
        /// <summary>J, springs (MassSpring, Xpbd); 0 for Pbd.</summary>
        public float ElasticEnergy;
        /// <summary>1 if the last step produced NaN/Inf (and was rolled back).</summary>
        public uint NonFinite;
        /// <summary>Steps rolled back since creation.</summary>
        public uint UnstableSteps;
        /// <summary>1 if the cloth is asleep (drape_sleep_desc): steps do no work.</summary>
        public uint Sleeping;
    }

    /// <summary>C twin: drape_collider. One element of the array given to
    /// <see cref="NativeCloth.SetColliders"/> (which sets StructSize).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ColliderDesc
    {
        public uint StructSize;
        public ColliderShape Shape;
        /// <summary>The host's stable id, unique in the array: a collider moves from the transform it
        /// had under the same id in the previous call, interpolated across the next step's substeps
        /// (no tunnelling); a new id starts at rest.</summary>
        public uint Id;
        /// <summary>m, simulation space. Plane: a point on it.</summary>
        public Float3 Position;
        /// <summary>Unit quaternion x, y, z, w (|q| within 1e-3 of 1). Capsule: its segment runs along
        /// the rotated local y; plane: the rotated +y points to the free side.</summary>
        public Float4 Rotation;
        /// <summary>m. Sphere: X = radius. Capsule: X = radius, Y = half length of the segment
        /// between the cap centres (Unity: max(0, height/2 - radius)). Box: half extents. Plane: unused.</summary>
        public Float3 Size;
        /// <summary>m, in [0, 10]: distance kept between cloth and surface. Typical 0.005.</summary>
        public float Margin;
        /// <summary>Coulomb coefficient in [0, 10]; 0 = frictionless. Typical 0.3-0.8.</summary>
        public float Friction;

        public static ColliderDesc Sphere(uint id, Float3 center, float radius, float margin = 0.005f, float friction = 0.5f) =>
            new ColliderDesc { StructSize = SizeOf.ColliderDesc, Shape = ColliderShape.Sphere, Id = id, Position = center,
                           Rotation = Float4.IdentityRotation, Size = new Float3(radius, 0f, 0f), Margin = margin,
                           Friction = friction };

        public static ColliderDesc Plane(uint id, Float3 point, Float4 rotation, float margin = 0.005f, float friction = 0.5f) =>
            new ColliderDesc { StructSize = SizeOf.ColliderDesc, Shape = ColliderShape.Plane, Id = id, Position = point,
                           Rotation = rotation, Margin = margin, Friction = friction };
    }

    /// <summary>C twin: drape_sleep_desc. A cloth whose fastest particle stays below Threshold for
    /// Time seconds of steps falls asleep (steps do no work) until something changes.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SleepDesc
    {
        public uint StructSize;
        /// <summary>m/s, in [0, 100]; 0 = never sleep. Typical 0.01.</summary>
        public float Threshold;
        /// <summary>s, in [0, 100]: how long motion must stay below Threshold. Typical 1.</summary>
        public float Time;
    }

    /// <summary>C twin: drape_view. How the cloth is seen, for touch drag and grabs. Matrices are
    /// column-major (Unity's Matrix4x4 memory order); OpenGL clip conventions (Unity: pass
    /// Camera.projectionMatrix, not GL.GetGPUProjectionMatrix).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct View
    {
        public uint StructSize;
        /// <summary>Simulation space -&gt; world (identity if the cloth simulates in world space).</summary>
        public Float4x4 World;
        /// <summary>World -&gt; camera (Unity: Camera.worldToCameraMatrix). C: `view` (a C# member
        /// cannot share its struct's name).</summary>
        public Float4x4 ViewMatrix;
        /// <summary>Camera -&gt; clip (Unity: Camera.projectionMatrix).</summary>
        public Float4x4 Projection;
        /// <summary>Pixels, width and height (&gt; 0); screen origin bottom-left.</summary>
        public Float2 Viewport;
    }

    /// <summary>C twin: drape_touch. One finger of a touch drag (paper eq. 9 with the exponent's sign
    /// restored): c = min(1, A exp(-r^2 / (2 sigma))), r = the vertex's screen distance (px) from
    /// Position; the vertex's screen position moves by c * Motion. <see cref="TouchPoint.Default"/> fills
    /// the library defaults.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct TouchPoint
    {
        public uint StructSize;
        /// <summary>px, where the finger was at the previous call (the touch point).</summary>
        public Float2 Position;
        /// <summary>px, finger motion since then.</summary>
        public Float2 Motion;
        /// <summary>A, &gt; 0. Default 200.</summary>
        public float Amplitude;
        /// <summary>px^2, &gt; 0. Default 300.</summary>
        public float Sigma;

        /// <summary>The library defaults (Position, Motion 0; A 200; sigma 300 px^2).</summary>
        public static TouchPoint Default()
        {
            NativeMethods.Check(NativeMethods.drape_touch_default(out TouchPoint t), "drape_touch_default");
            return t;
        }
    }

    /// <summary>C twin: drape_owner. The transform of the object the cloth hangs on, in simulation
    /// space: pins move rigidly with it; free vertices are carried along by (1 - inertia) of its
    /// motion. <see cref="Owner.Default"/> fills the library defaults.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Owner
    {
        public uint StructSize;
        /// <summary>m.</summary>
        public Float3 Position;
        /// <summary>Unit quaternion x, y, z, w.</summary>
        public Float4 Rotation;
        /// <summary>[0, 1], default 1: 0 carries the cloth fully (local space), 1 lets it lag (world space).</summary>
        public float LinearInertia;
        /// <summary>[0, 1], default 1.</summary>
        public float AngularInertia;
        /// <summary>m, &gt; 0, default 1: a jump further than this moves the cloth rigidly (velocities zeroed).</summary>
        public float TeleportDistance;

        /// <summary>The library defaults (identity transform, inertia 1, teleport distance 1 m).</summary>
        public static Owner Default()
        {
            NativeMethods.Check(NativeMethods.drape_owner_default(out Owner o), "drape_owner_default");
            return o;
        }
    }

    /// <summary>C twin: drape_self_collision_desc. Self-collision keeps particles of the cloth that are
    /// not neighbours in the rest mesh at least Thickness apart, so a cloth folding onto itself does
    /// not pass through itself. Off by default (no extra work). CPU backends only: enabling it on a
    /// GLES cloth is refused with ErrorBackendUnavailable. Set with <see cref="NativeCloth.SetSelfCollision(SelfCollisionDesc)"/>
    /// (which sets StructSize).</summary>
    [Serializable]
    [StructLayout(LayoutKind.Sequential)]
    public struct SelfCollisionDesc
    {
        public uint StructSize;
        /// <summary>1 = on, 0 = off (default); anything else is refused.</summary>
        public uint Enabled;
        /// <summary>m, distance kept between non-neighbour particles: &gt; 0 when enabled (&gt;= 0 when
        /// not), at most 1/4 of the diagonal of the cloth's rest bounding box. The particle spacing is a
        /// good value: well below it a particle can slip through a grid cell of another layer. Default 0.</summary>
        public float Thickness;
        /// <summary>Coulomb coefficient between layers in [0, 10]; 0 = frictionless (default). Typical 0.1-0.5.</summary>
        public float Friction;

        public SelfCollisionDesc(bool enabled, float thickness, float friction = 0f)
        {
            StructSize = SizeOf.SelfCollisionDesc;
            Enabled = enabled ? 1u : 0u;
            Thickness = thickness;
            Friction = friction;
        }

        /// <summary>True when <see cref="Enabled"/> is 1.</summary>
        public bool IsEnabled => Enabled != 0;
    }

    /// <summary>struct_size values (sizeof the C twin on this platform).</summary>
    public static class SizeOf
    {
        public static readonly uint WorldDesc = (uint)Marshal.SizeOf(typeof(WorldDesc));
        public static readonly uint ClothDesc = (uint)Marshal.SizeOf(typeof(ClothDesc));
        public static readonly uint GridDesc = (uint)Marshal.SizeOf(typeof(GridDesc));
        public static readonly uint MeshDesc = (uint)Marshal.SizeOf(typeof(MeshDesc));
        public static readonly uint Params = (uint)Marshal.SizeOf(typeof(Params));
        public static readonly uint VertexLayout = (uint)Marshal.SizeOf(typeof(VertexLayout));
        public static readonly uint Pin = (uint)Marshal.SizeOf(typeof(Pin));
        public static readonly uint ClothInfo = (uint)Marshal.SizeOf(typeof(ClothInfo));
        public static readonly uint Stats = (uint)Marshal.SizeOf(typeof(Stats));
        public static readonly uint ColliderDesc = (uint)Marshal.SizeOf(typeof(ColliderDesc));
        public static readonly uint SleepDesc = (uint)Marshal.SizeOf(typeof(SleepDesc));
        public static readonly uint View = (uint)Marshal.SizeOf(typeof(View));
        public static readonly uint TouchPoint = (uint)Marshal.SizeOf(typeof(TouchPoint));
        public static readonly uint Owner = (uint)Marshal.SizeOf(typeof(Owner));
        public static readonly uint SelfCollisionDesc = (uint)Marshal.SizeOf(typeof(SelfCollisionDesc));
    }
}
