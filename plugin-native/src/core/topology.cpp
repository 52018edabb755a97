#include "core/topology.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace drape {
namespace {

struct Spring {
    uint32_t a, b;
    uint8_t group;
};

// Fills the neighbour table from a list of unique springs (a != b, each pair once).
void build_neighbours(Topology& t, const std::vector<Spring>& springs) {
    const uint32_t n = t.particle_count;
    std::vector<uint32_t> degree(n, 0);
    for (const Spring& s : springs) {
        ++degree[s.a];
        ++degree[s.b];
        ++t.spring_count[s.group];
    }
    uint32_t slots = 1;
    for (uint32_t d : degree) slots = std::max(slots, d);
    NeighbourTable& nb = t.nbr;
    nb.slots = slots;
    nb.index.assign(size_t(n) * slots, 0);
    nb.rest.assign(size_t(n) * slots, 0.0f);
    nb.group.assign(size_t(n) * slots, NeighbourTable::kNoGroup);
    nb.count.assign(n, 0);
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t s = 0; s < slots; ++s) nb.index[size_t(i) * slots + s] = i;
    auto add = [&](uint32_t from, uint32_t to, float rest, uint8_t group) {
        size_t slot = size_t(from) * slots + nb.count[from]++;
        nb.index[slot] = to;
        nb.rest[slot] = rest;
        nb.group[slot] = group;
    };
    for (const Spring& s : springs) {
        float rest = glm::length(t.rest_position[s.a] - t.rest_position[s.b]);
        add(s.a, s.b, rest, s.group);
        add(s.b, s.a, rest, s.group);
    }
}

void finish(Topology& t, float total_mass) {
    // Mass by area: each triangle gives a third of its area to each corner. Without triangles
    // (a single row or column: a chain) mass is uniform.
    const uint32_t n = t.particle_count;
    std::vector<double> area(n, 0.0);
    double total_area = 0;
    for (size_t k = 0; k + 2 < t.triangles.size(); k += 3) {
        const glm::vec3& p0 = t.rest_position[t.triangles[k]];
        const glm::vec3& p1 = t.rest_position[t.triangles[k + 1]];
        const glm::vec3& p2 = t.rest_position[t.triangles[k + 2]];
        double a = 0.5 * double(glm::length(glm::cross(p1 - p0, p2 - p0)));
        for (int c = 0; c < 3; ++c) area[t.triangles[k + c]] += a / 3.0;
        total_area += a;
    }
    t.mass.assign(n, total_mass / float(n));
    if (total_area > 0)
        for (uint32_t i = 0; i < n; ++i) t.mass[i] = float(total_mass * area[i] / total_area);
    // A particle on no triangle (possible in a mesh with unused vertices) still needs mass.
    float min_positive = total_mass;
    for (float m : t.mass)
        if (m > 0) min_positive = std::min(min_positive, m);
    for (float& m : t.mass)
        if (!(m > 0)) m = min_positive;

    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : t.rest_position) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    t.extent = glm::length(hi - lo);
}

glm::vec3 axis_or(const float v[3], glm::vec3 fallback) {
    glm::vec3 a(v[0], v[1], v[2]);
    float len = glm::length(a);
    return len > 0 ? a / len : fallback;
}

}  // namespace

Topology cook_grid(const drape_grid_desc& g, float total_mass) {
    Topology t;
    const uint32_t cols = g.columns, rows = g.rows;
    t.vertex_count = t.particle_count = cols * rows;
    t.vertex_to_particle.resize(t.vertex_count);
    for (uint32_t i = 0; i < t.vertex_count; ++i) t.vertex_to_particle[i] = i;

    const glm::vec3 origin(g.origin[0], g.origin[1], g.origin[2]);
    const glm::vec3 u = axis_or(g.axis_u, {1, 0, 0});
    const glm::vec3 v = axis_or(g.axis_v, {0, 0, -1});
    const float du = cols > 1 ? g.width / float(cols - 1) : 0.0f;
    const float dv = rows > 1 ? g.height / float(rows - 1) : 0.0f;
    t.rest_position.resize(t.particle_count);
    for (uint32_t r = 0; r < rows; ++r)
        for (uint32_t c = 0; c < cols; ++c)
            t.rest_position[r * cols + c] = origin + u * (du * float(c)) + v * (dv * float(r));

    // The paper's 12 springs per vertex: structural (+-1,0),(0,+-1); shear (+-1,+-1);
    // bend/flex (+-2,0),(0,+-2). Each listed once here, from the lower-index end.
    struct Offset {
        int dc, dr;
        uint8_t group;
    };
    static const Offset kOffsets[] = {
        {1, 0, DRAPE_GROUP_STRUCTURAL}, {0, 1, DRAPE_GROUP_STRUCTURAL}, {1, 1, DRAPE_GROUP_SHEAR},
        {-1, 1, DRAPE_GROUP_SHEAR},     {2, 0, DRAPE_GROUP_BEND},       {0, 2, DRAPE_GROUP_BEND},
    };
    std::vector<Spring> springs;
    springs.reserve(size_t(t.particle_count) * 6);
    for (uint32_t r = 0; r < rows; ++r)
        for (uint32_t c = 0; c < cols; ++c)
            for (const Offset& o : kOffsets) {
                int cc = int(c) + o.dc, rr = int(r) + o.dr;
                if (cc < 0 || cc >= int(cols) || rr >= int(rows)) continue;
                springs.push_back({r * cols + c, uint32_t(rr) * cols + uint32_t(cc), o.group});
            }
    build_neighbours(t, springs);

    for (uint32_t r = 0; r + 1 < rows; ++r)
        for (uint32_t c = 0; c + 1 < cols; ++c) {
            uint32_t i00 = r * cols + c, i10 = i00 + 1, i01 = i00 + cols, i11 = i01 + 1;
            t.triangles.insert(t.triangles.end(), {i00, i01, i10, i10, i01, i11});
        }
    finish(t, total_mass);
    return t;
}

