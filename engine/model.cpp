// Model::build: validates a BodySpec and precomputes every constant a step needs.
#include "engine/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engine/internal/edge_springs.hpp"
#include "engine/internal/link_confinement.hpp"
#include "engine/internal/model_data.hpp"
#include "engine/internal/moduli.hpp"
#include "engine/internal/muscle_drive.hpp"
#include "engine/internal/poisson.hpp"
#include "engine/limits.hpp"

namespace bhm::engine {
namespace {

[[noreturn]] void reject(const std::string& what) {
    throw std::invalid_argument("body spec: " + what);
}

// The envelope lives in limits.cpp (shared with evo/'s validation): the first problem is the
// reason.
void validate(const BodySpec& spec) {
    const std::vector<limits::Problem> problems = limits::body_spec_problems(spec);
    if (!problems.empty()) reject(problems.front().field + " " + problems.front().message);
}

// The largest relative size change a voxel's actuation reaches (|size - 1|).
double actuation_reach(const Model::Data& d, int v) {
    const double reach = std::sqrt(d.act_sin[v] * d.act_sin[v] + d.act_cos[v] * d.act_cos[v]);
    // A muscle voxel's links reach further than its isotropic (mean) scale (muscle_drive.hpp).
    return d.muscle.signals == 0 ? reach : std::max(reach, d.muscle.reach[v]);
}

// A bound on the damping rate of one link: the largest eigenvalue of M^-1/2 C M^-1/2 over the
// link's twelve degrees of freedom (M: the masses m_a, m_b and inertias I = m L^2 / 6 of its
// ends, C = beta K in its frame, straight, at the largest actuated size `scale`, length
// scale L), so C <= lambda M. In the frame the modes decouple: axial k_a (1/m_a + 1/m_b),
// torsion k_t (1/I_a + 1/I_b), and per bending plane the rank-two pair of the shear mode
// (ta + tb - 2 omega_F, omega_F = (u_b - u_a) / l, stiffness k_s) and the curvature mode
// (ta - tb, k_b): the largest eigenvalue of their 2 x 2 Gram matrix. Axial stiffness scales with
// the size, bending and torsion with its square, l with it. Being proportional to M per end
// (isotropic per 3-vector), the bound holds in any rotated frame.
double link_damping_rate_bound(double beta, double k_axial, double k_bend, double k_torsion,
                               double m_a, double m_b, double L, double scale,
                               double rotary_inertia_scale) {
    const double i_a = rotary_inertia_scale * m_a * L * L / 6.0;
    const double i_b = rotary_inertia_scale * m_b * L * L / 6.0;
    const double ka = k_axial * scale, kb = k_bend * scale * scale;
    const double kt = k_torsion * scale * scale;
    const double ks = std::min(static_cast<double>(kShearPerTorsion) * kt, 3.0 * kb);
    const double l = L * scale;
    const double axial = ka * (1.0 / m_a + 1.0 / m_b);
    const double torsion = kt * (1.0 / i_a + 1.0 / i_b);
    const double rot = 1.0 / i_a + 1.0 / i_b;
    const double ss = ks * (rot + 4.0 / (l * l) * (1.0 / m_a + 1.0 / m_b));
    const double dd = kb * rot;
    const double sd = std::sqrt(ks * kb) * (1.0 / i_a - 1.0 / i_b);
    const double bend = 0.5 * (ss + dd) + std::sqrt(0.25 * (ss - dd) * (ss - dd) + sd * sd);
    return beta * std::max({axial, torsion, bend});
}

// Held voxels' rotation. A held voxel's centre is fixed; its rotation stands for the material's
// rotation at the clamp, w = (curl u) / 2. On a held face every displacement and its derivatives
// along the face vanish, so w about the face's normal is 0, but about an axis in the face it is
// half the shear strain there (d u_n / d x_t), which a clamped soft layer has: locking it
// stiffened 100x soft layers in a stiff cantilever by 2.3 points (docs/physics.md). So about
// axis a a held voxel turns when exactly one of the two axes across a has a held face
// neighbour: a held face's voxels turn about the two axes in it, a held line's about the two
// axes across the line (never about the line: the body would hinge on it), a lone held voxel or
// one inside a held block not at all. Free voxels turn about every axis.
// A held voxel that turns does so against a spring to the clamp of its own material,
// kClampWallStiffness E L^3 per radian (about all three axes; its locked axes stay at 0 anyway):
// a stiff voxel in a clamped face barely turns, so a stiff layer held between soft ones does not
// hinge at the clamp (freely turning, stiff layers in a 100x softer beam went -2.8 -> +14.9 %),
// while a soft voxel follows its layer's shear. For a held voxel and its free neighbour under
// simple shear gamma (chord turned by gamma, the neighbour by gamma / 2), the held end of their
// link (4 E I / L = E L^3 / 3) comes to rest at gamma / 2, the continuum's rotation, with a spring
// of E L^3 / 2; fitted on the 100x layered cantilevers against CalculiX it is 0.3 (docs/physics.md,
// "The clamp").
inline constexpr double kClampWallStiffness = 0.3;
std::array<bool, 3> held_voxel_turns(const Model::Data& d, int v) {
    if (!d.voxel_fixed[v]) return {true, true, true};
    const BodySpec& spec = d.spec;
    const int c = d.voxel_cell[v];
    const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
    const std::array<int, 3> limit{spec.nx, spec.ny, spec.nz};
    const std::array<int, 3> stride{1, spec.nx, spec.nx * spec.ny};
    std::array<bool, 3> held_along{false, false, false};
    for (int k = 0; k < 3; ++k)
        for (int s = -1; s <= 1; s += 2) {
            if (xyz[k] + s < 0 || xyz[k] + s >= limit[k]) continue;
            const int n = d.cell_voxel[c + s * stride[k]];
            if (n >= 0 && d.voxel_fixed[n]) held_along[k] = true;
        }
    std::array<bool, 3> turns{};
    for (int a = 0; a < 3; ++a)
        turns[a] = held_along[(a + 1) % 3] != held_along[(a + 2) % 3];
    return turns;
}

bool turns_at_all(const Model::Data& d, int v) {
    const std::array<bool, 3> turns = held_voxel_turns(d, v);
    return turns[0] || turns[1] || turns[2];
}

void resize_voxels(Model::Data& d, int n) {
    for (auto* v : {&d.movable, &d.mass, &d.dt_inv_mass, &d.dt_inv_inertia, &d.linear_keep,
                    &d.angular_keep[0], &d.angular_keep[1], &d.angular_keep[2], &d.wall_stiffness,
                    &d.floor_k, &d.floor_c, &d.mu_static, &d.mu_dynamic, &d.act_sin, &d.act_cos})
        v->assign(n, 0.0);
}

void resize_links(LinkParams& p, int n, float voxel_size) {
    for (auto* v : {&p.exists, &p.k_axial, &p.k_bend, &p.k_torsion, &p.damp_steps, &p.damp_beta,
                    &p.damp_relax, &p.rest_sin, &p.rest_cos})
        v->assign(n, 0.0f);
    p.rest_base.assign(n, voxel_size);  // keeps absent slots well formed
}

// The common offset of a whole vector of slots, or 0 when they differ (the chunk is gathered).
// `offset(v)` gives slot v's required offset, or 0 when any offset would do.
template <class Offset>
int chunk_offset(int begin, Offset offset) {
    int common = 0;
    for (int v = begin; v < begin + kLanes; ++v) {
        const int o = offset(v);
        if (o == 0) continue;
        if (common != 0 && o != common) return -1;
        common = o;
    }
    return common;
}

// Each run costs a loop entry in each pass (setup, a partial vector), more than gathering a few
// vectors does: a uniform run shorter than this next to a gathered or another short run is
// gathered instead (gathering is valid for any slot), then equal neighbours merge.
constexpr int kMinUniformRun = 4 * kLanes;

template <class Run, class IsGathered, class Gather>
void absorb_short_runs(std::vector<Run>& runs, IsGathered is_gathered, Gather gather) {
    auto joins = [&](std::size_t i, std::size_t j) {  // run j is i's neighbour and absorbs it
        const bool adjacent = runs[i].end == runs[j].begin || runs[j].end == runs[i].begin;
        return adjacent && (is_gathered(runs[j]) || runs[j].end - runs[j].begin < kMinUniformRun);
    };
    std::vector<Run> out;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        Run r = runs[i];
        const bool short_run = r.end - r.begin < kMinUniformRun;
        if (short_run && ((i > 0 && joins(i, i - 1)) || (i + 1 < runs.size() && joins(i, i + 1))))
            gather(r);
        const bool same =
            !out.empty() && out.back().end == r.begin && is_gathered(out.back()) && is_gathered(r);
        if (same)
            out.back().end = r.end;
        else
            out.push_back(r);
    }
    runs = std::move(out);
}

// Cuts [0, slots) into uniform and gathered runs (model_data.hpp) and sizes the zero lead of the
// link scratch and the tail of dummy voxels so every offset read stays in bounds.
void build_runs(Model::Data& d) {
    auto has_link = [&](int a, int v) { return v < d.voxels && d.plus[a][v] != v; };
    int max_delta = 1, max_below = 1;
    for (int a = 0; a < 3; ++a) {
        auto& runs = d.link_runs[a];
        runs.clear();
        for (int begin = 0; begin < d.slots; begin += kLanes) {
            bool any = false;
            for (int v = begin; v < begin + kLanes; ++v)
                any = any || has_link(a, v);
            // A vector of slots without a link is skipped: its scratch stays zero.
            if (!any) continue;
            int delta = a == 0 ? 1 : chunk_offset(begin, [&](int v) {
                return has_link(a, v) ? d.plus[a][v] - v : 0;
            });
            if (delta < 0) delta = 0;  // gathered
            const bool follows = !runs.empty() && runs.back().end == begin;
            if (follows && runs.back().delta == delta)
                runs.back().end = begin + kLanes;
            else
                runs.push_back({begin, begin + kLanes, delta});
            max_delta = std::max(max_delta, delta);
        }
        if (a != 0)  // (x links are always uniform: the +x neighbour is the next voxel)
            absorb_short_runs(
                runs, [](const LinkRun& r) { return r.delta == 0; },
                [](LinkRun& r) { r.delta = 0; });
    }
    // Voxel v may read slot v - below for axis a when that slot's link (if any) ends at v.
    auto below_ok = [&](int a, int v, int below) {
        const int w = v - below;
        if (d.minus[a][v] != kNoLink) return d.minus[a][v] == w;
        return w < 0 || !has_link(a, w) || d.plus[a][w] == v;
    };
    auto chunk_below = [&](int a, int begin) {
        return chunk_offset(begin, [&](int v) {
            return v < d.voxels && d.minus[a][v] != kNoLink ? v - d.minus[a][v] : 0;
        });
    };
    auto below_of = [&](int a, int begin, int previous) {
        int below = chunk_below(a, begin);
        if (below < 0) return 0;
        if (below == 0) below = previous;
        // A chunk with no such link (the first row or layer of a block) takes the offset of the
        // next chunk that has one, so it joins that chunk's uniform run instead of gathering.
        for (int next = begin + kLanes; below <= 0 && next < d.slots; next += kLanes) {
            below = chunk_below(a, next);
            if (below < 0) return 0;
        }
        if (below <= 0) return 0;
        for (int v = begin; v < begin + kLanes; ++v)
            if (!below_ok(a, v, below)) return 0;
        return below;
    };
    d.voxel_runs.clear();
    for (int begin = 0; begin < d.slots; begin += kLanes) {
        const VoxelRun* last = d.voxel_runs.empty() ? nullptr : &d.voxel_runs.back();
        int by = below_of(1, begin, last ? last->below_y : 0);
        int bz = below_of(2, begin, last ? last->below_z : 0);
        if (by == 0 || bz == 0) by = bz = 0;  // one gathered axis: gather both
        if (last && last->below_y == by && last->below_z == bz)
            d.voxel_runs.back().end = begin + kLanes;
        else
            d.voxel_runs.push_back({begin, begin + kLanes, by, bz});
        max_below = std::max({max_below, by, bz});
    }
    absorb_short_runs(
        d.voxel_runs, [](const VoxelRun& r) { return r.below_y == 0; },
        [](VoxelRun& r) { r.below_y = r.below_z = 0; });
    d.stored = d.slots + max_delta;
    d.link_lead = (std::max(max_below, kLinkLead) + kLanes - 1) / kLanes * kLanes;
}

// The compact voxel list in lattice order, its bounding-box origin and the neighbour tables.
void build_layout(Model::Data& d) {
    const BodySpec& spec = d.spec;
    const int cells = spec.cell_count();
    d.cell_voxel.assign(cells, -1);
    d.origin_cell = {spec.nx, spec.ny, spec.nz};
    for (int c = 0; c < cells; ++c) {
        if (spec.material[c] == 0) continue;
        d.cell_voxel[c] = static_cast<int>(d.voxel_cell.size());
        d.voxel_cell.push_back(c);
        d.voxel_material.push_back(spec.material[c]);
        d.voxel_fixed.push_back(spec.fixed.empty() ? 0 : (spec.fixed[c] ? 1 : 0));
        const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
        for (int i = 0; i < 3; ++i)
            d.origin_cell[i] = std::min(d.origin_cell[i], xyz[i]);
    }
    d.voxels = static_cast<int>(d.voxel_cell.size());
    d.slots = (d.voxels + kLanes - 1) / kLanes * kLanes;
    const double L = spec.voxel_size_m;
    for (int i = 0; i < 3; ++i)
        d.origin_m[i] = d.origin_cell[i] * L;

    // Neighbours, on the slots only (the tail of dummies is sized once the runs are known).
    const std::array<int, 3> limit{spec.nx, spec.ny, spec.nz};
    const std::array<int, 3> stride{1, spec.nx, spec.nx * spec.ny};
    for (int a = 0; a < 3; ++a) {
        d.plus[a].resize(d.slots + 1);
        d.minus[a].assign(d.slots + 1, kNoLink);
        for (int v = 0; v <= d.slots; ++v)
            d.plus[a][v] = v;
    }
    for (int v = 0; v < d.voxels; ++v) {
        const int c = d.voxel_cell[v];
        const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
        for (int a = 0; a < 3; ++a) {
            if (xyz[a] + 1 >= limit[a]) continue;
            const int b = d.cell_voxel[c + stride[a]];
            if (b < 0) continue;
            d.plus[a][v] = b;
            d.minus[a][b] = v;
        }
    }
    build_runs(d);

    // Dummies rest at the relative origin's cell centre; real voxels on their lattice points.
    d.rest_position.assign(d.stored, {0.5 * L, 0.5 * L, 0.5 * L});
    for (int v = 0; v < d.voxels; ++v) {
        const int c = d.voxel_cell[v];
        const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
        for (int i = 0; i < 3; ++i)
            d.rest_position[v][i] = (xyz[i] - d.origin_cell[i] + 0.5) * L;
    }
    for (int a = 0; a < 3; ++a) {
        d.plus[a].resize(d.stored, 0);
        d.minus[a].resize(d.stored, kNoLink);
        for (int v = d.slots + 1; v < d.stored; ++v)
            d.plus[a][v] = v;
    }
}

}  // namespace

