// A calibration applied to a live run (issue 28): a rule change that carries physics. From the
// generation it applies to, every member is simulated again under the new physics, so no fitness
// measured under the old physics is left in the population, the cache or the champion; the
// change is recorded in run.json and the checkpoint, and a resumed run equals its uninterrupted
// twin. The truth for "measured under the new physics" is evaluate_body called directly.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/run/physics_rules.hpp"
#include "evo/run/run_directory.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;
using bhm::evo::test::csv_without_wall;
using bhm::evo::test::run_options;

namespace {

//! The tiny experiment's physics, stiffer and with a weaker drive: a body's fitness changes.
PhysicsRules calibrated(const Experiment& e) {
    PhysicsRules p = physics_of(e);
    for (auto& m : p.materials)
        m.youngs_modulus_pa *= 1.7;
    p.temperature_amplitude_c *= 0.6;
    p.bond_damping_ratio = 0.5;
    return p;
}

void strip_clock(nlohmann::json& j) {
    if (j.is_object()) {
        for (const char* key : {"wall_s", "elapsed_s", "sim_wall_s", "checksum"})
            j.erase(key);
        for (auto& [key, value] : j.items())
            strip_clock(value);
    } else if (j.is_array()) {
        for (auto& value : j)
            strip_clock(value);
    }
}

}  // namespace

TEST_CASE("physics rules: read back as written, refused when they would change the bodies") {
    const Experiment e = test::tiny_experiment();
    const PhysicsRules p = calibrated(e);
    CHECK(physics_from_json(physics_to_json(p, e), e, "x") == p);
    CHECK(physics_of(with_physics(e, p)) == p);
    CHECK(with_physics(e, p).boundary == e.boundary);

    PhysicsRules passive_active = p;
    passive_active.materials[1].cte_per_c = 0.0;  // the active material would become passive
    CHECK_THROWS_WITH_AS(with_physics(e, passive_active),
                         doctest::Contains("materials[1].cte_per_c"), std::invalid_argument);
    PhysicsRules fewer = p;
    fewer.materials.pop_back();
    CHECK_THROWS_AS(with_physics(e, fewer), std::invalid_argument);
    PhysicsRules bad = p;
    bad.materials[0].youngs_modulus_pa = -1.0;
    CHECK_THROWS_WITH_AS(with_physics(e, bad), doctest::Contains("youngs_modulus"),
                         std::invalid_argument);
    EvolutionRun run(e, run_options(2, 1));
    CHECK_THROWS_AS(run.request_physics_change(bad), std::invalid_argument);

    const std::string said = describe_physics_change(e, p);
    CHECK(said.rfind("physics: E[passive] 5e+06 -> 8.5e+06 Pa", 0) == 0);
    CHECK(said.find("amplitude 14.47 -> 8.682 C") != std::string::npos);
    CHECK(said.find("bond damping 1 -> 0.5") != std::string::npos);
    CHECK(describe_physics_change(e, physics_of(e)) == "physics unchanged");
}

