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

    /// <summary>C twin: drape_params. Settable at any time; <see cref="Cloth.DefaultParams"/> fills
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
    }
}
