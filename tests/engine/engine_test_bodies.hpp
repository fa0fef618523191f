#pragma once
// Bodies and measurements shared by the engine tests.
#include <array>
#include <cmath>
#include <memory>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"

namespace bhm::engine::test {

//! A solid nx x ny x nz box of material 1 (paper Table 1 passive by default), no floor, no gravity.
inline BodySpec solid_box(int nx, int ny, int nz, Material material = {}) {
    BodySpec s;
    s.nx = nx;
    s.ny = ny;
    s.nz = nz;
    s.material.assign(static_cast<std::size_t>(nx) * ny * nz, 1);
    s.materials = {material};
    s.environment.floor = false;
    s.environment.gravity_m_s2 = 0.0;
    return s;
}

// A free 4x3x2 body, half active with scattered phases, actuated from t = 0 (no gravity, no floor,
// no global damping: nothing external acts on it, so its momenta are conserved).
inline BodySpec free_actuated_body() {
    BodySpec s = solid_box(4, 3, 2);
    Material active = s.materials[0];
    active.cte_per_c = 0.01;
    s.materials.push_back(active);
    s.phase_rad.assign(s.material.size(), 0.0f);
    for (int c = 0; c < s.cell_count(); ++c) {
        if (c % 2 == 0) s.material[c] = 2;
        s.phase_rad[c] = static_cast<float>(0.7 * c);
    }
    s.actuation.start_s = 0.0;
    s.actuation.frequency_hz = 5.0;
    s.damping.global_ratio = 0.0;
    return s;
}

//! Holds every voxel of the x = 0 layer.
inline void fix_x_min_layer(BodySpec& s) {
    s.fixed.assign(s.material.size(), 0);
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            s.fixed[s.cell_index(0, y, z)] = 1;
}

//! The paper's actuation scenes (docs/physics.md, "Actuation"): the all-active 8x8x7 block,
//! 4-voxel active/passive bands on 20x8x7 and the framed paper-exp3 body (a passive 1-voxel frame
//! around active voxels), held at x-, on the floor under gravity, 2 Hz from t = 0.05 s.
enum class Scene { AllActive, Banded, Framed };

inline BodySpec paper_scene(Scene scene, double amplitude_c) {
    Material passive;  // paper Table 1
    Material active = passive;
    active.cte_per_c = 0.01;
    const int nx = scene == Scene::AllActive ? 8 : 20;
    BodySpec s = solid_box(nx, 8, 7, passive);
    s.materials.push_back(active);
    for (int z = 0; z < 7; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < nx; ++x) {
                const bool frame = x == 0 || x == nx - 1 || y == 0 || y == 7 || z == 0 || z == 6;
                const bool is_active = scene == Scene::AllActive ? true
                                       : scene == Scene::Banded  ? (x / 4) % 2 == 0
                                                                 : !frame;
                s.material[s.cell_index(x, y, z)] = is_active ? 2 : 1;
            }
    fix_x_min_layer(s);
    s.environment.floor = true;
    s.environment.gravity_m_s2 = -9.81;
    s.actuation.frequency_hz = 2.0;
    s.actuation.temperature_amplitude_c = amplitude_c;
    s.actuation.start_s = 0.05;
    return s;  // default damping (1.0 / 0.01 / 0.8) and dt_fraction
}

//! Mean displacement (m) along `axis` of the voxels of the layer x = layer, from the lattice.
inline double layer_displacement(const World& w, int layer, int axis) {
    const Model& m = w.model();
    const double L = m.voxel_size_m();
    double sum = 0.0;
    int count = 0;
    for (int v = 0; v < m.voxel_count(); ++v) {
        const auto c = m.voxel_coords(v);
        if (c[0] != layer) continue;
        sum += w.voxel_position_m(v)[axis] - (c[axis] + 0.5) * L;
        ++count;
    }
    return sum / count;
}

//! Index of the voxel at lattice coordinates (x, y, z); -1 if none.
inline int voxel_at(const Model& m, int x, int y, int z) {
    for (int v = 0; v < m.voxel_count(); ++v)
        if (m.voxel_coords(v) == std::array<int, 3>{x, y, z}) return v;
    return -1;
}

}  // namespace bhm::engine::test
