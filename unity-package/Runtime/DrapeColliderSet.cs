using System;
using System.Collections.Generic;
using Drape.Core;
using UnityEngine;

namespace Drape
{
    /// <summary>Unity's own colliders (SphereCollider, CapsuleCollider, BoxCollider) and planes a
    /// cloth collides with. <see cref="Gather"/> turns them into drape_collider records in the cloth's
    /// simulation space, in a preallocated array (no allocation per frame), for one
    /// drape_cloth_set_colliders call per frame.</summary>
    [Serializable]
    public sealed class DrapeColliderSet
    {
        [Tooltip("SphereCollider, CapsuleCollider or BoxCollider components the cloth collides with " +
                 "(other collider types are skipped). At most 64 colliders and planes in all.")]
        public List<UnityEngine.Collider> Colliders = new List<UnityEngine.Collider>();

        [Tooltip("Infinite planes: each Transform's position is on the plane, its up (+Y) points to the free side.")]
        public List<Transform> Planes = new List<Transform>();

        [Tooltip("Distance kept between the cloth and every collider surface, metres (cloth thickness plus skin).")]
        [Range(0f, 0.1f)] public float Margin = 0.005f;

        [Tooltip("Coulomb friction between the cloth and the colliders; 0 = frictionless.")]
        [Range(0f, 2f)] public float Friction = 0.5f;

        // Capsule: drape's segment runs along local y; Unity's along x, y or z (direction 0, 1, 2).
        private static readonly Quaternion s_yToX = new Quaternion(0f, 0f, -0.70710677f, 0.70710677f);
        private static readonly Quaternion s_yToZ = new Quaternion(0.70710677f, 0f, 0f, 0.70710677f);

        private readonly Drape.Core.ColliderDesc[] _records = new Drape.Core.ColliderDesc[NativeCloth.MaxColliders];

        /// <summary>Records filled by the last <see cref="Gather"/>.</summary>
        public int Count { get; private set; }

        /// <summary>True if the last Gather had to drop colliders beyond <see cref="NativeCloth.MaxColliders"/>.</summary>
        public bool Truncated { get; private set; }

        /// <summary>The records of the last <see cref="Gather"/> (the first <see cref="Count"/>).</summary>
        public Span<Drape.Core.ColliderDesc> Records => new Span<Drape.Core.ColliderDesc>(_records, 0, Count);

