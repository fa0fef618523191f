// The passes read solid stretches through "uniform runs" (constant neighbour offsets, no tables)
// and everything else through the neighbour tables (engine/internal/model_data.hpp). The tables are the
// independent truth: a body stepped with the runs Model::build chose must move bit for bit like
// the same model with every run turned into a gathered one.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/internal/model_data.hpp"
#include "engine_test_bodies.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// A 12 x 6 x 5 block held at x = 0, bands of an active material (nu 0.35, so the Poisson pass
// runs too); with `holes`, every 5th cell of its top two layers is empty (a fragmented region
// above a solid one).
BodySpec banded_block(bool holes) {
    Material passive;
    Material active = passive;
    active.cte_per_c = 0.01;
    BodySpec s = solid_box(12, 6, 5, passive);
    s.materials.push_back(active);
    s.phase_rad.assign(s.material.size(), 0.0f);
    for (int c = 0; c < s.cell_count(); ++c) {
        s.material[c] = static_cast<std::uint8_t>((c % 12) / 3 % 2 == 0 ? 2 : 1);
        const int z = c / (12 * 6);
        if (holes && z >= 3 && c % 5 == 0 && c % 12 != 0) s.material[c] = 0;
        s.phase_rad[c] = static_cast<float>(0.37 * (c % 17));
    }
    fix_x_min_layer(s);
    s.environment.gravity_m_s2 = -9.81;
    s.actuation.start_s = 0.0;
    s.actuation.frequency_hz = 25.0;
    return s;
}

// The same model with every link and voxel run read through the tables.
std::shared_ptr<const Model> all_gathered(const Model& built) {
    auto data = std::make_unique<Model::Data>(built.data());
    for (auto& runs : data->link_runs)
        for (LinkRun& r : runs)
            r.delta = 0;
    for (VoxelRun& r : data->voxel_runs)
        r.below_y = r.below_z = 0;
    return std::make_shared<const Model>(std::move(data));
}

int gathered_link_slots(const Model& m) {
    int slots = 0;
    for (const auto& runs : m.data().link_runs)
        for (const LinkRun& r : runs)
            if (r.delta == 0) slots += r.end - r.begin;
    return slots;
}

int uniform_voxel_slots(const Model& m) {
    int slots = 0;
    for (const VoxelRun& r : m.data().voxel_runs)
        if (r.below_y > 0) slots += r.end - r.begin;
    return slots;
}

void check_runs_match_tables(const BodySpec& spec) {
    const auto built = Model::build(spec);
    const auto gathered = all_gathered(*built);
    REQUIRE(uniform_voxel_slots(*built) > 0);  // the comparison exercises both kinds
    REQUIRE(uniform_voxel_slots(*gathered) == 0);
    World a(built), b(gathered);
    for (int i = 0; i < 3000; ++i) {
        a.step();
        b.step();
    }
    REQUIRE_FALSE(a.diverged());
    REQUIRE_FALSE(b.diverged());
    int mismatches = 0;
    for (int v = 0; v < built->voxel_count(); ++v) {
        mismatches += a.voxel_position_m(v) != b.voxel_position_m(v);
        mismatches += a.voxel_orientation(v) != b.voxel_orientation(v);
    }
    CHECK(mismatches == 0);
    CHECK(a.kinetic_energy_j() > 0.0);
}

}  // namespace

TEST_CASE("uniform runs give the same trajectory as reading every neighbour from the tables") {
    SUBCASE("a solid block: every voxel in a uniform run, its first row and layer included") {
        const BodySpec s = banded_block(false);
        const auto m = Model::build(s);
        CHECK(uniform_voxel_slots(*m) == m->data().slots);
        check_runs_match_tables(s);
    }
    SUBCASE("a block with holes: uniform, gathered and absorbed short runs side by side") {
        const BodySpec s = banded_block(true);
        const auto m = Model::build(s);
        CHECK(uniform_voxel_slots(*m) < m->data().slots);
        CHECK(gathered_link_slots(*m) > 0);
        check_runs_match_tables(s);
    }
}

