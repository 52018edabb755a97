using System;

namespace Drape.Core
{
    /// <summary>Stability estimates used by the editor to warn before a cloth explodes.</summary>
    public static class Stability
    {
        /// <summary>Springs per interior vertex and group in the 12-neighbour stencil (paper: 4
        /// structural, 4 shear, 4 bend/flex).</summary>
        public const int SpringsPerGroup = 4;

        /// <summary>Margin kept below the explicit limit h*omega_max &lt; 2.</summary>
        public const float Safety = 0.9f;

        /// <summary>Upper bound of the highest angular frequency (rad/s) of a mass-spring grid whose
        /// interior vertices carry <paramref name="particleMass"/> kg. Gershgorin on M^-1 K: for
        /// equal masses every eigenvalue is at most 2 * sum_j k_ij / m, with 4 springs per group.</summary>
        public static double MassSpringOmegaMax(GroupValues stiffness, float particleMass)
        {
            if (!(particleMass > 0)) throw new ArgumentOutOfRangeException(nameof(particleMass), "must be > 0");
            double sumK = SpringsPerGroup * ((double)Math.Max(0f, stiffness.Structural) +
                                             Math.Max(0f, stiffness.Shear) + Math.Max(0f, stiffness.Bend));
            return Math.Sqrt(2.0 * sumK / particleMass);
        }

        /// <summary>Smallest substep count n such that (dt/n)*omega_max &lt;= 2*Safety (Verlet's
        /// stability bound, h*omega &lt; 2). At least 1.</summary>
        public static int MassSpringSubstepsNeeded(GroupValues stiffness, float particleMass, float dt)
        {
            if (!(dt > 0)) throw new ArgumentOutOfRangeException(nameof(dt), "must be > 0");
            double omega = MassSpringOmegaMax(stiffness, particleMass);
            double n = Math.Ceiling(dt * omega / (2.0 * Safety));
            if (n > int.MaxValue) return int.MaxValue;
            return Math.Max(1, (int)n);
        }
    }
}
