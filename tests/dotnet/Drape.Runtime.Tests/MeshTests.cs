using System.Collections.Generic;
using NUnit.Framework;
using Unity.Collections;
using UnityEngine;
using UnityEngine.Rendering;

namespace Drape.Tests
{
    /// <summary>The output mesh keeps every channel and submesh of the source mesh.</summary>
    public sealed class MeshTests : SceneFixture
    {
        /// <summary>A 3 x 3 vertex sheet with colours and UVs, its 8 triangles split over two submeshes.</summary>
        private static Mesh Source()
        {
            var positions = new Vector3[9];
            var colors = new Color[9];
            var uvs = new Vector2[9];
            for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
            {
                int i = r * 3 + c;
                positions[i] = new Vector3(c * 0.5f - 0.5f, -r * 0.5f, 0f);
                colors[i] = new Color(i / 8f, 0.25f, 0.5f, 1f);
                uvs[i] = new Vector2(c / 2f, 1f - r / 2f);
            }
            var mesh = new Mesh { name = "sheet", vertices = positions, colors = colors, uv = uvs };
            mesh.subMeshCount = 2;
            mesh.SetTriangles(new[] { 0, 1, 3, 1, 4, 3, 1, 2, 4, 2, 5, 4 }, 0);
            mesh.SetTriangles(new[] { 3, 4, 6, 4, 7, 6, 4, 5, 7, 5, 8, 7 }, 1);
            return mesh;
        }

        [Test]
        public void ChannelsMoveToStreamOneByteForByte()
        {
            Mesh source = Source();
            var go = new GameObject("sheet");
            go.AddComponent<MeshFilter>().sharedMesh = source;
            var cloth = go.AddComponent<DrapeCloth>();
            cloth.enabled = false;
            cloth.Source = DrapeShapeSource.MeshFilterMesh;
            cloth.Backend = DrapeBackendChoice.Cpu;
            cloth.PauseWhenInvisible = false;
            cloth.enabled = true;
            Scene.AssertNoErrors();
            Mesh output = go.GetComponent<MeshFilter>().sharedMesh;
            Assert.That(output, Is.Not.SameAs(source));

            var attributes = new List<VertexAttribute>();
            foreach (VertexAttributeDescriptor a in output.GetVertexAttributes()) attributes.Add(a.attribute);
            Assert.That(attributes, Is.EquivalentTo(new[] { VertexAttribute.Position, VertexAttribute.Normal, VertexAttribute.Color, VertexAttribute.TexCoord0 }));
            Assert.That(output.GetVertexAttributeStream(VertexAttribute.Position), Is.EqualTo(0));
            Assert.That(output.GetVertexAttributeStream(VertexAttribute.Normal), Is.EqualTo(0));
            Assert.That(output.GetVertexBufferStride(0), Is.EqualTo(24), "what the native side writes");
            Assert.That(output.GetVertexAttributeStream(VertexAttribute.Color), Is.EqualTo(1));
            Assert.That(output.colors[5].r, Is.EqualTo(5f / 8f));
            Assert.That(output.uv[7].y, Is.EqualTo(0f));

            Assert.That(output.subMeshCount, Is.EqualTo(2));
            Assert.That(output.GetIndices(0, true), Is.EqualTo(source.GetIndices(0, true)));
            Assert.That(output.GetIndices(1, true), Is.EqualTo(source.GetIndices(1, true)));

            cloth.enabled = false; // the source mesh comes back
            Assert.That(go.GetComponent<MeshFilter>().sharedMesh, Is.SameAs(source));
        }

        [Test]
        public void LayoutPlanKeepsFormatsAndOrder()
        {
            var source = new[]
            {
                new VertexAttributeDescriptor(VertexAttribute.Position, VertexAttributeFormat.Float32, 3, 0),
                new VertexAttributeDescriptor(VertexAttribute.Normal, VertexAttributeFormat.Float16, 4, 0),
                new VertexAttributeDescriptor(VertexAttribute.Tangent, VertexAttributeFormat.Float16, 4, 0),
                new VertexAttributeDescriptor(VertexAttribute.Color, VertexAttributeFormat.UNorm8, 4, 1),
                new VertexAttributeDescriptor(VertexAttribute.TexCoord1, VertexAttributeFormat.Float32, 2, 2),
            };
            int stride = DrapeMeshBuilder.PlanLayout(source, out VertexAttributeDescriptor[] layout);
            Assert.That(stride, Is.EqualTo(8 + 4 + 8));
            Assert.That(layout.Length, Is.EqualTo(5));
            Assert.That(layout[1].attribute, Is.EqualTo(VertexAttribute.Normal));
            Assert.That(layout[1].format, Is.EqualTo(VertexAttributeFormat.Float32), "the solver writes Float32 normals");
            Assert.That(layout[2].attribute, Is.EqualTo(VertexAttribute.Tangent));
            Assert.That(layout[2].format, Is.EqualTo(VertexAttributeFormat.Float16));
            Assert.That(layout[4].stream, Is.EqualTo(1));
        }
    }
}