TEST_CASE("run's poll hook slices without changing a step and can end the run early") {
    // Polling every 7 steps against a sample period that is no whole number of steps or slices:
    // the same samples at the same steps, the same final state to the last bit, as without it.
    Material active;
    active.cte_per_c = 0.01;
    BodySpec spec = test::solid_box(3, 2, 2, active);
    test::fix_x_min_layer(spec);
    spec.environment.gravity_m_s2 = 9.81;
    spec.actuation.start_s = 0.002;
    auto model = Model::build(spec);
    auto trace = [&](const RunHooks& extra, std::vector<std::int64_t>& steps) {
        World world(model);
        RunHooks hooks = extra;
        hooks.observe = [&](const World& w) { steps.push_back(w.steps()); };
        run(world, 0.01, 1370.0, hooks);
        return world.centre_of_mass_m();
    };
    std::vector<std::int64_t> plain_steps, polled_steps, stopped_steps;
    const auto plain = trace(RunHooks{}, plain_steps);
    int polls = 0;
    RunHooks polled;
    polled.poll_steps = 7;
    polled.poll = [&](const World&) {
        ++polls;
        return RunVerdict::Continue;
    };
    const auto with_polls = trace(polled, polled_steps);
    CHECK(polls > static_cast<int>(polled_steps.size()));  // between samples too
    CHECK(polled_steps == plain_steps);
    CHECK(with_polls == plain);
    // Stop at the third sample: nothing is stepped or observed after it.
    RunHooks stopping;
    int seen = 0;
    stopping.poll = [&](const World&) {
        return seen >= 3 ? RunVerdict::Stop : RunVerdict::Continue;
    };
    stopping.observe = nullptr;
    World world(model);
    RunHooks hooks = stopping;
    hooks.observe = [&](const World& w) {
        ++seen;
        stopped_steps.push_back(w.steps());
    };
    run(world, 0.01, 1370.0, hooks);
    REQUIRE(stopped_steps.size() == 3);
    CHECK(world.steps() == stopped_steps.back());
    CHECK(stopped_steps == std::vector<std::int64_t>(plain_steps.begin(), plain_steps.begin() + 3));
}

TEST_CASE("rest_until lets time pass without integrating, and a run resumes from there") {
    // A held block with no gravity and no drive until start_s is exactly at rest: passing the time
    // without stepping must leave it where stepping leaves it, and a run resumed after the rest
    // observes at the same steps and ends in the same state as one stepped all the way.
    Material active;
    active.cte_per_c = 0.01;
    BodySpec spec = test::solid_box(3, 2, 2, active);
    test::fix_x_min_layer(spec);
    spec.environment.gravity_m_s2 = 0.0;
    spec.environment.floor = false;
    spec.actuation.start_s = 0.004;
    auto model = Model::build(spec);
    const double dt = model->dt_s();
    std::vector<std::int64_t> full_steps, rested_steps;
    World full(model);
    run(full, 0.01, 1000.0, [&](const World& w) { full_steps.push_back(w.steps()); });
    World rested(model);
    rested.rest_until(0.004);
    CHECK(rested.time_s() >= 0.004);
    CHECK(rested.time_s() - dt < 0.004);
    CHECK(rested.integrated_steps() == 0);
    CHECK(rested.steps() > 0);
    rested.rest_until(0.001);  // the past: nothing
    CHECK(rested.time_s() >= 0.004);
    run(rested, 0.01, 1000.0, [&](const World& w) { rested_steps.push_back(w.steps()); });
    // The resumed run observes at the rest's end, then on the full run's schedule.
    REQUIRE(rested_steps.size() >= 2);
    CHECK(std::find(full_steps.begin(), full_steps.end(), rested_steps[1]) != full_steps.end());
    CHECK(rested_steps.back() == full_steps.back());
    CHECK(rested.integrated_steps() < full.integrated_steps());
    CHECK(rested.integrated_steps() + (rested.steps() - rested.integrated_steps()) == full.steps());
    const auto a = full.centre_of_mass_m(), b = rested.centre_of_mass_m();
    for (int i = 0; i < 3; ++i)
        CHECK(a[i] == doctest::Approx(b[i]).epsilon(1e-12));
    // Actuation moved it: the comparison is not of two bodies that stayed still.
    World still(model);
    const auto start = still.centre_of_mass_m();
    CHECK(std::abs(a[0] - start[0]) > 1e-9);
}
