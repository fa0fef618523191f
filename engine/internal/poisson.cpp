// Poisson coupling (poisson.hpp): moduli, the model's constants, the per-step pass and its energy.
#include "engine/internal/poisson.hpp"

#include <algorithm>
#include <cmath>

#include "engine/internal/kernel_dispatch.hpp"
#include "engine/internal/link_kinematics.hpp"  // BHM_ENGINE_INLINE

namespace bhm::engine {

PoissonModuli poisson_moduli(double e, double nu, int linked_axes) {
    if (linked_axes >= 3) {
        const double scale = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        return {scale * (1.0 - nu), scale * nu};
    }
    if (linked_axes == 2) return {e / (1.0 - nu * nu), e * nu / (1.0 - nu * nu)};
    return {e, 0.0};
}

double poisson_stiffness_factor(double nu) {
    return std::max(poisson_wave_factor(nu), 1.0 / (1.0 - 2.0 * nu));
}

double poisson_wave_factor(double nu) {
    return std::max(1.0, (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)));
}

double octant_volumetric_modulus(double e, double nu, int linked_axes) {
    if (linked_axes <= 0) return 0.0;
    return poisson_moduli(e, nu, linked_axes).m - e / (1.0 + nu);  // M_k - 2 G
}

namespace {

constexpr int kSides = 2;  // 0: a voxel's - half-link on an axis, 1: its + half-link

// x of the penalty x E d^2 / 2 per volume on the split d of a link of one material (poisson.hpp):
// fitted with the confinement of narrow ends (link_confinement.hpp) on the fitting half of the
// continuum suite (tests/engine/test_engine_continuum.cpp; docs/physics.md, "The relaxed split on
// every link"). x = infinity is the equal split, which locked 2-voxel-tall sections at nu 0.49
// (14-19 % stiff); x = 0 lets every link's halves part (a 2-voxel stalk 36 % soft at nu 0.49).
constexpr double kSameMaterialSplitPenalty = 10.0;

// The clamp's lateral constraint on a held voxel inside a held face (its octants with both
// lateral half-links), in units of lambda_2 (build_poisson_params): fitted on the fitting half of
// the continuum suite (tests/engine/test_engine_continuum.cpp: rms of the worst of tip and com
// 5.61 % without it, 5.41 % at 1, flat within 0.05 points from 0.75 to 1.5; docs/physics.md,
// "The clamp's lateral constraint"). Without it the uniform 20x8x7 cantilever was 2.6 % soft at
// nu 0.49 against the mesh-converged continuum (0.7 % with it).
constexpr double kHeldFaceConstraint = 1.0;

// 1 / theta_0: the volumetric stress saturates at lambda theta_0 (poisson.hpp). 0.2, the largest
// that keeps the envelope's framed and banded bodies stable at cte A = 0.6 (0.3 lets the banded
// block squeeze a link to L / 10); at 0.1 the saturation already softened the paper's own 14.5 %
// actuation in a framed body (docs/physics.md).
constexpr float kInverseSaturation = 1.0f / 0.2f;

// lambda of an octant whose linked axes are flagged hx, hy, hz (each 0 or 1), branch-free.
inline float octant_lambda(float hx, float hy, float hz, float lambda1, float lambda2,
                           float lambda3) {
    const float three = hx * hy * hz;
    const float pairs = hx * hy + hy * hz + hz * hx;
    const float two = pairs - 3.0f * three;
    const float one = hx + hy + hz - 2.0f * pairs + 3.0f * three;
    return one * lambda1 + two * lambda2 + three * lambda3;
}

// The neighbour of v on side s of axis a (its - neighbour is the slot of the link whose + end
// is v: a link slot is its - end voxel).
int partner_on(const Model::Data& d, int a, int s, int v) {
    return s == 1 ? d.plus[a][v] : d.minus[a][v];
}

int links_on_axis(const PoissonParams& pp, int a, int v) {
    return static_cast<int>(pp.has_minus[a][v] + pp.has_plus[a][v]);
}

// dW/dd^2 of one end of an isolated link (per volume): G from the deviatoric term, lambda_o / 8
// from each of the four octants on the linked side.
double pair_curvature(const PoissonParams& pp, int a, int v, int side) {
    (void)side;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    double sum = pp.shear[v];
    for (float hb : {pp.has_minus[b][v], pp.has_plus[b][v]})
        for (float hc : {pp.has_minus[c][v], pp.has_plus[c][v]}) {
            const int k = 1 + static_cast<int>(hb) + static_cast<int>(hc);
            const float lambda = k == 3 ? pp.lambda3[v] : k == 2 ? pp.lambda2[v] : pp.lambda1[v];
            sum += 0.125 * lambda;
        }
    return sum;
}

}  // namespace

