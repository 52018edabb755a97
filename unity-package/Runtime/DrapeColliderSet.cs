using System;
using System.Collections.Generic;
using UnityEngine;

namespace Drape
{
    /// <summary>Kinds of collider shapes a cloth can register.</summary>
    public enum DrapeColliderKind
    {
        Sphere = 0,
        Capsule = 1,
        Box = 2,
        Plane = 3,
    }

    /// <summary>One collider in the cloth's local (simulation) space: what will be pushed to the
    /// native side in one call per frame. AWAITS NATIVE API: drape.h has no collider function yet
    /// (a later issue adds it); this layout is the C# side's proposal, to be mirrored by then.</summary>
    [Serializable]
    public struct DrapeColliderShape
    {
        public DrapeColliderKind Kind;
        /// <summary>Sphere/capsule: centre; box: centre; plane: a point on the plane.</summary>
        public Vector3 Center;
        /// <summary>Sphere and capsule radius (m).</summary>
        public float Radius;
        /// <summary>Capsule: half the segment between the sphere centres, along Axis (m).</summary>
        public float HalfHeight;
        /// <summary>Capsule axis / plane normal (unit).</summary>
        public Vector3 Axis;
        /// <summary>Box half extents (m) along the box's rotated axes.</summary>
        public Vector3 HalfExtents;
        public Quaternion Rotation;
    }

    /// <summary>Collects Unity's own colliders into <see cref="DrapeColliderShape"/>s, relative to a
    /// cloth's transform, into a preallocated array (no allocation per frame).</summary>
    [Serializable]
    public sealed class DrapeColliderSet
    {
        [Tooltip("SphereCollider, CapsuleCollider or BoxCollider components the cloth collides with.")]
        public List<Collider> Colliders = new List<Collider>();

        [Tooltip("Infinite planes: each Transform's position is on the plane, its up (+Y) is the normal.")]
        public List<Transform> Planes = new List<Transform>();

        private DrapeColliderShape[] _shapes = new DrapeColliderShape[0];

        /// <summary>Shapes gathered by the last <see cref="Gather"/>.</summary>
        public int Count { get; private set; }

        public DrapeColliderShape[] Shapes => _shapes;

        /// <summary>Fills <see cref="Shapes"/> in the space of <paramref name="simulationSpace"/>.
        /// Grows the array only when colliders were added. Unsupported collider types and disabled
        /// colliders are skipped.</summary>
        public void Gather(Transform simulationSpace)
        {
            int needed = Colliders.Count + Planes.Count;
            if (_shapes.Length < needed) _shapes = new DrapeColliderShape[needed];
            Matrix4x4 toLocal = simulationSpace.worldToLocalMatrix;
            Quaternion invRotation = Quaternion.Inverse(simulationSpace.rotation);
            int n = 0;
            for (int i = 0; i < Colliders.Count; ++i)
            {
                Collider c = Colliders[i];
                if (c == null || !c.enabled) continue;
                Transform t = c.transform;
                Vector3 scale = t.lossyScale;
                var s = new DrapeColliderShape { Rotation = invRotation * t.rotation };
                if (c is SphereCollider sphere)
                {
                    s.Kind = DrapeColliderKind.Sphere;
                    s.Center = toLocal.MultiplyPoint3x4(t.TransformPoint(sphere.center));
                    s.Radius = sphere.radius * Mathf.Max(Mathf.Abs(scale.x), Mathf.Max(Mathf.Abs(scale.y), Mathf.Abs(scale.z)));
                }
                else if (c is CapsuleCollider capsule)
                {
                    s.Kind = DrapeColliderKind.Capsule;
                    s.Center = toLocal.MultiplyPoint3x4(t.TransformPoint(capsule.center));
                    Vector3 axis = capsule.direction == 0 ? Vector3.right : capsule.direction == 1 ? Vector3.up : Vector3.forward;
                    s.Axis = toLocal.MultiplyVector(t.TransformDirection(axis)).normalized;
                    float axisScale = Mathf.Abs(capsule.direction == 0 ? scale.x : capsule.direction == 1 ? scale.y : scale.z);
                    float radiusScale = capsule.direction == 0 ? Mathf.Max(Mathf.Abs(scale.y), Mathf.Abs(scale.z))
                                      : capsule.direction == 1 ? Mathf.Max(Mathf.Abs(scale.x), Mathf.Abs(scale.z))
                                                               : Mathf.Max(Mathf.Abs(scale.x), Mathf.Abs(scale.y));
                    s.Radius = capsule.radius * radiusScale;
                    s.HalfHeight = Mathf.Max(0f, capsule.height * axisScale * 0.5f - s.Radius);
                }
                else if (c is BoxCollider box)
                {
                    s.Kind = DrapeColliderKind.Box;
                    s.Center = toLocal.MultiplyPoint3x4(t.TransformPoint(box.center));
                    s.HalfExtents = Vector3.Scale(box.size, scale) * 0.5f;
                }
                else
                {
                    continue; // MeshCollider, TerrainCollider...: not supported
                }
                _shapes[n++] = s;
            }
            for (int i = 0; i < Planes.Count; ++i)
            {
                Transform t = Planes[i];
                if (t == null) continue;
                _shapes[n++] = new DrapeColliderShape
                {
                    Kind = DrapeColliderKind.Plane,
                    Center = toLocal.MultiplyPoint3x4(t.position),
                    Axis = toLocal.MultiplyVector(t.up).normalized,
                    Rotation = invRotation * t.rotation,
                };
            }
            Count = n;
        }
    }
}
