#include "evo/verify/coarse_nonlinearity.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace bhm::evo {

namespace {

using Vec = std::array<double, 3>;

const Vec& at(const NodalDisplacements& block, int id) {
    const auto it = block.find(id);
    if (it == block.end())
        throw std::runtime_error("ccx printed no displacement for node " + std::to_string(id));
    return it->second;
}

// The shape function of an element node at natural coordinates n (each -1, 0 or 1), evaluated
// at p in [-1, 1]^3: trilinear for the 8-node brick, serendipity for the 20-node one (corner:
// 1/8 prod(1 + p n) (sum p n - 2); mid-edge, n_k = 0: 1/4 (1 - p_k^2) prod_{a != k} (1 + p_a n_a)).
double shape(const std::array<int, 3>& n, const Vec& p, bool quadratic) {
    double product = 1.0, sum = 0.0;
    int mid_axis = -1;
    for (int a = 0; a < 3; ++a) {
        if (n[a] == 0) {
            mid_axis = a;
            continue;
        }
        product *= 1.0 + p[a] * n[a];
        sum += p[a] * n[a];
    }
    if (!quadratic) return product / 8.0;
    if (mid_axis < 0) return product * (sum - 2.0) / 8.0;
    return (1.0 - p[mid_axis] * p[mid_axis]) * product / 4.0;
}

}  // namespace

FemMeshOptions coarse_mesh_of(const FemMeshOptions& fine) {
    FemMeshOptions coarse = fine;
    coarse.subdivision = 1;
    return coarse;
}

NodalDisplacements with_coarse_nonlinearity(const FemModel& fine,
                                            const NodalDisplacements& fine_linear,
                                            const FemModel& coarse,
                                            const NodalDisplacements& coarse_linear,
                                            const NodalDisplacements& coarse_nonlinear) {
    if (fine.voxel_cells != coarse.voxel_cells)
        throw std::invalid_argument("the coarse and fine meshes are of different bodies");
    if (coarse.elements.size() != coarse.voxel_cells.size())
        throw std::invalid_argument("the coarse mesh has more than one element per voxel");
    const std::size_t voxels = fine.voxel_cells.size();
    if (voxels == 0 || fine.elements.size() % voxels != 0)
        throw std::invalid_argument("the fine mesh's elements are not a whole number per voxel");
    const std::size_t per_voxel = fine.elements.size() / voxels;
    const bool quadratic = coarse.options.element == FemElement::C3D20R;
    const int coarse_span = coarse.points_per_voxel;
    const double fine_span = fine.points_per_voxel;

    std::vector<char> fixed(fine.node_grid.size() + 1, 0);
    for (int id : fine.fixed_nodes)
        fixed[static_cast<std::size_t>(id)] = 1;
    std::vector<char> done(fine.node_grid.size() + 1, 0);
    NodalDisplacements out;
    for (std::size_t v = 0; v < voxels; ++v) {
        // The coarse element of voxel v: each node's natural coordinates and nonlinear part.
        const std::vector<int>& element = coarse.elements[v];
        const auto& coarse_low =
            coarse.node_grid[static_cast<std::size_t>(coarse.voxel_corners[v][0] - 1)];
        std::vector<std::array<int, 3>> natural;
        std::vector<Vec> part;
        for (int id : element) {
            const auto& g = coarse.node_grid[static_cast<std::size_t>(id - 1)];
            std::array<int, 3> n{};
            for (int a = 0; a < 3; ++a)
                n[a] = 2 * (g[a] - coarse_low[a]) / coarse_span - 1;
            natural.push_back(n);
            const Vec& nl = at(coarse_nonlinear, id);
            const Vec& lin = at(coarse_linear, id);
            part.push_back({nl[0] - lin[0], nl[1] - lin[1], nl[2] - lin[2]});
        }
        const auto& fine_low =
            fine.node_grid[static_cast<std::size_t>(fine.voxel_corners[v][0] - 1)];
        for (std::size_t e = v * per_voxel; e < (v + 1) * per_voxel; ++e)
            for (int id : fine.elements[e]) {
                if (done[static_cast<std::size_t>(id)]) continue;
                done[static_cast<std::size_t>(id)] = 1;
                Vec u = at(fine_linear, id);
                if (!fixed[static_cast<std::size_t>(id)]) {
                    const auto& g = fine.node_grid[static_cast<std::size_t>(id - 1)];
                    Vec p{};
                    for (int a = 0; a < 3; ++a)
                        p[a] = 2.0 * (g[a] - fine_low[a]) / fine_span - 1.0;
                    for (std::size_t i = 0; i < natural.size(); ++i) {
                        const double w = shape(natural[i], p, quadratic);
                        for (int a = 0; a < 3; ++a)
                            u[a] += w * part[i][a];
                    }
                }
                out[id] = u;
            }
    }
    return out;
}

}  // namespace bhm::evo