std::array<std::vector<double>, 3> build_poisson_params(Model::Data& d) {
    const BodySpec& spec = d.spec;
    const int n = d.voxels;
    PoissonParams& pp = d.poisson;
    std::array<std::vector<double>, 3> octant_modulus;  // per axis: that mean / E, per voxel
    for (auto* v : {&pp.shear, &pp.lambda1, &pp.lambda2, &pp.lambda3})
        v->assign(d.stored, 0.0f);
    for (auto& v : pp.octant_lambda8)
        v.assign(d.stored, 0.0f);
    for (int a = 0; a < 3; ++a) {
        pp.has_plus[a].assign(d.stored, 0.0f);
        pp.has_minus[a].assign(d.stored, 0.0f);
        pp.rest_scale[a].assign(d.stored, 0.0f);
        pp.pair_step[a].assign(d.stored, 0.0f);
        pp.pair_penalty[a].assign(d.stored, 0.0f);
        pp.pair_keep[a].assign(d.stored, 1.0f);
        for (int s = 0; s < kSides; ++s) {
            for (auto* v : {&pp.mu_own[a][s], &pp.mu_other[a][s], &pp.mu_far[a][s],
                            &pp.mu_pair[a][s], &pp.dev_scale[a][s]})
                v->assign(d.stored, 0.0f);
            pp.far_slot[a][s].assign(d.stored, kNoLink);
            pp.far_pair[a][s].assign(d.stored, 0.0f);
        }
        octant_modulus[a].assign(d.stored, 0.0);
    }
    pp.mixed = false;
    std::vector<char> relaxed(d.stored, 0);
    for (int v = 0; v < n; ++v) {
        for (int a = 0; a < 3; ++a) {
            pp.has_plus[a][v] = d.plus[a][v] != v ? 1.0f : 0.0f;
            pp.has_minus[a][v] = d.minus[a][v] != kNoLink ? 1.0f : 0.0f;
        }
        const Material& mat = spec.materials[d.voxel_material[v] - 1];
        // A held voxel is the clamp plane through its centre. Its octants are uncoupled (nu = 0)
        // except where the clamp holds the material laterally on both axes across its link, an
        // octant whose two lateral half-links both exist (inside a held face: they join held
        // voxels and do not stretch): there the half-link to the free body takes
        // kHeldFaceConstraint times lambda_2, so its modulus is E + lambda_2 = E (1 + nu / (1 -
        // nu^2)), bounded as nu -> 1/2 (the continuum clamp's constraint fades within a fraction
        // of a voxel; the full lambda_3 made the 20x8x7 block 8 % stiff at nu 0.49). A held line
        // or a lone held voxel can contract across itself and stays uncoupled.
        const bool held = d.voxel_fixed[v] != 0;
        const double e = mat.youngs_modulus_pa, nu = held ? 0.0 : mat.poisson_ratio;
        pp.shear[v] = static_cast<float>(e / (2.0 * (1.0 + nu)));
        pp.lambda1[v] = static_cast<float>(octant_volumetric_modulus(e, nu, 1));
        pp.lambda2[v] = static_cast<float>(octant_volumetric_modulus(e, nu, 2));
        pp.lambda3[v] = static_cast<float>(octant_volumetric_modulus(e, nu, 3));
        // Only where every neighbour of the held voxel, held or free, is of its own E and nu.
        // Across a mixed link the soft half's lateral restraint is mixed_link_stiffening's
        // (link_confinement.hpp, fitted on soft/stiff slices whose held layer is soft), which the
        // constraint doubled (the 10x slices at nu 0.49 went from -0.1 to -6.0 %); and a held
        // layer one voxel thick between layers of another material is not held across by them
        // (stiff layers holding 100x softer ones at nu 0.35, -4.7 %, went to -6.1 %).
        bool held_by_own_material = held && mat.poisson_ratio > 0.0;
        for (int a = 0; a < 3 && held_by_own_material; ++a)
            for (int p : {d.minus[a][v], d.plus[a][v]}) {
                if (p == kNoLink || p == v) continue;
                const Material& other = spec.materials[d.voxel_material[p] - 1];
                if (other.youngs_modulus_pa != mat.youngs_modulus_pa ||
                    other.poisson_ratio != mat.poisson_ratio)
                    held_by_own_material = false;
            }
        const double held_lambda3 =
            held_by_own_material
                ? kHeldFaceConstraint * octant_volumetric_modulus(e, mat.poisson_ratio, 2)
                : 0.0;
        if (held_lambda3 > 0.0) pp.lambda3[v] = static_cast<float>(held_lambda3);
        pp.active = pp.active || nu != 0.0;
        // Auxetic voxels (lambda < 0) keep the half-link strains: the centre estimates below are
        // not contractions, and only lambda >= 0 keeps their energy positive for any estimate.
        relaxed[v] = nu > 0.0;
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            double sum = 0.0;
            for (float hb : {pp.has_minus[b][v], pp.has_plus[b][v]})
                for (float hc : {pp.has_minus[c][v], pp.has_plus[c][v]}) {
                    const int k = 1 + static_cast<int>(hb) + static_cast<int>(hc);
                    sum += poisson_moduli(e, nu, k).m + (k == 3 ? held_lambda3 : 0.0);
                }
            octant_modulus[a][v] = 0.25 * sum / e;  // relative to E
        }
    }
    for (int v = 0; v < n; ++v)
        for (int o = 0; o < 8; ++o)
            pp.octant_lambda8[o][v] =
                0.125f * octant_lambda(o & 4 ? pp.has_plus[0][v] : pp.has_minus[0][v],
                                       o & 2 ? pp.has_plus[1][v] : pp.has_minus[1][v],
                                       o & 1 ? pp.has_plus[2][v] : pp.has_minus[2][v],
                                       pp.lambda1[v], pp.lambda2[v], pp.lambda3[v]);
    // The centre strain of each voxel on each axis (poisson.hpp), in the voxel's own strain
    // units: a link's strain times E_link / E_voxel (its stress over the voxel's modulus).
    auto young = [&](int v) { return spec.materials[d.voxel_material[v] - 1].youngs_modulus_pa; };
    // Two voxels are one material to the coupling when E, nu and the free (actuation) strain
    // agree. A link whose halves have different free strains (an active voxel bonded to a
    // passive one, or two phases or muscle signals) takes the relaxed split too: with the equal
    // split the passive half was forced to share the active half's thinning, which near a narrow
    // part turned it (an actuated 2-voxel stalk 84 % too far at nu 0.49; docs/physics.md).
    // (Per unit drive, so the model is the same at any amplitude, 0 included: a rest state and
    // an actuated one are solved on one model.)
    auto phase = [&](int v) {
        return spec.phase_rad.empty() ? 0.0 : spec.phase_rad[d.voxel_cell[v]];
    };
    // A controller's amplitude scale (issue 44) changes the free strain per unit drive too.
    auto scale = [&](int v) {
        return spec.amplitude_scale.empty() ? 1.0f : spec.amplitude_scale[d.voxel_cell[v]];
    };
    auto same_free_strain = [&](int v, int p) {
        const double cte_v = spec.materials[d.voxel_material[v] - 1].cte_per_c;
        const double cte_p = spec.materials[d.voxel_material[p] - 1].cte_per_c;
        if (cte_v != cte_p || (cte_v != 0.0 && (phase(v) != phase(p) || scale(v) != scale(p))))
            return false;
        const MuscleDrive& m = d.muscle;
        for (int a = 0; a < 3; ++a) {
            if (!m.axis_signal0[a].empty() && m.axis_signal0[a][v] != m.axis_signal0[a][p])
                return false;
            if (!m.axis_signal1[a].empty() && m.axis_signal1[a][v] != m.axis_signal1[a][p])
                return false;
        }
        // Two muscle voxels whose stimuli a controller delays differently (issue 44) strain
        // apart in time: a relaxed split, as for two sine phases.
        if (m.delayed && m.voxel_signal[v] != m.voxel_signal[p]) return false;
        return true;
    };
    auto same_material = [&](int v, int p) {
        const Material& a = spec.materials[d.voxel_material[v] - 1];
        const Material& b = spec.materials[d.voxel_material[p] - 1];
        return a.youngs_modulus_pa == b.youngs_modulus_pa && a.poisson_ratio == b.poisson_ratio &&
               same_free_strain(v, p);
    };
    std::vector<char> pair_voxel(d.stored, 0);
    for (int v = 0; v < n; ++v)
        for (int a = 0; a < 3; ++a) {
            const float h[kSides] = {pp.has_minus[a][v], pp.has_plus[a][v]};
            const int partner[kSides] = {d.minus[a][v], d.plus[a][v]};
            float w[kSides] = {0.0f, 0.0f};
            for (int s = 0; s < kSides; ++s)
                if (h[s] != 0.0f) {
                    const double ep = young(partner[s]), ev = young(v);
                    w[s] = static_cast<float>(2.0 * ep / (ep + ev));  // series(E_v, E_p) / E_v
                }
            for (int s = 0; s < kSides; ++s)
                pp.dev_scale[a][s][v] = w[s];
            if (!relaxed[v]) {
                for (int s = 0; s < kSides; ++s)
                    pp.mu_own[a][s][v] = w[s];
                continue;
            }
            // A link between two materials (E or nu differ, both ends coupled) splits its strain
            // between its halves by a relaxed internal variable d, h = w e -+ d, instead of by
            // the series weights alone (poisson.hpp): the coefficient of d in mu is set below.
            bool mixed[kSides] = {false, false};
            for (int s = 0; s < kSides; ++s)
                mixed[s] = h[s] != 0.0f && relaxed[partner[s]] && !same_material(v, partner[s]);
            // A link of one material takes a d too, held by the penalty x E d^2 / 2 per volume
            // (kSameMaterialSplitPenalty; poisson.hpp): `split` marks a side with a d, `mixed`
            // keeps choosing the centre's interpolation weights (so x = infinity is the equal
            // split exactly).
            bool split[kSides] = {false, false};
            for (int s = 0; s < kSides; ++s) {
                split[s] = h[s] != 0.0f && relaxed[partner[s]];
                if (split[s] && !mixed[s]) {
                    const int slot = s == 1 ? v : partner[s];
                    pp.pair_penalty[a][slot] =
                        static_cast<float>(kSameMaterialSplitPenalty * young(v));
                }
            }
            const int count = links_on_axis(pp, a, v);
            if (count == 2) {
                // Interior: the centre strain interpolated between the two half-links' own
                // centres. A link of one material samples the strain half a voxel out, the mean
                // of the two; a mixed link's half in this voxel (w e -+ d) spans only the voxel's
                // half, a quarter out, so with one mixed side the line through both samples gives
                // it 2/3 and the other link 1/3. (With the mean, the stiff voxel at a soft
                // interface took half its thinning from the nearly rigid series share: the
                // heated bilayer at nu 0.49 was 9-12 % too stiff; docs/physics.md.)
                const bool one_mixed = mixed[0] != mixed[1];
                for (int s = 0; s < kSides; ++s) {
                    const float weight = one_mixed ? (mixed[s] ? 2.0f / 3.0f : 1.0f / 3.0f) : 0.5f;
                    pp.mu_own[a][s][v] = weight * w[s];
                    pp.mu_other[a][s][v] = (1.0f - weight) * w[1 - s];
                    pp.mixed = pp.mixed || split[s];
                    if (split[s]) {
                        pp.mu_pair[a][s][v] = s == 1 ? -weight : weight;
                        pair_voxel[v] = 1;
                    }
                }
                continue;
            }
            if (count == 0) continue;
            const int s = h[1] != 0.0f ? 1 : 0;
            const int p = partner[s];
            const bool column = links_on_axis(pp, a, p) == 2;  // v ends a column of three or more
            const int next = column ? (s == 1 ? d.plus[a][p] : d.minus[a][p]) : p;
            // The end estimate extrapolates stresses. Through a partner or far link stiffer than
            // v it divides their stress by v's smaller modulus: the far link's strain is weighted
            // by up to E_far / E_v and gains a stiffness beyond its own, which the stable step
            // and the damping cap do not know (4x4x4 random mixtures of E and 100 E at nu = 0.35
            // diverged within 37-61 steps at the default step). There v keeps its half-link.
            const bool extrapolate = column && young(p) <= young(v) && young(next) <= young(v);
            if (extrapolate) {
                // End of a column of three or more: the derivative at the end of the parabola
                // through the last three centres, (3 e_link - e_next) / 2.
                const double ep = young(p), en = young(next);
                pp.mu_own[a][s][v] = 1.5f * w[s];
                pp.mu_far[a][s][v] =
                    static_cast<float>(-0.5 * (2.0 * ep * en / (ep + en)) / young(v));
                pp.far_slot[a][s][v] = s == 1 ? p : d.minus[a][p];
                pp.mixed = pp.mixed || split[s];
                if (split[s]) {
                    pp.mu_pair[a][s][v] = s == 1 ? -1.5f : 1.5f;
                    pair_voxel[v] = 1;
                }
            } else if (!column && relaxed[p]) {
                // An isolated link (a column of two): the two centres are e_link -+ d, d relaxed
                // freely (no penalty: nothing locks a column of two).
                pp.mu_own[a][s][v] = w[s];
                pp.mu_pair[a][s][v] = s == 1 ? -1.0f : 1.0f;
                pp.pair_penalty[a][s == 1 ? v : p] = 0.0f;
                pair_voxel[v] = 1;
            } else {
                pp.mu_own[a][s][v] = w[s];
                pp.mixed = pp.mixed || split[s];
                if (split[s]) {
                    pp.mu_pair[a][s][v] = s == 1 ? -1.0f : 1.0f;
                    pair_voxel[v] = 1;
                }
            }
        }
    for (int a = 0; a < 3; ++a) {
        pp.far_reads[a].clear();
        pp.far_pair_reads[a].clear();
        pp.far_pos_links[a].clear();
        pp.far_neg_links[a].clear();
        for (int v = 0; v < n; ++v)
            for (int s = 0; s < kSides; ++s) {
                if (pp.mu_far[a][s][v] == 0.0f) continue;
                const int slot = pp.far_slot[a][s][v];
                // A far link with a relaxed split (its - end carries the d): the end estimate
                // reads its half at the partner p, w_p e -+ d in p's units (+ d where p is the
                // link's + end, side 0), in v's units (E_p / E_v) that: mu_far already holds
                // series(E_p, E_n) / E_v, so e_far = e +- d E_p / series(E_p, E_n). Reading the
                // link's e alone left the d out of the estimate, which then disagreed with the
                // half-link the interface voxel itself uses.
                if (pp.mu_pair[a][1][slot] != 0.0f) {
                    const int p = partner_on(d, a, s, v), far = partner_on(d, a, s, p);
                    const double ep = young(p), en = young(far);
                    pp.far_pair[a][s][v] =
                        static_cast<float>((s == 0 ? 1.0 : -1.0) * (ep + en) / (2.0 * en));
                }
                const PoissonParams::FarRead read{v, s, slot, pp.far_pair[a][s][v]};
                if (a != 0 || pp.mixed) pp.far_reads[a].push_back(read);
                if (read.pair != 0.0f) pp.far_pair_reads[a].push_back(read);
                (s == 1 ? pp.far_pos_links : pp.far_neg_links)[a].push_back({slot, v});
            }
    }
    pp.pair_voxels.clear();
    for (int v = 0; v < n; ++v)
        if (pair_voxel[v]) pp.pair_voxels.push_back(v);
    return octant_modulus;
}

