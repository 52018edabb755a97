using System;

namespace Drape.Core
{
    /// <summary>Stability estimates used by the editor to warn before a cloth explodes. They come from
    /// the native library (drape_estimate_stability): the same cooking (area-weighted masses, springs per
    /// particle) and the same explicit bound a cloth uses to choose its substeps, so the editor and the
    /// simulation cannot disagree.</summary>
    public static class Stability
    {
        /// <summary>Estimate for a grid cloth (as <see cref="NativeCloth.CreateGrid"/> would create it)
        /// stepped by <paramref name="dt"/> seconds with <paramref name="parameters"/>. StructSize fields
        /// are set here. Bad input throws <see cref="DrapeException"/> like creation does.</summary>
        public static StabilityEstimate ForGrid(GridDesc grid, float totalMass, Params parameters, float dt)
        {
            var desc = new ClothDesc { StructSize = SizeOf.ClothDesc, Backend = Backend.Cpu, TotalMass = totalMass };
            grid.StructSize = SizeOf.GridDesc;
            parameters.StructSize = SizeOf.Params;
            var estimate = new StabilityEstimate { StructSize = SizeOf.StabilityEstimate };
            NativeMethods.Check(NativeMethods.drape_estimate_stability(ref desc, ref grid, IntPtr.Zero, ref parameters, dt,
                                                                       ref estimate),
                                "drape_estimate_stability");
            return estimate;
        }

        /// <summary>Estimate for a triangle-mesh cloth (as <see cref="NativeCloth.CreateMesh"/> would
        /// create it: xyz triples, triangle list, weld distance).</summary>
        public static unsafe StabilityEstimate ForMesh(ReadOnlySpan<float> positions, ReadOnlySpan<int> indices,
                                                       float weldDistance, float totalMass, Params parameters, float dt)
        {
            var desc = new ClothDesc { StructSize = SizeOf.ClothDesc, Backend = Backend.Cpu, TotalMass = totalMass };
            parameters.StructSize = SizeOf.Params;
            var estimate = new StabilityEstimate { StructSize = SizeOf.StabilityEstimate };
            fixed (float* p = positions)
            fixed (int* i = indices)
            {
                var mesh = MeshDesc.Pinned(p, positions.Length, i, indices.Length, weldDistance);
                NativeMethods.Check(NativeMethods.drape_estimate_stability(ref desc, IntPtr.Zero, ref mesh, ref parameters,
                                                                           dt, ref estimate),
                                    "drape_estimate_stability");
            }
            return estimate;
        }
    }
}
