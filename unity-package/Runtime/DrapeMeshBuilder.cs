using Unity.Collections;
using UnityEngine;
using UnityEngine.Rendering;

namespace Drape
{
    /// <summary>Builds the mesh a <see cref="DrapeCloth"/> renders. Stream 0 holds what the native side
    /// writes every step: position and normal, Float32, 24 bytes (<see cref="DrapeVertex"/>). Every other
    /// vertex attribute of the source mesh (tangents, colours, all UV channels, blend weights and
    /// indices) moves to stream 1 in its own format, byte for byte, and every submesh keeps its
    /// indices and topology, so materials and textures keep working. Blend shapes and bind poses are
    /// not carried over (skinned cloth is not supported).</summary>
    internal static class DrapeMeshBuilder
    {
        internal static readonly VertexAttributeDescriptor Position =
            new VertexAttributeDescriptor(VertexAttribute.Position, VertexAttributeFormat.Float32, 3, 0);
        internal static readonly VertexAttributeDescriptor Normal =
            new VertexAttributeDescriptor(VertexAttribute.Normal, VertexAttributeFormat.Float32, 3, 0);

        /// <summary>A grid's output mesh: stream 0 dynamic, stream 1 UV0 (static).</summary>
        internal static Mesh ForGrid(string owner, int columns, int rows, Vector2 size)
        {
            DrapeCloth.MakeGrid(columns, rows, size, out Vector3[] positions, out Vector2[] uvs, out int[] triangles);
            var mesh = new Mesh { name = "Drape " + owner };
            mesh.MarkDynamic();
            mesh.SetVertexBufferParams(positions.Length, Position, Normal,
                new VertexAttributeDescriptor(VertexAttribute.TexCoord0, VertexAttributeFormat.Float32, 2, 1));
            mesh.SetVertexBufferData(uvs, 0, 0, uvs.Length, 1);
            mesh.SetIndexBufferParams(triangles.Length, IndexFormat.UInt32);
            mesh.SetIndexBufferData(triangles, 0, 0, triangles.Length);
            mesh.subMeshCount = 1;
            mesh.SetSubMesh(0, new SubMeshDescriptor(0, triangles.Length));
            return mesh;
        }

        /// <summary>Bytes of one component of a vertex attribute format.</summary>
        internal static int FormatSize(VertexAttributeFormat format)
        {
            switch (format)
            {
                case VertexAttributeFormat.Float32:
                case VertexAttributeFormat.UInt32:
                case VertexAttributeFormat.SInt32:
                    return 4;
                case VertexAttributeFormat.Float16:
                case VertexAttributeFormat.UNorm16:
                case VertexAttributeFormat.SNorm16:
                case VertexAttributeFormat.UInt16:
                case VertexAttributeFormat.SInt16:
                    return 2;
                default:
                    return 1;
            }
        }

        /// <summary>The output layout for a source layout: position and normal (Float32 x3) in stream 0,
        /// every other attribute, in the source's order and format, in stream 1. Returns stream 1's stride.</summary>
        internal static int PlanLayout(VertexAttributeDescriptor[] source, out VertexAttributeDescriptor[] layout)
        {
            int extra = 0;
            for (int i = 0; i < source.Length; ++i)
                if (source[i].attribute != VertexAttribute.Position && source[i].attribute != VertexAttribute.Normal) extra++;
            layout = new VertexAttributeDescriptor[2 + extra];
            layout[0] = Position;
            layout[1] = Normal;
            int k = 2, stride = 0;
            for (int i = 0; i < source.Length; ++i)
            {
                VertexAttributeDescriptor a = source[i];
                if (a.attribute == VertexAttribute.Position || a.attribute == VertexAttribute.Normal) continue;
                layout[k++] = new VertexAttributeDescriptor(a.attribute, a.format, a.dimension, 1);
                stride += FormatSize(a.format) * a.dimension;
            }
            return stride;
        }

        /// <summary>A copy of <paramref name="source"/> (readable) with stream 0 made dynamic for the
        /// solver and everything else kept (see the class summary).</summary>
        internal static Mesh CopyWithDynamicStream0(string owner, Mesh source)
        {
            int n = source.vertexCount;
            VertexAttributeDescriptor[] attributes = source.GetVertexAttributes();
            int stride = PlanLayout(attributes, out VertexAttributeDescriptor[] layout);

            var mesh = new Mesh { name = "Drape " + owner + " (" + source.name + ")" };
            mesh.MarkDynamic();
            mesh.SetVertexBufferParams(n, layout);
            if (stride > 0)
            {
                var packed = new byte[n * stride];
                using (Mesh.MeshDataArray data = Mesh.AcquireReadOnlyMeshData(source))
                {
                    Mesh.MeshData md = data[0];
                    int at = 0;
                    for (int i = 2; i < layout.Length; ++i)
                    {
                        VertexAttribute attribute = layout[i].attribute;
                        int size = FormatSize(layout[i].format) * layout[i].dimension;
                        int stream = source.GetVertexAttributeStream(attribute);
                        int offset = source.GetVertexAttributeOffset(attribute);
                        int srcStride = source.GetVertexBufferStride(stream);
                        NativeArray<byte> bytes = md.GetVertexData<byte>(stream);
                        for (int v = 0; v < n; ++v)
                        for (int b = 0; b < size; ++b)
                            packed[v * stride + at + b] = bytes[v * srcStride + offset + b];
                        at += size;
                    }
                }
                mesh.SetVertexBufferData(packed, 0, 0, packed.Length, 1);
            }

            int submeshes = source.subMeshCount;
            int total = 0;
            for (int s = 0; s < submeshes; ++s) total += (int)source.GetIndexCount(s);
            var indices = new int[total];
            var descriptors = new SubMeshDescriptor[submeshes];
            int start = 0;
            for (int s = 0; s < submeshes; ++s)
            {
                int[] sub = source.GetIndices(s, true);
                System.Array.Copy(sub, 0, indices, start, sub.Length);
                descriptors[s] = new SubMeshDescriptor(start, sub.Length, source.GetTopology(s));
                start += sub.Length;
            }
            mesh.SetIndexBufferParams(total, IndexFormat.UInt32);
            mesh.SetIndexBufferData(indices, 0, 0, total);
            mesh.subMeshCount = submeshes;
            for (int s = 0; s < submeshes; ++s) mesh.SetSubMesh(s, descriptors[s]);
            mesh.bounds = source.bounds;
            return mesh;
        }
    }
}
