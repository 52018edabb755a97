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