namespace {

// The Jacobi step of a body with mixed links is half the row-sum step: at the full step, one of
// the 60 random bodies of test_engine_envelope.cpp (seed 2026, body 37: E 95 and 163 MPa at nu
// 0.2 and 0.49, densities 133 and 1247 kg/m^3, dt_fraction 1) diverged within 270 steps, also at
// half the time step; it runs at 0.7 and at 0.5 of it and without the time extrapolation. The
// static iteration alone is stable at the full step, so the coupling with the moving positions
// takes the margin. The static answer is the same, reached in about twice the steps.
constexpr double kMixedStepFactor = 0.5;

// The d's of one voxel: local index k = 2 a + s, set where mu_pair[a][s] != 0.
// hessian[k][l] = d^2 (W / V) / (dd_k dd_l) of this voxel's octants (linear volumetric stress,
// its saturation only lowers it): mu[a][s'] takes d_(a,s) with pair (s' = s) or inner * pair
// (s' != s), the half-link gamma[a][s] with weight 1 inside a column (half_link_pair) and pair at
// an isolated link or a column's end (where gamma is mu).
using LocalHessian = std::array<std::array<double, 6>, 6>;

LocalHessian local_hessian(const PoissonParams& pp, int v) {
    LocalHessian hess{};
    double mu_coef[6][3][kSides] = {}, gamma_coef[6][3][kSides] = {};
    for (int a = 0; a < 3; ++a)
        for (int s = 0; s < kSides; ++s) {
            const int k = 2 * a + s;
            const double pair = pp.mu_pair[a][s][v];
            if (pair == 0.0) continue;
            const double inner = pp.mu_other[a][s][v] > 0.0f ? 1.0 : 0.0;
            mu_coef[k][a][s] = pair;
            mu_coef[k][a][1 - s] = inner * pair;
            gamma_coef[k][a][s] = inner != 0.0 ? (pair > 0.0 ? 1.0 : -1.0) : pair;
        }
    const float* has[3][kSides] = {{pp.has_minus[0].data(), pp.has_plus[0].data()},
                                   {pp.has_minus[1].data(), pp.has_plus[1].data()},
                                   {pp.has_minus[2].data(), pp.has_plus[2].data()}};
    for (int o = 0; o < 8; ++o) {
        const int side[3] = {(o >> 2) & 1, (o >> 1) & 1, o & 1};
        const double lambda8 = pp.octant_lambda8[o][v];
        for (int k = 0; k < 6; ++k)
            for (int l = 0; l < 6; ++l) {
                double theta_k = 0.0, theta_l = 0.0, shear = 0.0;
                for (int a = 0; a < 3; ++a) {
                    const double h = has[a][side[a]][v];
                    theta_k += h * mu_coef[k][a][side[a]];
                    theta_l += h * mu_coef[l][a][side[a]];
                    shear += h * gamma_coef[k][a][side[a]] * gamma_coef[l][a][side[a]];
                }
                // W / V = sum_o (G sum gamma^2 + lambda_o theta^2 / 2) / 8
                hess[k][l] += 0.25 * pp.shear[v] * shear + lambda8 * theta_k * theta_l;
            }
    }
    return hess;
}

}  // namespace

