using Drape.Core;
using UnityEngine;

namespace Drape
{
    /// <summary>Unity types to Drape.Core's blittable twins (field copies; no allocation).</summary>
    public static class DrapeConvert
    {
        public static Float3 ToDrape(Vector3 v) => new Float3(v.x, v.y, v.z);

        /// <summary>Quaternion x, y, z, w, renormalised (drape.h wants |q| within 1e-3 of 1).</summary>
        public static Float4 ToDrape(Quaternion q)
        {
            float n = Mathf.Sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
            if (n < 1e-6f) return Float4.IdentityRotation;
            float s = 1f / n;
            return new Float4(q.x * s, q.y * s, q.z * s, q.w * s);
        }

        /// <summary>Unity's Matrix4x4 and drape.h's float[16] are both column-major (m00, m10, m20,
        /// m30, m01, ...): element for element, same order.</summary>
        public static Float4x4 ToDrape(Matrix4x4 m) => new Float4x4
        {
            M00 = m.m00, M10 = m.m10, M20 = m.m20, M30 = m.m30,
            M01 = m.m01, M11 = m.m11, M21 = m.m21, M31 = m.m31,
            M02 = m.m02, M12 = m.m12, M22 = m.m22, M32 = m.m32,
            M03 = m.m03, M13 = m.m13, M23 = m.m23, M33 = m.m33,
        };
    }
}
