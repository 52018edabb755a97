// Small blittable value types used by the struct twins (Structs.cs): C arrays float[2], float[3],
// float[4], float[16] and the per-group triples.
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

    /// <summary>One time per <see cref="Stage"/>, ms (C: float[DRAPE_STAGE_COUNT]).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct StageTimes
    {
        public float Begin;
        public float Predict;
        public float Solve;
        public float Tether;
        public float SelfCollide;
        public float Collide;
        public float Verify;
        public float Finish;
    }
}