void finish_poisson_params(Model::Data& d) {
    PoissonParams& pp = d.poisson;
    if (pp.mixed) {
        // Bodies with mixed links: the same row-sum Jacobi step from each end's local Hessian
        // (off-diagonal terms: the other d's at either end).
        std::vector<LocalHessian> hess(d.voxels);
        for (int v : pp.pair_voxels)
            hess[v] = local_hessian(pp, v);
        // A far link's d in a column end's estimate (far_pair): its curvature there, on that
        // link's row, and a bound on its coupling with the end voxel's own d's, on both rows.
        std::array<std::vector<double>, 3> extra_h, extra_off;
        for (int a = 0; a < 3; ++a) {
            extra_h[a].assign(d.voxels, 0.0);
            extra_off[a].assign(d.voxels, 0.0);
        }
        for (int a = 0; a < 3; ++a)
            for (const PoissonParams::FarRead& r : pp.far_pair_reads[a]) {
                const int v = r.voxel;
                const double coef = std::fabs(pp.mu_far[a][r.side][v] * r.pair);
                double side_modulus = 0.0;  // sum over the side's octants of (G / 4 + lambda_o / 8)
                for (int o = 0; o < 8; ++o)
                    if (((o >> (2 - a)) & 1) == r.side)
                        side_modulus += 0.25 * pp.shear[v] + pp.octant_lambda8[o][v];
                extra_h[a][r.slot] += side_modulus * coef * coef;
                for (int a2 = 0; a2 < 3; ++a2)
                    for (int s2 = 0; s2 < kSides; ++s2) {
                        const double own = std::fabs(pp.mu_pair[a2][s2][v]);
                        if (own == 0.0) continue;
                        // mu takes at most 1.5 d, gamma at most 1.5 d (a column's end)
                        const double bound = side_modulus * coef * 2.0 * std::max(own, 1.0);
                        extra_off[a][r.slot] += bound;
                        extra_off[a2][s2 == 1 ? v : d.minus[a2][v]] += bound;  // its slot
                    }
            }
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < d.voxels; ++c) {
                if (pp.mu_pair[a][1][c] == 0.0f) continue;
                const int b = d.plus[a][c];
                const int kc = 2 * a + 1, kb = 2 * a;
                const double penalty = pp.pair_penalty[a][c];
                double h = hess[c][kc][kc] + hess[b][kb][kb] + extra_h[a][c] + penalty,
                       off = extra_off[a][c];
                for (int l = 0; l < 6; ++l) {
                    if (l != kc) off += std::fabs(hess[c][kc][l]);
                    if (l != kb) off += std::fabs(hess[b][kb][l]);
                }
                const double step = kMixedStepFactor / (h + off);
                pp.pair_step[a][c] = static_cast<float>(step);
                pp.pair_keep[a][c] = static_cast<float>(1.0 - step * penalty);
            }
        return;
    }
    // dW/(dd dd') / V between this link's d and the d of another isolated link at the same end
    // voxel u (side s of axis a): lambda_o / 8 over the two octants both half-links span.
    auto coupling = [&](int a, int u, int s) {
        double sum = 0.0;
        for (int a2 = 0; a2 < 3; ++a2) {
            if (a2 == a) continue;
            for (int s2 = 0; s2 < kSides; ++s2) {
                if (pp.mu_pair[a2][s2][u] == 0.0f) continue;
                const int c = 3 - a - a2;
                (void)s;
                for (float hc : {pp.has_minus[c][u], pp.has_plus[c][u]}) {
                    const float lambda = hc != 0.0f ? pp.lambda3[u] : pp.lambda2[u];
                    sum += 0.125 * std::fabs(lambda);
                }
            }
        }
        return sum;
    };
    // One Jacobi step per time step with the row-sum step 1 / (h + sum |coupling|): the
    // iteration matrix then has eigenvalues in [0, 1), which keeps the time-extrapolated guess
    // of poisson_pass stable (a negative eigenvalue would make it oscillate and grow).
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < d.voxels; ++c) {
            if (pp.mu_pair[a][1][c] == 0.0f) continue;
            const int b = d.plus[a][c];
            const double h = pair_curvature(pp, a, c, 1) + pair_curvature(pp, a, b, 0);
            const double off = coupling(a, c, 1) + coupling(a, b, 0);
            pp.pair_step[a][c] = static_cast<float>(1.0 / (h + off));
        }
}

