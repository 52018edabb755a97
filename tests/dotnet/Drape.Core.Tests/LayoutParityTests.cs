// Compares every C# twin in Runtime/Core/Structs.cs and Enums.cs with what the C compiler makes of
// drape.h (LayoutProbe/drape_layout_probe.c, built by the csproj): struct sizes, field names,
// order, offsets and sizes, and enumerator values. Only in tests/dotnet: it needs a C compiler.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Reflection;
using System.Runtime.InteropServices;
using System.Text;
using Drape.Core;
using NUnit.Framework;

namespace Drape.Tests
{
    public class LayoutParityTests
    {
        [DllImport("drape_layout_probe")] private static extern int drape_probe_count();
        [DllImport("drape_layout_probe")] private static extern IntPtr drape_probe_name(int i);
        [DllImport("drape_layout_probe")] private static extern long drape_probe_value(int i);

        private static Dictionary<string, long> s_c;

        private static Dictionary<string, long> C
        {
            get
            {
                if (s_c != null) return s_c;
                var map = new Dictionary<string, long>();
                int n = drape_probe_count();
                for (int i = 0; i < n; ++i) map[Marshal.PtrToStringAnsi(drape_probe_name(i))] = drape_probe_value(i);
                return s_c = map;
            }
        }

        /// <summary>PascalCase -> snake_case: AxisU -> axis_u, StructSize -> struct_size.</summary>
        internal static string Snake(string pascal)
        {
            var sb = new StringBuilder();
            for (int i = 0; i < pascal.Length; ++i)
            {
                char ch = pascal[i];
                if (char.IsUpper(ch) && i > 0) sb.Append('_');
                sb.Append(char.ToLowerInvariant(ch));
            }
            return sb.ToString();
        }

        private static readonly object[] Twins =
        {
            new object[] { "drape_world_desc", typeof(WorldDesc) },
            new object[] { "drape_cloth_desc", typeof(ClothDesc) },
            new object[] { "drape_grid_desc", typeof(GridDesc) },
            new object[] { "drape_mesh_desc", typeof(MeshDesc) },
            new object[] { "drape_params", typeof(Params) },
            new object[] { "drape_vertex_layout", typeof(VertexLayout) },
            new object[] { "drape_pin", typeof(Pin) },
            new object[] { "drape_cloth_info", typeof(ClothInfo) },
            new object[] { "drape_stats", typeof(Stats) },
            new object[] { "drape_collider", typeof(ColliderDesc) },
            new object[] { "drape_sleep_desc", typeof(SleepDesc) },
            new object[] { "drape_view", typeof(View) },
            new object[] { "drape_touch", typeof(TouchPoint) },
            new object[] { "drape_owner", typeof(Owner) },
            new object[] { "drape_self_collision_desc", typeof(SelfCollisionDesc) },
            new object[] { "drape_stability", typeof(StabilityEstimate) },
        };

        /// <summary>C# fields whose C name is not Snake(name): a member cannot share its struct's name.</summary>
        private static readonly Dictionary<string, string> Renamed = new Dictionary<string, string>
        {
            ["View.ViewMatrix"] = "view",
        };

        private static string CField(Type csType, FieldInfo f) =>
            Renamed.TryGetValue(csType.Name + "." + f.Name, out string c) ? c : Snake(f.Name);

        [TestCaseSource(nameof(Twins))]
        public void StructMatchesC(string cName, Type csType)
        {
            Assert.That(C.ContainsKey(cName), Is.True, cName + " is not in the probe");
            Assert.That((long)Marshal.SizeOf(csType), Is.EqualTo(C[cName]), "sizeof(" + cName + ")");

            string[] cFields = C.Keys.Where(k => k.StartsWith(cName + ".", StringComparison.Ordinal) && !k.EndsWith(":size", StringComparison.Ordinal))
                                .OrderBy(k => C[k]).Select(k => k.Substring(cName.Length + 1)).ToArray();
            FieldInfo[] csFields = csType.GetFields(BindingFlags.Instance | BindingFlags.Public | BindingFlags.NonPublic)
                                         .OrderBy(f => (long)Marshal.OffsetOf(csType, f.Name)).ToArray();
            Assert.That(csFields.Select(f => CField(csType, f)).ToArray(), Is.EqualTo(cFields), "fields of " + cName);

            foreach (FieldInfo f in csFields)
            {
                string key = cName + "." + CField(csType, f);
                Assert.That((long)Marshal.OffsetOf(csType, f.Name), Is.EqualTo(C[key]), "offsetof " + key);
                Type ft = f.FieldType.IsEnum ? Enum.GetUnderlyingType(f.FieldType) : f.FieldType;
                Assert.That((long)Marshal.SizeOf(ft), Is.EqualTo(C[key + ":size"]), "sizeof " + key);
            }
        }

