// The voxel pass: gather link forces, add gravity, floor and friction, integrate.
//
// Floor (z = 0): penalty contact on the voxel's bottom (centre z - half its current size), with
// stiffness E L (the axial stiffness of a link) and collision damping 2 zeta_c sqrt(m k) on the
// normal velocity; the normal force never pulls. Coulomb friction at the voxel centre: a voxel
// held by static friction stays put tangentially while |F_t| <= mu_s N; otherwise kinetic friction
// mu_k N opposes the tangential velocity, and a voxel whose tangential speed it would reverse
// stops and becomes held. Global damping (toward rest) is applied implicitly, so any ratio is
// stable.
#include "engine/internal/voxel_pass.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

#include "engine/internal/kernel_dispatch.hpp"

namespace bhm::engine {
namespace {

// Raw views of every array the pass touches, taken once per pass.
struct Arrays {
    const double *movable, *mass, *dt_inv_mass, *dt_inv_inertia, *linear_keep, *angular_keep[3],
        *floor_k, *floor_c, *mu_static, *mu_dynamic, *act_sin, *act_cos, *wall_stiffness;
    double *pos[3], *quat[4], *vel[3], *omega[3], *stuck;
    double *vel_star[3], *omega_star[3], *vel_delta[3], *omega_delta[3];
    float* quat_f[4];
    const double* ext[3];
    const float *force[3][3], *moment_neg[3][3], *moment_pos[3][3];  // [link axis][component]
    const int *minus_y, *minus_z;  // slot of the link whose + end is the voxel (x: voxel - 1)
    double dt, voxel_size;
};

Arrays arrays_of(const Model::Data& d, VoxelState& s, const std::array<LinkScratch, 3>& links) {
    Arrays a{};
    a.movable = d.movable.data();
    a.mass = d.mass.data();
    a.dt_inv_mass = d.dt_inv_mass.data();
    a.dt_inv_inertia = d.dt_inv_inertia.data();
    a.linear_keep = d.linear_keep.data();
    for (int i = 0; i < 3; ++i)
        a.angular_keep[i] = d.angular_keep[i].data();
    a.floor_k = d.floor_k.data();
    a.wall_stiffness = d.wall_stiffness.data();
    a.floor_c = d.floor_c.data();
    a.mu_static = d.mu_static.data();
    a.mu_dynamic = d.mu_dynamic.data();
    a.act_sin = d.act_sin.data();
    a.act_cos = d.act_cos.data();
    for (int i = 0; i < 3; ++i) {
        a.vel_star[i] = s.vel_star[i].data();
        a.omega_star[i] = s.omega_star[i].data();
        a.vel_delta[i] = s.vel_delta[i].data();
        a.omega_delta[i] = s.omega_delta[i].data();
        a.pos[i] = s.pos[i].data();
        a.vel[i] = s.vel[i].data();
        a.omega[i] = s.omega[i].data();
        a.ext[i] = s.ext_force[i].data();
        for (int k = 0; k < 3; ++k) {
            a.force[i][k] = links[i].force[k];
            a.moment_neg[i][k] = links[i].moment_neg[k];
            a.moment_pos[i][k] = links[i].moment_pos[k];
        }
    }
    for (int i = 0; i < 4; ++i) {
        a.quat[i] = s.quat[i].data();
        a.quat_f[i] = s.quat_f[i].data();
    }
    a.stuck = s.stuck.data();
    a.minus_y = d.minus[1].data();
    a.minus_z = d.minus[2].data();
    a.dt = d.dt_s;
    a.voxel_size = d.voxel_size_m;
    return a;
}

// max(x, 0), exactly, as arithmetic.
__attribute__((always_inline)) inline double positive_part(double x) {
    return 0.5 * (x + std::fabs(x));
}

// The loads of voxel slot c's links, gathered onto f0 (the external force, or none) in a fixed
// order: per axis, the link from the - neighbour, then the link to the +.
__attribute__((always_inline)) inline void gather(const Arrays& a, int c, int below_y, int below_z,
                                                  const double* const* f0, double f[3],
                                                  double m[3]) {
    const int below_of[3] = {c - 1, below_y, below_z};
    for (int i = 0; i < 3; ++i) {
        double fi = f0 ? f0[i][c] : 0.0, mi = 0.0;
        for (int ax = 0; ax < 3; ++ax) {
            const int below = below_of[ax];
            fi += static_cast<double>(a.force[ax][i][below]) - a.force[ax][i][c];
            mi += static_cast<double>(a.moment_pos[ax][i][below]) + a.moment_neg[ax][i][c];
        }
        f[i] = fi;
        m[i] = mi;
    }
}

struct Update {
    double p[3], q[4], v[3], w[3], stuck;
    bool ok;
};

// The pose of voxel slot c after the step, from its new velocities u.v and u.w, and the sanity
// verdict.
__attribute__((always_inline)) inline void advance_pose(const Arrays& a, int c, Update& u) {
    const double dt = a.dt;
    for (int i = 0; i < 3; ++i)
        u.p[i] = a.pos[i][c] + dt * u.v[i];
    // q' = normalise(q + dt/2 (0, w) q)
    const double qw = a.quat[0][c], qx = a.quat[1][c], qy = a.quat[2][c], qz = a.quat[3][c];
    const double h = 0.5 * dt;
    const double wx = u.w[0], wy = u.w[1], wz = u.w[2];
    const double nw = qw - h * (wx * qx + wy * qy + wz * qz);
    const double nx = qx + h * (qw * wx + wy * qz - wz * qy);
    const double ny = qy + h * (qw * wy + wz * qx - wx * qz);
    const double nz = qz + h * (qw * wz + wx * qy - wy * qx);
    const double inv = 1.0 / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
    u.q[0] = nw * inv;
    u.q[1] = nx * inv;
    u.q[2] = ny * inv;
    u.q[3] = nz * inv;

    // Sanity: finite, under one voxel and one radian per step (NaN fails every comparison).
    const double step2 = dt * dt * (u.v[0] * u.v[0] + u.v[1] * u.v[1] + u.v[2] * u.v[2]);
    const double turn2 = dt * dt * (wx * wx + wy * wy + wz * wz);
    u.ok = (step2 < a.voxel_size * a.voxel_size) & (turn2 < 1.0) & (inv > 0.5) & (inv < 2.0);
}

// The new state of voxel slot c: a pure function of the old state and the link scratch.
// below_y, below_z: the slots of the y and z links whose + end is c (x in lattice order is the
// slot before, zero when that slot's link goes elsewhere or is absent).
__attribute__((always_inline)) inline Update integrate(const Arrays& a, const VoxelPassInput& in,
                                                       int c, int below_y, int below_z) {
    double f[3], m[3];
    gather(a, c, below_y, below_z, a.ext, f, m);
    f[2] += in.gravity_m_s2 * a.mass[c];

    const double vx = a.vel[0][c], vy = a.vel[1][c], vz = a.vel[2][c];
    const double dt_inv_m = a.dt_inv_mass[c];

    // Floor contact.
    const double scale = 1.0 + a.act_sin[c] * in.sin_t + a.act_cos[c] * in.cos_t;
    const double penetration = 0.5 * a.voxel_size * scale - (a.pos[2][c] - in.floor_z);
    const double depth = positive_part(penetration);
    const bool contact = depth > 0.0;
    const double collision_damping = a.floor_c[c] * vz;
    const double normal = positive_part(a.floor_k[c] * depth - (contact ? collision_damping : 0.0));
    f[2] += normal;

    Update u;
    u.v[0] = vx + dt_inv_m * f[0];
    u.v[1] = vy + dt_inv_m * f[1];
    u.v[2] = vz + dt_inv_m * f[2];

    // Coulomb friction on the tangential (x, y) motion.
    const double limit = a.mu_static[c] * normal;
    const bool held = contact & (a.stuck[c] != 0.0) & (f[0] * f[0] + f[1] * f[1] <= limit * limit);
    const double speed = std::sqrt(u.v[0] * u.v[0] + u.v[1] * u.v[1]);
    const double kinetic_dv = a.mu_dynamic[c] * normal * dt_inv_m;
    const bool stops = contact & (speed <= kinetic_dv);
    // (kinetic_dv is 0 off the floor; at speed 0 a positive kinetic_dv means `stops`.)
    const double kinetic_keep = 1.0 - kinetic_dv / (speed + 1e-300);
    const bool grip = held | stops;
    const double keep_t = grip ? 0.0 : kinetic_keep;
    u.stuck = grip ? 1.0 : 0.0;

    const double lin = a.linear_keep[c] * a.movable[c];
    u.v[0] *= keep_t * lin;
    u.v[1] *= keep_t * lin;
    u.v[2] *= lin;

    // Rotation: isotropic inertia (cube), so no gyroscopic term.
    // (A held voxel's locked axes keep 0: model.cpp, "Held voxels' rotation".)
    const double dt_inv_i = a.dt_inv_inertia[c];
    // A turning held voxel's spring to the clamp (model.cpp): the moment -2 k q_vec of the energy
    // 4 k (1 - |w|), k theta^2 / 2 for small turns; 0 for every other voxel.
    const double wall = a.wall_stiffness[c] * (a.quat[0][c] < 0.0 ? -2.0 : 2.0);
    for (int i = 0; i < 3; ++i)
        m[i] -= wall * a.quat[1 + i][c];
    for (int i = 0; i < 3; ++i)
        u.w[i] = (a.omega[i][c] + dt_inv_i * m[i]) * a.angular_keep[i][c];
    advance_pose(a, c, u);
    return u;
}

// The voxels of one run. kGather: the y and z links of which voxel c is the + end come from the
// model's minus tables; otherwise from slots c - below_y and c - below_z. kVelocityOnly: the
// implicit bond damping follows (damping_pass.hpp): only the velocities are written, kept as v*,
// and the pose moves after the last sweep.
template <bool kGather, bool kVelocityOnly>
__attribute__((always_inline)) inline int voxel_loop(const Arrays& a, double* __restrict refused,
                                                     const VoxelPassInput& in,
                                                     const VoxelRun& run) {
    const int below_y = run.below_y, below_z = run.below_z;
    // Each iteration reads and writes its own voxel slot only (link scratch is read-only here).
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        const Update u = kGather ? integrate(a, in, c, a.minus_y[c], a.minus_z[c])
                                 : integrate(a, in, c, c - below_y, c - below_z);
        a.stuck[c] = u.stuck;
        if constexpr (kVelocityOnly) {
            // The sweeps start from v* plus the last step's damping change (none along the floor
            // for a voxel that static friction holds).
            const double free_t = 1.0 - u.stuck;
            for (int i = 0; i < 3; ++i) {
                a.vel_star[i][c] = u.v[i];
                a.omega_star[i][c] = u.w[i];
                a.vel[i][c] = u.v[i] + (i < 2 ? free_t : 1.0) * a.vel_delta[i][c];
                a.omega[i][c] = u.w[i] + a.omega_delta[i][c];
            }
        } else {
            // Written unconditionally (a conditional store would stop the vectorisation). A
            // refused step is still finite: it starts from a checked state and parameters are
            // bounded.
            for (int i = 0; i < 3; ++i) {
                a.pos[i][c] = u.p[i];
                a.vel[i][c] = u.v[i];
                a.omega[i][c] = u.w[i];
            }
            for (int i = 0; i < 4; ++i) {
                a.quat[i][c] = u.q[i];
                a.quat_f[i][c] = static_cast<float>(u.q[i]);
            }
            refused[c] = u.ok ? 0.0 : 1.0;
        }
    }
    if constexpr (kVelocityOnly) return 0;
    int count = 0;
    for (int c = run.begin; c < run.end; ++c)
        count += refused[c] != 0.0;
    return count;
}

// The voxel half of one sweep of (M + dt C) v = M v* on the voxels of one run (damping_pass.hpp),
// the link scratch holding the loads of the links' relaxed damping rates. kLast: the pose then
// moves with the new velocities, and the change v - v* is kept for the next step's start.
template <bool kGather, bool kLast>
__attribute__((always_inline)) inline int damping_loop(const Arrays& a, double* __restrict refused,
                                                       const VoxelRun& run) {
    const int below_y = run.below_y, below_z = run.below_z;
#pragma GCC ivdep
    for (int c = run.begin; c < run.end; ++c) {
        double f[3], m[3];
        if (kGather)
            gather(a, c, a.minus_y[c], a.minus_z[c], nullptr, f, m);
        else
            gather(a, c, c - below_y, c - below_z, nullptr, f, m);
        Update u;
        // v = v* - dt M^-1 C v, the links' loads from their relaxed rates (damping_pass.hpp). A
        // voxel held by static friction stays held: no change along the floor.
        const double free_t = 1.0 - a.stuck[c];
        const double dt_inv_m = a.dt_inv_mass[c], dt_inv_i = a.dt_inv_inertia[c];
        for (int i = 0; i < 3; ++i) {
            const double dv = dt_inv_m * f[i];
            u.v[i] = a.vel_star[i][c] + (i < 2 ? free_t * dv : dv);
            u.w[i] = a.omega_star[i][c] + (a.angular_keep[i][c] != 0.0 ? dt_inv_i * m[i] : 0.0);
        }
        for (int i = 0; i < 3; ++i) {
            a.vel[i][c] = u.v[i];
            a.omega[i][c] = u.w[i];
        }
        if constexpr (kLast) {
            for (int i = 0; i < 3; ++i) {
                a.vel_delta[i][c] = u.v[i] - a.vel_star[i][c];
                a.omega_delta[i][c] = u.w[i] - a.omega_star[i][c];
            }
            advance_pose(a, c, u);
            for (int i = 0; i < 3; ++i)
                a.pos[i][c] = u.p[i];
            for (int i = 0; i < 4; ++i) {
                a.quat[i][c] = u.q[i];
                a.quat_f[i][c] = static_cast<float>(u.q[i]);
            }
            refused[c] = u.ok ? 0.0 : 1.0;
        }
    }
    if constexpr (!kLast) return 0;
    int count = 0;
    for (int c = run.begin; c < run.end; ++c)
        count += refused[c] != 0.0;
    return count;
}

}  // namespace

