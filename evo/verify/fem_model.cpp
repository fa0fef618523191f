#include "evo/verify/fem_model.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <unordered_map>

namespace bhm::evo {

namespace {

// Abaqus node order of a 20-node brick as offsets (in half-element steps) from its low corner;
// the first 8 are the corners, which are also the order of an 8-node brick.
constexpr int kOffsets[20][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2},
                                 {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {2, 1, 0},
                                 {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2}, {1, 2, 2},
                                 {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};

bool quadratic(FemElement e) {
    return e == FemElement::C3D20R;
}

// A muscle cell's own fibre axis where it differs from its material's, else -1 (the material's).
int own_fibre_axis(const engine::BodySpec& spec, int cell) {
    if (spec.fibre_axis.empty()) return -1;
    const std::uint8_t axis = spec.fibre_axis[static_cast<std::size_t>(cell)];
    const int k = spec.material[static_cast<std::size_t>(cell)];
    if (axis > 2 || k == 0) return -1;
    const engine::Material& m = spec.materials.at(static_cast<std::size_t>(k - 1));
    if (m.actuation_model != engine::ActuationModel::Muscle || !engine::is_active(m)) return -1;
    return axis == m.muscle.fibre_axis ? -1 : axis;
}

}  // namespace

std::string fem_element_name(FemElement element) {
    return element == FemElement::C3D20R ? "C3D20R" : "C3D8I";
}

FemElement parse_fem_element(const std::string& name) {
    if (name == "C3D20R") return FemElement::C3D20R;
    if (name == "C3D8I") return FemElement::C3D8I;
    throw std::invalid_argument("element '" + name + "' is not C3D20R or C3D8I");
}

std::array<double, 3> FemModel::node_position_m(int id) const {
    const auto& g = node_grid.at(static_cast<std::size_t>(id - 1));
    const double h = voxel_size_m / points_per_voxel;
    return {g[0] * h, g[1] * h, g[2] * h};
}

FemModel build_fem_model(const engine::BodySpec& spec, const FemMeshOptions& options) {
    // Up to 6: the continuum suite's third mesh (tests/engine/test_engine_continuum.cpp); bhm
    // verify's own meshes stop at 4 (cmd_verify.cpp, the node cap).
    if (options.subdivision < 1 || options.subdivision > 6)
        throw std::invalid_argument("subdivision " + std::to_string(options.subdivision) +
                                    " is not in [1, 6]");
    FemModel m;
    m.options = options;
    m.voxel_size_m = spec.voxel_size_m;
    const int s = options.subdivision;
    const int step = quadratic(options.element) ? 2 : 1;  // grid points per element edge
    const int ppv = s * step;
    m.points_per_voxel = ppv;
    m.grid = {spec.nx * ppv + 1, spec.ny * ppv + 1, spec.nz * ppv + 1};
    const std::array<int, 3> n{spec.nx, spec.ny, spec.nz};

    auto cell_at = [&](int x, int y, int z) -> int {  // material, 0 outside or empty
        if (x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) return 0;
        return spec.material[static_cast<std::size_t>(spec.cell_index(x, y, z))];
    };
    auto held = [&](int x, int y, int z) {
        return !spec.fixed.empty() &&
               spec.fixed[static_cast<std::size_t>(spec.cell_index(x, y, z))] != 0;
    };

    // A node is a grid point of one group of face-joined voxels around it: voxels that meet only
    // along an edge or at a corner (no face path between them among the voxels around the point)
    // each get a node of their own there. Our engine does not bond such voxels (its links join
    // face neighbours; an edge spring needs both voxels between them), and the continuum's
    // limit does not either (a line or point contact's compliance grows without bound as the
    // mesh is refined), so a shared node would weld them at a stiffness set by the mesh
    // (docs/verify.md, "Edge and corner contacts").
    const auto grid_index = [&](int i, int j, int k) {
        return static_cast<std::int64_t>(i) + static_cast<std::int64_t>(m.grid[0]) *
                                                  (j + static_cast<std::int64_t>(m.grid[1]) * k);
    };
    // The lowest cell index of the face-joined group of material voxels around grid point g
    // that holds voxel `cell` (which contains g).
    const auto group_of = [&](const std::array<int, 3>& g, const std::array<int, 3>& cell) {
        std::array<std::array<int, 3>, 8> around{};
        int count = 0;
        std::array<int, 3> lo{}, hi{};
        for (int a = 0; a < 3; ++a) {
            const bool on_plane = g[a] % ppv == 0;
            lo[a] = on_plane ? g[a] / ppv - 1 : g[a] / ppv;
            hi[a] = g[a] / ppv;
            if (!on_plane) lo[a] = hi[a];
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x)
                    if (cell_at(x, y, z) != 0)
                        around[static_cast<std::size_t>(count++)] = {x, y, z};
        if (count <= 1) return spec.cell_index(cell[0], cell[1], cell[2]);
        // Grow the group from `cell` across shared faces (neighbours differ by one on one axis).
        std::array<bool, 8> in{};
        for (int i = 0; i < count; ++i)
            in[static_cast<std::size_t>(i)] = around[static_cast<std::size_t>(i)] == cell;
        for (bool grew = true; grew;) {
            grew = false;
            for (int i = 0; i < count; ++i) {
                if (in[static_cast<std::size_t>(i)]) continue;
                for (int j = 0; j < count && !in[static_cast<std::size_t>(i)]; ++j) {
                    if (!in[static_cast<std::size_t>(j)]) continue;
                    const auto& p = around[static_cast<std::size_t>(i)];
                    const auto& q = around[static_cast<std::size_t>(j)];
                    const int apart =
                        std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
                    if (apart == 1) in[static_cast<std::size_t>(i)] = grew = true;
                }
            }
        }
        int lowest = spec.cell_index(cell[0], cell[1], cell[2]);
        for (int i = 0; i < count; ++i)
            if (in[static_cast<std::size_t>(i)]) {
                const auto& p = around[static_cast<std::size_t>(i)];
                lowest = std::min(lowest, spec.cell_index(p[0], p[1], p[2]));
            }
        return lowest;
    };
    std::unordered_map<std::int64_t, int> ids;  // (grid point, group) -> node id
    std::vector<int> node_group;                // node id - 1 -> its group (group_of)
    const std::int64_t groups = static_cast<std::int64_t>(n[0]) * n[1] * n[2];
    const auto key_of = [&](const std::array<int, 3>& cell, int i, int j, int k) {
        return grid_index(i, j, k) * groups + group_of({i, j, k}, cell);
    };
    // The node of voxel `cell` at grid point (i, j, k), made on first use.
    const auto node_of = [&](const std::array<int, 3>& cell, int i, int j, int k) {
        const auto [it, added] = ids.try_emplace(key_of(cell, i, j, k), 0);
        if (added) {
            m.node_grid.push_back({i, j, k});
            node_group.push_back(group_of({i, j, k}, cell));
            it->second = static_cast<int>(m.node_grid.size());
        }
        return it->second;
    };
    // The node of voxel `cell` at (i, j, k) if one was made, else 0.
    const auto existing = [&](const std::array<int, 3>& cell, int i, int j, int k) {
        const auto it = ids.find(key_of(cell, i, j, k));
        return it == ids.end() ? 0 : it->second;
    };

    const int corners = quadratic(options.element) ? 20 : 8;
    for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y)
            for (int x = 0; x < n[0]; ++x) {
                const int material = cell_at(x, y, z);
                if (material == 0) continue;
                const std::array<int, 3> cell{x, y, z};
                m.voxel_cells.push_back(spec.cell_index(x, y, z));
                const int fibre = own_fibre_axis(spec, spec.cell_index(x, y, z));
                for (int c = 0; c < s; ++c)
                    for (int b = 0; b < s; ++b)
                        for (int a = 0; a < s; ++a) {
                            const std::array<int, 3> low{(x * s + a) * step, (y * s + b) * step,
                                                         (z * s + c) * step};
                            std::vector<int> element(static_cast<std::size_t>(corners));
                            for (int e = 0; e < corners; ++e)
                                element[static_cast<std::size_t>(e)] =
                                    node_of(cell, low[0] + kOffsets[e][0] * step / 2,
                                            low[1] + kOffsets[e][1] * step / 2,
                                            low[2] + kOffsets[e][2] * step / 2);
                            m.elements.push_back(std::move(element));
                            m.element_material.push_back(material);
                            m.element_fibre.push_back(fibre);
                        }
                // The voxel's centre: a node for an even subdivision, else the middle element's
                // shape functions at its centre (20-node serendipity: -1/4 corners, 1/4 edges).
                std::vector<std::pair<int, double>> centre;
                if (s % 2 == 0) {
                    centre.push_back(
                        {node_of(cell, x * ppv + ppv / 2, y * ppv + ppv / 2, z * ppv + ppv / 2),
                         1.0});
                } else {
                    const int mid = (s - 1) / 2;
                    const auto& e = m.elements[m.elements.size() - static_cast<std::size_t>(
                                                                        s * s * s) +
                                               static_cast<std::size_t>(mid + s * (mid + s * mid))];
                    for (int k = 0; k < corners; ++k)
                        centre.push_back({e[static_cast<std::size_t>(k)],
                                          corners == 8 ? 0.125 : (k < 8 ? -0.25 : 0.25)});
                }
                m.voxel_centre.push_back(std::move(centre));
                std::array<int, 8> box{};
                for (int c = 0; c < 8; ++c)
                    box[static_cast<std::size_t>(c)] =
                        node_of(cell, (x + (c & 1)) * ppv, (y + ((c >> 1) & 1)) * ppv,
                                (z + ((c >> 2) & 1)) * ppv);
                m.voxel_corners.push_back(box);
            }

