// Enums mirroring drape.h; the values are part of the ABI. Keep in sync with drape.h
// (a test in tests/dotnet compares every value with the C enumerators).
namespace Drape.Core
{
    /// <summary>C twin: drape_status.</summary>
    public enum Status : int
    {
        Ok = 0,
        ErrorNullPointer = 1,
        ErrorInvalidHandle = 2,
        ErrorStructSize = 3,
        ErrorInvalidEnum = 4,
        ErrorInvalidArgument = 5,
        ErrorNotFinite = 6,
        ErrorIndexOutOfRange = 7,
        ErrorDegenerateMesh = 8,
        ErrorBufferTooSmall = 9,
        ErrorBackendUnavailable = 10,
        ErrorUnstable = 11,
        ErrorOutOfMemory = 12,
        ErrorGl = 13,
        ErrorInternal = 14,
    }

    /// <summary>C twin: drape_backend.</summary>
    public enum Backend : uint
    {
        /// <summary>One thread, deterministic.</summary>
        Cpu = 0,
        /// <summary>The world's worker pool; same results as Cpu.</summary>
        CpuThreaded = 1,
        /// <summary>OpenGL ES 3.0 transform feedback.</summary>
        Gles = 2,
    }

    /// <summary>C twin: drape_model.</summary>
    public enum Model : uint
    {
        /// <summary>Hooke springs + damping, Verlet (paper eq. 1-3).</summary>
        MassSpring = 0,
        /// <summary>Stretch constraints, stiffness in [0,1] (paper eq. 4-8).</summary>
        Pbd = 1,
        /// <summary>Compliance = 1/stiffness in physical units; the default.</summary>
        Xpbd = 2,
    }

    /// <summary>C twin: drape_group. Spring / constraint groups of the 12-neighbour stencil.</summary>
    public enum Group : uint
    {
        Structural = 0,
        Shear = 1,
        Bend = 2,
        Count = 3,
    }

    /// <summary>C twin: drape_collider_shape.</summary>
    public enum ColliderShape : uint
    {
        /// <summary>Size.X = radius (&gt; 0).</summary>
        Sphere = 0,
        /// <summary>Size.X = radius (&gt; 0), Size.Y = half length (&gt;= 0) of the segment along local y.</summary>
        Capsule = 1,
        /// <summary>Size = half extents (each &gt; 0), oriented by the rotation.</summary>
        Box = 2,
        /// <summary>Infinite; local +y points to the free side; Size ignored.</summary>
        Plane = 3,
    }
}
