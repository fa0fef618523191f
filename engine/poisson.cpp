// Poisson coupling (poisson.hpp): moduli, the per-step rest-length shifts and their energy.
#include "engine/poisson.hpp"

#include <algorithm>
#include <cmath>

#include "engine/kernel_dispatch.hpp"
#include "engine/link_kinematics.hpp"  // BHM_ENGINE_INLINE

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
    const double m = (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    return std::max({1.0, m, 1.0 / (1.0 - 2.0 * nu)});
}

void poisson_cross_weights(PoissonParams& pp, int stored) {
    for (auto& axis : pp.cross_weight)
        for (auto& w : axis)
            w.assign(stored, 0.0f);
    // Cross modulus of an octant whose half-links on the two lateral axes exist as hb, hc.
    auto octant_lambda = [&](int v, double hb, double hc) {
        return hb * hc * pp.lambda3[v] + (hb + hc - 2.0 * hb * hc) * pp.lambda2[v];
    };
    for (int v = 0; v < stored; ++v) {
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const double hb[2] = {pp.has_minus[b][v], pp.has_plus[b][v]};
            const double hc[2] = {pp.has_minus[c][v], pp.has_plus[c][v]};
            // term_a = 1/8 sum_{sb,sc} lambda(sb, sc) (e_b[sb] + e_c[sc]): e_b[sb] collects the
            // two octants on its side, lambda(sb, 0) + lambda(sb, 1), and e_c[sc] likewise.
            for (int side = 0; side < 2; ++side) {
                const double along_b =
                    octant_lambda(v, hb[side], hc[0]) + octant_lambda(v, hb[side], hc[1]);
                const double along_c =
                    octant_lambda(v, hb[0], hc[side]) + octant_lambda(v, hb[1], hc[side]);
                pp.cross_weight[a][side][v] = static_cast<float>(0.125 * hb[side] * along_b);
                pp.cross_weight[a][2 + side][v] = static_cast<float>(0.125 * hc[side] * along_c);
            }
        }
    }
}

void prepare_poisson_scratch(const Model::Data& d, PoissonScratch& p) {
    const std::size_t lead = static_cast<std::size_t>(d.link_lead);
    if (p.term[0].size() == static_cast<std::size_t>(d.stored) &&
        p.strain_storage[0].size() == lead + d.stored)
        return;
    for (int a = 0; a < 3; ++a) {
        // Zero lead slots: voxel runs read the strain of slot c - below (model_data.hpp), and
        // kNoLink (-1) in gathered ones; slots the passes never write stay zero.
        p.strain_storage[a].assign(lead + d.stored, 0.0f);
        p.strain[a] = p.strain_storage[a].data() + lead;
        p.term[a].assign(d.stored, 0.0f);
    }
}

namespace {

// The step runs three loops, each over the same runs as the link and voxel passes (whole vectors,
// empty vectors skipped, uniform runs without gathers; model_data.hpp):
//   1. strains: per link slot, e = (|d| - actuated rest) / L, exactly 0 for absent slots;
//   2. cross terms: per voxel and axis a, term_a = sum of cross_weight[a][k] times the four
//      lateral half-link strains (the - and + links of the two other axes). The octant moduli
//      depend only on which half-links exist, so the weights are precomputed at model build
//      (poisson_cross_weights) and a voxel costs 6 strain reads and 12 products;
//   3. shifts: per link slot, shift = rest_scale (term at its - end + term at its + end).
// Each loop writes only its own slot: no atomics, fixed order, the same bits on every ISA level.

template <bool kGather>
BHM_ENGINE_INLINE void strain_loop(const Model::Data& d, const VoxelState& s, int axis, float sin_t,
                                   float cos_t, const LinkRun& run, float* __restrict out) {
    const LinkParams& lp = d.links[axis];
    const float* __restrict exists = lp.exists.data();
    const float* __restrict rest_base = lp.rest_base.data();
    const float* __restrict rest_sin = lp.rest_sin.data();
    const float* __restrict rest_cos = lp.rest_cos.data();
    const float inv_l = static_cast<float>(1.0 / d.voxel_size_m);
    const double* __restrict px = s.pos[0].data();
    const double* __restrict py = s.pos[1].data();
    const double* __restrict pz = s.pos[2].data();
    const int* __restrict plus = d.plus[axis].data();
    const int delta = run.delta;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const int b = kGather ? plus[c] : c + delta;
        const float dx = static_cast<float>(px[b] - px[c]);
        const float dy = static_cast<float>(py[b] - py[c]);
        const float dz = static_cast<float>(pz[b] - pz[c]);
        const float rest = rest_base[c] + sin_t * rest_sin[c] + cos_t * rest_cos[c];
        out[c] = exists[c] * (std::sqrt(dx * dx + dy * dy + dz * dz) - rest) * inv_l;
    }
}

BHM_ENGINE_INLINE void compute_strains(const Model::Data& d, const VoxelState& s, float sin_t,
                                       float cos_t, PoissonScratch& p) {
    for (int a = 0; a < 3; ++a)
        for (const LinkRun& run : d.link_runs[a])
            if (run.delta == 0)
                strain_loop<true>(d, s, a, sin_t, cos_t, run, p.strain[a]);
            else
                strain_loop<false>(d, s, a, sin_t, cos_t, run, p.strain[a]);
}