namespace {

// Strain of every link slot: (|d| - actuated rest) / L, exactly 0 for absent slots, over the
// same runs as the link pass (whole vectors, empty vectors skipped, uniform runs without
// gathers; model_data.hpp). Slots in no run keep the zero they were sized with. Each slot's chord
// and length are kept for the link pass, as it would measure them (link axis first; an absent
// link's is the straight rest chord), so it need not read the double positions again.
template <bool kGather>
BHM_ENGINE_INLINE void strain_loop(const Model::Data& d, const VoxelState& s, int axis, float sin_t,
                                   float cos_t, const LinkRun& run, float* __restrict out,
                                   LinkScratch& link) {
    const LinkParams& lp = d.links[axis];
    const float* __restrict exists = lp.exists.data();
    const float* __restrict rest_base = lp.rest_base.data();
    const float* __restrict rest_sin = lp.rest_sin.data();
    const float* __restrict rest_cos = lp.rest_cos.data();
    const float inv_l = static_cast<float>(1.0 / d.voxel_size_m);
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const double* __restrict p0 = s.pos[axis].data();
    const double* __restrict p1 = s.pos[a1].data();
    const double* __restrict p2 = s.pos[a2].data();
    float* __restrict chord0 = link.chord[0];
    float* __restrict chord1 = link.chord[1];
    float* __restrict chord2 = link.chord[2];
    float* __restrict lengths = link.length;
    const int* __restrict plus = d.plus[axis].data();
    const int delta = run.delta;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const int b = kGather ? plus[c] : c + delta;
        const float e = exists[c];
        const Chord chord = link_chord(p0, p1, p2, c, b, e, rest_base[c]);
        const float length = chord_length(chord.d0, chord.d1, chord.d2);
        chord0[c] = chord.d0;
        chord1[c] = chord.d1;
        chord2[c] = chord.d2;
        lengths[c] = length;
        const float rest = rest_base[c] + sin_t * rest_sin[c] + cos_t * rest_cos[c];
        out[c] = e * (length - rest) * inv_l;
    }
}

BHM_ENGINE_INLINE void link_strains(const Model::Data& d, const VoxelState& s, int axis,
                                    float sin_t, float cos_t, float* __restrict out,
                                    LinkScratch& link) {
    for (const LinkRun& run : d.link_runs[axis])
        if (run.delta == 0)
            strain_loop<true>(d, s, axis, sin_t, cos_t, run, out, link);
        else
            strain_loop<false>(d, s, axis, sin_t, cos_t, run, out, link);
}

// lead: zero slots before slot 0 (uniform voxel runs read slot v - below, model_data.hpp).
void ensure(PoissonScratch& p, int stored, int lead) {
    constexpr int kFields = 13;
    const std::size_t span = static_cast<std::size_t>(lead) + stored + kLanes;
    if (p.storage[0].size() == kFields * span) return;
    for (int a = 0; a < 3; ++a) {
        p.storage[a].assign(kFields * span, 0.0f);
        float* base = p.storage[a].data() + lead;
        float** fields[kFields] = {&p.strain[a],         &p.pair_d[a],         &p.pair_last[a],
                                   &p.grad_neg[a],       &p.grad_pos[a],       &p.far_neg[a],
                                   &p.far_pos[a],        &p.dgrad_neg[a],      &p.dgrad_pos[a],
                                   &p.far_strain_neg[a], &p.far_strain_pos[a], &p.far_from_below[a],
                                   &p.far_from_above[a]};
        for (float** f : fields) {
            *f = base;
            base += span;
        }
    }
}

