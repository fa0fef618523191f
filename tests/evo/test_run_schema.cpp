// The run directory's schema (issue 41): one serialisation of each type (a rule change is written
// and read by rule_change_json.hpp for run.json and the checkpoint alike), cache entries by name
// with the old positional form still read, and old run directories resuming as their
// uninterrupted twins.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness_json.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/checkpoint_schema.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/run/physics_rules.hpp"
#include "evo/run/rule_change_json.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/run/run_file_schema.hpp"
#include "evo/run/run_output.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;
using bhm::evo::test::csv_without_wall;
using bhm::evo::test::run_options;
using nlohmann::json;

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

namespace {

//! A report's JSON without its wall-clock time (the one field that depends on the machine).
json without_sim_wall(const FitnessReport& report) {
    json j = report_to_json(report);
    j.erase("sim_wall_s");
    return j;
}

//! Every cache entry's report, oldest first.
std::vector<const FitnessReport*> cache_reports(const RunState& state) {
    std::vector<const FitnessReport*> out;
    for (const auto hash : state.cache.insertion_order())
        out.push_back(state.cache.find(hash));
    return out;
}

}  // namespace

TEST_CASE("the fitness cache's entries are named objects and read back exactly as simulated") {
    const Experiment e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("schema-cache", false);
    EvolutionRun run(e, run_options(2, 2, dir.string()));
    run.run();
    const json payload = payload_of(dir / kCheckpointFile);
    CHECK(payload.at("format_version") == kCheckpointFormatVersion);
    REQUIRE(payload.at("cache").size() == run.state().cache.size());
    REQUIRE(run.state().cache.size() > 0);
    for (const auto& entry : payload.at("cache")) {
        REQUIRE(entry.is_object());
        CHECK(entry.at("hash").is_string());
        CHECK(entry.at("report").at("measures").is_object());  // measures by name too
    }

    // The round trip keeps every field of every report, sim_wall_s and fitness included (the
    // positional form dropped the first and scored the second again on load).
    const RunState back = run_state_from_json(payload, "x");
    CHECK(back.cache.insertion_order() == run.state().cache.insertion_order());
    CHECK(back.cache.capacity() == run.state().cache.capacity());
    const auto before = cache_reports(run.state()), after = cache_reports(back);
    int timed = 0;
    for (std::size_t i = 0; i < before.size(); ++i) {
        CHECK(report_to_json(*after[i]) == report_to_json(*before[i]));
        timed += before[i]->sim_wall_s > 0.0 ? 1 : 0;
    }
    CHECK(timed > 0);  // so the check above covers sim_wall_s
    CHECK(run_state_to_json(back) == payload);

    // The same cache in the positional form of formats 1 to 3 reads as the same results.
    json old = payload;
    test::as_positional_cache(old, 3);
    REQUIRE(old.at("cache")[0].is_array());
    const RunState positional = run_state_from_json(old, "x");
    CHECK(positional.cache.insertion_order() == run.state().cache.insertion_order());
    const auto read = cache_reports(positional);
    for (std::size_t i = 0; i < before.size(); ++i) {
        CHECK(without_sim_wall(*read[i]) == without_sim_wall(*before[i]));
        CHECK(read[i]->sim_wall_s == 0.0);
    }
    fs::remove_all(dir);
}

TEST_CASE("a malformed cache entry is one line naming the file and the field") {
    const Experiment e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("schema-cache-bad", false);
    EvolutionRun(e, run_options(1, 1, dir.string())).run();
    const json good = payload_of(dir / kCheckpointFile);
    REQUIRE(good.at("cache").size() >= 2);
    fs::remove(dir / kPreviousCheckpointFile);  // so that no backup is taken instead
    const std::string file = (dir / kCheckpointFile).string();

    auto problem = [&](const json& payload) -> std::string {
        spit(dir / kCheckpointFile,
             checkpoint_text(payload));  // a valid checksum: the field is read
        try {
            load_checkpoint(dir.string());
        } catch (const std::runtime_error& error) {
            return error.what();
        }
        return "(loaded)";
    };
    auto check_names = [&](const std::string& what, const std::string& field) {
        CAPTURE(what);
        CHECK(what.find(file + ": " + field) != std::string::npos);
        CHECK(what.find('\n') == std::string::npos);
    };

    json bad = good;
    bad["cache"][1]["report"]["measures"]["com_max_3d"] = "far";
    check_names(problem(bad), "cache[1].report.measures.com_max_3d: expected a number");
    bad = good;
    bad["cache"][0].erase("hash");
    check_names(problem(bad), "cache[0].hash: missing");
    bad = good;
    bad["cache"][1]["report"].erase("steps");
    check_names(problem(bad), "cache[1].report.steps: missing");

    // A form that does not match the file's version is named as such.
    bad = good;
    test::as_positional_cache(bad, kCheckpointFormatVersion);
    check_names(problem(bad), "cache[0]: a positional entry in a format 4 checkpoint");
    bad = good;
    test::as_positional_cache(bad, 3);
    bad["cache"][1] = good["cache"][1];
    check_names(problem(bad), "cache[1]: expected [hash, diverged");
    // A positional entry names its element.
    bad = good;
    test::as_positional_cache(bad, 3);
    bad["cache"][1][4] = json::array({1.0, 2.0});
    check_names(problem(bad),
                "cache[1][4] (measures): expected an array of one number per measure");
    bad = good;
    test::as_positional_cache(bad, 3);
    bad["cache"][0][2] = 1.5;
    check_names(problem(bad), "cache[0][2] (steps): expected an integer");
    fs::remove_all(dir);
}

