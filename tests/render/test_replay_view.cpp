// From a replay to poses at any time, the centre-of-mass trail and per-voxel scalars.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "render/replay_view.hpp"

using namespace bhm::render;
using bhm::engine::Replay;
using bhm::engine::VoxelPoses;
using bhm::engine::pose_at;
using bhm::engine::PoseSampling;

namespace {

VoxelPoses frame(double t, std::vector<float> x, float turn_rad = 0.0f) {
    VoxelPoses f;
    f.time_s = t;
    for (float xi : x) {
        f.position_m.insert(f.position_m.end(), {xi, 0.005f, 0.005f});
        f.orientation.insert(f.orientation.end(),
                             {std::cos(0.5f * turn_rad), 0.0f, 0.0f, std::sin(0.5f * turn_rad)});
        f.size_m.insert(f.size_m.end(), {0.01f, 0.01f, 0.01f});
    }
    return f;
}

Replay two_voxel_replay() {
    Replay r;
    r.nx = 2, r.ny = 1, r.nz = 1;
    r.voxel_cell = {0, 1};
    r.voxel_material = {1, 2};
    r.voxel_fixed = {1, 0};
    r.frames = {frame(0.0, {0.005f, 0.015f}), frame(0.1, {0.005f, 0.025f}, 0.4f),
                frame(0.2, {0.005f, 0.035f})};
    return r;
}

}  // namespace

TEST_CASE("the body view of a replay carries its lattice, materials, fixed flags and frame 0") {
    const Replay r = two_voxel_replay();
    const BodyView body = body_view_from_replay(r);
    CHECK(body.voxel_count() == 2);
    CHECK(body.voxel_fixed == std::vector<std::uint8_t>{1, 0});
    CHECK(body.poses.position_m == r.frames[0].position_m);
    Replay empty = r;
    empty.frames.clear();
    CHECK(body_view_from_replay(empty).poses.position_m[3] ==
          doctest::Approx(0.015f));  // rest pose
}

TEST_CASE("poses at a time: the frame at or before it, or a blend of the two around it") {
    const Replay r = two_voxel_replay();
    const VoxelPoses before = pose_at(r, 0.15, PoseSampling::NearestBefore);
    CHECK(before.time_s == doctest::Approx(0.1));
    CHECK(before.position_m[3] == doctest::Approx(0.025f));
    const VoxelPoses blend = pose_at(r, 0.15, PoseSampling::Interpolate);
    CHECK(blend.position_m[3] == doctest::Approx(0.030f));
    CHECK(blend.time_s == doctest::Approx(0.15));
    // Half way between a 0.4 rad turn and none: 0.2 rad, still a unit quaternion.
    CHECK(blend.orientation[0] == doctest::Approx(std::cos(0.1f)).epsilon(2e-3));
    CHECK(blend.orientation[3] == doctest::Approx(std::sin(0.1f)).epsilon(2e-2));
    const float norm = std::hypot(blend.orientation[0], blend.orientation[3]);
    CHECK(norm == doctest::Approx(1.0f));
    // Exact frame times and times outside the recording.
    CHECK(pose_at(r, 0.1).position_m[3] == doctest::Approx(0.025f));
    CHECK(pose_at(r, -5.0).position_m[3] == doctest::Approx(0.015f));
    CHECK(pose_at(r, 99.0).position_m[3] == doctest::Approx(0.035f));
    Replay empty = r;
    empty.frames.clear();
    CHECK_THROWS_AS(pose_at(empty, 0.0), std::invalid_argument);
}

TEST_CASE("interpolation takes the short way between q and -q") {
    Replay r = two_voxel_replay();
    // Same rotation written with the opposite sign: the blend must not pass through zero.
    for (float& q : r.frames[2].orientation)
        q = -q;
    r.frames[1] = frame(0.1, {0.005f, 0.025f});
    const VoxelPoses blend = pose_at(r, 0.15);
    CHECK(std::fabs(blend.orientation[0]) == doctest::Approx(1.0f));
}

TEST_CASE("centre-of-mass trail: one weighted mean per frame up to the time") {
    const Replay r = two_voxel_replay();
    const auto trail = centre_of_mass_trail(r, 0.1);
    REQUIRE(trail.size() == 2);
    CHECK(trail[0].x == doctest::Approx(0.010f));
    CHECK(trail[1].x == doctest::Approx(0.015f));
    // Weights 3 : 1 pull the mean toward the first voxel.
    const auto weighted = centre_of_mass_trail(r, 1.0, {3.0, 1.0});
    REQUIRE(weighted.size() == 3);
    CHECK(weighted[2].x == doctest::Approx((3 * 0.005 + 0.035) / 4));
}

TEST_CASE("replay bounds cover every voxel in every frame") {
    const Bounds b = replay_bounds(two_voxel_replay());
    const float half_diagonal = 0.5f * std::sqrt(3.0f) * 0.01f;
    CHECK(b.min.x == doctest::Approx(0.005f - half_diagonal));
    CHECK(b.max.x == doctest::Approx(0.035f + half_diagonal));
}

TEST_CASE("per-voxel displacement and volumetric strain") {
    const Replay r = two_voxel_replay();
    const auto d = voxel_displacement_m(r.frames[2], r.frames[0]);
    CHECK(d[0] == doctest::Approx(0.0f));
    CHECK(d[1] == doctest::Approx(0.02f));
    VoxelPoses swollen = r.frames[0];
    swollen.size_m[0] = 0.011f;  // 10 % longer along x: volume +10 %
    swollen.size_m[3] = swollen.size_m[4] = swollen.size_m[5] = 0.009f;
    const auto strain = voxel_volume_strain(swollen, 0.01);
    CHECK(strain[0] == doctest::Approx(0.1f).epsilon(1e-4));
    CHECK(strain[1] == doctest::Approx(0.729f - 1.0f).epsilon(1e-4));
}
