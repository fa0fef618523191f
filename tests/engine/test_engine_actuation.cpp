// Thermal actuation: active voxels change size by cte * dT; passive ones never do.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "engine/poses.hpp"
#include "engine_test_bodies.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

BodySpec active_box(int nx, int ny, int nz) {
    Material active;
    active.cte_per_c = 0.01;  // paper Table 1
    BodySpec s = solid_box(nx, ny, nz, active);
    s.actuation.start_s = 0.0;
    s.actuation.frequency_hz = 2.0;
    s.actuation.temperature_amplitude_c = 14.47;
    return s;
}

}  // namespace

TEST_CASE("an unconstrained active voxel grows by cte * dT in each dimension") {
    const BodySpec s = active_box(1, 1, 1);
    World w(Model::build(s));
    // dT peaks at a quarter period: t = 1 / (4 f).
    REQUIRE(w.advance_to(0.125));
    VoxelPoses poses;
    w.read_poses(poses);
    const double dT = 14.47 * std::sin(2.0 * std::numbers::pi * 2.0 * poses.time_s);
    const double expected = s.voxel_size_m * (1.0 + 0.01 * dT);
    for (int i = 0; i < 3; ++i)
        CHECK(poses.size_m[i] == bhm::test::relative(expected, 1e-6));
}

TEST_CASE("a free active 2x2x2 block grows by cte * dT along every axis (within 1%)") {
    const BodySpec s = active_box(2, 2, 2);
    auto model = Model::build(s);
    World w(model);
    REQUIRE(w.advance_to(0.125));
    const double dT = 14.47 * std::sin(2.0 * std::numbers::pi * 2.0 * w.time_s());
    const double expected_growth = 0.01 * dT;  // ~14.5%
    const double L = s.voxel_size_m;
    const auto a = w.voxel_position_m(voxel_at(*model, 0, 0, 0));
    const auto b = w.voxel_position_m(voxel_at(*model, 1, 1, 1));
    for (int i = 0; i < 3; ++i) {
        const double growth = (b[i] - a[i]) / L - 1.0;
        CHECK(growth == bhm::test::relative(expected_growth, 0.01));
    }
}

TEST_CASE("actuation is off before start_s and passive voxels never change size") {
    BodySpec s = active_box(2, 1, 1);
    s.materials.push_back(Material{});  // passive
    s.material[1] = 2;
    s.actuation.start_s = 0.5;
    auto model = Model::build(s);
    World w(model);
    VoxelPoses poses;
    REQUIRE(w.advance_to(0.4));
    w.read_poses(poses);
    for (float size : poses.size_m)
        CHECK(size == bhm::test::relative(s.voxel_size_m, 1e-7));  // float32 sizes
    CHECK(w.voxel_position_m(1)[0] - w.voxel_position_m(0)[0] ==
          bhm::test::relative(s.voxel_size_m, 1e-6));
    REQUIRE(w.advance_to(0.5 + 0.125));
    w.read_poses(poses);
    CHECK(poses.size_m[0] > 1.1 * s.voxel_size_m);                            // active grew
    CHECK(poses.size_m[3] == bhm::test::relative(s.voxel_size_m, 1e-7));  // passive did not
    // The link rests at the mean of the two sizes: centres 1 + cte dT / 2 apart.
    const double dT = 14.47 * std::sin(2.0 * std::numbers::pi * 2.0 * (w.time_s() - 0.5));
    CHECK((w.voxel_position_m(1)[0] - w.voxel_position_m(0)[0]) / s.voxel_size_m ==
          bhm::test::relative(1.0 + 0.5 * 0.01 * dT, 0.002));
}
