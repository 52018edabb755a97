using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Fabric presets in physical units run stable on the native solver.</summary>
    public sealed class FabricTests : SceneFixture
    {
        [Test]
        public void EveryPresetRunsStable([Values(0, 1, 2, 3, 4)] int index)
        {
            DrapeFabric fabric = DrapeFabric.Presets[index];
            DrapeCloth cloth = Scene.Grid(16, 16);
            cloth.ApplyFabric(fabric);
            // 1 m x 1 m: mass = areal density (kg/m^2) x 1 m^2; bend springs k = B / h^2 with h = 1/15 m.
            Assert.That(cloth.TotalMass, Is.EqualTo(fabric.ArealDensity).Within(1e-6f));
            Assert.That(cloth.StructuralStiffness, Is.EqualTo(fabric.StretchStiffness));
            Assert.That(cloth.BendStiffness, Is.EqualTo(fabric.BendingRigidity * 225f).Within(1e-3f * fabric.BendingRigidity * 225f));
            Scene.Frames(120);
            Scene.AssertNoErrors();
            Assert.That(cloth.UnstableEvents, Is.EqualTo(0));
            Stats s = cloth.LastStats;
            Assert.That(s.NonFinite, Is.EqualTo(0u));
            Assert.That(s.MaxStrain, Is.LessThan(0.5f), fabric.Name + " hangs without tearing apart");
        }
    }
}