    // Held nodes: on a held voxel, and at least half a voxel from every free material voxel.
    for (std::size_t id = 1; id <= m.node_grid.size(); ++id) {
        const auto& g = m.node_grid[id - 1];
        bool on_held = false, near_free = false;
        std::array<int, 3> lo{}, hi{};
        for (int a = 0; a < 3; ++a) {
            lo[a] = g[a] / ppv - 2;
            hi[a] = g[a] / ppv + 1;
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) {
                    if (cell_at(x, y, z) == 0) continue;
                    const std::array<int, 3> c{x, y, z};
                    bool contains = true, within_half = true;
                    for (int a = 0; a < 3; ++a) {
                        contains = contains && c[a] * ppv <= g[a] && g[a] <= (c[a] + 1) * ppv;
                        // the cell meets the open box (p - 1/2, p + 1/2) around the node
                        within_half = within_half && 2 * (c[a] + 1) * ppv > 2 * g[a] - ppv &&
                                      2 * c[a] * ppv < 2 * g[a] + ppv;
                    }
                    if (held(x, y, z)) {
                        // only a held voxel of the node's own group holds it
                        on_held = on_held || (contains && group_of(g, c) == node_group[id - 1]);
                    } else if (within_half) {
                        near_free = true;
                    }
                }
        if (on_held && !near_free) m.fixed_nodes.push_back(static_cast<int>(id));
    }