// Raw views of every array the voxel kernel touches, taken once per pass ([axis][side]).
struct Views {
    const float *shear, *lambda8[8];
    const float *own[3][kSides], *other[3][kSides], *far[3][kSides], *pair[3][kSides],
        *dev[3][kSides];
    const int *far_slot[3][kSides], *below[3];
    const float* far_pair[3][kSides];
    const float *strain[3], *d[3], *far_strain[3][kSides];
    float *grad_neg[3], *grad_pos[3], *far_neg[3], *far_pos[3], *dgrad_neg[3], *dgrad_pos[3];
};

Views views_of(const Model::Data& d, PoissonScratch& p) {
    const PoissonParams& pp = d.poisson;
    Views w{};
    w.shear = pp.shear.data();
    for (int o = 0; o < 8; ++o)
        w.lambda8[o] = pp.octant_lambda8[o].data();
    for (int a = 0; a < 3; ++a) {
        for (int s = 0; s < kSides; ++s) {
            w.own[a][s] = pp.mu_own[a][s].data();
            w.other[a][s] = pp.mu_other[a][s].data();
            w.far[a][s] = pp.mu_far[a][s].data();
            w.pair[a][s] = pp.mu_pair[a][s].data();
            w.dev[a][s] = pp.dev_scale[a][s].data();
            w.far_slot[a][s] = pp.far_slot[a][s].data();
            w.far_pair[a][s] = pp.far_pair[a][s].data();
        }
        w.below[a] = d.minus[a].data();
        w.strain[a] = p.strain[a];
        w.d[a] = p.pair_d[a];
        w.far_strain[a][0] = p.far_strain_neg[a];
        w.far_strain[a][1] = p.far_strain_pos[a];
        w.grad_neg[a] = p.grad_neg[a];
        w.grad_pos[a] = p.grad_pos[a];
        w.far_neg[a] = p.far_neg[a];
        w.far_pos[a] = p.far_pos[a];
        w.dgrad_neg[a] = p.dgrad_neg[a];
        w.dgrad_pos[a] = p.dgrad_pos[a];
    }
    return w;
}

// Flags derived from the coefficients (one array stream less each, per axis and side): a
// half-link exists exactly where its series weight dev_scale is set (> 0), and a side is a
// column's end estimate exactly where it reads a far link (mu_far < 0). Exactly 1 or 0.
BHM_ENGINE_INLINE float half_link_exists(const Views& w, int a, int s, int v) {
    return static_cast<float>(w.dev[a][s][v] > 0.0f);
}
BHM_ENGINE_INLINE float at_column_end(const Views& w, int a, int s, int v) {
    return static_cast<float>(w.far[a][s][v] < 0.0f);
}
// 1 inside a column of a coupled voxel (its centre strain is the mean of both half-links):
// exactly where the other half-link's weight is set.
BHM_ENGINE_INLINE float inside_column(const Views& w, int a, int s, int v) {
    return static_cast<float>(w.other[a][s][v] > 0.0f);
}

// The weight of a mixed link's d in this voxel's half-link strain: +-1 inside a column (mu takes
// it with the interpolation weight, 1/2 or 2/3, in pair), pair itself at an isolated link or a
// column's end (weight 1 or, where gamma is the end estimate, 1.5).
BHM_ENGINE_INLINE float half_link_pair(float pair, float inner) {
    const float sign = static_cast<float>(pair > 0.0f) - static_cast<float>(pair < 0.0f);
    return inner * sign + (1.0f - inner) * pair;
}

// The strains one voxel's octants see: mu (volumetric term) and gamma (deviatoric term) of each
// axis and side, h = 1 where that half-link exists.
struct VoxelStrains {
    float mu[3][kSides], gamma[3][kSides], h[3][kSides];
};

// below: per axis, the link slot whose + end is v (kNoLink reads the zero lead slot); far: per
// axis and side, the strain of the partner's other link (only used where mu_far != 0).
// kMixed: the body has links with a split d inside columns (PoissonParams::mixed); without, the
// inner terms are zero and left out (a body of one material pays nothing for them).
template <bool kMixed>
BHM_ENGINE_INLINE VoxelStrains voxel_strains(const Views& w, int v, const int (&below)[3],
                                             const float (&far_strain)[3][kSides]) {
    VoxelStrains out;
#pragma GCC unroll 8
    for (int a = 0; a < 3; ++a) {
        const float e[kSides] = {w.strain[a][below[a]], w.strain[a][v]};
        const float dd[kSides] = {w.d[a][below[a]], w.d[a][v]};
        const float pair_weight[kSides] = {w.pair[a][0][v], w.pair[a][1][v]};
        const float pair[kSides] = {pair_weight[0] * dd[0], pair_weight[1] * dd[1]};
#pragma GCC unroll 8
        for (int s = 0; s < kSides; ++s) {
            out.h[a][s] = half_link_exists(w, a, s, v);
            const float far = far_strain[a][s];
            // Inside a column the centre interpolates both half-links, d's included (a mixed
            // link's d enters mu with its interpolation weight, its half-link with the full one).
            const float inner = kMixed ? inside_column(w, a, s, v) : 0.0f;
            out.mu[a][s] = w.own[a][s][v] * e[s] + w.other[a][s][v] * e[1 - s] +
                           w.far[a][s][v] * far + pair[s];
            if constexpr (kMixed) out.mu[a][s] += inner * pair[1 - s];
            // The deviatoric term uses the half-link, except at a column's end, where it takes
            // the same estimate as the volumetric one (so a uniform strain stays exact there).
            const float half =
                w.dev[a][s][v] * e[s] +
                (kMixed ? half_link_pair(pair_weight[s], inner) * dd[s] : pair[s]);
            out.gamma[a][s] = half + at_column_end(w, a, s, v) * (out.mu[a][s] - half);
        }
    }
    return out;
}