TEST_CASE("a run directory written before issue 41 (format 3) resumes as its uninterrupted twin") {
    // tests/data/run-format3: stopped after generation 2 of 5 by the code before named cache
    // entries (its README says how it was made).
    const fs::path fixture = fs::path(BHM_SOURCE_DIR) / "tests/data/run-format3";
    const fs::path dir = bhm::test::scratch_dir("schema-format3", false),
                   whole = bhm::test::scratch_dir("schema-format3-whole", false);
    fs::copy(fixture, dir, fs::copy_options::recursive);
    const json old = payload_of(dir / kCheckpointFile);
    REQUIRE(old.at("format_version") == 3);
    REQUIRE(old.at("cache").size() > 0);
    REQUIRE(old.at("cache")[0].is_array());
    REQUIRE(old.at("cache")[0].size() == 9);

    const RunInfo info = read_run_info(dir.string());
    CHECK(info.warnings.empty());
    REQUIRE(info.rule_changes.size() == 2);
    REQUIRE(info.rule_changes[1].physics);
    const Experiment e = info.started;

    auto resumed = EvolutionRun::resume(run_options(5, 2, dir.string()));
    CHECK(resumed->resume_warnings().empty());
    CHECK(resumed->state().generation == 2);
    CHECK(resumed->state().cache.size() == old.at("cache").size());
    CHECK(resumed->state().rule_changes == info.rule_changes);
    CHECK(resumed->run() == StopReason::GenerationBudget);

    EvolutionRun twin(e, run_options(5, 2, whole.string()));
    REQUIRE(run_with_changes(twin, info.rule_changes[0].fitness, *info.rule_changes[1].physics) ==
            StopReason::GenerationBudget);
    const std::string csv = csv_without_wall(bhm::test::read_file(dir / kFitnessCsvFile));
    CHECK(csv == csv_without_wall(bhm::test::read_file(whole / kFitnessCsvFile)));
    // And what the old code's own uninterrupted run wrote.
    CHECK(csv == csv_without_wall(bhm::test::read_file(fixture / "expected-fitness.csv")));
    CHECK(resumed->state().rng == twin.state().rng);
    CHECK(resumed->state().champion->individual.genome == twin.state().champion->individual.genome);
    CHECK(resumed->state().cache.insertion_order() == twin.state().cache.insertion_order());
    const auto mine = cache_reports(resumed->state()), theirs = cache_reports(twin.state());
    for (std::size_t i = 0; i < mine.size(); ++i)
        CHECK(without_sim_wall(*mine[i]) == without_sim_wall(*theirs[i]));
    resumed.reset();

    // Its next checkpoint is in the new form.
    const json now = payload_of(dir / kCheckpointFile);
    CHECK(now.at("format_version") == kCheckpointFormatVersion);
    CHECK(now.at("cache")[0].is_object());
    fs::remove_all(dir);
    fs::remove_all(whole);
}

namespace {

//! Walks a checkpoint payload against the schema table: every field it holds must be a row of
//! the right type. `seen` gets each row's path met.
void walk_schema(const json& j, const std::string& path, std::set<std::string>& seen) {
    for (const auto& [key, value] : j.items()) {
        const std::string at = path.empty() ? key : path + "." + key;
        CAPTURE(at);
        const CheckpointField* row = find_checkpoint_field(at);
        REQUIRE_MESSAGE(row, "a field the writer writes is not in checkpoint_schema.cpp");
        seen.insert(at);
        const std::string type = row->type;
        CHECK(row->since <= kCheckpointFormatVersion);
        if (type == "objects") {
            REQUIRE(value.is_array());
            for (const auto& element : value) {
                REQUIRE(element.is_object());
                walk_schema(element, at + "[]", seen);
            }
        } else if (type == "object" || type == "object or null") {
            CHECK((value.is_object() || (type == "object or null" && value.is_null())));
            if (value.is_object()) walk_schema(value, at, seen);
        } else if (type == "string" || type == "hex") {
            CHECK(value.is_string());
        } else if (type == "integer") {
            CHECK(value.is_number_integer());
        } else if (type == "number") {
            CHECK(value.is_number());
        } else if (type == "boolean") {
            CHECK(value.is_boolean());
        } else if (type == "array") {
            CHECK(value.is_array());
        }  // else a part with a schema of its own (experiment, genome, report, ...)
    }
}

//! A run of 3 generations in `name`: the fitness and physics changes for AFPO (so rule_changes
//! has every kind of row), none for NEAT and novelty search. Returns its folder.
fs::path run_of(const std::string& name, const Experiment& e, bool with_changes) {
    const fs::path dir = bhm::test::scratch_dir("schema-" + name, false);
    EvolutionRun run(e, run_options(3, 2, dir.string()));
    Fitness changed = e.fitness;
    changed.measure = FitnessMeasure::ComFinal3d;
    if (with_changes)
        REQUIRE(run_with_changes(run, changed, stiffer(e)) == StopReason::GenerationBudget);
    else
        REQUIRE(run.run() == StopReason::GenerationBudget);
    return dir;
}

}  // namespace

