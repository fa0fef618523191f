// The run directory's schema (issue 41): one serialisation of each type (a rule change is written
// and read by rule_change_json.hpp for run.json and the checkpoint alike), cache entries by name
// with the old positional form still read, and old run directories resuming as their
// uninterrupted twins.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness_json.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/run/physics_rules.hpp"
#include "evo/run/rule_change_json.hpp"
#include "evo/run/run_directory.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;
using nlohmann::json;
using bhm::evo::test::csv_without_wall;
using bhm::evo::test::run_options;

namespace {

void spit(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

json payload_of(const fs::path& checkpoint) {
    std::vector<std::string> notes;
    return parse_checkpoint_text(bhm::test::read_file(checkpoint), notes);
}

//! The tiny experiment's physics made stiffer with a weaker drive (the fixture's change).
PhysicsRules stiffer(const Experiment& e) {
    PhysicsRules p = physics_of(e);
    for (auto& m : p.materials)
        m.youngs_modulus_pa *= 1.7;
    p.temperature_amplitude_c *= 0.6;
    return p;
}

//! A run of `generations` with a fitness change after generation 0 and a physics change after
//! generation 1 (tests/data/run-format3/README.md), stopped after `stop_at` (-1: never).
StopReason run_with_changes(EvolutionRun& run, const Fitness& fitness, const PhysicsRules& physics,
                            int stop_at = -1) {
    run.set_report_callback([&](auto r) {
        if (r->generation == 0) run.request_fitness_change(fitness);
        if (r->generation == 1) run.request_physics_change(physics);
        if (r->generation == stop_at) run.request_stop();
    });
    return run.run();
}

}  // namespace

TEST_CASE("a rule change has one form: run.json and the checkpoint write and read it alike") {
    const Experiment e = test::tiny_experiment();
    Fitness changed = e.fitness;
    changed.measure = FitnessMeasure::ComFinal3d;
    const fs::path dir = bhm::test::scratch_dir("schema-rules", false);
    {
        EvolutionRun run(e, run_options(3, 2, dir.string()));
        REQUIRE(run_with_changes(run, changed, stiffer(e)) == StopReason::GenerationBudget);
    }
    const json run_json = json::parse(bhm::test::read_file(dir / kRunInfoFile));
    const json checkpoint = payload_of(dir / kCheckpointFile);
    REQUIRE(run_json.at("rule_changes").size() == 2);
    CHECK(run_json.at("rule_changes") == checkpoint.at("rule_changes"));
    CHECK(run_json.at("rule_changes")[1].contains("physics"));

    // Read back the same through both files' readers, and through the one pair directly.
    const RunInfo info = read_run_info(dir.string());
    CHECK(info.warnings.empty());
    const auto loaded = load_checkpoint(dir.string());
    CHECK(info.rule_changes == loaded.state.rule_changes);
    CHECK(rule_changes_from_json(rule_changes_to_json(info.rule_changes, e), e, "x") ==
          info.rule_changes);

    // A malformed change is one line naming the file and the field, in either file.
    json bad = run_json;
    bad["rule_changes"][1].erase("generation");
    spit(dir / kRunInfoFile, bad.dump(2));
    const std::string missing =
        (dir / kRunInfoFile).string() + ":rule_changes[1].generation: missing";
    CHECK_THROWS_WITH(read_run_info(dir.string()), doctest::Contains(missing.c_str()));
    bad = run_json;
    bad["rule_changes"][0]["fitness"]["measure"] = "no_such_measure";
    spit(dir / kRunInfoFile, bad.dump(2));
    try {
        read_run_info(dir.string());
        FAIL("a bad fitness section was read");
    } catch (const std::runtime_error& error) {
        const std::string what = error.what();
        CHECK(what.find("rule_changes[0].fitness") != std::string::npos);
        CHECK(what.find("measure") != std::string::npos);
    }
    fs::remove_all(dir);
}