CookResult cook_mesh(const drape_mesh_desc& m, float total_mass, Topology& out) {
    Topology t;
    t.vertex_count = m.vertex_count;
    const uint32_t tri_count = m.index_count / 3;
    for (uint32_t k = 0; k < m.index_count; ++k)
        if (m.indices[k] >= m.vertex_count)
            return {DRAPE_ERROR_INDEX_OUT_OF_RANGE, "mesh index " + std::to_string(k) + " is " +
                                                        std::to_string(m.indices[k]) + ", vertex_count is " +
                                                        std::to_string(m.vertex_count)};

    // Weld: positions quantised to weld_distance cells (exact bits when 0); a vertex joins the
    // first earlier vertex within weld_distance found in its own or a neighbouring cell.
    auto pos = [&](uint32_t i) { return glm::vec3(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]); };
    t.vertex_to_particle.resize(m.vertex_count);
    const float cell = m.weld_distance;
    struct KeyHash {
        size_t operator()(const glm::ivec3& k) const {
            return size_t(k.x) * 73856093u ^ size_t(k.y) * 19349663u ^ size_t(k.z) * 83492791u;
        }
    };
    std::unordered_map<glm::ivec3, std::vector<uint32_t>, KeyHash> cells;
    auto key_of = [&](const glm::vec3& p) {
        if (cell > 0) return glm::ivec3(glm::floor(p / cell));
        const glm::vec3 q = p + glm::vec3(0.0f);  // -0 and +0 weld
        glm::ivec3 k;
        std::memcpy(&k, &q, sizeof k);
        return k;
    };
    for (uint32_t i = 0; i < m.vertex_count; ++i) {
        const glm::vec3 p = pos(i);
        const glm::ivec3 k = key_of(p);
        int32_t found = -1;
        const int reach = cell > 0 ? 1 : 0;
        for (int dz = -reach; dz <= reach && found < 0; ++dz)
            for (int dy = -reach; dy <= reach && found < 0; ++dy)
                for (int dx = -reach; dx <= reach && found < 0; ++dx) {
                    auto it = cells.find(k + glm::ivec3(dx, dy, dz));
                    if (it == cells.end()) continue;
                    for (uint32_t particle : it->second)
                        if (glm::length(t.rest_position[particle] - p) <= cell) {
                            found = int32_t(particle);
                            break;
                        }
                }
        if (found < 0) {
            found = int32_t(t.rest_position.size());
            t.rest_position.push_back(p);
            cells[k].push_back(uint32_t(found));
        }
        t.vertex_to_particle[i] = uint32_t(found);
    }
    t.particle_count = uint32_t(t.rest_position.size());

    // Triangles in particle indices; reject degenerate ones (after welding) with their index.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : t.rest_position) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float size = glm::length(hi - lo);
    const float min_area = 1e-12f * size * size;
    t.triangles.resize(size_t(tri_count) * 3);
    for (uint32_t f = 0; f < tri_count; ++f) {
        uint32_t a = t.vertex_to_particle[m.indices[3 * f]], b = t.vertex_to_particle[m.indices[3 * f + 1]],
                 c = t.vertex_to_particle[m.indices[3 * f + 2]];
        float area = 0.5f * glm::length(glm::cross(t.rest_position[b] - t.rest_position[a],
                                                   t.rest_position[c] - t.rest_position[a]));
        if (a == b || b == c || a == c || !(area > min_area))
            return {DRAPE_ERROR_DEGENERATE_MESH,
                    "triangle " + std::to_string(f) + " is degenerate (repeated vertex after welding or zero area)"};
        t.triangles[3 * f] = a, t.triangles[3 * f + 1] = b, t.triangles[3 * f + 2] = c;
    }

    // Structural springs on edges; for each edge, the two opposite corners get a bend spring
    // (unless they are already joined).
    auto edge_key = [](uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a; };
    std::unordered_map<uint64_t, uint32_t> first_opposite;  // edge -> opposite corner of its first triangle
    std::vector<Spring> springs;
    std::unordered_map<uint64_t, uint8_t> joined;
    for (uint32_t f = 0; f < tri_count; ++f)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = t.triangles[3 * f + e], b = t.triangles[3 * f + (e + 1) % 3], c = t.triangles[3 * f + (e + 2) % 3];
            uint64_t key = edge_key(a, b);
            if (joined.emplace(key, DRAPE_GROUP_STRUCTURAL).second) springs.push_back({a, b, DRAPE_GROUP_STRUCTURAL});
            auto it = first_opposite.find(key);
            if (it == first_opposite.end()) {
                first_opposite.emplace(key, c);
            } else if (it->second != c) {
                uint64_t bend = edge_key(it->second, c);
                if (joined.emplace(bend, DRAPE_GROUP_BEND).second) springs.push_back({it->second, c, DRAPE_GROUP_BEND});
            }
        }
    // A bend spring recorded before the same pair showed up as an edge stays a bend spring; that
    // only happens for tiny closed meshes (a tetrahedron) and is harmless.
    build_neighbours(t, springs);
    finish(t, total_mass);
    out = std::move(t);
    return {};
}

}  // namespace drape