std::shared_ptr<const Model> Model::build(const BodySpec& spec) {
    validate(spec);
    auto data = std::make_unique<Data>();
    Data& d = *data;
    d.spec = spec;
    const double L = spec.voxel_size_m;
    d.voxel_size_m = L;
    const double rot_scale = spec.rotary_inertia_scale;
    d.rotary_inertia_scale = rot_scale;
    build_layout(d);
    const int n = d.voxels;

    // Per voxel constants.
    resize_voxels(d, d.stored);
    const double volume = L * L * L;
    double max_omega2 = 0.0;  // largest k/m (or k_rot/I) seen, for the stable step
    for (int v = 0; v < n; ++v) {
        const int c = d.voxel_cell[v];
        const Material& mat = spec.materials[d.voxel_material[v] - 1];
        const double m = mat.density_kg_m3 * volume;
        const double k_axial = mat.youngs_modulus_pa * L;  // E A / L
        d.mass[v] = m;
        d.total_mass_kg += m;
        d.floor_k[v] = k_axial;
        d.floor_c[v] = 2.0 * spec.damping.collision_ratio * std::sqrt(m * k_axial);
        d.mu_static[v] = mat.static_friction;
        d.mu_dynamic[v] = mat.dynamic_friction;
        const double phase = spec.phase_rad.empty() ? 0.0 : spec.phase_rad[c];
        double amplitude = mat.cte_per_c * spec.actuation.temperature_amplitude_c;
        if (!spec.amplitude_scale.empty()) amplitude *= spec.amplitude_scale[c];
        // sin(w tau + phase) = sin(w tau) cos(phase) + cos(w tau) sin(phase)
        d.act_sin[v] = amplitude * std::cos(phase);
        d.act_cos[v] = amplitude * std::sin(phase);
        if (amplitude != 0.0) d.any_active = true;
        max_omega2 = std::max(
            max_omega2,
            limits::voxel_omega2(mat, L, spec.actuation.temperature_amplitude_c, rot_scale));
        // A turning held voxel's spring to the clamp. It needs no bound of its own: with its
        // links (at most six of E L^3 / 3) it is at most 1.15 times the rotational stiffness of a
        // free voxel inside the body, whose step is already set by the links.
        if (d.voxel_fixed[v] && turns_at_all(d, v))
            d.wall_stiffness[v] = kClampWallStiffness * mat.youngs_modulus_pa * L * L * L;
    }
    build_muscle_drive(d);  // muscle voxels' signals and coefficients (issue 43)

    // Poisson coupling (poisson.hpp): per-voxel moduli and centre-strain coefficients; a link's
    // own modulus is the mean over the four octants at each end.
    const std::array<std::vector<double>, 3> octant_modulus = build_poisson_params(d);
    PoissonParams& pp = d.poisson;

    // Links: slot v of axis a joins v and plus[a][v] when that neighbour exists.
    std::array<std::vector<double>, 3> link_omega2;  // per link, for the damping cap (3 K)
    // Implicit bond damping: per voxel, the sum over its links of a bound on the link's damping
    // rate, so that P = m sum >= C in the Loewner order (link_damping_rate_bound).
    const bool implicit = spec.damping.implicit_sweeps > 0;
    d.implicit_sweeps = spec.damping.implicit_sweeps;
    std::vector<double> damping_rate(implicit ? d.stored : 0, 0.0);
    const double beam_inertia_over_l = std::pow(L, 4) / 12.0 / L;  // I / L
    // The stiffest mode limits::step_range allows for these materials: a mixed link's bending
    // factor (mixed_link_bending_factor) is capped so that its modes stay within it, so the step
    // stays inside the range evo/ predicts (a light soft voxel between heavy stiff ones could
    // otherwise take the step below it).
    const double envelope_omega2 = [&] {
        const double shortest =
            limits::step_range(spec.materials, L, 1.0, spec.actuation.temperature_amplitude_c, 0,
                               rot_scale)
                .shortest_s;
        return 1.0 / (4.0 * std::numbers::pi * std::numbers::pi * shortest * shortest);
    }();
    const double torsion_over_l = kSquareTorsionFactor * std::pow(L, 4) / L;
    for (int axis = 0; axis < 3; ++axis) {
        LinkParams& p = d.links[axis];
        resize_links(p, d.stored, static_cast<float>(L));
        link_omega2[axis].assign(d.stored, 0.0);
        for (int v = 0; v < n; ++v) {
            const int b = d.plus[axis][v];
            if (b == v) continue;
            const Material& ma = spec.materials[d.voxel_material[v] - 1];
            const Material& mb = spec.materials[d.voxel_material[b] - 1];
            const double e = series(ma.youngs_modulus_pa, mb.youngs_modulus_pa);
            const double g = series(shear_modulus(ma), shear_modulus(mb));
            // The link's own strain: the two materials' E in series, times the mean of the eight
            // octants' modulus over E (1 when nu = 0). The plain mean keeps the energy the sum of
            // the octants' Hooke energies, positive definite up to nu = 0.5.
            const double m_link = e * (0.5 * (octant_modulus[axis][v] + octant_modulus[axis][b]));
            // A half-link inside a wider region is stiffer (link_confinement.hpp): every mode of
            // the link, its normal stress with the Poisson coupling (rest_scale keeps m_link)
            // included. A link across two materials is stiffer axially where the stiff face
            // restrains the soft half's contraction (mixed_link_stiffening); together within the
            // cap that keeps the stable step valid.
            const ConfinedLinkFactors confined =
                confined_link_factors(d, v, b, axis, ma.poisson_ratio, mb.poisson_ratio);
            // A mixed link beside stiffer links bends and shears toward the arithmetic mean
            // (mixed_link_bending_factor); the stable step and the damping cap know it.
            double mixed_bending = mixed_link_bending_factor(d, v, b, axis, ma, mb);
            if (mixed_bending > 1.0) {
                // Past the envelope only the bending and torsion modes can be (the plain link's
                // are inside it), and they scale with the factor.
                const double omega2 = limits::link_omega2(
                    ma, mb, L, spec.actuation.temperature_amplitude_c, mixed_bending, rot_scale);
                if (omega2 > envelope_omega2)
                    mixed_bending = std::max(1.0, mixed_bending * envelope_omega2 / omega2);
            }
            const double bending = confined.bending * mixed_bending;
            const double k_axial =
                std::min(kConfinedLinkCap,
                         confined.axial * mixed_link_stiffening(d, v, b, axis, ma, mb)) *
                m_link * L;
            if (pp.active) pp.rest_scale[axis][v] = static_cast<float>(-L / m_link);
            const double m_a = d.mass[v], m_b = d.mass[b];
            const double reduced_mass = m_a * m_b / (m_a + m_b);
            // Bond damping as Voxelyze: c = 2 zeta sqrt(m k) on each end's velocity relative to
            // the link's midpoint, i.e. half the relative velocity (m: the harmonic mean of the
            // two masses, so the pair stays symmetric). Applied as Rayleigh damping C = beta K to
            // every mode of the beam, beta = c / (2 k).
            const double pair_mass = 2.0 * reduced_mass;
            // (Relative to the link's Young's modulus e L, as Voxelyze, so the ratio means the same
            // with Poisson coupling; the cap below keeps the stiffer coupled modes stable.)
            const double beta = spec.damping.bond_ratio * std::sqrt(pair_mass / (e * L));
            p.exists[v] = 1.0f;
            p.k_axial[v] = static_cast<float>(k_axial);
            p.k_bend[v] = static_cast<float>(bending * e * beam_inertia_over_l);
            p.k_torsion[v] = static_cast<float>(bending * g * torsion_over_l);
            p.damp_steps[v] = static_cast<float>(beta);  // capped and divided by dt below
            p.rest_sin[v] = static_cast<float>(0.5 * L * (d.act_sin[v] + d.act_sin[b]));
            p.rest_cos[v] = static_cast<float>(0.5 * L * (d.act_cos[v] + d.act_cos[b]));
            ++d.link_count;
            if (implicit) {
                const double lambda = link_damping_rate_bound(
                    beta, k_axial, bending * e * beam_inertia_over_l, bending * g * torsion_over_l,
                    m_a, m_b, L, 1.0 + std::max(actuation_reach(d, v), actuation_reach(d, b)),
                    rot_scale);
                damping_rate[v] += lambda;
                damping_rate[b] += lambda;
            }
            const double amplitude_c = spec.actuation.temperature_amplitude_c;
            link_omega2[axis][v] =
                limits::link_damping_omega2(ma, mb, L, amplitude_c, mixed_bending, rot_scale);
            max_omega2 = std::max(
                max_omega2, limits::link_omega2(ma, mb, L, amplitude_c, mixed_bending, rot_scale));
        }
    }

    set_muscle_link_rests(d);
    build_edge_springs(d, max_omega2);

    // A body without links (a lone voxel) has no strain to couple: skip the pass (it would
    // write zeros every step).
    if (d.link_count == 0) pp.active = false;
    if (pp.active) finish_poisson_params(d);

    // Voxelyze's recommended step: 1 / (2 pi sqrt(k_max / m_min)), rotational modes included.
    // With the implicit bond damping the damping no longer bounds it (limits::step_multiple).
    d.stable_dt_s =
        limits::stable_step_for(max_omega2) * limits::step_multiple(spec.damping.implicit_sweeps);
    d.dt_s = spec.dt_fraction * d.stable_dt_s;
    const double dt = d.dt_s;
    // Explicit (velocity-lagged) Rayleigh damping is stable only while pi beta omega^2 dt stays
    // below ~0.92 (omega^2: the link's max(k/m, k_rot/I); measured on kicked solid blocks up to
    // 10^3, the stiffest lattice modes go first). Cap beta at 0.8 of that: with uniform material
    // at nu = 0 this is bond_ratio * dt_fraction <= 1.13, so the paper's 1.0 at 0.9 would be
    // untouched and a larger ratio cannot make the integration unstable (at the default step: the
    // bound falls as the step grows, 1.4x already lets a pulled 16x4x4 bar at nu = 0.25 blow up,
    // docs/physics.md "Damping and the step"). The cap's omega^2 takes
    // the Poisson coupling's bulk stiffness 3 K (link_damping_omega2), the step only the P-wave
    // modulus M: at the paper's nu = 0.35 links with an active end keep 75 % of the paper's
    // zeta = 1 (pi beta omega^2 dt = 1.06 uncapped), the passive links of an actuated body 86 %.
    // (With the step from 3 K as well: 91 % and 100 %, for 1.21x the steps; docs/physics.md.)
    // With the implicit damping (damping_pass.hpp) beta is applied in full, never capped, and the
    // link pass's explicit term is zero.
    constexpr double kStableDampingProduct = 0.8 / std::numbers::pi;
    for (int axis = 0; axis < 3; ++axis) {
        LinkParams& p = d.links[axis];
        for (int v = 0; v < n; ++v) {
            if (p.exists[v] == 0.0f) continue;
            if (implicit) {
                p.damp_beta[v] = p.damp_steps[v];
                p.damp_steps[v] = 0.0f;
                continue;
            }
            const double beta = std::min<double>(
                p.damp_steps[v], kStableDampingProduct / (link_omega2[axis][v] * dt));
            p.damp_steps[v] = static_cast<float>(beta / dt);
        }
    }

    // The implicit damping relaxes each link's damping rates by 1 / (1 + dt max(P_a, P_b)), the
    // larger of its two ends' bounds (damping_pass.hpp): the link-space Jacobi splitting with that
    // diagonal converges, since twice it bounds the weighted row sum P_a + P_b of the link-space
    // operator. The loads of one link stay equal and opposite and balanced in moment, so a free
    // body's momentum is exact (per-voxel factors scaled the two ends' shares differently and a
    // free body drifted by 0.2 % of its internal momentum in 0.2 s). Held voxels take no part.
    for (int axis = 0; axis < 3 && implicit; ++axis) {
        LinkParams& p = d.links[axis];
        for (int v = 0; v < n; ++v) {
            if (p.exists[v] == 0.0f) continue;
            const int b = d.plus[axis][v];
            const double rate_a = turns_at_all(d, v) ? damping_rate[v] : 0.0;
            const double rate_b = turns_at_all(d, b) ? damping_rate[b] : 0.0;
            p.damp_relax[v] = static_cast<float>(1.0 / (1.0 + dt * std::max(rate_a, rate_b)));
        }
    }
    for (int v = 0; v < n; ++v) {
        const double m = d.mass[v];
        const double inertia = rot_scale * m * L * L / 6.0;
        const Material& mat = spec.materials[d.voxel_material[v] - 1];
        const double c_lin =
            2.0 * spec.damping.global_ratio * std::sqrt(m * mat.youngs_modulus_pa * L);
        const double c_rot = 2.0 * spec.damping.global_ratio *
                             std::sqrt(inertia * mat.youngs_modulus_pa * L * L * L / 3.0);
        d.linear_keep[v] = 1.0 / (1.0 + dt * c_lin / m);
        const double keep = 1.0 / (1.0 + dt * c_rot / inertia);
        const std::array<bool, 3> turns = held_voxel_turns(d, v);
        for (int i = 0; i < 3; ++i)
            d.angular_keep[i][v] = turns[i] ? keep : 0.0;
        if (turns[0] || turns[1] || turns[2]) d.dt_inv_inertia[v] = dt / inertia;
        if (d.voxel_fixed[v]) continue;
        d.movable[v] = 1.0;
        d.dt_inv_mass[v] = dt / m;
    }
    finish_edge_springs(d);
    return std::make_shared<const Model>(std::move(data));
}

Model::Model(std::unique_ptr<Data> data) : data_(std::move(data)) {}
Model::~Model() = default;

int Model::voxel_count() const {
    return static_cast<int>(data_->voxel_cell.size());
}
int Model::link_count() const {
    return data_->link_count;
}
int Model::edge_spring_count() const {
    return static_cast<int>(data_->edge_springs.size());
}
double Model::dt_s() const {
    return data_->dt_s;
}
double Model::voxel_size_m() const {
    return data_->voxel_size_m;
}
const BodySpec& Model::spec() const {
    return data_->spec;
}
int Model::voxel_cell(int v) const {
    return data_->voxel_cell.at(v);
}
std::array<int, 3> Model::voxel_coords(int v) const {
    const int c = data_->voxel_cell.at(v);
    const int nx = data_->spec.nx, ny = data_->spec.ny;
    return {c % nx, (c / nx) % ny, c / (nx * ny)};
}
int Model::voxel_material(int v) const {
    return data_->voxel_material.at(v);
}
bool Model::voxel_fixed(int v) const {
    return data_->voxel_fixed.at(v) != 0;
}
double Model::total_mass_kg() const {
    return data_->total_mass_kg;
}

}  // namespace bhm::engine
