#include "engine/internal/edge_springs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "engine/internal/moduli.hpp"

namespace bhm::engine {
namespace {

struct Vec {
    double x, y, z;
};
__attribute__((always_inline)) inline Vec operator+(Vec a, Vec b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
__attribute__((always_inline)) inline Vec operator-(Vec a, Vec b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
__attribute__((always_inline)) inline Vec operator*(double s, Vec a) {
    return {s * a.x, s * a.y, s * a.z};
}
__attribute__((always_inline)) inline double dot(Vec a, Vec b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
__attribute__((always_inline)) inline Vec cross(Vec a, Vec b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// v turned by the unit quaternion (w, x, y, z): v + 2 w (u x v) + 2 u x (u x v).
__attribute__((always_inline)) inline Vec rotate(double w, Vec u, Vec v) {
    const Vec t = 2.0 * cross(u, v);
    return v + w * t + cross(u, t);
}

}  // namespace

void build_edge_springs(Model::Data& d, double& max_omega2) {
    const BodySpec& spec = d.spec;
    const double L = spec.voxel_size_m;
    Model::Data::EdgeSprings& springs = d.edge_springs;
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
                        springs.half[k].push_back(k == i ? 0.5 * L : k == j ? 0.5 * s * L : 0.0);
                        springs.gauss[k].push_back(k == edge_axis ? L / (2.0 * std::sqrt(3.0))
                                                                  : 0.0);
                        springs.edge[k].push_back(k == edge_axis ? 1.0 : 0.0);
                    }
                    const double k_across = per_point / (1.0 - nu * nu);
                    const double k_along = per_point / (1.0 + nu);  // 2 G / E
                    springs.k_across.push_back(k_across);
                    springs.k_along.push_back(k_along);
                    springs.damping.push_back(0.0);
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
    for (int n = 0; n < springs.size(); ++n) {
        ++per_voxel[springs.a[n]];
        ++per_voxel[springs.b[n]];
    }
    for (int n = 0; n < springs.size(); ++n) {
        // Bond damping as the links' (2 zeta sqrt(m k) on the pair's reduced mass). All springs
        // see the same velocities (edge_pass), so the explicit damping is stable while each
        // voxel's sum over its springs' points of c dt / m_point stays below 1, m_point = m / 4
        // (a Gauss point's effective mass with the lever L / sqrt 2 and I = m L^2 / 6): capped
        // at half that.
        const int a = springs.a[n], b = springs.b[n];
        const double m = d.mass[a] * d.mass[b] / (d.mass[a] + d.mass[b]);
        const double k = std::max(springs.k_across[n], springs.k_along[n]);
        const double cap =
            0.5 * std::min(d.mass[a] / per_voxel[a], d.mass[b] / per_voxel[b]) / (8.0 * dt);
        springs.damping[n] = std::min(2.0 * d.spec.damping.bond_ratio * std::sqrt(m * k), cap);
    }
}

namespace {

// The loads of every spring from the voxels' poses, per spring (the scatter comes after; scalar:
// GCC 12 does not vectorise the gathers, docs/physics.md has the cost). The two Gauss points p =
// -1, +1 sit at h + p g from each centre, so the gap and its rate are G0 + p G1 and V0 + p V1, the
// force F0 + p F1, and the sums over the two points close in form: force 2 F0 on a; moments 2 ((h_a
// + G0 / 2) x F0 + (g_a + G1 / 2) x F1) on a and -2 ((h_b - G0 / 2) x F0 + (g_b - G1 / 2) x F1) on
// b (each point's force pair acts at the gap's midpoint, so the moments balance for any direction
// of the force).
void edge_loads(const Model::Data& d, const VoxelState& s, EdgeScratch& out, double sin_t,
                double cos_t) {
    const Model::Data::EdgeSprings& e = d.edge_springs;
    auto quat = [&](int v) { return Vec{s.quat[1][v], s.quat[2][v], s.quat[3][v]}; };
    auto pos = [&](int v) { return Vec{s.pos[0][v], s.pos[1][v], s.pos[2][v]}; };
    auto vel = [&](int v) { return Vec{s.vel[0][v], s.vel[1][v], s.vel[2][v]}; };
    auto spin = [&](int v) { return Vec{s.omega[0][v], s.omega[1][v], s.omega[2][v]}; };
    for (int n = 0; n < e.size(); ++n) {
        const int a = e.a[n], b = e.b[n];
        const double scale_a = 1.0 + d.act_sin[a] * sin_t + d.act_cos[a] * cos_t;
        const double scale_b = 1.0 + d.act_sin[b] * sin_t + d.act_cos[b] * cos_t;
        const Vec half{e.half[0][n], e.half[1][n], e.half[2][n]};
        const Vec gauss{e.gauss[0][n], e.gauss[1][n], e.gauss[2][n]};
        const Vec h_a = scale_a * rotate(s.quat[0][a], quat(a), half);
        const Vec h_b = -scale_b * rotate(s.quat[0][b], quat(b), half);
        const Vec g_a = scale_a * rotate(s.quat[0][a], quat(a), gauss);
        const Vec g_b = scale_b * rotate(s.quat[0][b], quat(b), gauss);
        const Vec t = rotate(s.quat[0][a], quat(a), Vec{e.edge[0][n], e.edge[1][n], e.edge[2][n]});
        const Vec gap0 = (pos(b) + h_b) - (pos(a) + h_a);
        const Vec gap1 = g_b - g_a;
        const Vec rate0 = (vel(b) + cross(spin(b), h_b)) - (vel(a) + cross(spin(a), h_a));
        const Vec rate1 = cross(spin(b), g_b) - cross(spin(a), g_a);
        // Across the edge k_across, along it k_along.
        const double k = e.k_across[n], dk = e.k_along[n] - e.k_across[n], c = e.damping[n];
        const Vec f0 = k * gap0 + (dk * dot(gap0, t)) * t + c * rate0;
        const Vec f1 = k * gap1 + (dk * dot(gap1, t)) * t + c * rate1;
        const Vec m_a = 2.0 * (cross(h_a + 0.5 * gap0, f0) + cross(g_a + 0.5 * gap1, f1));
        const Vec m_b = -2.0 * (cross(h_b - 0.5 * gap0, f0) + cross(g_b - 0.5 * gap1, f1));
        const Vec loads[3] = {2.0 * f0, m_a, m_b};
        std::array<std::vector<double>, 3>* targets[3] = {&out.force, &out.moment_a, &out.moment_b};
        for (int l = 0; l < 3; ++l) {
            (*targets[l])[0][n] = loads[l].x;
            (*targets[l])[1][n] = loads[l].y;
            (*targets[l])[2][n] = loads[l].z;
        }
    }
}

}  // namespace

void edge_pass(const Model::Data& d, VoxelState& s, EdgeScratch& scratch, double sin_t,
               double cos_t) {
    edge_loads(d, s, scratch, sin_t, cos_t);
    // The scatter, in spring order (a voxel is in several springs).
    const Model::Data::EdgeSprings& e = d.edge_springs;
    for (int n = 0; n < e.size(); ++n) {
        const int a = e.a[n], b = e.b[n];
        for (int i = 0; i < 3; ++i) {
            s.vel[i][a] += d.dt_inv_mass[a] * scratch.force[i][n];
            s.vel[i][b] -= d.dt_inv_mass[b] * scratch.force[i][n];
            s.omega[i][a] += d.dt_inv_inertia[a] * scratch.moment_a[i][n];
            s.omega[i][b] += d.dt_inv_inertia[b] * scratch.moment_b[i][n];
        }
    }
}

}  // namespace bhm::engine