TEST_CASE(
    "the checkpoint's field table covers what the writer writes, and the docs are the table") {
    std::set<std::string> seen;
    auto walk_run = [&](Experiment e, bool with_changes) {
        const fs::path dir = run_of("table", e, with_changes);
        walk_schema(payload_of(dir / kCheckpointFile), "", seen);
        fs::remove_all(dir);
    };
    walk_run(test::tiny_experiment(), true);
    Experiment neat = test::tiny_experiment();
    neat.evolution.algorithm = Algorithm::Neat;
    neat.evolution.population = 10;
    walk_run(neat, false);
    Experiment novelty = test::tiny_experiment();
    novelty.evolution.algorithm = Algorithm::Novelty;
    walk_run(novelty, false);
    // Each row said to be in every checkpoint is; so are NEAT's and novelty search's.
    for (const auto& row : checkpoint_fields()) {
        CAPTURE(row.path);
        const std::string when = row.when;
        if (when.empty() || when == "NEAT runs" || when == "novelty search runs" ||
            when == "a change that set the physics" || when == "champion not null")
            CHECK(seen.count(row.path) == 1);
    }

    // docs/evolution.md holds the table as checkpoint_schema_markdown() writes it.
    const std::string doc =
        bhm::test::read_file(std::string(BHM_SOURCE_DIR) + "/docs/evolution.md");
    const std::string begin = "<!-- checkpoint fields: begin -->\n",
                      end = "<!-- checkpoint fields: end -->";
    const auto from = doc.find(begin), to = doc.find(end);
    REQUIRE(from != std::string::npos);
    REQUIRE(to != std::string::npos);
    const std::string table = doc.substr(from + begin.size(), to - from - begin.size());
    if (table != checkpoint_schema_markdown()) {
        const std::string fresh = std::string(BHM_BINARY_DIR) + "/checkpoint-fields.md";
        spit(fresh, checkpoint_schema_markdown());
        FAIL(
            "docs/evolution.md's checkpoint table differs from evo/run/checkpoint_schema.cpp: "
            "put "
            << fresh << " between its markers");
    }
}

namespace {


//! The three kinds of run every schema test walks: AFPO with rule changes, NEAT, novelty search.
std::vector<fs::path> three_runs() {
    Experiment neat = test::tiny_experiment();
    neat.evolution.algorithm = Algorithm::Neat;
    neat.evolution.population = 10;
    Experiment novelty = test::tiny_experiment();
    novelty.evolution.algorithm = Algorithm::Novelty;
    return {run_of("afpo", test::tiny_experiment(), true), run_of("neat", neat, false),
            run_of("novelty", novelty, false)};
}

//! A schema path ("history[].novelty.best_novelty") made concrete with element 0 of each array
//! ("history[0].novelty.best_novelty"), and the JSON it names erased from `payload`. False when
//! the payload does not hold it (an empty array, an absent optional part, a null champion).
bool erase_first(json& payload, const std::string& path, std::string& concrete) {
    json* at = &payload;
    concrete.clear();
    std::size_t from = 0;
    while (true) {
        const std::size_t dot = path.find('.', from);
        std::string key =
            path.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
        const bool each = key.size() > 2 && key.ends_with("[]");
        if (each) key.resize(key.size() - 2);
        if (!at->is_object() || !at->contains(key)) return false;
        concrete += (concrete.empty() ? "" : ".") + key;
        if (dot == std::string::npos && !each) {
            at->erase(key);
            return true;
        }
        at = &(*at)[key];
        if (each) {
            if (!at->is_array() || at->empty()) return false;
            at = &(*at)[0];
            concrete += "[0]";
        }
        from = dot + 1;
    }
}

}  // namespace

