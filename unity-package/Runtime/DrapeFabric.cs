using UnityEngine;

namespace Drape
{
    /// <summary>A fabric in physical units, applied with <see cref="DrapeCloth.ApplyFabric"/> (XPBD).
    /// Stretch and shear are sheet moduli (N/m: force per unit width per unit strain). On a square
    /// grid a spring between neighbours carries a strip as wide as it is long, so its stiffness in
    /// N/m equals the sheet modulus at any resolution. Bending is a rigidity B (N*m, moment per unit
    /// width per unit curvature); a bend spring spanning two cells of spacing h approximates it with
    /// k = B / h^2, so that one depends on the resolution. The presets are representative values of
    /// the order of magnitude (Kawabata KES-F style measurements vary widely between weaves and
    /// directions); tune from them.</summary>
    [System.Serializable]
    public struct DrapeFabric
    {
        public string Name;
        /// <summary>kg/m^2 (fabric "weight": 100 g/m^2 = 0.1).</summary>
        public float ArealDensity;
        /// <summary>N/m, sheet stretch modulus.</summary>
        public float StretchStiffness;
        /// <summary>N/m, in-plane shear modulus.</summary>
        public float ShearStiffness;
        /// <summary>N*m, bending rigidity per unit width.</summary>
        public float BendingRigidity;
        /// <summary>N*s/m per spring.</summary>
        public float Damping;

        public DrapeFabric(string name, float arealDensity, float stretch, float shear, float bendingRigidity, float damping)
        {
            Name = name;
            ArealDensity = arealDensity;
            StretchStiffness = stretch;
            ShearStiffness = shear;
            BendingRigidity = bendingRigidity;
            Damping = damping;
        }

        /// <summary>N/m: the bend spring stiffness for a particle spacing of <paramref name="spacing"/> m.</summary>
        public float BendSpringStiffness(float spacing) => BendingRigidity / Mathf.Max(1e-8f, spacing * spacing);

        public static readonly DrapeFabric Silk = new DrapeFabric("Silk (chiffon)", 0.04f, 2000f, 20f, 1e-6f, 0.01f);
        public static readonly DrapeFabric Cotton = new DrapeFabric("Cotton (shirting)", 0.12f, 5000f, 100f, 1e-5f, 0.02f);
        public static readonly DrapeFabric Jersey = new DrapeFabric("Jersey knit", 0.18f, 300f, 10f, 5e-6f, 0.02f);
        public static readonly DrapeFabric Denim = new DrapeFabric("Denim", 0.40f, 20000f, 500f, 1e-4f, 0.05f);
        public static readonly DrapeFabric Canvas = new DrapeFabric("Canvas", 0.35f, 15000f, 400f, 2e-4f, 0.05f);

        /// <summary>The presets, lightest first.</summary>
        public static DrapeFabric[] Presets => new[] { Silk, Cotton, Jersey, Canvas, Denim };

        /// <summary>m^2: the area of a triangle mesh (the grid's Size.x * Size.y when no triangles).</summary>
        public static float MeshArea(Vector3[] positions, int[] triangles)
        {
            if (positions == null || triangles == null) return 0f;
            double area = 0;
            for (int t = 0; t + 2 < triangles.Length; t += 3)
            {
                Vector3 a = positions[triangles[t]], b = positions[triangles[t + 1]], c = positions[triangles[t + 2]];
                Vector3 u = b - a, v = c - a;
                float x = u.y * v.z - u.z * v.y, y = u.z * v.x - u.x * v.z, z = u.x * v.y - u.y * v.x;
                area += 0.5 * Mathf.Sqrt(x * x + y * y + z * z);
            }
            return (float)area;
        }
    }
}
