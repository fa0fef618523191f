#include "engine/internal/link_confinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/internal/poisson.hpp"

namespace bhm::engine {

namespace {

// Calls visit(neighbour cell) for each of v's four lateral neighbours across `axis` that lies
// inside the lattice (filled or not): the walk both counts below share.
template <typename Visit>
void visit_lateral_cells(const Model::Data& d, int v, int axis, Visit visit) {
    const BodySpec& spec = d.spec;
    const int c = d.voxel_cell[v];
    const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
    const std::array<int, 3> limit{spec.nx, spec.ny, spec.nz};
    const std::array<int, 3> stride{1, spec.nx, spec.nx * spec.ny};
    for (int lateral = 0; lateral < 3; ++lateral) {
        if (lateral == axis) continue;
        for (int s = -1; s <= 1; s += 2)
            if (xyz[lateral] + s >= 0 && xyz[lateral] + s < limit[lateral])
                visit(c + s * stride[lateral]);
    }
}

}  // namespace

int confining_neighbours(const Model::Data& d, int v, int axis, int side) {
    const BodySpec& spec = d.spec;
    const int c = d.voxel_cell[v];
    const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
    const std::array<int, 3> limit{spec.nx, spec.ny, spec.nz};
    const std::array<int, 3> stride{1, spec.nx, spec.nx * spec.ny};
    const int along = xyz[axis] + side;
    const bool in_lattice = along >= 0 && along < limit[axis];
    int count = 0;
    visit_lateral_cells(d, v, axis, [&](int neighbour) {
        if (spec.material[neighbour] == 0) return;
        if (!in_lattice || spec.material[neighbour + side * stride[axis]] == 0) ++count;
    });
    return count;
}

namespace {

// 2 / (1 / kappa_a + 1 / kappa_b) with kappa = 1 + c n g, at most kConfinedLinkCap.
double series_factor(int n_a, double g_a, int n_b, double g_b) {
    const double kappa_a = 1.0 + kConfinedHalfStiffening * n_a * g_a;
    const double kappa_b = 1.0 + kConfinedHalfStiffening * n_b * g_b;
    return std::min(kConfinedLinkCap, 2.0 / (1.0 / kappa_a + 1.0 / kappa_b));
}

}  // namespace

ConfinedLinkFactors confined_link_factors(const Model::Data& d, int v, int b, int axis, double nu_v,
                                          double nu_b) {
    const int n_v = confining_neighbours(d, v, axis, +1);
    const int n_b = confining_neighbours(d, b, axis, -1);
    if (n_v == 0 && n_b == 0) return {};
    const double root_v = std::sqrt(poisson_wave_factor(nu_v));
    const double root_b = std::sqrt(poisson_wave_factor(nu_b));
    // The axial mode takes g = 1 (its normal stress carries the Poisson coupling's volumetric
    // term, which the relaxed split no longer locks), bending and torsion sqrt(M / E).
    return {series_factor(n_v, 1.0, n_b, 1.0), series_factor(n_v, root_v, n_b, root_b)};
}

int same_material_lateral_neighbours(const Model::Data& d, int v, int axis) {
    const std::vector<std::uint8_t>& material = d.spec.material;
    const std::uint8_t own = material[d.voxel_cell[v]];
    int count = 0;
    visit_lateral_cells(d, v, axis, [&](int neighbour) { count += material[neighbour] == own; });
    return count;
}

double mixed_link_stiffening(const Model::Data& d, int v, int b, int axis, const Material& mv,
                             const Material& mb) {
    const double e_v = mv.youngs_modulus_pa, e_b = mb.youngs_modulus_pa;
    if (e_v == e_b) return 1.0;
    const bool v_soft = e_v < e_b;
    const double nu_v = mv.poisson_ratio, nu_b = mb.poisson_ratio;
    const double layer = same_material_lateral_neighbours(d, v_soft ? v : b, axis) / 4.0;
    const double e_soft = v_soft ? e_v : e_b, e_stiff = v_soft ? e_b : e_v;
    const double nu_soft = v_soft ? nu_v : nu_b;
    const double contrast = e_stiff / e_soft;
    const double kappa =
        1.0 + kMixedSoftStiffening * layer *
                  std::pow(1.0 - 1.0 / contrast, kMixedContrastExponent) *
                  std::pow(1.0 - 1.0 / poisson_wave_factor(nu_soft), kMixedPoissonExponent);
    // Halves of stiffness proportional to E_soft kappa and E_stiff in series, over the plain pair.
    return (contrast + 1.0) / (contrast / kappa + 1.0);
}

int stiff_lateral_links(const Model::Data& d, int v, int b, int axis) {
    const BodySpec& spec = d.spec;
    const auto modulus = [&](int material) {
        return spec.materials[material - 1].youngs_modulus_pa;
    };
    const double e_v = modulus(spec.material[d.voxel_cell[v]]);
    const double e_b = modulus(spec.material[d.voxel_cell[b]]);
    if (e_v == e_b) return 0;
    const double e_max = std::max(e_v, e_b);
    // b's cell is v's one step along axis, so v's lateral cell plus that step is b's.
    const int step = d.voxel_cell[b] - d.voxel_cell[v];
    int count = 0;
    visit_lateral_cells(d, v, axis, [&](int beside_v) {
        const int mv = spec.material[beside_v], mb = spec.material[beside_v + step];
        if (mv != 0 && mb != 0 && modulus(mv) >= e_max && modulus(mb) >= e_max) ++count;
    });
    return count;
}

double mixed_link_bending_factor(const Model::Data& d, int v, int b, int axis, const Material& mv,
                                 const Material& mb) {
    const int stiff = stiff_lateral_links(d, v, b, axis);
    if (stiff == 0) return 1.0;
    const double e_v = mv.youngs_modulus_pa, e_b = mb.youngs_modulus_pa;
    // The arithmetic mean over the harmonic one (series), a quarter of the way per stiff link.
    const double voigt_over_series = (e_v + e_b) * (e_v + e_b) / (4.0 * e_v * e_b);
    return 1.0 + 0.25 * stiff * (voigt_over_series - 1.0);
}

}  // namespace bhm::engine
