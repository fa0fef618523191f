#pragma once
// Conservation checks shared by the engine tests: a free body (no gravity, floor, held voxel or
// global damping) keeps zero momentum, its centre of mass and zero spin however it moves inside.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/model.hpp"
#include "engine/world.hpp"

namespace bhm::engine::test {

//! Advances w (a free body at rest) through `slices` slices of `slice_s` seconds and checks after
//! each that its linear momentum, centre of mass and angular momentum stay put, relative to the
//! internal motion's own scale. Returns the largest rms speed reached.
inline double check_free_body_keeps_momenta(World& w, int slices, double slice_s) {
    const Model& model = w.model();
    auto norm = [](const std::array<double, 3>& a) {
        return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    };
    const auto com0 = w.centre_of_mass_m();
    double max_speed = 0.0, max_moment_arm = 0.0;
    for (int k = 1; k <= slices; ++k) {
        REQUIRE(w.advance_to(slice_s * k));
        // Scales for the tolerances: the internal motion is real (cm/s speeds).
        for (int v = 0; v < model.voxel_count(); ++v) {
            const auto p = w.voxel_position_m(v);
            max_moment_arm =
                std::max(max_moment_arm, norm({p[0] - com0[0], p[1] - com0[1], p[2] - com0[2]}));
        }
        max_speed =
            std::max(max_speed, std::sqrt(2.0 * w.kinetic_energy_j() / model.total_mass_kg()));
        const double momentum_scale = model.total_mass_kg() * max_speed;
        CHECK(norm(w.linear_momentum()) < 1e-9 * momentum_scale);
        const auto com = w.centre_of_mass_m();
        CHECK(norm({com[0] - com0[0], com[1] - com0[1], com[2] - com0[2]}) < 1e-9);
        // Angular momentum about the (fixed) centre of mass = about the origin, as P = 0. Float
        // rounding of the link moments leaves a random walk far below the internal motion's.
        CHECK(norm(w.angular_momentum()) < 1e-4 * momentum_scale * max_moment_arm);
    }
    return max_speed;
}

}  // namespace bhm::engine::test