        /// <summary>Fills <see cref="Records"/> with the current transforms, in the space of
        /// <paramref name="simulationSpace"/> (null: world space). Disabled, missing, duplicate and
        /// unsupported colliders are skipped. The simulation space should be uniformly scaled
        /// (sizes are divided by its mean scale). Ids are the components' instance ids, so each
        /// collider's motion from the previous frame is swept by the native side.</summary>
        public void Gather(Transform simulationSpace)
        {
            Matrix4x4 toSim = simulationSpace != null ? simulationSpace.worldToLocalMatrix : Matrix4x4.identity;
            Quaternion invRotation = simulationSpace != null ? Quaternion.Inverse(simulationSpace.rotation) : Quaternion.identity;
            float invScale = 1f;
            if (simulationSpace != null)
            {
                Vector3 s = simulationSpace.lossyScale;
                invScale = 3f / Mathf.Max(1e-6f, Mathf.Abs(s.x) + Mathf.Abs(s.y) + Mathf.Abs(s.z));
            }
            int n = 0;
            Truncated = false;
            for (int i = 0; i < Colliders.Count; ++i)
            {
                UnityEngine.Collider c = Colliders[i];
                if (c == null || !c.enabled || !c.gameObject.activeInHierarchy) continue;
                if (n == _records.Length)
                {
                    Truncated = true;
                    break;
                }
                uint id = StableId(c);
                if (Contains(n, id)) continue;
                Transform t = c.transform;
                Vector3 scale = t.lossyScale;
                float ax = Mathf.Abs(scale.x), ay = Mathf.Abs(scale.y), az = Mathf.Abs(scale.z);
                Quaternion rotation = invRotation * t.rotation;
                Vector3 center, size;
                ColliderShape shape;
                if (c is SphereCollider sphere)
                {
                    shape = ColliderShape.Sphere;
                    center = t.TransformPoint(sphere.center);
                    size = new Vector3(sphere.radius * Mathf.Max(ax, Mathf.Max(ay, az)) * invScale, 0f, 0f);
                }
                else if (c is CapsuleCollider capsule)
                {
                    shape = ColliderShape.Capsule;
                    center = t.TransformPoint(capsule.center);
                    float axisScale, radiusScale;
                    if (capsule.direction == 0)
                    {
                        axisScale = ax;
                        radiusScale = Mathf.Max(ay, az);
                        rotation = rotation * s_yToX;
                    }
                    else if (capsule.direction == 2)
                    {
                        axisScale = az;
                        radiusScale = Mathf.Max(ax, ay);
                        rotation = rotation * s_yToZ;
                    }
                    else
                    {
                        axisScale = ay;
                        radiusScale = Mathf.Max(ax, az);
                    }
                    float radius = capsule.radius * radiusScale;
                    // drape.h: half length of the segment between the cap centres = max(0, height/2 - radius).
                    float halfLength = Mathf.Max(0f, capsule.height * axisScale * 0.5f - radius);
                    size = new Vector3(radius * invScale, halfLength * invScale, 0f);
                }
                else if (c is BoxCollider box)
                {
                    shape = ColliderShape.Box;
                    center = t.TransformPoint(box.center);
                    size = new Vector3(Mathf.Abs(box.size.x) * ax, Mathf.Abs(box.size.y) * ay, Mathf.Abs(box.size.z) * az) *
                           (0.5f * invScale);
                }
                else
                {
                    continue; // MeshCollider, TerrainCollider...: not supported
                }
                _records[n++] = new Drape.Core.ColliderDesc
                {
                    StructSize = SizeOf.ColliderDesc,
                    Shape = shape,
                    Id = id,
                    Position = DrapeConvert.ToDrape(toSim.MultiplyPoint3x4(center)),
                    Rotation = DrapeConvert.ToDrape(rotation),
                    Size = DrapeConvert.ToDrape(size),
                    Margin = Margin * invScale,
                    Friction = Friction,
                };
            }
            for (int i = 0; i < Planes.Count; ++i)
            {
                Transform t = Planes[i];
                if (t == null || !t.gameObject.activeInHierarchy) continue;
                if (n == _records.Length)
                {
                    Truncated = true;
                    break;
                }
                uint id = StableId(t);
                if (Contains(n, id)) continue;
                _records[n++] = new Drape.Core.ColliderDesc
                {
                    StructSize = SizeOf.ColliderDesc,
                    Shape = ColliderShape.Plane,
                    Id = id,
                    Position = DrapeConvert.ToDrape(toSim.MultiplyPoint3x4(t.position)),
                    Rotation = DrapeConvert.ToDrape(invRotation * t.rotation),
                    Margin = Margin * invScale,
                    Friction = Friction,
                };
            }
            Count = n;
        }

        /// <summary>A per-object id, unique among live objects. Unity 6000.4 deprecates GetInstanceID
        /// (an error from 6000.5); its EntityId keeps the object's index in the low 32 bits
        /// (UnityCsReference 6000.4-6000.7, Runtime/Export/Scripting/UnityEngineObject.bindings.cs).</summary>
        internal static uint StableId(UnityEngine.Object o)
        {
#if UNITY_6000_4_OR_NEWER
            return unchecked((uint)EntityId.ToULong(o.GetEntityId()));
#else
            return unchecked((uint)o.GetInstanceID());
#endif
        }

        private bool Contains(int n, uint id)
        {
            for (int k = 0; k < n; ++k)
                if (_records[k].Id == id) return true;
            return false;
        }
    }
}