    // Held voxels whose rotation the fixed nodes leave free: tie their opposite face centres
    // (only where the mesh has a node there: an even number of grid points per voxel edge).
    if (ppv % 2 == 0 && !spec.fixed.empty()) {
        std::vector<char> fixed(m.node_grid.size() + 1, 0);
        for (int id : m.fixed_nodes)
            fixed[static_cast<std::size_t>(id)] = 1;
        const int h = ppv / 2;
        // The voxel's fixed nodes lie on one line (or are one point): they cannot hold its
        // rotation by themselves.
        auto fixed_points_collinear = [&](int x, int y, int z) {
            std::vector<std::array<int, 3>> points;
            for (int k = z * ppv; k <= (z + 1) * ppv; ++k)
                for (int j = y * ppv; j <= (y + 1) * ppv; ++j)
                    for (int i = x * ppv; i <= (x + 1) * ppv; ++i) {
                        const int id = existing({x, y, z}, i, j, k);
                        if (id != 0 && fixed[static_cast<std::size_t>(id)])
                            points.push_back({i, j, k});
                    }
            for (std::size_t a = 2; a < points.size(); ++a) {
                const auto& p0 = points[0];
                const std::array<int, 3> d1{points[1][0] - p0[0], points[1][1] - p0[1],
                                            points[1][2] - p0[2]};
                const std::array<int, 3> d{points[a][0] - p0[0], points[a][1] - p0[1],
                                           points[a][2] - p0[2]};
                if (d1[1] * d[2] - d1[2] * d[1] != 0 || d1[2] * d[0] - d1[0] * d[2] != 0 ||
                    d1[0] * d[1] - d1[1] * d[0] != 0)
                    return false;
            }
            return true;
        };
        for (int z = 0; z < n[2]; ++z)
            for (int y = 0; y < n[1]; ++y)
                for (int x = 0; x < n[0]; ++x) {
                    if (cell_at(x, y, z) == 0 || !held(x, y, z)) continue;
                    if (!fixed_points_collinear(x, y, z)) continue;  // a fixed plane holds it
                    const std::array<int, 3> centre{x * ppv + h, y * ppv + h, z * ppv + h};
                    for (int axis = 0; axis < 3; ++axis) {
                        std::array<int, 3> lo = centre, hi = centre;
                        lo[static_cast<std::size_t>(axis)] -= h;
                        hi[static_cast<std::size_t>(axis)] += h;
                        const int minus = existing({x, y, z}, lo[0], lo[1], lo[2]);
                        const int plus = existing({x, y, z}, hi[0], hi[1], hi[2]);
                        if (minus == 0 || plus == 0 || fixed[static_cast<std::size_t>(minus)] ||
                            fixed[static_cast<std::size_t>(plus)])
                            continue;  // held already by two fixed points on this axis
                        for (int dof = 1; dof <= 3; ++dof)
                            if (dof != axis + 1) m.rotation_ties.push_back({plus, minus, dof});
                    }
                }
    }
    return m;
}

}  // namespace bhm::evo
