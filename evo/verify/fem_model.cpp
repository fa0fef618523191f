#include "evo/verify/fem_model.hpp"

#include <stdexcept>

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
    if (options.subdivision < 1 || options.subdivision > 4)
        throw std::invalid_argument("subdivision " + std::to_string(options.subdivision) +
                                    " is not in [1, 4]");
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

    std::vector<int> ids(static_cast<std::size_t>(m.grid[0]) * m.grid[1] * m.grid[2], 0);
    auto node = [&](int i, int j, int k) {
        int& id = ids[static_cast<std::size_t>(i + m.grid[0] * (j + m.grid[1] * k))];
        if (id == 0) {
            m.node_grid.push_back({i, j, k});
            id = static_cast<int>(m.node_grid.size());
        }
        return id;
    };

    const int corners = quadratic(options.element) ? 20 : 8;
    for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y)
            for (int x = 0; x < n[0]; ++x) {
                const int material = cell_at(x, y, z);
                if (material == 0) continue;
                m.voxel_cells.push_back(spec.cell_index(x, y, z));
                for (int c = 0; c < s; ++c)
                    for (int b = 0; b < s; ++b)
                        for (int a = 0; a < s; ++a) {
                            const std::array<int, 3> low{(x * s + a) * step, (y * s + b) * step,
                                                         (z * s + c) * step};
                            std::vector<int> element(static_cast<std::size_t>(corners));
                            for (int e = 0; e < corners; ++e)
                                element[static_cast<std::size_t>(e)] =
                                    node(low[0] + kOffsets[e][0] * step / 2,
                                         low[1] + kOffsets[e][1] * step / 2,
                                         low[2] + kOffsets[e][2] * step / 2);
                            m.elements.push_back(std::move(element));
                            m.element_material.push_back(material);
                        }
                // The voxel's centre: a node for an even subdivision, else the middle element's
                // shape functions at its centre (20-node serendipity: -1/4 corners, 1/4 edges).
                std::vector<std::pair<int, double>> centre;
                if (s % 2 == 0) {
                    centre.push_back({node(x * ppv + ppv / 2, y * ppv + ppv / 2, z * ppv + ppv / 2),
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
                        node((x + (c & 1)) * ppv, (y + ((c >> 1) & 1)) * ppv,
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
                        on_held = on_held || contains;
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
        auto existing = [&](int i, int j, int k) {
            return ids[static_cast<std::size_t>(i + m.grid[0] * (j + m.grid[1] * k))];
        };
        const int h = ppv / 2;
        // The voxel's fixed nodes lie on one line (or are one point): they cannot hold its
        // rotation by themselves.
        auto fixed_points_collinear = [&](int x, int y, int z) {
            std::vector<std::array<int, 3>> points;
            for (int k = z * ppv; k <= (z + 1) * ppv; ++k)
                for (int j = y * ppv; j <= (y + 1) * ppv; ++j)
                    for (int i = x * ppv; i <= (x + 1) * ppv; ++i) {
                        const int id = existing(i, j, k);
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
                        const int minus = existing(lo[0], lo[1], lo[2]);
                        const int plus = existing(hi[0], hi[1], hi[2]);
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