        [TestCase(typeof(Status), "DRAPE_")]
        [TestCase(typeof(Backend), "DRAPE_BACKEND_")]
        [TestCase(typeof(Model), "DRAPE_MODEL_")]
        [TestCase(typeof(Group), "DRAPE_GROUP_")]
        [TestCase(typeof(ColliderShape), "DRAPE_COLLIDER_")]
        public void EnumMatchesC(Type csEnum, string prefix)
        {
            var fromCs = new SortedDictionary<string, long>();
            foreach (object v in Enum.GetValues(csEnum))
                fromCs["enum:" + prefix + Snake(Enum.GetName(csEnum, v)).ToUpperInvariant()] = Convert.ToInt64(v);
            var fromC = new SortedDictionary<string, long>();
            foreach (KeyValuePair<string, long> kv in C)
            {
                if (!kv.Key.StartsWith("enum:" + prefix, StringComparison.Ordinal)) continue;
                // DRAPE_ prefixes every enum; for Status keep only the status names.
                if (csEnum == typeof(Status) && !(kv.Key == "enum:DRAPE_OK" || kv.Key.StartsWith("enum:DRAPE_ERROR_", StringComparison.Ordinal))) continue;
                fromC[kv.Key] = kv.Value;
            }
            Assert.That(fromCs, Is.EqualTo(fromC));
        }

        [Test]
        public void AbiVersionConstantMatchesHeader()
        {
            Assert.That((long)NativeWorld.ExpectedAbiVersion, Is.EqualTo(C["DRAPE_ABI_VERSION"]));
        }

        [Test]
        public void SizeOfConstantsMatchC()
        {
            Assert.That((long)SizeOf.Params, Is.EqualTo(C["drape_params"]));
            Assert.That((long)SizeOf.Stats, Is.EqualTo(C["drape_stats"]));
            Assert.That((long)SizeOf.MeshDesc, Is.EqualTo(C["drape_mesh_desc"]));
            Assert.That((long)SizeOf.ColliderDesc, Is.EqualTo(C["drape_collider"]));
            Assert.That((long)SizeOf.SleepDesc, Is.EqualTo(C["drape_sleep_desc"]));
            Assert.That((long)SizeOf.View, Is.EqualTo(C["drape_view"]));
            Assert.That((long)SizeOf.TouchPoint, Is.EqualTo(C["drape_touch"]));
            Assert.That((long)SizeOf.Owner, Is.EqualTo(C["drape_owner"]));
            Assert.That((long)SizeOf.SelfCollisionDesc, Is.EqualTo(C["drape_self_collision_desc"]));
            Assert.That((long)SizeOf.StabilityEstimate, Is.EqualTo(C["drape_stability"]));
            Assert.That((long)NativeCloth.MaxColliders, Is.EqualTo(C["DRAPE_MAX_COLLIDERS"]));
            Assert.That((long)NativeCloth.GrabOnGpu, Is.EqualTo(C["DRAPE_GRAB_ON_GPU"]));
        }

        [Test]
        public void Float4x4IsColumnMajorLikeUnityMatrix4x4()
        {
            // drape.h: element (row r, column c) at [c*4 + r]; Unity's Matrix4x4 fields m00, m10, ...
            Assert.That((long)Marshal.SizeOf(typeof(Float4x4)), Is.EqualTo(64));
            for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                Assert.That((long)Marshal.OffsetOf(typeof(Float4x4), "M" + r + c), Is.EqualTo(4L * (c * 4 + r)));
            var m = new Float4x4();
            m[1, 3] = 7f;
            Assert.That(m.M13, Is.EqualTo(7f));
            Assert.That(C["drape_view.world:size"], Is.EqualTo(64));
        }

        [Test]
        public void SnakeCaseConversion()
        {
            Assert.That(Snake("AxisU"), Is.EqualTo("axis_u"));
            Assert.That(Snake("StructSize"), Is.EqualTo("struct_size"));
            Assert.That(Snake("Ok"), Is.EqualTo("ok"));
        }
    }
}
