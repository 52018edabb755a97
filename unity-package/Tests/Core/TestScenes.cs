using System;
using Drape.Core;

namespace Drape.Tests
{
    /// <summary>Tiny scenes built by hand for the Core tests.</summary>
    internal static class TestScenes
    {
        /// <summary>A horizontal 1 m x 1 m grid at height <paramref name="y"/>: columns along +x,
        /// rows along -z (the drape.h default axes), 0.1 kg.</summary>
        public static NativeCloth HorizontalGrid(NativeWorld world, uint columns, uint rows, float y = 1f,
                                           Backend backend = Backend.Cpu)
        {
            var desc = new ClothDesc { Backend = backend, TotalMass = 0.1f };
            var grid = new GridDesc
            {
                Columns = columns,
                Rows = rows,
                Width = 1f,
                Height = 1f,
                Origin = new Float3(0f, y, 0f),
            };
            return NativeCloth.CreateGrid(world, desc, grid);
        }

        /// <summary>A vertical grid in the z = 0 plane facing +z: columns along +x from x = -0.5,
        /// rows down -y from y = 0.5, 1 m x 1 m, 0.1 kg (vertex r*columns + c).</summary>
        public static NativeCloth FacingGrid(NativeWorld world, uint columns, uint rows)
        {
            var desc = new ClothDesc { Backend = Backend.Cpu, TotalMass = 0.1f };
            var grid = new GridDesc
            {
                Columns = columns,
                Rows = rows,
                Width = 1f,
                Height = 1f,
                Origin = new Float3(-0.5f, 0.5f, 0f),
                AxisU = new Float3(1f, 0f, 0f),
                AxisV = new Float3(0f, -1f, 0f),
            };
            return NativeCloth.CreateGrid(world, desc, grid);
        }

        /// <summary>A camera at (0, 0, <paramref name="distance"/>) looking down -z (OpenGL convention, as Unity's
        /// worldToCameraMatrix), 60 degree vertical field of view, 400 x 300 px viewport, identity
        /// simulation -> world. Matrices column-major, built by hand like Camera.projectionMatrix.</summary>
        public static View PerspectiveView(float distance = 3f)
        {
            var v = new View { World = Float4x4.Identity, ViewMatrix = Float4x4.Identity, Viewport = new Float2(400f, 300f) };
            v.ViewMatrix.M23 = -distance; // world -> camera: translate by -distance along z
            const float aspect = 400f / 300f, zn = 0.1f, zf = 100f;
            float f = 1f / (float)Math.Tan(0.5 * Math.PI / 3.0);
            v.Projection.M00 = f / aspect;
            v.Projection.M11 = f;
            v.Projection.M22 = (zf + zn) / (zn - zf);
            v.Projection.M32 = -1f;
            v.Projection.M23 = 2f * zf * zn / (zn - zf);
            return v;
        }

        /// <summary>Pixel position (origin bottom-left) of a simulation-space point seen through <paramref name="v"/>.</summary>
        public static Float2 Project(in View v, float x, float y, float z)
        {
            Mul(v.World, ref x, ref y, ref z, out _);
            Mul(v.ViewMatrix, ref x, ref y, ref z, out _);
            Mul(v.Projection, ref x, ref y, ref z, out float w);
            return new Float2((x / w * 0.5f + 0.5f) * v.Viewport.X, (y / w * 0.5f + 0.5f) * v.Viewport.Y);
        }

        private static void Mul(in Float4x4 m, ref float x, ref float y, ref float z, out float w)
        {
            float nx = m[0, 0] * x + m[0, 1] * y + m[0, 2] * z + m[0, 3];
            float ny = m[1, 0] * x + m[1, 1] * y + m[1, 2] * z + m[1, 3];
            float nz = m[2, 0] * x + m[2, 1] * y + m[2, 2] * z + m[2, 3];
            w = m[3, 0] * x + m[3, 1] * y + m[3, 2] * z + m[3, 3];
            x = nx;
            y = ny;
            z = nz;
        }
    }
}