// The same through the tables (energy diagnostics).
VoxelStrains voxel_strains(const Views& w, int v) {
    const int below[3] = {w.below[0][v], w.below[1][v], w.below[2][v]};
    float far[3][kSides];
    for (int a = 0; a < 3; ++a)
        for (int s = 0; s < kSides; ++s)
            far[a][s] = w.strain[a][w.far_slot[a][s][v]] +
                        w.far_pair[a][s][v] * w.d[a][w.far_slot[a][s][v]];
    return voxel_strains<true>(w, v, below, far);
}

// Per voxel: dW/d(strain) of each octant's terms, pulled back to its half-links, to the far links
// of its end estimates and to the relaxations d (all per unit volume).
template <bool kMixed>
BHM_ENGINE_INLINE void voxel_gradients(const Views& w, int v, const int (&below)[3],
                                       const float (&far_strain)[3][kSides]) {
    const VoxelStrains k = voxel_strains<kMixed>(w, v, below, far_strain);
    float P[3][kSides] = {};
#pragma GCC unroll 8
    for (int sx = 0; sx < kSides; ++sx)
#pragma GCC unroll 8
        for (int sy = 0; sy < kSides; ++sy)
#pragma GCC unroll 8
            for (int sz = 0; sz < kSides; ++sz) {
                const float hx = k.h[0][sx], hy = k.h[1][sy], hz = k.h[2][sz];
                const float theta = hx * k.mu[0][sx] + hy * k.mu[1][sy] + hz * k.mu[2][sz];
                // Volumetric stress lambda theta / sqrt(1 + (theta / theta_0)^2) (poisson.hpp).
                // (Only where lambda > 0: an auxetic voxel's negative lambda stays linear, its
                // energy is positive only with the deviatoric term's full weight.)
                const float lambda8 = w.lambda8[4 * sx + 2 * sy + sz][v];  // lambda_o / 8
                const float q = theta * kInverseSaturation * static_cast<float>(lambda8 > 0.0f);
                const float t = lambda8 * theta / std::sqrt(1.0f + q * q);
                P[0][sx] += hx * t;
                P[1][sy] += hy * t;
                P[2][sz] += hz * t;
            }
    const float g = w.shear[v];
#pragma GCC unroll 8
    for (int a = 0; a < 3; ++a) {
        float grad[kSides], far[kSides], dgrad[kSides];
#pragma GCC unroll 8
        for (int s = 0; s < kSides; ++s) {
            const float deviatoric = g * k.gamma[a][s];  // 4 octants x 2 G gamma / 8
            const float end = at_column_end(w, a, s, v);
            const float own = w.own[a][s][v];
            const float dev = w.dev[a][s][v];
            grad[s] = own * P[a][s] + w.other[a][1 - s][v] * P[a][1 - s] +
                      (dev + end * (own - dev)) * deviatoric;
            far[s] = w.far[a][s][v] * (P[a][s] + deviatoric);
            // d_s enters mu_s, mu of the other side inside a column (its interpolation weight
            // in both, pair) and the half-link (half_link_pair).
            if constexpr (kMixed) {
                const float inner = inside_column(w, a, s, v);
                const float pair = w.pair[a][s][v];
                dgrad[s] = pair * (P[a][s] + inner * P[a][1 - s]) +
                           half_link_pair(pair, inner) * deviatoric;
            } else {
                dgrad[s] = w.pair[a][s][v] * (P[a][s] + deviatoric);
            }
        }
        w.grad_neg[a][v] = grad[0];
        w.grad_pos[a][v] = grad[1];
        w.far_neg[a][v] = far[0];
        w.far_pos[a][v] = far[1];
        w.dgrad_neg[a][v] = dgrad[0];
        w.dgrad_pos[a][v] = dgrad[1];
    }
}

// The voxels of one run (dummy slots have all coefficients zero, so whole vectors run). Along x
// the - link, the partner's other links and d are contiguous (lattice order: slots v - 1, v - 2
// and v + 1); along y and z a uniform run reads them at a constant offset, a gathered one
// through the tables, and the far links (nonzero only at column ends) from the far strains the
// sparse copy filled (far_strain_copies).
template <bool kGather, bool kMixed>
BHM_ENGINE_INLINE void voxel_loop(const Views& w, const VoxelRun& run) {
    const int below_y = run.below_y, below_z = run.below_z;
    const float* __restrict ex = w.strain[0];
#pragma GCC ivdep
    for (int v = run.begin; v < run.end; ++v) {
        const int below[3] = {v - 1, kGather ? w.below[1][v] : v - below_y,
                              kGather ? w.below[2][v] : v - below_z};
        // (a mixed body's x far strains may carry a d: far_strain_copies fills them)
        const float far[3][kSides] = {{kMixed ? w.far_strain[0][0][v] : ex[v - 2],
                                       kMixed ? w.far_strain[0][1][v] : ex[v + 1]},
                                      {w.far_strain[1][0][v], w.far_strain[1][1][v]},
                                      {w.far_strain[2][0][v], w.far_strain[2][1][v]}};
        voxel_gradients<kMixed>(w, v, below, far);
    }
}

// The far links are a few per column (its two ends): copied through the model's sparse lists
// instead of gathered on every slot of the dense loops (a gather is one scalar load per lane).
void far_strain_copies(const PoissonParams& pp, PoissonScratch& p) {
    for (int a = 0; a < 3; ++a) {  // (x only in a mixed body: far_reads[0] is empty otherwise)
        float* far[kSides] = {p.far_strain_neg[a], p.far_strain_pos[a]};
        for (const PoissonParams::FarRead& r : pp.far_reads[a])
            far[r.side][r.voxel] = p.strain[a][r.slot];
        for (const PoissonParams::FarRead& r : pp.far_pair_reads[a])
            far[r.side][r.voxel] += r.pair * p.pair_d[a][r.slot];
    }
}

void far_gradient_copies(const PoissonParams& pp, PoissonScratch& p) {
    for (int a = 0; a < 3; ++a) {
        // A far link's d in an end estimate: dW/dd = pair dW/de_far, on that link's row.
        for (const PoissonParams::FarRead& r : pp.far_pair_reads[a])
            p.dgrad_pos[a][r.slot] +=
                r.pair * (r.side == 1 ? p.far_pos[a][r.voxel] : p.far_neg[a][r.voxel]);
        for (const PoissonParams::FarLink& f : pp.far_pos_links[a])
            p.far_from_below[a][f.link] = p.far_pos[a][f.voxel];
        for (const PoissonParams::FarLink& f : pp.far_neg_links[a])
            p.far_from_above[a][f.link] = p.far_neg[a][f.voxel];
    }
}

}  // namespace

