// The link pass: Euler-Bernoulli beam forces of every link of one lattice axis.
//
// Per link, in its co-rotational frame F (link_kinematics.hpp) with chord direction e, extension
// x = |d| - rest, end rotations ta (- end) and tb (+ end) relative to F, their twists t = theta.e,
// and k_b = E I / L, k_t = G J / L, k_a = E A / L:
//   axial force    N = k_a x                                       (tension > 0)
//   bending        M_a = -k_b (4 ta + 2 tb),  M_b = -k_b (2 ta + 4 tb)   (parts normal to e)
//   torsion        M_a.e = k_t (t_b - t_a),   M_b.e = -M_a.e
//   shear force    from moment balance about the - end, d x F_b = -(M_a + M_b):
//                  F_b = -N e + e x (M_a + M_b) / |d|,   F_a = -F_b
// which is the standard beam element stiffness (12EI/L^3, 6EI/L^2, 4EI/L, 2EI/L) with the
// transverse end offsets absorbed by the frame. Forces and moments are built directly in world
// coordinates (no rotation back from a local frame). Bond damping is Rayleigh damping C = beta K:
// the same equations evaluated at deformation + beta * rate, the rate being the backward difference
// of the deformation (for symplectic Euler positions this is the current velocity). As in Voxelyze,
// the axial deformation is the extension beyond the actuated rest length, so damping resists the
// elastic strain rate, not the thermal expansion itself. Linear and
// angular momentum are conserved exactly by construction: equal and opposite forces, and moments
// that balance the couple of the forces.
#include "engine/internal/link_pass.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/internal/beam_forces.hpp"
#include "engine/internal/kernel_dispatch.hpp"
#include "engine/internal/link_kinematics.hpp"

