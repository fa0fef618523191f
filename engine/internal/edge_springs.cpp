#include "engine/internal/edge_springs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/internal/kernel_dispatch.hpp"
#include "engine/internal/link_kinematics.hpp"  // BHM_ENGINE_INLINE
#include "engine/internal/moduli.hpp"

namespace bhm::engine {
void build_edge_springs(Model::Data& d, double& max_omega2) {
    const BodySpec& spec = d.spec;
    const double L = spec.voxel_size_m;
    Model::Data::EdgeSprings& springs = d.edge_springs;
    springs.gauss_m = static_cast<float>(L / (2.0 * std::sqrt(3.0)));
    const std::array<int, 3> limit{spec.nx, spec.ny, spec.nz};
    const std::array<int, 3> stride{1, spec.nx, spec.nx * spec.ny};
    auto material = [&](int v) -> const Material& {
        return spec.materials[d.voxel_material[v] - 1];
    };
    for (int a = 0; a < d.voxels; ++a) {
        const int c = d.voxel_cell[a];
        const std::array<int, 3> xyz{c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
        // b = a + e_i + s e_j (i < j): each face-diagonal pair once.
        for (int i = 0; i < 3; ++i) {
            if (xyz[i] + 1 >= limit[i]) continue;
            for (int j = i + 1; j < 3; ++j) {
                for (int s = -1; s <= 1; s += 2) {
                    if (xyz[j] + s < 0 || xyz[j] + s >= limit[j]) continue;
                    const int b = d.cell_voxel[c + stride[i] + s * stride[j]];
                    const int bridge_i = d.cell_voxel[c + stride[i]];
                    const int bridge_j = d.cell_voxel[c + s * stride[j]];
                    if (b < 0 || bridge_i < 0 || bridge_j < 0) continue;
                    if (d.voxel_fixed[a] && d.voxel_fixed[b]) continue;
                    const double e_end =
                        series(material(a).youngs_modulus_pa, material(b).youngs_modulus_pa);
                    const Material& bridge =
                        material(bridge_i).youngs_modulus_pa >= material(bridge_j).youngs_modulus_pa
                            ? material(bridge_i)
                            : material(bridge_j);
                    const double e_bridge = bridge.youngs_modulus_pa, nu = bridge.poisson_ratio;
                    if (!(e_end > e_bridge)) continue;
                    // Per unit length of edge: the stiff phase's term and the soft wedge's in
                    // series (edge_springs.hpp); per Gauss point half the edge's length.
                    const double stiff_phase = kEdgeStiffPhase * (e_end - e_bridge);
                    const double soft_wedge = kEdgeSoftWedge * e_bridge;
                    const double per_point =
                        stiff_phase * soft_wedge / (stiff_phase + soft_wedge) * 0.5 * L;
                    const int edge_axis = 3 - i - j;
                    springs.a.push_back(a);
                    springs.b.push_back(b);
                    for (int k = 0; k < 3; ++k) {
                        springs.half[k].push_back(static_cast<float>(k == i   ? 0.5 * L
                                                                     : k == j ? 0.5 * s * L
                                                                              : 0.0));
                        springs.edge[k].push_back(k == edge_axis ? 1.0f : 0.0f);
                    }
                    springs.act_sin_a.push_back(static_cast<float>(d.act_sin[a]));
                    springs.act_cos_a.push_back(static_cast<float>(d.act_cos[a]));
                    springs.act_sin_b.push_back(static_cast<float>(d.act_sin[b]));
                    springs.act_cos_b.push_back(static_cast<float>(d.act_cos[b]));
                    const double k_across = per_point / (1.0 - nu * nu);
                    const double k_along = per_point / (1.0 + nu);  // 2 G / E
                    springs.k_across.push_back(static_cast<float>(k_across));
                    springs.k_along.push_back(static_cast<float>(k_along));
                    springs.damping.push_back(0.0f);
                    // Stiffest mode: a point's effective mass, with the lever |half| = L / sqrt 2
                    // and I = m L^2 / 6, is m / 4 per end; both points on the lighter pair.
                    const double m = std::min(d.mass[a], d.mass[b]);
                    max_omega2 = std::max(max_omega2, 16.0 * std::max(k_across, k_along) / m);
                }
            }
        }
    }
}

void finish_edge_springs(Model::Data& d) {
    const double dt = d.dt_s;
    Model::Data::EdgeSprings& springs = d.edge_springs;
    std::vector<int> per_voxel(d.voxels, 0);
    for (auto* v : {&springs.turn_a, &springs.turn_b})
        v->assign(springs.size(), 0.0f);
    for (int n = 0; n < springs.size(); ++n) {
        ++per_voxel[springs.a[n]];
        ++per_voxel[springs.b[n]];
    }
    // The scatter's plan: each touched voxel's increments, in spring order.
    springs.touched.clear();
    springs.incidence_begin.assign(1, 0);
    std::vector<int> first(d.voxels, 0);  // a voxel's first entry in incidence
    for (int v = 0; v < d.voxels; ++v) {
        if (per_voxel[v] == 0) continue;
        first[v] = springs.incidence_begin.back();
        springs.touched.push_back(v);
        springs.incidence_begin.push_back(first[v] + per_voxel[v]);
    }
    springs.incidence.assign(springs.incidence_begin.back(), 0);
    std::vector<int> filled = first;
    for (int n = 0; n < springs.size(); ++n) {
        springs.incidence[filled[springs.a[n]]++] = n;
        springs.incidence[filled[springs.b[n]]++] = springs.size() + n;
    }
    for (int n = 0; n < springs.size(); ++n) {
        // Bond damping as the links' (2 zeta sqrt(m k) on the pair's reduced mass). All springs
        // see the same velocities (edge_pass), so the explicit damping is stable while each
        // voxel's sum over its springs' points of c dt / m_point stays below 1, m_point = m / 4
        // (a Gauss point's effective mass with the lever L / sqrt 2 and I = m L^2 / 6): capped
        // at half that. Stored over dt: the kernel damps the gap's change over a step.
        const int a = springs.a[n], b = springs.b[n];
        const double m = d.mass[a] * d.mass[b] / (d.mass[a] + d.mass[b]);
        const double k = std::max(springs.k_across[n], springs.k_along[n]);
        const double cap =
            0.5 * std::min(d.mass[a] / per_voxel[a], d.mass[b] / per_voxel[b]) / (8.0 * dt);
        const double c = std::min(2.0 * d.spec.damping.bond_ratio * std::sqrt(m * k), cap);
        springs.damping[n] = static_cast<float>(c / dt);
        springs.turn_a[n] = static_cast<float>(d.dt_inv_inertia[a]);
        springs.turn_b[n] = static_cast<float>(d.dt_inv_inertia[b]);
    }
}

namespace {

struct Vecf {
    float x, y, z;
};
BHM_ENGINE_INLINE Vecf operator+(Vecf a, Vecf b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
BHM_ENGINE_INLINE Vecf operator-(Vecf a, Vecf b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
BHM_ENGINE_INLINE Vecf operator*(float s, Vecf a) {
    return {s * a.x, s * a.y, s * a.z};
}
BHM_ENGINE_INLINE float dot(Vecf a, Vecf b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
BHM_ENGINE_INLINE Vecf cross(Vecf a, Vecf b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// v turned by the unit quaternion (w, u): v + 2 w (u x v) + 2 u x (u x v).
BHM_ENGINE_INLINE Vecf rotate(float w, Vecf u, Vecf v) {
    const Vecf t = 2.0f * cross(u, v);
    return v + w * t + cross(u, t);
}

// v into slot n of three component arrays.
BHM_ENGINE_INLINE void store(float* x, float* y, float* z, int n, Vecf v) {
    x[n] = v.x;
    y[n] = v.y;
    z[n] = v.z;
}

// What the kernel reads and writes, as plain pointers (restrict: the outputs alias no input).
struct EdgeKernel {
    const std::int32_t* __restrict a;
    const std::int32_t* __restrict b;
    const float* __restrict half[3];
    const float* __restrict edge[3];
    const float* __restrict k_across;
    const float* __restrict k_along;
    const float* __restrict damping;
    const float* __restrict act_sin_a;
    const float* __restrict act_cos_a;
    const float* __restrict act_sin_b;
    const float* __restrict act_cos_b;
    const double* __restrict pos[3];
    float* __restrict last_gap[6];  // G0 and G1 of the step before (x, y, z each), updated
    const float* __restrict quat[4];
    const float* __restrict turn_a;  // dt / I of a and b
    const float* __restrict turn_b;
    float* __restrict out[12];  // force and spin increment of a, then b; x, y, z each
    float gauss, sin_t, cos_t;
    int count;
};

// The loads of every spring from the voxels' poses, per spring; the scatter comes after. Float
// like the link kernel, and vectorised like it (gathers of the two voxels' poses; the quaternions
// are the voxel pass's float copies); the centres' difference is taken in double first, so the
// gap loses nothing to the body's distance from its origin. The two Gauss points p = -1, +1 sit
// at h + p g from each centre, so the gap is G0 + p G1, its change over the step C0 + p C1, the
// force F0 + p F1, and the sums over the two points close in form: force 2 F0 on
// a; moments 2 ((h_a + G0 / 2) x F0 + (g_a + G1 / 2) x F1) on a and -2 ((h_b - G0 / 2) x F0 +
// (g_b - G1 / 2) x F1) on b (each point's force pair acts at the gap's midpoint, so the moments
// balance for any direction of the force).
BHM_ENGINE_KERNEL void edge_loads(const EdgeKernel& k) {
    // Every pointer in a local of its own: GCC vectorises no load through an array of pointers.
    const std::int32_t* __restrict ia = k.a;
    const std::int32_t* __restrict ib = k.b;
    const float* __restrict half0 = k.half[0], * __restrict half1 = k.half[1], * __restrict half2 = k.half[2];
    const float* __restrict edge0 = k.edge[0], * __restrict edge1 = k.edge[1], * __restrict edge2 = k.edge[2];
    const float* __restrict k_across = k.k_across, * __restrict k_along = k.k_along, * __restrict damping = k.damping;
    const float* __restrict sin_a = k.act_sin_a, * __restrict cos_a = k.act_cos_a, * __restrict sin_b = k.act_sin_b, * __restrict cos_b = k.act_cos_b;
    const double* __restrict p0 = k.pos[0], * __restrict p1 = k.pos[1], * __restrict p2 = k.pos[2];
    float* __restrict l0 = k.last_gap[0], * __restrict l1 = k.last_gap[1], * __restrict l2 = k.last_gap[2], * __restrict l3 = k.last_gap[3], * __restrict l4 = k.last_gap[4], * __restrict l5 = k.last_gap[5];
    const float* __restrict qw = k.quat[0], * __restrict qx = k.quat[1], * __restrict qy = k.quat[2], * __restrict qz = k.quat[3];
    float* __restrict fa0 = k.out[0], * __restrict fa1 = k.out[1], * __restrict fa2 = k.out[2];
    float* __restrict dwa0 = k.out[3], * __restrict dwa1 = k.out[4], * __restrict dwa2 = k.out[5];
    float* __restrict fb0 = k.out[6], * __restrict fb1 = k.out[7], * __restrict fb2 = k.out[8];
    float* __restrict dwb0 = k.out[9], * __restrict dwb1 = k.out[10], * __restrict dwb2 = k.out[11];
    const float* __restrict turn_a = k.turn_a, * __restrict turn_b = k.turn_b;
    const float gauss = k.gauss, sin_t = k.sin_t, cos_t = k.cos_t;
    const int count = k.count;
    // GCC honours restrict on parameters only; the outputs alias no input (edge_pass).
#pragma GCC ivdep
    for (int n = 0; n < count; ++n) {
        const int a = ia[n], b = ib[n];
        const float scale_a = 1.0f + sin_a[n] * sin_t + cos_a[n] * cos_t;
        const float scale_b = 1.0f + sin_b[n] * sin_t + cos_b[n] * cos_t;
        const Vecf qa{qx[a], qy[a], qz[a]};
        const Vecf qb{qx[b], qy[b], qz[b]};
        const float wa = qw[a], wb = qw[b];
        const Vecf half{half0[n], half1[n], half2[n]};
        const Vecf edge{edge0[n], edge1[n], edge2[n]};
        const Vecf h_a = scale_a * rotate(wa, qa, half);
        const Vecf h_b = -scale_b * rotate(wb, qb, half);
        const Vecf t = rotate(wa, qa, edge);  // the edge's direction (a's)
        const Vecf g_a = (scale_a * gauss) * t;
        const Vecf g_b = (scale_b * gauss) * rotate(wb, qb, edge);
        const Vecf centres{static_cast<float>(p0[b] - p0[a]), static_cast<float>(p1[b] - p1[a]),
                           static_cast<float>(p2[b] - p2[a])};
        const Vecf gap0 = centres + (h_b - h_a);
        const Vecf gap1 = g_b - g_a;
        // Damping on the gap's change over the last step, as the links' (link_pass.cpp): with
        // symplectic Euler positions it is the current velocities' rate, and it leaves out the
        // actuated size's own change, which is not an elastic rate.
        const Vecf change0{gap0.x - l0[n], gap0.y - l1[n], gap0.z - l2[n]};
        const Vecf change1{gap1.x - l3[n], gap1.y - l4[n], gap1.z - l5[n]};
        l0[n] = gap0.x;
        l1[n] = gap0.y;
        l2[n] = gap0.z;
        l3[n] = gap1.x;
        l4[n] = gap1.y;
        l5[n] = gap1.z;
        // Across the edge k_across, along it k_along.
        const float kx = k_across[n], dk = k_along[n] - k_across[n], c = damping[n];
        const Vecf f0 = kx * gap0 + (dk * dot(gap0, t)) * t + c * change0;
        const Vecf f1 = kx * gap1 + (dk * dot(gap1, t)) * t + c * change1;
        const Vecf m_a = 2.0f * (cross(h_a + 0.5f * gap0, f0) + cross(g_a + 0.5f * gap1, f1));
        const Vecf m_b = -2.0f * (cross(h_b - 0.5f * gap0, f0) + cross(g_b - 0.5f * gap1, f1));
        // Forces (a gets 2 F0, b -2 F0: the voxel pass adds them to the links') and angular
        // impulses over the inertias.
        store(fa0, fa1, fa2, n, 2.0f * f0);
        store(dwa0, dwa1, dwa2, n, turn_a[n] * m_a);
        store(fb0, fb1, fb2, n, -2.0f * f0);
        store(dwb0, dwb1, dwb2, n, turn_b[n] * m_b);
    }
}

}  // namespace

void edge_pass(const Model::Data& d, VoxelState& s, EdgeScratch& scratch, double sin_t,
               double cos_t) {
    const Model::Data::EdgeSprings& e = d.edge_springs;
    EdgeKernel k{};
    k.a = e.a.data();
    k.b = e.b.data();
    for (int i = 0; i < 3; ++i) {
        k.half[i] = e.half[i].data();
        k.edge[i] = e.edge[i].data();
        k.pos[i] = s.pos[i].data();
        k.last_gap[i] = scratch.last_gap[i].data();
        k.last_gap[3 + i] = scratch.last_gap[3 + i].data();
        for (int end = 0; end < 2; ++end) {
            k.out[6 * end + i] = scratch.increment[i].data() + end * e.size();
            k.out[6 * end + 3 + i] = scratch.increment[3 + i].data() + end * e.size();
        }
    }
    for (int i = 0; i < 4; ++i)
        k.quat[i] = s.quat_f[i].data();
    k.k_across = e.k_across.data();
    k.k_along = e.k_along.data();
    k.damping = e.damping.data();
    k.act_sin_a = e.act_sin_a.data();
    k.act_cos_a = e.act_cos_a.data();
    k.act_sin_b = e.act_sin_b.data();
    k.act_cos_b = e.act_cos_b.data();
    k.turn_a = e.turn_a.data();
    k.turn_b = e.turn_b.data();
    k.gauss = e.gauss_m;
    k.sin_t = static_cast<float>(sin_t);
    k.cos_t = static_cast<float>(cos_t);
    k.count = e.size();
    edge_loads(k);
    // The scatter, per voxel: its springs' forces and spin increments summed (in spring order)
    // and applied once, so no store waits on the one before (adding each spring's increments to
    // its two voxels in turn chained a voxel's load-add-stores through its springs). The forces
    // go with the external force to the voxel pass, which adds them to the links' before its
    // static friction test; the spins turn the voxel now.
    const std::int32_t* __restrict touched = e.touched.data();
    const std::int32_t* __restrict begin = e.incidence_begin.data();
    const std::int32_t* __restrict incidence = e.incidence.data();
    const auto& inc = scratch.increment;
    const float *__restrict fx = inc[0].data(), *__restrict fy = inc[1].data(),
                *__restrict fz = inc[2].data();
    const float *__restrict dwx = inc[3].data(), *__restrict dwy = inc[4].data(),
                *__restrict dwz = inc[5].data();
    const auto& ext = s.ext_force;
    const double *__restrict ext_x = ext[0].data(), *__restrict ext_y = ext[1].data(),
                 *__restrict ext_z = ext[2].data();
    double *__restrict force_x = scratch.force[0].data(),
           *__restrict force_y = scratch.force[1].data(),
           *__restrict force_z = scratch.force[2].data();
    double *__restrict wx = s.omega[0].data(), *__restrict wy = s.omega[1].data(),
           *__restrict wz = s.omega[2].data();
    const int touched_count = static_cast<int>(e.touched.size());
    for (int t = 0; t < touched_count; ++t) {
        // In double: a sum in float let a free checkerboard's momentum drift by 1e-6 of its
        // scale (tests/engine/test_engine_edge_springs.cpp allows 1e-9).
        double sum[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        for (int entry = begin[t]; entry < begin[t + 1]; ++entry) {
            const int i = incidence[entry];
            sum[0] += fx[i];
            sum[1] += fy[i];
            sum[2] += fz[i];
            sum[3] += dwx[i];
            sum[4] += dwy[i];
            sum[5] += dwz[i];
        }
        const int v = touched[t];
        force_x[v] = ext_x[v] + sum[0];
        force_y[v] = ext_y[v] + sum[1];
        force_z[v] = ext_z[v] + sum[2];
        wx[v] += sum[3];
        wy[v] += sum[4];
        wz[v] += sum[5];
    }
}

}  // namespace bhm::engine
