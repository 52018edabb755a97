using System;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    /// <summary>Bad input must come back as a DrapeException with the native status and message,
    /// never a crash, and must leave the object unchanged.</summary>
    public class BadInputTests
    {
        private NativeWorld _world;
        private NativeCloth _cloth;

        [SetUp]
        public void SetUp()
        {
            _world = new NativeWorld(1);
            _cloth = TestScenes.HorizontalGrid(_world, 4, 4);
        }

        [TearDown]
        public void TearDown()
        {
            _cloth.Dispose();
            _world.Dispose();
        }

        private static DrapeException Fails(TestDelegate call, Status expected)
        {
            var e = Assert.Throws<DrapeException>(call);
            Assert.That(e.Status, Is.EqualTo(expected));
            Assert.That(e.NativeMessage, Is.Not.Empty, "the native message is missing");
            Assert.That(e.Message, Does.Contain(e.NativeMessage));
            return e;
        }

        [Test]
        public void ZeroDt()
        {
            DrapeException e = Fails(() => _cloth.Step(0f), Status.ErrorInvalidArgument);
            Assert.That(e.NativeMessage, Does.Contain("dt"));
            Assert.That(e.Function, Is.EqualTo("drape_cloth_step"));
        }

        [Test]
        public void NaNDt()
        {
            Fails(() => _cloth.Step(float.NaN), Status.ErrorNotFinite);
            Fails(() => _world.Step(float.PositiveInfinity), Status.ErrorNotFinite);
        }

        [Test]
        public void EmptyGrid()
        {
            var grid = new GridDesc { Columns = 0, Rows = 4, Width = 1f, Height = 1f };
            Fails(() => NativeCloth.CreateGrid(_world, new ClothDesc { TotalMass = 1f }, grid), Status.ErrorInvalidArgument);
        }

        [Test]
        public void NegativeMass()
        {
            var grid = new GridDesc { Columns = 3, Rows = 3, Width = 1f, Height = 1f };
            DrapeException e = Fails(() => NativeCloth.CreateGrid(_world, new ClothDesc { TotalMass = -1f }, grid),
                                     Status.ErrorInvalidArgument);
            Assert.That(e.NativeMessage, Does.Contain("total_mass"));
        }

        [Test]
        public void UnknownBackendEnum()
        {
            var grid = new GridDesc { Columns = 3, Rows = 3, Width = 1f, Height = 1f };
            Fails(() => NativeCloth.CreateGrid(_world, new ClothDesc { Backend = (Backend)99, TotalMass = 1f }, grid),
                  Status.ErrorInvalidEnum);
        }

        [Test]
        public void UnavailableBackendFailsSoftly()
        {
            if (NativeWorld.IsBackendAvailable(Backend.Gles)) Assert.Ignore("GLES is available here");
            var grid = new GridDesc { Columns = 3, Rows = 3, Width = 1f, Height = 1f };
            Fails(() => NativeCloth.CreateGrid(_world, new ClothDesc { Backend = Backend.Gles, TotalMass = 1f }, grid),
                  Status.ErrorBackendUnavailable);
        }

        [Test]
        public void DegenerateTriangle()
        {
            float[] positions = { 0, 0, 0, 1, 0, 0, 2, 0, 0 }; // collinear: zero area
            int[] indices = { 0, 1, 2 };
            Fails(() => NativeCloth.CreateMesh(_world, new ClothDesc { TotalMass = 1f }, positions, indices, 0f),
                  Status.ErrorDegenerateMesh);
        }

        [Test]
        public void IndexOutOfRange()
        {
            float[] positions = { 0, 0, 0, 1, 0, 0, 0, 0, 1 };
            int[] indices = { 0, 1, 7 };
            Fails(() => NativeCloth.CreateMesh(_world, new ClothDesc { TotalMass = 1f }, positions, indices, 0f),
                  Status.ErrorIndexOutOfRange);
        }

        [Test]
        public void WrongInverseMassCount()
        {
            DrapeException e = Fails(() => _cloth.SetInverseMasses(new float[5]), Status.ErrorInvalidArgument);
            Assert.That(e.NativeMessage, Does.Contain("16"));
        }

        [Test]
        public void PinOutOfRange()
        {
            var pins = new[] { new Pin(16, new Float3(0f, 0f, 0f)) };
            Fails(() => _cloth.SetPins(pins), Status.ErrorIndexOutOfRange);
        }

        [Test]
        public void ReadIntoTooSmallBuffer()
        {
            DrapeException e = Fails(() => _cloth.ReadPositions(new float[3 * 16 - 1]), Status.ErrorBufferTooSmall);
            Assert.That(e.NativeMessage, Does.Contain("192"), "message should name the bytes needed (16*12)");
        }

        [Test]
        public void BadParamsLeaveTheClothUnchanged()
        {
            Params good = NativeWorld.DefaultParams();
            good.Damping = 0.75f;
            _cloth.SetParams(good);

            Params bad = good;
            bad.Damping = float.NaN;
            Fails(() => _cloth.SetParams(bad), Status.ErrorNotFinite);
            bad = good;
            bad.Iterations = 1001; // above DRAPE_MAX_ITERATIONS (1000) (0 means automatic and is accepted)
            Fails(() => _cloth.SetParams(bad), Status.ErrorInvalidArgument);
            bad = good;
            bad.Model = (Model)7;
            Fails(() => _cloth.SetParams(bad), Status.ErrorInvalidEnum);

            Assert.That(_cloth.GetParams().Damping, Is.EqualTo(0.75f));
            Assert.That(_cloth.GetParams().Iterations, Is.EqualTo(good.Iterations));
        }

        [Test]
        public void WrongStructSizeIsRefusedWithTheNativeMessage()
        {
            // Through the raw binding: the wrappers always set StructSize themselves.
            Params p = NativeWorld.DefaultParams();
            p.StructSize = SizeOf.Params + 4;
            Status s = NativeMethods.drape_cloth_set_params(_cloth.Handle, ref p);
            Assert.That(s, Is.EqualTo(Status.ErrorStructSize));
            Assert.That(NativeMethods.LastError(), Does.Contain("struct_size"));
        }

        [Test]
        public void LastErrorIsClearedBySuccess()
        {
            Assert.Throws<DrapeException>(() => _cloth.Step(-1f));
            Assert.That(NativeMethods.LastError(), Is.Not.Empty);
            _cloth.Step(0.01f);
            Assert.That(NativeMethods.LastError(), Is.Empty);
        }

        [Test]
        public void OddPositionArrayIsRefusedBeforeTheNativeCall()
        {
            Assert.Throws<ArgumentException>(() =>
                NativeCloth.CreateMesh(_world, new ClothDesc { TotalMass = 1f }, new float[7], new[] { 0, 1, 2 }, 0f));
        }
    }
}