namespace bhm::engine {
namespace {

// The voxel arrays seen from one axis: index 0 of each triple is the link axis.
struct AxisView {
    const double* p[3];
    const float* q[4];  // w, then the vector part in local order (float copies)
    const int* plus;    // + neighbour of each slot (y, z); x uses slot + 1
};

AxisView axis_view(const Model::Data& model, const VoxelState& s, int axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    return {{s.pos[axis].data(), s.pos[a1].data(), s.pos[a2].data()},
            {s.quat_f[0].data(), s.quat_f[1 + axis].data(), s.quat_f[1 + a1].data(),
             s.quat_f[1 + a2].data()},
            model.plus[axis].data()};
}

// The frame of the link from voxel a to voxel b (link_chord). Restrict pointers: nothing the link
// pass writes aliases them.
BHM_ENGINE_INLINE LinkFrame frame_of(const double* __restrict p0, const double* __restrict p1,
                                     const double* __restrict p2, const float* __restrict qw,
                                     const float* __restrict q0, const float* __restrict q1,
                                     const float* __restrict q2, int a, int b, float exists,
                                     float rest_base) {
    const Chord d = link_chord(p0, p1, p2, a, b, exists, rest_base);
    return link_frame(d.d0, d.d1, d.d2, qw[a], q0[a], q1[a], q2[a], qw[b], q0[b], q1[b], q2[b]);
}

BHM_ENGINE_INLINE int plus_of(const AxisView& v, int axis, int c) {
    return axis == 0 ? c + 1 : v.plus[c];
}

BHM_ENGINE_INLINE LinkFrame frame_of(const AxisView& v, int axis, float exists, float rest_base,
                                     int c) {
    return frame_of(v.p[0], v.p[1], v.p[2], v.q[0], v.q[1], v.q[2], v.q[3], c, plus_of(v, axis, c),
                    exists, rest_base);
}

BHM_ENGINE_INLINE bool healthy(const LinkFrame& f, float extension, float rest_base) {
    // Written so that NaN fails every test. Bounds on the lattice length L, not the actuated rest
    // length: a link of a voxel contracted to 0.4 L may legitimately stretch past 0.8 L.
    return (f.length > 0.1f * rest_base) & (extension < 2.0f * rest_base) &
           (f.axis_cos > kMinOnePlusCos - 1.0f);
}

// The Poisson coupling's inputs to the link pass of one axis (poisson.hpp): the strains and
// stresses its pass left in scratch, from which the rest-length shift L e - L sigma / M_link is
// formed here (one pass over the links less, and no shift array to write and read back).
struct PoissonInputs {
    const float* strain = nullptr;
    const float* grad_pos = nullptr;    // of the link's - end voxel (its + half-link)
    const float* grad_neg = nullptr;    // of the link's + end voxel (its - half-link)
    const float* from_below = nullptr;  // far terms of the column-end estimates
    const float* from_above = nullptr;
    const float* rest_scale = nullptr;  // -L / M_link
};

PoissonInputs poisson_inputs(const Model::Data& model, const PoissonScratch& p, int axis) {
    return {p.strain[axis],         p.grad_pos[axis],       p.grad_neg[axis],
            p.far_from_below[axis], p.far_from_above[axis], model.poisson.rest_scale[axis].data()};
}

// One axis's loop over the link slots of one run. kGather: the + end of slot c is plus[c];
// otherwise it is voxel c + delta, and nothing is gathered. kPoisson: the chords come from the
// Poisson pass's scratch and the rest lengths take its shift.
// kExplicitDamping: the explicit (velocity-lagged) bond damping; without it (the implicit
// damping, damping_pass.hpp, applies it) the loop neither reads nor keeps the last deformation.
template <bool kGather, bool kPoisson, bool kExplicitDamping>
BHM_ENGINE_INLINE int link_loop(const Model::Data& model, const AxisView& v, LinkScratch& out,
                                const PoissonInputs& pi, int axis, float sin_t, float cos_t,
                                const LinkRun& run) {
    const LinkParams& lp = model.links[axis];
    const float* __restrict exists = lp.exists.data();
    const float* __restrict k_axial = lp.k_axial.data();
    const float* __restrict k_bend = lp.k_bend.data();
    const float* __restrict k_torsion = lp.k_torsion.data();
    const float* __restrict damp = lp.damp_steps.data();
    const float* __restrict rest_base = lp.rest_base.data();
    const float* __restrict rest_sin = lp.rest_sin.data();
    const float* __restrict rest_cos = lp.rest_cos.data();
    const float* __restrict chord0 = out.chord[0];
    const float* __restrict chord1 = out.chord[1];
    const float* __restrict chord2 = out.chord[2];
    const float* __restrict lengths = out.length;
    const float* __restrict strain = pi.strain;
    const float* __restrict grad_pos = pi.grad_pos;
    const float* __restrict grad_neg = pi.grad_neg;
    const float* __restrict from_below = pi.from_below;
    const float* __restrict from_above = pi.from_above;
    const float* __restrict rest_scale = pi.rest_scale;
    const float voxel_size = static_cast<float>(model.voxel_size_m);
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
    float* __restrict prev_ext = out.prev_extension;
    float* __restrict pa0 = out.prev_theta_neg[0];
    float* __restrict pa1 = out.prev_theta_neg[1];
    float* __restrict pa2 = out.prev_theta_neg[2];
    float* __restrict pb0 = out.prev_theta_pos[0];
    float* __restrict pb1 = out.prev_theta_pos[1];
    float* __restrict pb2 = out.prev_theta_pos[2];

    const double* __restrict p0 = v.p[0];
    const double* __restrict p1 = v.p[1];
    const double* __restrict p2 = v.p[2];
    const float* __restrict qw = v.q[0];
    const float* __restrict q0 = v.q[1];
    const float* __restrict q1 = v.q[2];
    const float* __restrict q2 = v.q[3];

    int bad = 0;  // an integer sum: a float one would be an in-order (unvectorisable) reduction
    const int delta = run.delta;
    // Every array is distinct (restrict on locals is not enough for GCC's dependence analysis).
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const int b = kGather ? plus[c] : c + delta;
        LinkFrame f;
        float rest_shift = 0.0f;
        if constexpr (kPoisson) {
            f = link_frame(chord0[c], chord1[c], chord2[c], lengths[c], qw[c], q0[c], q1[c], q2[c],
                           qw[b], q0[b], q1[b], q2[b]);
            const float sigma = grad_pos[c] + grad_neg[b] + from_below[c] + from_above[c];
            rest_shift = voxel_size * strain[c] + rest_scale[c] * sigma;
        } else {
            f = frame_of(p0, p1, p2, qw, q0, q1, q2, c, b, exists[c], rest_base[c]);
        }
        const float actuated = rest_base[c] + sin_t * rest_sin[c] + cos_t * rest_cos[c];
        const float rest = actuated + rest_shift;
        const float extension = f.length - rest;
        // Stiffness follows the actuated size s: axial E A / L ~ s, and bending and torsion
        // ~ s^2, so the transverse (shear) stiffness, moment / |d|^2, stays that of the rest
        // size instead of growing as 1 / s^2 when the link contracts (the divergence of large
        // contractions). The voxels' inertia is kept, so omega^2 <= s^2 omega_0^2, which the
        // stable step bounds at the largest size (limits::link_omega2).
        const float size = actuated * inv_voxel_size;
        const float size2 = size * size;
        // The guard measures the geometric stretch (beyond the actuated rest), not `extension`,
        // which also holds the Poisson shift (it is stress / M, large under large cross strains
        // though the link itself is not stretched).
        bad +=
            static_cast<int>((exists[c] > 0.0f) & !healthy(f, f.length - actuated, rest_base[c]));

        // Deformation plus beta times its rate (Rayleigh damping), then the beam equations.
        float x = extension;
        float ta0 = f.theta_neg[0], ta1 = f.theta_neg[1], ta2 = f.theta_neg[2];
        float tb0 = f.theta_pos[0], tb1 = f.theta_pos[1], tb2 = f.theta_pos[2];
        if constexpr (kExplicitDamping) {
            const float k = damp[c];
            x = extension + k * (extension - prev_ext[c]);
            ta0 = f.theta_neg[0] + k * (f.theta_neg[0] - pa0[c]);
            ta1 = f.theta_neg[1] + k * (f.theta_neg[1] - pa1[c]);
            ta2 = f.theta_neg[2] + k * (f.theta_neg[2] - pa2[c]);
            tb0 = f.theta_pos[0] + k * (f.theta_pos[0] - pb0[c]);
            tb1 = f.theta_pos[1] + k * (f.theta_pos[1] - pb1[c]);
            tb2 = f.theta_pos[2] + k * (f.theta_pos[2] - pb2[c]);
            prev_ext[c] = extension;
            pa0[c] = f.theta_neg[0];
            pa1[c] = f.theta_neg[1];
            pa2[c] = f.theta_neg[2];
            pb0[c] = f.theta_pos[0];
            pb1[c] = f.theta_pos[1];
            pb2[c] = f.theta_pos[2];
        }

        const float kb = k_bend[c] * size2;
        const float kt = k_torsion[c] * size2;
        const float inv_len = 1.0f / f.length;
        const float axial = k_axial[c] * size * x;
        const BeamLoads o =
            beam_loads(f.ex, f.ey, f.ez, inv_len, axial, kb, kt, ta0, ta1, ta2, tb0, tb1, tb2);
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
    return bad;
}

template <bool kExplicitDamping>
BHM_ENGINE_INLINE int link_runs(const Model::Data& model, const AxisView& v, LinkScratch& out,
                                const PoissonScratch* poisson, int axis, float sin_t, float cos_t) {
    int bad = 0;
    if (poisson) {
        const PoissonInputs pi = poisson_inputs(model, *poisson, axis);
        for (const LinkRun& run : model.link_runs[axis])
            bad += run.delta == 0 ? link_loop<true, true, kExplicitDamping>(model, v, out, pi, axis,
                                                                            sin_t, cos_t, run)
                                  : link_loop<false, true, kExplicitDamping>(
                                        model, v, out, pi, axis, sin_t, cos_t, run);
    } else {
        const PoissonInputs none;
        for (const LinkRun& run : model.link_runs[axis])
            bad += run.delta == 0 ? link_loop<true, false, kExplicitDamping>(
                                        model, v, out, none, axis, sin_t, cos_t, run)
                                  : link_loop<false, false, kExplicitDamping>(
                                        model, v, out, none, axis, sin_t, cos_t, run);
    }
    return bad;
}

}  // namespace

BHM_ENGINE_KERNEL int link_pass(const Model::Data& model, const VoxelState& voxels,
                                LinkScratch& out, const PoissonScratch* poisson, int axis,
                                float sin_t, float cos_t) {
    const AxisView v = axis_view(model, voxels, axis);
    if (model.implicit_sweeps > 0)
        return link_runs<false>(model, v, out, poisson, axis, sin_t, cos_t);
    return link_runs<true>(model, v, out, poisson, axis, sin_t, cos_t);
}

int first_bad_link(const Model::Data& model, const VoxelState& voxels,
                   const LinkScratch& /*scratch: the guard ignores the Poisson shift*/, int axis,
                   float sin_t, float cos_t) {
    const AxisView v = axis_view(model, voxels, axis);
    const LinkParams& lp = model.links[axis];
    for (int c = 0; c < model.voxels; ++c) {
        if (lp.exists[c] == 0.0f) continue;
        const LinkFrame f = frame_of(v, axis, 1.0f, lp.rest_base[c], c);
        const float rest = lp.rest_base[c] + sin_t * lp.rest_sin[c] + cos_t * lp.rest_cos[c];
        if (!healthy(f, f.length - rest, lp.rest_base[c])) return c;
    }
    return -1;
}

std::string describe_link(const Model::Data& model, const VoxelState& voxels, int axis, int c,
                          float sin_t, float cos_t) {
    const AxisView v = axis_view(model, voxels, axis);
    const LinkParams& lp = model.links[axis];
    const LinkFrame f = frame_of(v, axis, 1.0f, lp.rest_base[c], c);
    const float rest = lp.rest_base[c] + sin_t * lp.rest_sin[c] + cos_t * lp.rest_cos[c];
    const float L = lp.rest_base[c];
    char buf[160];
    std::snprintf(buf, sizeof buf, "length %.3g L, actuated rest %.3g L, axis %.0f degrees off",
                  f.length / L, rest / L,
                  std::acos(std::fmax(-1.0f, std::fmin(1.0f, f.axis_cos))) * 57.29578f);
    return buf;
}

double link_elastic_energy(const Model::Data& model, const VoxelState& voxels, int axis,
                           float sin_t, float cos_t) {
    const AxisView v = axis_view(model, voxels, axis);
    const LinkParams& lp = model.links[axis];
    double energy = 0.0;
    for (int c = 0; c < model.voxels; ++c) {
        if (lp.exists[c] == 0.0f) continue;
        const LinkFrame f = frame_of(v, axis, 1.0f, lp.rest_base[c], c);
        const double rest = lp.rest_base[c] + sin_t * lp.rest_sin[c] + cos_t * lp.rest_cos[c];
        const double x = f.length - rest;
        const double e[3] = {f.ex, f.ey, f.ez};
        double ta_e = 0.0, tb_e = 0.0, ta_ta = 0.0, tb_tb = 0.0, ta_tb = 0.0;
        for (int i = 0; i < 3; ++i) {
            const double ta = f.theta_neg[i], tb = f.theta_pos[i];
            ta_e += ta * e[i];
            tb_e += tb * e[i];
            ta_ta += ta * ta;
            tb_tb += tb * tb;
            ta_tb += ta * tb;
        }
        // Normal parts: |ta_n|^2 = |ta|^2 - (ta.e)^2 etc. U_bend = k_s / 2 |ta_n + tb_n|^2 +
        // k_b / 2 |ta_n - tb_n|^2 (k_s = 3 k_b at nu = 0: k_b (2 ta_n^2 + 2 tb_n^2 + 2 ta_n.tb_n))
        const double aa = ta_ta - ta_e * ta_e, bb = tb_tb - tb_e * tb_e, ab = ta_tb - ta_e * tb_e;
        const double k_shear = std::fmin(kShearPerTorsion * lp.k_torsion[c], 3.0f * lp.k_bend[c]);
        const double bend =
            0.5 * k_shear * (aa + bb + 2.0 * ab) + 0.5 * lp.k_bend[c] * (aa + bb - 2.0 * ab);
        const double twist = tb_e - ta_e;
        energy += 0.5 * lp.k_axial[c] * x * x + 0.5 * lp.k_torsion[c] * twist * twist + bend;
    }
    return energy;
}

}  // namespace bhm::engine