BHM_ENGINE_KERNEL int voxel_pass(const Model::Data& d, VoxelState& s,
                                 const std::array<LinkScratch, 3>& links,
                                 const VoxelPassInput& in) {
    Arrays a = arrays_of(d, s, links);
    if (in.applied_force)
        for (int i = 0; i < 3; ++i)
            a.ext[i] = (*in.applied_force)[i].data();
    int count = 0;
    for (const VoxelRun& run : d.voxel_runs) {
        if (in.velocity_only)
            count += run.below_y == 0 ? voxel_loop<true, true>(a, s.refused.data(), in, run)
                                      : voxel_loop<false, true>(a, s.refused.data(), in, run);
        else
            count += run.below_y == 0 ? voxel_loop<true, false>(a, s.refused.data(), in, run)
                                      : voxel_loop<false, false>(a, s.refused.data(), in, run);
    }
    return count;
}

BHM_ENGINE_KERNEL int damping_voxel_pass(const Model::Data& d, VoxelState& s,
                                         const std::array<LinkScratch, 3>& links, bool last) {
    const Arrays a = arrays_of(d, s, links);
    int count = 0;
    for (const VoxelRun& run : d.voxel_runs) {
        if (last)
            count += run.below_y == 0 ? damping_loop<true, true>(a, s.refused.data(), run)
                                      : damping_loop<false, true>(a, s.refused.data(), run);
        else
            count += run.below_y == 0 ? damping_loop<true, false>(a, s.refused.data(), run)
                                      : damping_loop<false, false>(a, s.refused.data(), run);
    }
    return count;
}

int first_refused_voxel(const Model::Data& d, const VoxelState& s) {
    for (int c = 0; c < d.voxels; ++c)
        if (s.refused[c] != 0.0) return c;
    return -1;
}

}  // namespace bhm::engine