template <bool kGather>
BHM_ENGINE_INLINE void cross_term_loop(const Model::Data& d, PoissonScratch& p,
                                       const VoxelRun& run) {
    const auto& w = d.poisson.cross_weight;
    const float* __restrict wx0 = w[0][0].data();
    const float* __restrict wx1 = w[0][1].data();
    const float* __restrict wx2 = w[0][2].data();
    const float* __restrict wx3 = w[0][3].data();
    const float* __restrict wy0 = w[1][0].data();
    const float* __restrict wy1 = w[1][1].data();
    const float* __restrict wy2 = w[1][2].data();
    const float* __restrict wy3 = w[1][3].data();
    const float* __restrict wz0 = w[2][0].data();
    const float* __restrict wz1 = w[2][1].data();
    const float* __restrict wz2 = w[2][2].data();
    const float* __restrict wz3 = w[2][3].data();
    const float* __restrict sx = p.strain[0];
    const float* __restrict sy = p.strain[1];
    const float* __restrict sz = p.strain[2];
    const int* __restrict minus_y = d.minus[1].data();
    const int* __restrict minus_z = d.minus[2].data();
    float* __restrict tx = p.term[0].data();
    float* __restrict ty = p.term[1].data();
    float* __restrict tz = p.term[2].data();
    const int below_y = run.below_y, below_z = run.below_z;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        // Half-link strains: [0] the link whose + end is c, [1] the link c owns.
        const float ex0 = sx[c - 1], ex1 = sx[c];
        const float ey0 = sy[kGather ? minus_y[c] : c - below_y], ey1 = sy[c];
        const float ez0 = sz[kGather ? minus_z[c] : c - below_z], ez1 = sz[c];
        tx[c] = (wx0[c] * ey0 + wx1[c] * ey1) + (wx2[c] * ez0 + wx3[c] * ez1);
        ty[c] = (wy0[c] * ez0 + wy1[c] * ez1) + (wy2[c] * ex0 + wy3[c] * ex1);
        tz[c] = (wz0[c] * ex0 + wz1[c] * ex1) + (wz2[c] * ey0 + wz3[c] * ey1);
    }
}

template <bool kGather>
BHM_ENGINE_INLINE void shift_loop(const Model::Data& d, const PoissonScratch& p, int axis,
                                  const LinkRun& run, float* __restrict shift) {
    const float* __restrict scale = d.poisson.rest_scale[axis].data();
    const float* __restrict term = p.term[axis].data();
    const int* __restrict plus = d.plus[axis].data();
    const int delta = run.delta;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const int b = kGather ? plus[c] : c + delta;
        shift[c] = scale[c] * (term[c] + term[b]);
    }
}

// The six half-link strains of voxel v (energy diagnostics): [axis][0] the link whose + end is
// v (minus[a][v]), [axis][1] the one it owns (slot v); zero slots when absent.
struct HalfLinks {
    float e[3][2];
    float h[3][2];  // 1 = the half-link exists
};

HalfLinks half_links(const Model::Data& d, const PoissonScratch& p, int v) {
    HalfLinks out;
    for (int a = 0; a < 3; ++a) {
        out.e[a][0] = p.strain[a][d.minus[a][v]];  // kNoLink reads a zero lead slot
        out.e[a][1] = p.strain[a][v];
        out.h[a][0] = d.poisson.has_minus[a][v];
        out.h[a][1] = d.poisson.has_plus[a][v];
    }
    return out;
}

}  // namespace

BHM_ENGINE_KERNEL void poisson_pass(const Model::Data& d, const VoxelState& s,
                                    std::array<LinkScratch, 3>& links, PoissonScratch& p,
                                    float sin_t, float cos_t) {
    prepare_poisson_scratch(d, p);  // (sized at World creation: allocates nothing here)
    compute_strains(d, s, sin_t, cos_t, p);
    for (const VoxelRun& run : d.voxel_runs)
        if (run.below_y == 0)
            cross_term_loop<true>(d, p, run);
        else
            cross_term_loop<false>(d, p, run);
    for (int a = 0; a < 3; ++a)
        for (const LinkRun& run : d.link_runs[a])
            if (run.delta == 0)
                shift_loop<true>(d, p, a, run, links[a].poisson_rest);
            else
                shift_loop<false>(d, p, a, run, links[a].poisson_rest);
}

double poisson_cross_energy(const Model::Data& d, const VoxelState& s, float sin_t, float cos_t) {
    if (!d.poisson.active) return 0.0;
    PoissonScratch p;
    prepare_poisson_scratch(d, p);
    compute_strains(d, s, sin_t, cos_t, p);
    const double volume = std::pow(d.voxel_size_m, 3);
    double energy = 0.0;
    // Per octant: lambda (e_a e_b + e_b e_c + e_c e_a) over its linked half-links, volume V / 8.
    for (int v = 0; v < d.voxels; ++v) {
        const HalfLinks k = half_links(d, p, v);
        for (int sx = 0; sx < 2; ++sx)
            for (int sy = 0; sy < 2; ++sy)
                for (int sz = 0; sz < 2; ++sz) {
                    const double hx = k.h[0][sx], hy = k.h[1][sy], hz = k.h[2][sz];
                    const double count = hx + hy + hz;
                    const double lambda = count == 3.0   ? d.poisson.lambda3[v]
                                          : count == 2.0 ? d.poisson.lambda2[v]
                                                         : 0.0;
                    const double ex = k.e[0][sx], ey = k.e[1][sy], ez = k.e[2][sz];
                    energy += 0.125 * volume * lambda * (ex * ey + ey * ez + ez * ex);
                }
    }
    return energy;
}

}  // namespace bhm::engine
