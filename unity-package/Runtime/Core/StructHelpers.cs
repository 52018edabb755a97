// Constructors and helpers of the struct twins. The fields are generated (Structs.cs, from
// tools/abi/abi.py); this half of each partial struct is written by hand.
namespace Drape.Core
{
    public partial struct VertexLayout
    {
        public VertexLayout(uint stride, int positionOffset, int normalOffset)
        {
            StructSize = SizeOf.VertexLayout;
            Stride = stride;
            PositionOffset = positionOffset;
            NormalOffset = normalOffset;
            Origin = default;  // positions in simulation space
        }
    }

    public partial struct Pin
    {
        public Pin(uint vertex, Float3 position)
        {
            StructSize = SizeOf.Pin;
            Vertex = vertex;
            Position = position;
        }
    }

    public partial struct MeshDesc
    {
        /// <summary>A mesh description over pinned arrays: xyz triples (positionFloats of them) and
        /// a triangle list. Unity's int indices are reinterpreted as uint32: a negative one becomes
        /// huge and is refused natively with ErrorIndexOutOfRange.</summary>
        internal static unsafe MeshDesc Pinned(float* positions, int positionFloats, int* indices, int indexCount,
                                               float weldDistance)
        {
            if (positionFloats % 3 != 0)
                throw new System.ArgumentException("positions holds xyz triples; length " + positionFloats +
                                                   " is not a multiple of 3", "positions");
            return new MeshDesc
            {
                StructSize = SizeOf.MeshDesc,
                VertexCount = (uint)(positionFloats / 3),
                Positions = (System.IntPtr)positions,
                IndexCount = (uint)indexCount,
                Indices = (System.IntPtr)indices,
                WeldDistance = weldDistance,
            };
        }
    }

    public partial struct ColliderDesc
    {
        public static ColliderDesc Sphere(uint id, Float3 center, float radius, float margin = 0.005f, float friction = 0.5f) =>
            new ColliderDesc { StructSize = SizeOf.ColliderDesc, Shape = ColliderShape.Sphere, Id = id, Position = center,
                               Rotation = Float4.IdentityRotation, Size = new Float3(radius, 0f, 0f), Margin = margin,
                               Friction = friction };

        public static ColliderDesc Plane(uint id, Float3 point, Float4 rotation, float margin = 0.005f, float friction = 0.5f) =>
            new ColliderDesc { StructSize = SizeOf.ColliderDesc, Shape = ColliderShape.Plane, Id = id, Position = point,
                               Rotation = rotation, Margin = margin, Friction = friction };
    }

    public partial struct TouchPoint
    {
        /// <summary>The library defaults (Position, Motion 0; A 200; sigma 300 px^2).</summary>
        public static TouchPoint Default()
        {
            NativeMethods.Check(NativeMethods.drape_touch_default(out TouchPoint t), "drape_touch_default");
            return t;
        }
    }

    public partial struct Owner
    {
        /// <summary>The library defaults (identity transform, inertia 1, teleport distance 1 m).</summary>
        public static Owner Default()
        {
            NativeMethods.Check(NativeMethods.drape_owner_default(out Owner o), "drape_owner_default");
            return o;
        }
    }

    public partial struct SelfCollisionDesc
    {
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
}
