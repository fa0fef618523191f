#include "evo/formats/surface_mesh.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "engine/io/text_file.hpp"

namespace bhm::evo {

namespace {

using Vec3 = std::array<double, 3>;

//! One boundary face of an occupied cell, its four lattice corners counter-clockwise from outside.
struct Quad {
    int cell = 0;
    std::array<int, 4> corner_bits{};     //!< bit 0 = +x, bit 1 = +y, bit 2 = +z of the cell
    std::array<std::int64_t, 4> point{};  //!< lattice point ids
    std::int64_t empty_side = 0;          //!< id of the empty (or outside) cell the face looks into
};

struct DisjointSets {
    std::vector<int> parent;
    explicit DisjointSets(int n) : parent(static_cast<std::size_t>(n)) {
        std::iota(parent.begin(), parent.end(), 0);
    }
    int find(int a) {
        while (parent[a] != a)
            a = parent[a] = parent[parent[a]];
        return a;
    }
    void join(int a, int b) { parent[find(a)] = find(b); }
};

std::vector<Quad> boundary_quads(const std::array<int, 3>& n,
                                 const std::vector<std::uint8_t>& cells) {
    const auto occupied = [&](int x, int y, int z) {
        if (x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) return false;
        return cells[static_cast<std::size_t>(x + n[0] * (y + n[1] * z))] != 0;
    };
    const std::int64_t px = n[0] + 1, py = n[1] + 1;
    std::vector<Quad> quads;
    for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y)
            for (int x = 0; x < n[0]; ++x) {
                if (!occupied(x, y, z)) continue;
                const int xyz[3] = {x, y, z};
                for (int axis = 0; axis < 3; ++axis)
                    for (int side = 0; side < 2; ++side) {
                        int nb[3] = {x, y, z};
                        nb[axis] += side ? 1 : -1;
                        if (occupied(nb[0], nb[1], nb[2])) continue;
                        // (u, v, axis) right-handed: (0,0),(1,0),(1,1),(0,1) in (u, v) turns
                        // counter-clockwise about +axis; the -axis face runs the other way.
                        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                        static constexpr int kPlus[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                        static constexpr int kMinus[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
                        Quad q;
                        q.cell = x + n[0] * (y + n[1] * z);
                        q.empty_side =
                            (nb[0] + 1) + (n[0] + 2) * static_cast<std::int64_t>(
                                                           (nb[1] + 1) + (n[1] + 2) * (nb[2] + 1));
                        for (int k = 0; k < 4; ++k) {
                            int offset[3];
                            offset[axis] = side;
                            offset[u] = side ? kPlus[k][0] : kMinus[k][0];
                            offset[v] = side ? kPlus[k][1] : kMinus[k][1];
                            q.corner_bits[k] = offset[0] | offset[1] << 1 | offset[2] << 2;
                            q.point[k] = (xyz[0] + offset[0]) +
                                         px * ((xyz[1] + offset[1]) + py * (xyz[2] + offset[2]));
                        }
                        quads.push_back(q);
                    }
            }
    return quads;
}

//! Builds the mesh; corner(cell, bits) gives that corner of that cell's voxel in metres.
template <class CornerFn>
SurfaceMesh build_surface(const std::array<int, 3>& n, const std::vector<std::uint8_t>& cells,
                          CornerFn corner) {
    if (n[0] < 0 || n[1] < 0 || n[2] < 0 ||
        cells.size() != static_cast<std::size_t>(n[0]) * n[1] * n[2])
        throw std::invalid_argument("surface mesh: lattice cells do not match its size");
    const std::vector<Quad> quads = boundary_quads(n, cells);
    const int incidences = static_cast<int>(quads.size()) * 4;  // (quad, corner slot)

    // The faces around each lattice edge: two normally; four where two voxels touch only along
    // this edge. Those four pair up either around each voxel (keeping the voxels apart) or around
    // each empty cell (keeping the two empty cells apart).
    struct EdgeUse {
        int quad, slot;  // the edge runs from slot to slot + 1 of the quad
    };
    std::unordered_map<std::int64_t, std::vector<EdgeUse>> edges;
    const std::int64_t points =
        static_cast<std::int64_t>(n[0] + 1) * (n[1] + 1) * static_cast<std::int64_t>(n[2] + 1);
    for (int q = 0; q < static_cast<int>(quads.size()); ++q)
        for (int k = 0; k < 4; ++k) {
            const auto a = quads[q].point[k], b = quads[q].point[(k + 1) % 4];
            edges[std::min(a, b) * points + std::max(a, b)].push_back({q, k});
        }
    std::vector<const std::vector<EdgeUse>*> crossings;  // the four-face edges
    for (const auto& [key, uses] : edges) {
        if (uses.size() == 4)
            crossings.push_back(&uses);
        else if (uses.size() != 2)
            throw std::logic_error("surface mesh: a lattice edge with an odd number of faces");
    }
    std::vector<char> around_empty(crossings.size(), 0);

    const auto sheets_of = [&] {
        DisjointSets sheets(incidences);
        const auto join_along = [&](EdgeUse e1, EdgeUse e2) {
            const Quad& q1 = quads[e1.quad];
            const Quad& q2 = quads[e2.quad];
            for (int end = 0; end < 2; ++end) {
                const int s1 = (e1.slot + end) % 4;
                for (int s2 : {e2.slot, (e2.slot + 1) % 4})
                    if (q2.point[s2] == q1.point[s1])
                        sheets.join(e1.quad * 4 + s1, e2.quad * 4 + s2);
            }
        };
        for (const auto& [key, uses] : edges)
            if (uses.size() == 2) join_along(uses[0], uses[1]);
        for (std::size_t c = 0; c < crossings.size(); ++c) {
            const auto& uses = *crossings[c];
            for (std::size_t i = 0; i < 4; ++i)
                for (std::size_t j = i + 1; j < 4; ++j) {
                    const Quad &a = quads[uses[i].quad], &b = quads[uses[j].quad];
                    if (around_empty[c] ? a.empty_side == b.empty_side : a.cell == b.cell)
                        join_along(uses[i], uses[j]);
                }
        }
        return sheets;
    };
    // A crossing whose two face pairs end up on the same two mesh vertices would leave an edge in
    // four triangles; the other pairing then separates them (at each end at most one pairing
    // merges). Flip such crossings until none is left.
    DisjointSets sheets = sheets_of();
    for (int round = 0; round < 16; ++round) {
        bool flipped = false;
        for (std::size_t c = 0; c < crossings.size(); ++c) {
            const auto& uses = *crossings[c];
            const auto ends = [&](const EdgeUse& u) {
                return std::pair{sheets.find(u.quad * 4 + u.slot),
                                 sheets.find(u.quad * 4 + (u.slot + 1) % 4)};
            };
            std::vector<std::pair<int, int>> seen;
            for (const auto& u : uses) {
                auto e = ends(u);
                if (e.first > e.second) std::swap(e.first, e.second);
                seen.push_back(e);
            }
            std::sort(seen.begin(), seen.end());
            if (std::unique(seen.begin(), seen.end()) - seen.begin() < 2) {
                around_empty[c] = !around_empty[c];
                flipped = true;
            }
        }
        if (!flipped) break;
        sheets = sheets_of();
    }

    // One mesh vertex per sheet; its position is the mean corner of the distinct voxels in it.
    SurfaceMesh mesh;
    std::vector<int> vertex_of_root(static_cast<std::size_t>(incidences), -1);
    std::vector<std::vector<int>> vertex_cells;
    std::vector<int> vertex_of(static_cast<std::size_t>(incidences));
    for (int i = 0; i < incidences; ++i) {
        const int root = sheets.find(i);
        int& v = vertex_of_root[root];
        if (v < 0) {
            v = static_cast<int>(mesh.vertices.size());
            mesh.vertices.push_back({0.0, 0.0, 0.0});
            vertex_cells.emplace_back();
        }
        vertex_of[i] = v;
        const Quad& q = quads[i / 4];
        auto& seen = vertex_cells[v];
        if (std::find(seen.begin(), seen.end(), q.cell) != seen.end()) continue;
        seen.push_back(q.cell);
        const Vec3 c = corner(q.cell, q.corner_bits[i % 4]);
        for (int a = 0; a < 3; ++a)
            mesh.vertices[v][a] += c[a];
    }
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        for (auto& coordinate : mesh.vertices[v])
            coordinate /= static_cast<double>(vertex_cells[v].size());

    mesh.triangles.reserve(quads.size() * 2);
    for (int q = 0; q < static_cast<int>(quads.size()); ++q) {
        const int* v = &vertex_of[static_cast<std::size_t>(q) * 4];
        const int material = cells[static_cast<std::size_t>(quads[q].cell)];
        mesh.triangles.push_back({v[0], v[1], v[2]});
        mesh.triangles.push_back({v[0], v[2], v[3]});
        mesh.triangle_material.push_back(material);
        mesh.triangle_material.push_back(material);
    }
    return mesh;
}

Vec3 rotate(const float* q, const Vec3& p) {
    // v' = v + 2 w (u x v) + 2 u x (u x v), q = (w, u) a unit quaternion.
    const double w = q[0], u[3] = {q[1], q[2], q[3]};
    const double t[3] = {2.0 * (u[1] * p[2] - u[2] * p[1]), 2.0 * (u[2] * p[0] - u[0] * p[2]),
                         2.0 * (u[0] * p[1] - u[1] * p[0])};
    return {p[0] + w * t[0] + (u[1] * t[2] - u[2] * t[1]),
            p[1] + w * t[1] + (u[2] * t[0] - u[0] * t[2]),
            p[2] + w * t[2] + (u[0] * t[1] - u[1] * t[0])};
}

Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

void put_u32(std::string& out, std::uint32_t value) {
    for (int i = 0; i < 4; ++i)
        out += static_cast<char>((value >> (8 * i)) & 0xffu);
}
void put_f32(std::string& out, double value) {
    put_u32(out, std::bit_cast<std::uint32_t>(static_cast<float>(value)));
}

}  // namespace

SurfaceMesh rest_surface(const std::array<int, 3>& size, const std::vector<std::uint8_t>& cells,
                         double L) {
    return build_surface(size, cells, [&](int cell, int bits) {
        const int x = cell % size[0], y = (cell / size[0]) % size[1],
                  z = cell / (size[0] * size[1]);
        return Vec3{(x + (bits & 1)) * L, (y + (bits >> 1 & 1)) * L, (z + (bits >> 2 & 1)) * L};
    });
}

SurfaceMesh deformed_surface(const engine::Replay& replay, const engine::VoxelPoses& frame) {
    const std::array<int, 3> size{replay.nx, replay.ny, replay.nz};
    const std::size_t cell_count = static_cast<std::size_t>(replay.nx) * replay.ny * replay.nz;
    const std::size_t voxels = replay.voxel_cell.size();
    if (frame.position_m.size() != 3 * voxels || frame.orientation.size() != 4 * voxels ||
        frame.size_m.size() != 3 * voxels || replay.voxel_material.size() != voxels)
        throw std::invalid_argument("surface mesh: the frame does not match the replay's voxels");
    std::vector<std::uint8_t> cells(cell_count, 0);
    std::vector<int> voxel_of_cell(cell_count, -1);
    for (std::size_t v = 0; v < voxels; ++v) {
        const auto c = static_cast<std::size_t>(replay.voxel_cell[v]);
        if (c >= cell_count)
            throw std::invalid_argument("surface mesh: voxel cell outside lattice");
        cells[c] = replay.voxel_material[v];
        voxel_of_cell[c] = static_cast<int>(v);
    }
    return build_surface(size, cells, [&](int cell, int bits) {
        const auto v = static_cast<std::size_t>(voxel_of_cell[static_cast<std::size_t>(cell)]);
        Vec3 local;
        for (int a = 0; a < 3; ++a)
            local[a] = ((bits >> a & 1) ? 0.5 : -0.5) * frame.size_m[3 * v + a];
        const Vec3 r = rotate(&frame.orientation[4 * v], local);
        return Vec3{frame.position_m[3 * v] + r[0], frame.position_m[3 * v + 1] + r[1],
                    frame.position_m[3 * v + 2] + r[2]};
    });
}

double enclosed_volume(const SurfaceMesh& mesh) {
    double six_v = 0.0;
    for (const auto& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[t[0]];
        const Vec3 c = cross(mesh.vertices[t[1]], mesh.vertices[t[2]]);
        six_v += a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
    }
    return six_v / 6.0;
}

std::string stl_binary(const SurfaceMesh& mesh) {
    std::string out(80, ' ');
    const std::string header = "BHM Studio voxel body surface, metres";
    out.replace(0, header.size(), header);
    out.reserve(84 + mesh.triangles.size() * 50);
    put_u32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const auto& t : mesh.triangles) {
        const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        Vec3 normal =
            cross({b[0] - a[0], b[1] - a[1], b[2] - a[2]}, {c[0] - a[0], c[1] - a[1], c[2] - a[2]});
        const double length = std::hypot(normal[0], normal[1], normal[2]);
        for (auto& component : normal)
            component = length > 0.0 ? component / length : 0.0;
        for (const Vec3* p : {static_cast<const Vec3*>(&normal), &a, &b, &c})
            for (double component : *p)
                put_f32(out, component);
        out += '\0';  // attribute byte count
        out += '\0';
    }
    return out;
}

std::vector<std::string> obj_material_names(const std::vector<MaterialEntry>& materials) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        std::string name;
        for (char c : materials[i].name)
            name += (c == ' ' || c == '\t' || c == '\n' || c == '\r') ? '_' : c;
        if (name.empty()) name = "material";
        // Unique: a later duplicate gets its 1-based palette index appended.
        if (std::find(names.begin(), names.end(), name) != names.end())
            name += "_" + std::to_string(i + 1);
        names.push_back(name);
    }
    return names;
}

