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

namespace {

// Calls visit(neighbour cell) for each of v's lateral neighbours across `axis` that is a voxel and
// has no link on `side` along `axis` (the confining neighbours).
template <typename Visit>
void visit_confining(const Model::Data& d, int v, int axis, int side, Visit visit) {
    const BodySpec& spec = d.spec;
    const int c = d.voxel_cell[v];
    const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
    const std::array<int, 3> limit{spec.nx, spec.ny, spec.nz};
    const std::array<int, 3> stride{1, spec.nx, spec.nx * spec.ny};
    const int along = xyz[axis] + side;
    const bool in_lattice = along >= 0 && along < limit[axis];
    visit_lateral_cells(d, v, axis, [&](int neighbour) {
        if (spec.material[neighbour] == 0) return;
        if (!in_lattice || spec.material[neighbour + side * stride[axis]] == 0) visit(neighbour);
    });
}

}  // namespace

int confining_neighbours(const Model::Data& d, int v, int axis, int side) {
    int count = 0;
    visit_confining(d, v, axis, side, [&](int) { ++count; });
    return count;
}

bool held_confining_neighbour(const Model::Data& d, int v, int axis, int side) {
    const std::vector<std::uint8_t>& fixed = d.spec.fixed;
    bool held = false;
    if (fixed.empty()) return false;
    visit_confining(d, v, axis, side, [&](int neighbour) { held = held || fixed[neighbour] != 0; });
    return held;
}

namespace {

// The stiffening kappa of one confined half, per mode.
struct ConfinedHalf {
    double axial = 1.0, bending = 1.0;
};

// The half of the link inside voxel `w`, confined by n of its neighbours on `side`; `narrow` is
// the link's other end. A neck end (neither end held, no held neighbour confining it) takes the
// lateral stress form of the header, every other confined end kappa = 1 + c n g with g = 1 axial
// and sqrt(M / E) in bending.
ConfinedHalf confined_half(const Model::Data& d, int w, int narrow, int axis, int side, int n,
                           double nu, bool free_link) {
    if (n == 0) return {};
    if (!free_link || held_confining_neighbour(d, w, axis, side))
        return {1.0 + kConfinedHalfStiffening * n * 1.0,
                1.0 + kConfinedHalfStiffening * n * std::sqrt(poisson_wave_factor(nu))};
    int beside_narrow = 0;  // the narrow end's lateral neighbours: its faces that are not free
    visit_lateral_cells(d, narrow, axis, [&](int c) { beside_narrow += d.spec.material[c] != 0; });
    // n > 0 leaves the narrow end at least one free lateral face (a confining neighbour's cell
    // beside `narrow` is empty).
    const double shape_factor = 1.0 / (4 - beside_narrow);
    // K0; an auxetic end (nu < 0, outside the fitted range) keeps K0 = 0, so kappa >= 1.
    const double lateral_stress_ratio = std::max(0.0, nu) / (1.0 - nu);
    return {1.0 + kConfinedHalfStiffening * n / poisson_wave_factor(nu),
            1.0 + kNeckHalfStiffening * n *
                      (1.0 + kNeckLateralStress * shape_factor * lateral_stress_ratio)};
}

// 2 / (1 / kappa_a + 1 / kappa_b), at most kConfinedLinkCap.
double series_factor(double kappa_a, double kappa_b) {
    return std::min(kConfinedLinkCap, 2.0 / (1.0 / kappa_a + 1.0 / kappa_b));
}

}  // namespace

ConfinedLinkFactors confined_link_factors(const Model::Data& d, int v, int b, int axis, double nu_v,
                                          double nu_b) {
    const int n_v = confining_neighbours(d, v, axis, +1);
    const int n_b = confining_neighbours(d, b, axis, -1);
    if (n_v == 0 && n_b == 0) return {};
    const bool free_link = d.voxel_fixed[v] == 0 && d.voxel_fixed[b] == 0;
    const ConfinedHalf half_v = confined_half(d, v, b, axis, +1, n_v, nu_v, free_link);
    const ConfinedHalf half_b = confined_half(d, b, v, axis, -1, n_b, nu_b, free_link);
    return {series_factor(half_v.axial, half_b.axial),
            series_factor(half_v.bending, half_b.bending)};
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
