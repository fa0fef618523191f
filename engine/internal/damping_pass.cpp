// The link half of a sweep of the implicit bond damping (damping_pass.hpp).
//
// The deformation rate of a link from the velocities of its ends, in the link frame of
// link_kinematics.hpp (chord e, length |d|): the extension rate e . (v_b - v_a), and each end's
// rotation rate relative to the frame, w_end - w_F, the frame turning with the chord at
// w_F = e x (v_b - v_a) / |d| (its roll about e cancels: torsion takes the difference of the two
// ends, bending only the normal parts). The beam equations at beta times that rate are the
// damping loads; they are the exact transpose of the rate map (power balance), so C is symmetric
// positive semidefinite and conserves linear and angular momentum like the elastic loads.
#include "engine/internal/damping_pass.hpp"

#include "engine/internal/beam_forces.hpp"
#include "engine/internal/kernel_dispatch.hpp"
#include "engine/internal/link_kinematics.hpp"

namespace bhm::engine {
namespace {

struct DampingView {
    const double* p[3];  // positions, link axis first
    const double* v[3];  // velocities, same order
    const double* w[3];  // angular velocities, same order
    const int* plus;
};

DampingView damping_view(const Model::Data& model, const VoxelState& s, int axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    return {{s.pos[axis].data(), s.pos[a1].data(), s.pos[a2].data()},
            {s.vel[axis].data(), s.vel[a1].data(), s.vel[a2].data()},
            {s.omega[axis].data(), s.omega[a1].data(), s.omega[a2].data()},
            model.plus[axis].data()};
}

template <bool kGather, bool kPoisson>
BHM_ENGINE_INLINE void damping_loop(const Model::Data& model, const DampingView& v,
                                    LinkScratch& out, const PoissonScratch* poisson, int axis,
                                    float sin_t, float cos_t, float rate_sin, float rate_cos,
                                    const LinkRun& run) {
    const LinkParams& lp = model.links[axis];
    const float* __restrict exists = lp.exists.data();
    const float* __restrict k_axial = lp.k_axial.data();
    const float* __restrict k_bend = lp.k_bend.data();
    const float* __restrict k_torsion = lp.k_torsion.data();
    const float* __restrict beta = lp.damp_beta.data();
    const float* __restrict rest_base = lp.rest_base.data();
    const float* __restrict rest_sin = lp.rest_sin.data();
    const float* __restrict rest_cos = lp.rest_cos.data();
    const float* __restrict relax = lp.damp_relax.data();
    float* __restrict kept_x = out.damp_extension;
    float* __restrict kept_a0 = out.damp_turn_neg[0];
    float* __restrict kept_a1 = out.damp_turn_neg[1];
    float* __restrict kept_a2 = out.damp_turn_neg[2];
    float* __restrict kept_b0 = out.damp_turn_pos[0];
    float* __restrict kept_b1 = out.damp_turn_pos[1];
    float* __restrict kept_b2 = out.damp_turn_pos[2];
    const float* __restrict chord0 = kPoisson ? out.chord[0] : nullptr;
    const float* __restrict chord1 = kPoisson ? out.chord[1] : nullptr;
    const float* __restrict chord2 = kPoisson ? out.chord[2] : nullptr;
    const float* __restrict lengths = kPoisson ? out.length : nullptr;
    (void)poisson;
    const float inv_voxel_size = static_cast<float>(1.0 / model.voxel_size_m);
    const int* __restrict plus = v.plus;
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    float* __restrict f0 = out.force[axis];
    float* __restrict f1 = out.force[a1];
    float* __restrict f2 = out.force[a2];
    float* __restrict mn0 = out.moment_neg[axis];
    float* __restrict mn1 = out.moment_neg[a1];
    float* __restrict mn2 = out.moment_neg[a2];
    float* __restrict mp0 = out.moment_pos[axis];
    float* __restrict mp1 = out.moment_pos[a1];
    float* __restrict mp2 = out.moment_pos[a2];
    const double* __restrict p0 = v.p[0];
    const double* __restrict p1 = v.p[1];
    const double* __restrict p2 = v.p[2];
    const double* __restrict v0 = v.v[0];
    const double* __restrict v1 = v.v[1];
    const double* __restrict v2 = v.v[2];
    const double* __restrict w0 = v.w[0];
    const double* __restrict w1 = v.w[1];
    const double* __restrict w2 = v.w[2];
    const int delta = run.delta;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const int b = kGather ? plus[c] : c + delta;
        float d0, d1, d2, len;
        if constexpr (kPoisson) {
            d0 = chord0[c];
            d1 = chord1[c];
            d2 = chord2[c];
            len = lengths[c];
        } else {
            const Chord d = link_chord(p0, p1, p2, c, b, exists[c], rest_base[c]);
            d0 = d.d0;
            d1 = d.d1;
            d2 = d.d2;
            len = chord_length(d0, d1, d2);
        }
        const float inv_len = 1.0f / len;
        const float ex = d0 * inv_len, ey = d1 * inv_len, ez = d2 * inv_len;
        const float dv0 = static_cast<float>(v0[b] - v0[c]);
        const float dv1 = static_cast<float>(v1[b] - v1[c]);
        const float dv2 = static_cast<float>(v2[b] - v2[c]);
        // Frame rate (normal part) e x dv / |d|.
        const float wf0 = (ey * dv2 - ez * dv1) * inv_len;
        const float wf1 = (ez * dv0 - ex * dv2) * inv_len;
        const float wf2 = (ex * dv1 - ey * dv0) * inv_len;
        const float k = beta[c];
        // The extension's rate: the length's less the actuated rest length's (the damping resists
        // the elastic strain rate, not the thermal expansion, as the explicit form does).
        const float rest_rate = rate_sin * rest_sin[c] + rate_cos * rest_cos[c];
        // This sweep's rates from the current velocities, relaxed toward from the kept ones by
        // the link's factor (damping_pass.hpp): g <- g + s (beta B v - g).
        const float s = relax[c];
        const float x =
            kept_x[c] + s * (k * (ex * dv0 + ey * dv1 + ez * dv2 - rest_rate) - kept_x[c]);
        const float ta0 = kept_a0[c] + s * (k * (static_cast<float>(w0[c]) - wf0) - kept_a0[c]);
        const float ta1 = kept_a1[c] + s * (k * (static_cast<float>(w1[c]) - wf1) - kept_a1[c]);
        const float ta2 = kept_a2[c] + s * (k * (static_cast<float>(w2[c]) - wf2) - kept_a2[c]);
        const float tb0 = kept_b0[c] + s * (k * (static_cast<float>(w0[b]) - wf0) - kept_b0[c]);
        const float tb1 = kept_b1[c] + s * (k * (static_cast<float>(w1[b]) - wf1) - kept_b1[c]);
        const float tb2 = kept_b2[c] + s * (k * (static_cast<float>(w2[b]) - wf2) - kept_b2[c]);
        kept_x[c] = x;
        kept_a0[c] = ta0;
        kept_a1[c] = ta1;
        kept_a2[c] = ta2;
        kept_b0[c] = tb0;
        kept_b1[c] = tb1;
        kept_b2[c] = tb2;
        // Stiffness at the actuated size, as in the elastic pass.
        const float size =
            (rest_base[c] + sin_t * rest_sin[c] + cos_t * rest_cos[c]) * inv_voxel_size;
        const float size2 = size * size;
        const BeamLoads o =
            beam_loads(ex, ey, ez, inv_len, k_axial[c] * size * x, k_bend[c] * size2,
                       k_torsion[c] * size2, ta0, ta1, ta2, tb0, tb1, tb2);
        f0[c] = o.f0;
        f1[c] = o.f1;
        f2[c] = o.f2;
        mn0[c] = o.ma0;
        mn1[c] = o.ma1;
        mn2[c] = o.ma2;
        mp0[c] = o.mb0;
        mp1[c] = o.mb1;
        mp2[c] = o.mb2;
    }
}

}  // namespace

BHM_ENGINE_KERNEL void damping_link_pass(const Model::Data& model, const VoxelState& voxels,
                                         LinkScratch& out, const PoissonScratch* poisson, int axis,
                                         float sin_t, float cos_t, float rate_sin, float rate_cos) {
    const DampingView v = damping_view(model, voxels, axis);
    for (const LinkRun& run : model.link_runs[axis]) {
        if (poisson)
            run.delta == 0 ? damping_loop<true, true>(model, v, out, poisson, axis, sin_t, cos_t,
                                                      rate_sin, rate_cos, run)
                           : damping_loop<false, true>(model, v, out, poisson, axis, sin_t, cos_t,
                                                       rate_sin, rate_cos, run);
        else
            run.delta == 0 ? damping_loop<true, false>(model, v, out, poisson, axis, sin_t, cos_t,
                                                       rate_sin, rate_cos, run)
                           : damping_loop<false, false>(model, v, out, poisson, axis, sin_t, cos_t,
                                                        rate_sin, rate_cos, run);
    }
}

}  // namespace bhm::engine
