// engine::run's poll hook (for callers that must notice Ctrl-C or a cancel within milliseconds):
// called every kDefaultPollSteps steps however rare the samples, able to abandon the run, and without
// any effect on the motion.
#include <doctest/doctest.h>

#include <stdexcept>
#include <vector>

#include "engine_test_bodies.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

const int kDefaultPollSteps = RunHooks{}.poll_steps;

std::shared_ptr<const Model> held_beam() {
    BodySpec s = solid_box(6, 2, 2);
    fix_x_min_layer(s);
    s.environment.gravity_m_s2 = -9.81;
    return Model::build(s);
}

}  // namespace

TEST_CASE("run's poll hook is called every kDefaultPollSteps steps and changes nothing") {
    const auto model = held_beam();
    const double total_s = 3000 * model->dt_s();
    const double sample_hz = 1.0 / total_s;  // one sample for the whole run: poll must not wait
    World plain(model), polled(model);
    std::vector<double> plain_times, polled_times;
    run(plain, total_s, sample_hz, [&](const World& w) { plain_times.push_back(w.time_s()); });
    std::vector<std::int64_t> polls;
    RunHooks hooks;
    hooks.observe = [&](const World& w) { polled_times.push_back(w.time_s()); };
    hooks.poll = [&](const World& w) {
        polls.push_back(w.steps());
        return RunVerdict::Continue;
    };
    run(polled, total_s, sample_hz, hooks);
    CHECK(polled.steps() == plain.steps());
    CHECK(polled_times == plain_times);
    for (int v = 0; v < model->voxel_count(); ++v)
        CHECK(polled.voxel_position_m(v) == plain.voxel_position_m(v));  // bit for bit
    REQUIRE(polls.size() >= static_cast<std::size_t>(plain.steps() / kDefaultPollSteps));
    std::int64_t previous = 0;
    for (const auto steps : polls) {
        CHECK(steps - previous <= kDefaultPollSteps);
        previous = steps;
    }
}

TEST_CASE("a poll hook that throws abandons the run at once") {
    const auto model = held_beam();
    World world(model);
    int polls = 0;
    RunHooks hooks;
    hooks.poll = [&](const World&) {
        if (++polls == 3) throw std::runtime_error("interrupted");
        return RunVerdict::Continue;
    };
    CHECK_THROWS_AS(run(world, 3000 * model->dt_s(), 1.0, hooks), std::runtime_error);
    // Polls: after the observation at t = 0, then every poll_steps steps: the third is at 2 of them.
    CHECK(world.steps() == 2 * kDefaultPollSteps);
}