namespace {

// The isolated links' d (the link pass applies the normal stresses, link_pass.cpp): the forces
// used d extrapolated in time from the last two relaxed values (2 d_n-1 - d_n-2, an error of
// order dt^2, an inertia-like term; a d one step behind would be an error of order dt, a damping
// or, coupled across axes, an anti-damping of the bending modes); one Jacobi step from it is the
// relaxed value, and the next step's guess is set here.
template <bool kGather>
BHM_ENGINE_INLINE void pair_loop(const Model::Data& d, PoissonScratch& p, int a,
                                 const LinkRun& run) {
    const float* __restrict step = d.poisson.pair_step[a].data();
    const float* __restrict keep = d.poisson.pair_keep[a].data();
    const int* __restrict plus = d.plus[a].data();
    const float* __restrict dgrad_pos = p.dgrad_pos[a];
    const float* __restrict dgrad_neg = p.dgrad_neg[a];
    float* __restrict pair_d = p.pair_d[a];
    float* __restrict pair_last = p.pair_last[a];
    const int delta = run.delta;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const int b = kGather ? plus[c] : c + delta;
        const float relaxed = keep[c] * pair_d[c] - step[c] * (dgrad_pos[c] + dgrad_neg[b]);
        pair_d[c] = 2.0f * relaxed - pair_last[c];
        pair_last[c] = relaxed;
    }
}

}  // namespace

void prepare_poisson_scratch(const Model::Data& d, PoissonScratch& p) {
    ensure(p, d.stored, d.link_lead);
}

BHM_ENGINE_KERNEL void poisson_pass(const Model::Data& d, const VoxelState& s,
                                    std::array<LinkScratch, 3>& links, PoissonScratch& p,
                                    float sin_t, float cos_t) {
    ensure(p, d.stored, d.link_lead);  // (sized at World creation: allocates nothing here)
    for (int a = 0; a < 3; ++a)
        link_strains(d, s, a, sin_t, cos_t, p.strain[a], links[a]);
    far_strain_copies(d.poisson, p);
    const Views w = views_of(d, p);
    for (const VoxelRun& run : d.voxel_runs)
        if (run.below_y == 0)
            d.poisson.mixed ? voxel_loop<true, true>(w, run) : voxel_loop<true, false>(w, run);
        else
            d.poisson.mixed ? voxel_loop<false, true>(w, run) : voxel_loop<false, false>(w, run);
    far_gradient_copies(d.poisson, p);
    if (d.poisson.pair_voxels.empty()) return;
    for (int a = 0; a < 3; ++a)
        for (const LinkRun& run : d.link_runs[a])
            if (run.delta == 0)
                pair_loop<true>(d, p, a, run);
            else
                pair_loop<false>(d, p, a, run);
}

double poisson_cross_energy(const Model::Data& d, const VoxelState& s, const PoissonScratch& state,
                            float sin_t, float cos_t) {
    if (!d.poisson.active) return 0.0;
    PoissonScratch p;
    ensure(p, d.stored, d.link_lead);
    const bool stepped = !state.storage[0].empty();
    // The strain pass also keeps the chords for the link pass: give it somewhere to put them.
    std::array<LinkScratch, 3> chords;
    const std::size_t span = static_cast<std::size_t>(d.link_lead) + d.stored;
    for (LinkScratch& l : chords) {
        l.storage.assign(4 * span, 0.0f);
        for (int i = 0; i < 3; ++i)
            l.chord[i] = l.storage.data() + d.link_lead + i * span;
        l.length = l.storage.data() + d.link_lead + 3 * span;
    }
    for (int a = 0; a < 3; ++a) {
        link_strains(d, s, a, sin_t, cos_t, p.strain[a], chords[a]);
        // The relaxed d of the last step (the forces used its extrapolation).
        if (stepped) std::copy(state.pair_last[a], state.pair_last[a] + d.stored, p.pair_d[a]);
    }
    const Views w = views_of(d, p);
    const double volume = std::pow(d.voxel_size_m, 3);
    double energy = 0.0;
    // W = sum over octants of V / 8 (G sum gamma^2 + lambda_o / 2 theta^2) ...
    for (int v = 0; v < d.voxels; ++v) {
        const VoxelStrains k = voxel_strains(w, v);
        for (int sx = 0; sx < kSides; ++sx)
            for (int sy = 0; sy < kSides; ++sy)
                for (int sz = 0; sz < kSides; ++sz) {
                    const float hx = k.h[0][sx], hy = k.h[1][sy], hz = k.h[2][sz];
                    const double theta = hx * k.mu[0][sx] + hy * k.mu[1][sy] + hz * k.mu[2][sz];
                    const double gx = k.gamma[0][sx], gy = k.gamma[1][sy], gz = k.gamma[2][sz];
                    const double lambda = 8.0 * w.lambda8[4 * sx + 2 * sy + sz][v];
                    const double q = theta * kInverseSaturation;
                    const double theta0 = 1.0 / kInverseSaturation;
                    const double volumetric =
                        lambda > 0.0 ? lambda * theta0 * theta0 * (std::sqrt(1.0 + q * q) - 1.0)
                                     : 0.5 * lambda * theta * theta;
                    energy +=
                        0.125 * volume *
                        (w.shear[v] * (hx * gx * gx + hy * gy * gy + hz * gz * gz) + volumetric);
                }
    }
    // ... less the links' own 1/2 M_link V e^2, which link_elastic_energy counts; plus the
    // penalty x E V d^2 / 2 on the d of links of one material.
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < d.voxels; ++c) {
            const double e = p.strain[a][c], dd = p.pair_d[a][c];
            energy -= 0.5 * d.links[a].k_axial[c] * d.voxel_size_m * d.voxel_size_m * e * e;
            energy += 0.5 * volume * d.poisson.pair_penalty[a][c] * dd * dd;
        }
    return energy;
}

}  // namespace bhm::engine
