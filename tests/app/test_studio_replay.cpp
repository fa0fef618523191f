// Replay playback: the clock (play, loop, stop at the end, steps), frame lookup, interpolation of
// poses between frames, and the centre of mass per frame, on replays built by hand.
#include <doctest/doctest.h>

#include <cmath>

#include "app/gui/session/replay_player.hpp"

using namespace bhm;
using namespace bhm::app::gui;

namespace {

// Two voxels, frames at t = 0, 0.5, 1.0 s; voxel 0 moves +x by 1 cm per frame, voxel 1 stays;
// voxel 1 turns 90 degrees about z between the last two frames.
engine::Replay two_voxel_replay() {
    engine::Replay r;
    r.nx = 2, r.ny = 1, r.nz = 1;
    r.voxel_cell = {0, 1};
    r.voxel_material = {1, 2};
    r.voxel_fixed = {0, 0};
    const float s = std::sqrt(0.5f);
    for (int i = 0; i < 3; ++i) {
        engine::VoxelPoses p;
        p.time_s = 0.5 * i;
        p.position_m = {0.005f + 0.01f * i, 0.005f, 0.005f, 0.015f, 0.005f, 0.005f};
        p.orientation = {1, 0, 0, 0, 1, 0, 0, 0};
        if (i == 2) p.orientation = {1, 0, 0, 0, s, 0, 0, s};
        p.size_m = {0.01f, 0.01f, 0.01f, 0.01f, 0.01f, 0.01f};
        r.frames.push_back(p);
    }
    return r;
}

}  // namespace

TEST_CASE("studio replay clock: plays at its speed, loops or stops at the end, steps by frames") {
    ReplayClock clock;
    clock.set_duration(10.0);
    clock.advance(1.0);
    CHECK(clock.time_s == 0.0);  // paused: time stands still
    clock.playing = true;
    clock.speed = 2.0;
    clock.advance(1.5);
    CHECK(clock.time_s == doctest::Approx(3.0));
    clock.advance(4.0);  // 3 + 8 = 11 -> wraps to 1
    CHECK(clock.time_s == doctest::Approx(1.0));
    CHECK(clock.playing);
    clock.loop = false;
    clock.advance(10.0);
    CHECK(clock.time_s == 10.0);
    CHECK_FALSE(clock.playing);
    clock.seek(-3.0);
    CHECK(clock.time_s == 0.0);
    clock.seek(5.0);
    clock.playing = true;
    clock.step_frames(3, 1.0 / 30.0);
    CHECK(clock.time_s == doctest::Approx(5.1));
    CHECK_FALSE(clock.playing);
    clock.set_duration(4.0);  // a shorter replay clamps the time
    CHECK(clock.time_s == 4.0);
}

TEST_CASE("studio replay: frame lookup and linear interpolation of poses") {
    const auto replay = two_voxel_replay();
    CHECK(frame_index_at(replay, -1.0) == 0);
    CHECK(frame_index_at(replay, 0.0) == 0);
    CHECK(frame_index_at(replay, 0.49) == 0);
    CHECK(frame_index_at(replay, 0.5) == 1);
    CHECK(frame_index_at(replay, 7.0) == 2);
    CHECK(frame_index_at(engine::Replay{}, 1.0) == -1);

    const auto mid = engine::pose_at(replay, 0.25);
    CHECK(mid.time_s == 0.25);
    CHECK(mid.position_m[0] == doctest::Approx(0.010f));  // halfway between 0.005 and 0.015
    CHECK(mid.position_m[3] == doctest::Approx(0.015f));
    // Half of a 90-degree turn about z is 45 degrees: w = cos(22.5), z = sin(22.5).
    const auto turning = engine::pose_at(replay, 0.75);
    CHECK(turning.orientation[4] == doctest::Approx(std::cos(M_PI / 8)).epsilon(1e-5));
    CHECK(turning.orientation[7] == doctest::Approx(std::sin(M_PI / 8)).epsilon(1e-5));
    const auto end = engine::pose_at(replay, 9.0);
    CHECK(end.position_m[0] == doctest::Approx(0.025f));
}

TEST_CASE("studio replay: the centre of mass weights voxels by density, as the engine does") {
    auto replay = two_voxel_replay();
    // Material 2 is three times as dense: the COM sits 3/4 of the way toward voxel 1.
    const auto com = centre_of_mass_per_frame(replay, {1000.0, 3000.0});
    REQUIRE(com.size() == 3);
    CHECK(com[0].x == doctest::Approx(0.25f * 0.005f + 0.75f * 0.015f));
    CHECK(com[1].x == doctest::Approx(0.25f * 0.015f + 0.75f * 0.015f));
    // Equal densities: the midpoint, also when one voxel is actuated to twice its length (its
    // mass stays, so the COM agrees with World::centre_of_mass_m, which the fitness uses).
    replay.frames[0].size_m[0] = 0.02f;
    const auto equal = centre_of_mass_per_frame(replay, {});
    CHECK(equal[0].x == doctest::Approx(0.5f * (0.005f + 0.015f)));
}