std::string obj_document(const SurfaceMesh& mesh, const std::vector<MaterialEntry>& materials,
                         const std::string& mtl_file_name) {
    const auto names = obj_material_names(materials);
    std::string out = "# BHM Studio voxel body surface, metres\nmtllib " + mtl_file_name + "\n";
    for (const auto& v : mesh.vertices)
        out += "v " + engine::format_number(v[0]) + " " + engine::format_number(v[1]) + " " +
               engine::format_number(v[2]) + "\n";
    for (std::size_t m = 1; m <= materials.size(); ++m) {
        bool started = false;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            if (mesh.triangle_material[t] != static_cast<int>(m)) continue;
            if (!started) {
                out += "g " + names[m - 1] + "\nusemtl " + names[m - 1] + "\n";
                started = true;
            }
            const auto& tri = mesh.triangles[t];
            out += "f " + std::to_string(tri[0] + 1) + " " + std::to_string(tri[1] + 1) + " " +
                   std::to_string(tri[2] + 1) + "\n";
        }
    }
    for (int material : mesh.triangle_material)
        if (material < 1 || material > static_cast<int>(materials.size()))
            throw std::invalid_argument("OBJ export: material index " + std::to_string(material) +
                                        " is not in the palette of " +
                                        std::to_string(materials.size()));
    return out;
}

std::string mtl_document(const std::vector<MaterialEntry>& materials) {
    const auto names = obj_material_names(materials);
    std::string out = "# BHM Studio materials\n";
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const auto& c = materials[i].color;
        out += "newmtl " + names[i] + "\nKd " + engine::format_number(c[0]) + " " +
               engine::format_number(c[1]) + " " + engine::format_number(c[2]) + "\n";
    }
    return out;
}

}  // namespace bhm::evo
