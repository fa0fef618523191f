// Poisson coupling (poisson.hpp): moduli, the per-step rest-length shifts and their energy.
#include "engine/poisson.hpp"

#include <algorithm>
#include <cmath>

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

namespace {

// Strain of every link slot of one axis: (|d| - actuated rest) / L, 0 for absent slots.
void link_strains(const Model::Data& d, const VoxelState& s, int axis, float sin_t, float cos_t,
                  float* __restrict out) {
    const LinkParams& lp = d.links[axis];
    const float inv_l = static_cast<float>(1.0 / d.voxel_size_m);
    const double* px = s.pos[0].data();
    const double* py = s.pos[1].data();
    const double* pz = s.pos[2].data();
    const int* plus = d.plus[axis].data();
    for (int c = 0; c < d.slots; ++c) {
        const int b = axis == 0 ? c + 1 : plus[c];
        const float dx = static_cast<float>(px[b] - px[c]);
        const float dy = static_cast<float>(py[b] - py[c]);
        const float dz = static_cast<float>(pz[b] - pz[c]);
        const float rest = lp.rest_base[c] + sin_t * lp.rest_sin[c] + cos_t * lp.rest_cos[c];
        out[c] = lp.exists[c] * (std::sqrt(dx * dx + dy * dy + dz * dz) - rest) * inv_l;
    }
}

// The six half-link strains of voxel v: [axis][0] the link to its - neighbour (slot v - 1 along
// minus[a][v]), [axis][1] the one it owns (slot v); zero slots when absent.
struct HalfLinks {
    float e[3][2];
    float h[3][2];  // 1 = the half-link exists
};

HalfLinks half_links(const Model::Data& d, const float* const* strain, int v) {
    HalfLinks out;
    for (int a = 0; a < 3; ++a) {
        const int below = d.minus[a][v];  // kNoLink reads the zero lead slot
        out.e[a][0] = strain[a][below];
        out.e[a][1] = strain[a][v];
        out.h[a][0] = d.poisson.has_minus[a][v];
        out.h[a][1] = d.poisson.has_plus[a][v];
    }
    return out;
}

// Cross modulus of an octant spanning 1 + hb + hc linked axes.
float octant_lambda(const Model::Data& d, int v, float hb, float hc) {
    return hb * hc * d.poisson.lambda3[v] + (hb + hc - 2.0f * hb * hc) * d.poisson.lambda2[v];
}

// The cross stress that voxel v adds to either of its links on axis a: the mean over the four
// octants beside that link of lambda_octant (e_b + e_c) / 2 (half of each octant's volume-weighted
// share, the other end adds its own half; poisson.hpp).
float cross_term(const Model::Data& d, const HalfLinks& k, int v, int a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    float sum = 0.0f;
    for (int sb = 0; sb < 2; ++sb)
        for (int sc = 0; sc < 2; ++sc)
            sum += octant_lambda(d, v, k.h[b][sb], k.h[c][sc]) * (k.e[b][sb] + k.e[c][sc]);
    return 0.125f * sum;
}

void ensure(PoissonScratch& p, int stored) {
    if (p.term[0].size() == static_cast<std::size_t>(stored)) return;
    for (int a = 0; a < 3; ++a) {
        p.strain_storage[a].assign(static_cast<std::size_t>(kLinkLead) + stored, 0.0f);
        p.strain[a] = p.strain_storage[a].data() + kLinkLead;
        p.term[a].assign(stored, 0.0f);
    }
}

}  // namespace

void poisson_pass(const Model::Data& d, const VoxelState& s, std::array<LinkScratch, 3>& links,
                  PoissonScratch& p, float sin_t, float cos_t) {
    ensure(p, d.stored);
    for (int a = 0; a < 3; ++a)
        link_strains(d, s, a, sin_t, cos_t, p.strain[a]);
    for (int v = 0; v < d.voxels; ++v) {
        const HalfLinks k = half_links(d, p.strain.data(), v);
        for (int a = 0; a < 3; ++a)
            p.term[a][v] = cross_term(d, k, v, a);
    }
    for (int a = 0; a < 3; ++a) {
        const float* scale = d.poisson.rest_scale[a].data();
        const float* term = p.term[a].data();
        const int* plus = d.plus[a].data();
        float* shift = links[a].poisson_rest;
        for (int c = 0; c < d.slots; ++c) {
            const int b = a == 0 ? c + 1 : plus[c];
            shift[c] = scale[c] * (term[c] + term[b]);
        }
    }
}

double poisson_cross_energy(const Model::Data& d, const VoxelState& s, float sin_t, float cos_t) {
    if (!d.poisson.active) return 0.0;
    PoissonScratch p;
    ensure(p, d.stored);
    for (int a = 0; a < 3; ++a)
        link_strains(d, s, a, sin_t, cos_t, p.strain[a]);
    const double volume = std::pow(d.voxel_size_m, 3);
    double energy = 0.0;
    // Per octant: lambda (e_a e_b + e_b e_c + e_c e_a) over its linked half-links, volume V / 8.
    for (int v = 0; v < d.voxels; ++v) {
        const HalfLinks k = half_links(d, p.strain.data(), v);
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
