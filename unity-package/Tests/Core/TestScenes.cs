using Drape.Core;

namespace Drape.Tests
{
    /// <summary>Tiny scenes built by hand for the Core tests.</summary>
    internal static class TestScenes
    {
        /// <summary>A horizontal 1 m x 1 m grid at height <paramref name="y"/>: columns along +x,
        /// rows along -z (the drape.h default axes), 0.1 kg.</summary>
        public static Cloth HorizontalGrid(World world, uint columns, uint rows, float y = 1f,
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
            return Cloth.CreateGrid(world, desc, grid);
        }
    }
}