TEST_CASE("a checkpoint round-trips through its field table: written, read, written, same bytes") {
    for (const auto& dir : three_runs()) {
        CAPTURE(dir);
        const std::string text = bhm::test::read_file(dir / kCheckpointFile);
        const RunState state = run_state_from_json(payload_of(dir / kCheckpointFile), "x");
        CHECK(checkpoint_text(run_state_to_json(state)) == text);
        // run.json likewise, through its own table.
        const RunInfo info = read_run_info(dir.string());
        CHECK(write_fields(run_info_fields(), info, RunFileContext{}) ==
              json::parse(bhm::test::read_file(dir / kRunInfoFile)));
        fs::remove_all(dir);
    }
}

TEST_CASE("a field missing from a checkpoint is named in a one-line error, for every row") {
    std::set<std::string> named;
    for (const auto& dir : three_runs()) {
        const json good = payload_of(dir / kCheckpointFile);
        for (const auto& row : checkpoint_fields()) {
            json bad = good;
            std::string concrete;
            if (row.path == "bhm_version" || !erase_first(bad, row.path, concrete)) continue;
            CAPTURE(concrete);
            try {
                run_state_from_json(bad, "cp.json");
                // Only a field the table says is not always written may be absent.
                CHECK(!row.when.empty());
                CHECK(row.when != "champion not null");
            } catch (const std::runtime_error& error) {
                const std::string what = error.what();
                CHECK(what.find("cp.json: " + concrete + ": missing") == 0);
                CHECK(what.find('\n') == std::string::npos);
                named.insert(row.path);
            }
        }
        fs::remove_all(dir);
    }
    // Every row each checkpoint of its kind holds was named when missing (bhm_version is not
    // read back).
    for (const auto& row : checkpoint_fields()) {
        const std::string when = row.when;
        if ((when.empty() || when == "NEAT runs" || when == "novelty search runs" ||
             when == "champion not null") &&
            row.path != "bhm_version" && row.path != "history[].novelty")
            CHECK_MESSAGE(named.count(row.path) == 1, row.path);
    }
}

TEST_CASE(
    "run.json and champion.json: their readers name a missing field, and the docs are "
    "their tables") {
    const Experiment e = test::tiny_experiment();
    const fs::path dir = run_of("run-files", e, false);
    const json run_json = json::parse(bhm::test::read_file(dir / kRunInfoFile));
    const json champion = json::parse(bhm::test::read_file(dir / kChampionFile));
    const auto from_checkpoint = load_checkpoint(dir.string()).state.champion;
    CHECK(champion == champion_to_json(e, *from_checkpoint));
    // The summary the studio lists reads the same rows, without the experiment.
    const ChampionSummary summary = read_champion_summary((dir / kChampionFile).string());
    CHECK(summary.generation_found == from_checkpoint->generation_found);
    CHECK(summary.id == from_checkpoint->individual.id);
    CHECK(summary.measure == e.fitness.measure);
    CHECK(summary.voxels == from_checkpoint->individual.phenotype.voxels);
    for (const char* key : {"seed", "experiment"}) {
        json bad = run_json;
        bad.erase(key);
        spit(dir / kRunInfoFile, bad.dump(2));
        const std::string expected = (dir / kRunInfoFile).string() + ":" + key + ": missing";
        CHECK_THROWS_WITH(read_run_info(dir.string()), doctest::Contains(expected.c_str()));
    }
    spit(dir / kRunInfoFile, run_json.dump(2));
    for (const char* key : {"phenotype", "generation_found", "report", "voxels", "genome"}) {
        json bad = champion;
        bad.erase(key);
        spit(dir / kChampionFile, bad.dump(2));
        const std::string expected = (dir / kChampionFile).string() + ":" + key + ": missing";
        CHECK_THROWS_WITH(read_champion_file(dir.string(), e), doctest::Contains(expected.c_str()));
    }
    fs::remove_all(dir);

    const std::string doc =
        bhm::test::read_file(std::string(BHM_SOURCE_DIR) + "/docs/evolution.md");
    for (const std::string file : {kRunInfoFile, kChampionFile}) {
        CAPTURE(file);
        const std::string begin = "<!-- " + file + " fields: begin -->\n",
                          end = "<!-- " + file + " fields: end -->";
        const auto from = doc.find(begin), to = doc.find(end);
        REQUIRE(from != std::string::npos);
        REQUIRE(to != std::string::npos);
        if (doc.substr(from + begin.size(), to - from - begin.size()) !=
            run_file_schema_markdown(file)) {
            const std::string fresh = std::string(BHM_BINARY_DIR) + "/" + file + "-fields.md";
            spit(fresh, run_file_schema_markdown(file));
            FAIL("docs/evolution.md's "
                 << file << " table differs from evo/run/run_file_schema.cpp: put " << fresh
                 << " between its markers");
        }
    }
}