TEST_CASE("a physics change at generation g: every member simulated again, nothing old kept") {
    const Experiment e = test::tiny_experiment();
    const PhysicsRules p = calibrated(e);
    const Experiment after = with_physics(e, p);
    EvolutionRun run(e, run_options(4, 2));
    REQUIRE(run.run_generation());
    REQUIRE(run.run_generation());
    const std::vector<Individual> before = run.state().population;
    run.request_physics_change(p);
    std::shared_ptr<const GenerationReport> report;
    run.set_report_callback([&](auto r) { report = r; });
    REQUIRE(run.run_generation());  // generation 2, the first under the new physics
    REQUIRE(report);
    CHECK(report->rules_changed);
    CHECK(report->rules_version == 1);
    CHECK(run.state().experiment == after);
    REQUIRE(run.state().rule_changes.size() == 1);
    CHECK(run.state().rule_changes[0].generation == 2);
    REQUIRE(run.state().rule_changes[0].physics);
    CHECK(*run.state().rule_changes[0].physics == p);
    // The P carried members were simulated again besides the new ones (twins at most once).
    CHECK(report->simulations > report->evaluations - report->cache_hits);

    // Every member's and the champion's result is what the new physics gives, exactly.
    int old_differs = 0;
    for (const auto& m : run.state().population) {
        const FitnessReport truth = evaluate_body(after, m.phenotype.body);
        CHECK(m.report.measures == truth.measures);
        CHECK(m.report.fitness == truth.fitness);
        for (const auto& b : before)
            if (b.phenotype.hash == m.phenotype.hash && b.report.measures != truth.measures)
                ++old_differs;
    }
    CHECK(old_differs > 0);  // the change mattered: old results would have been wrong
    const Individual& champion = run.state().champion->individual;
    CHECK(champion.report.measures == evaluate_body(after, champion.phenotype.body).measures);
    CHECK(run.state().champion->generation_found == 2);
    // The cache holds only results of the new physics.
    REQUIRE(run.state().cache.size() > 0);
    for (const auto& m : run.state().population)
        if (const FitnessReport* hit = run.state().cache.find(m.phenotype.hash))
            CHECK(hit->measures == evaluate_body(after, m.phenotype.body).measures);

    // Applied once; sending the same physics again changes nothing.
    run.request_physics_change(p);
    REQUIRE(run.run_generation());
    CHECK_FALSE(report->rules_changed);
    CHECK(run.state().rule_changes.size() == 1);
}

TEST_CASE("a run with a physics change equals its resumed twin; run.json records the change") {
    const Experiment e = test::tiny_experiment();
    const PhysicsRules p = calibrated(e);
    const fs::path whole = bhm::test::scratch_dir("physics-whole", false),
                   parts = bhm::test::scratch_dir("physics-parts", false);
    {
        EvolutionRun run(e, run_options(5, 2, whole.string()));
        run.set_report_callback([&](auto r) {
            if (r->generation == 1) run.request_physics_change(p);
        });
        REQUIRE(run.run() == StopReason::GenerationBudget);
    }
    {
        // Stopped right after the change's generation, then resumed from its checkpoint.
        EvolutionRun first(e, run_options(5, 1, parts.string()));
        first.set_report_callback([&](auto r) {
            if (r->generation == 1) first.request_physics_change(p);
            if (r->generation == 2) first.request_stop();
        });
        REQUIRE(first.run() == StopReason::StopRequested);
    }
    auto resumed = EvolutionRun::resume(run_options(5, 2, parts.string()));
    CHECK(resumed->resume_warnings().empty());
    REQUIRE(resumed->state().rule_changes.size() == 1);
    CHECK(resumed->state().rule_changes[0].physics == p);
    CHECK(resumed->experiment() == with_physics(e, p));
    REQUIRE(resumed->run() == StopReason::GenerationBudget);
    CHECK(csv_without_wall(bhm::test::read_file(parts / "fitness.csv")) ==
          csv_without_wall(bhm::test::read_file(whole / "fitness.csv")));
    // The files without their wall-clock fields (wall_s, elapsed_s, sim_wall_s).
    auto file = [](const fs::path& path) {
        auto j = nlohmann::json::parse(bhm::test::read_file(path));
        strip_clock(j);
        return j;
    };
    CHECK(file(parts / "checkpoint.json") == file(whole / "checkpoint.json"));
    CHECK(file(parts / "champion.json") == file(whole / "champion.json"));

    // run.json: the change with its physics, read back by the run directory's reader.
    const RunInfo info = read_run_info(whole.string());
    CHECK(info.started == e);
    REQUIRE(info.rule_changes.size() == 1);
    CHECK(info.rule_changes[0].generation == 2);
    REQUIRE(info.rule_changes[0].physics);
    CHECK(*info.rule_changes[0].physics == p);
    CHECK(info.current() == with_physics(e, p));
    resumed.reset();
    fs::remove_all(whole);
    fs::remove_all(parts);
}
