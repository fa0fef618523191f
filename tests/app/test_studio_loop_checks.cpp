// CalculiX in the evolution loop, the studio's part (evolution.verify; docs/studio.md, "CalculiX in
// the loop"): the badge of a checked body and which check belongs to which body, the checks'
// settings sent to a live run as a rule change (and refused with the run's reason), and, with
// CalculiX installed, checks turned on mid-run marking the bodies in the tables and the 3D view.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/widgets/check_badge.hpp"
#include "evo/run/run_directory.hpp"
#include "support/ccx_skip.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

evo::LoopCheck made_check(evo::LoopCheckOutcome outcome, double worst, int generation,
                          std::int64_t id, std::uint64_t hash, const std::string& verdict) {
    evo::LoopCheck c;
    c.outcome = outcome;
    c.worst = worst;
    c.generation = generation;
    c.id = id;
    c.hash = hash;
    c.verdict = verdict;
    return c;
}

bool drawn_now(const Studio& s, const std::string& widget) {
    const auto it = s.ui.widgets.find(widget);
    return it != s.ui.widgets.end() && it->second.frame == s.ui.frame;
}

//! PATH without CalculiX for as long as it lives (ccx_available asks the shell for `ccx`).
struct PathWithoutCcx {
    explicit PathWithoutCcx(const fs::path& empty) : saved(std::getenv("PATH")) {
        fs::create_directories(empty);
        setenv("PATH", empty.c_str(), 1);
    }
    ~PathWithoutCcx() { setenv("PATH", saved.c_str(), 1); }
    std::string saved;
};

}  // namespace

TEST_CASE("studio loop checks: the badge says how the check came out, in its colour") {
    const auto ok = check_badge(
        made_check(evo::LoopCheckOutcome::Agrees, 0.041, 3, 17, 1, "agrees within 4.1 %"));
    CHECK(ok.text == "FEM ok 4 %");
    CHECK(ok.color.y > 2.0f * ok.color.x);  // green
    CHECK(ok.tooltip.rfind("agrees within 4.1 %\n", 0) == 0);
    // Picked from generation 3's population, solved and applied in generation 4.
    CHECK(ok.tooltip.find("in generation 4 (individual #17 of generation 3)") != std::string::npos);

    const auto differs = check_badge(
        made_check(evo::LoopCheckOutcome::Differs, 0.234, 0, 2, 1, "differs by 23.4 %"));
    CHECK(differs.text == "FEM differs 23 %");
    CHECK(differs.color.x > 2.0f * differs.color.y);  // red

    const auto far = check_badge(
        made_check(evo::LoopCheckOutcome::OutOfReach, 0.0, 1, 5, 1, "static tip 0.3 voxels"));
    CHECK(far.text == "FEM n/a");
    CHECK(far.tooltip.rfind("out of reach: static tip 0.3 voxels", 0) == 0);
    const auto failed =
        check_badge(made_check(evo::LoopCheckOutcome::Failed, 0.0, 1, 5, 1, "ccx exited 201"));
    CHECK(failed.text == "FEM n/a");
    CHECK(failed.tooltip.rfind("failed: ccx exited 201", 0) == 0);
    CHECK(far.color.x == doctest::Approx(far.color.y).epsilon(0.1));  // grey
}

TEST_CASE("studio loop checks: a member's check is its body's, an earlier champion's its id's") {
    EvolutionSnapshot run;
    PopulationMember twin;  // the same body as #3, checked under that id and again as #5
    twin.id = 5;
    twin.hash = 77;
    PopulationMember fresh;
    fresh.id = 6;
    fresh.hash = 66;
    run.population = {twin, fresh};
    run.has_champion = true;
    run.champion = fresh;
    run.loop_checks = {
        made_check(evo::LoopCheckOutcome::Differs, 0.3, 1, 3, 77, "first"),
        made_check(evo::LoopCheckOutcome::Agrees, 0.02, 2, 2, 22, "gone"),
        made_check(evo::LoopCheckOutcome::Agrees, 0.05, 3, 5, 77, "again"),
    };
    const evo::LoopCheck* of_twin = loop_check_of(run, 5);
    REQUIRE(of_twin);
    CHECK(of_twin->verdict == "again");  // the last check of its body wins, as in the run
    // #2 left the population (an earlier champion, say): its own check by id.
    REQUIRE(loop_check_of(run, 2));
    CHECK(loop_check_of(run, 2)->verdict == "gone");
    // Unchecked bodies have no badge, whether members, the champion or strangers.
    CHECK(loop_check_of(run, 6) == nullptr);
    CHECK(loop_check_of(run, 4) == nullptr);
    // #3 is not in the population: its id's check, though #5 carries that body now.
    REQUIRE(loop_check_of(run, 3));
    CHECK(loop_check_of(run, 3)->verdict == "first");
}

TEST_CASE("studio loop checks: a change of the checks alone is described as what it sets") {
    evo::Experiment started = testing::tiny_experiment();
    std::vector<evo::RuleChange> changes(1);
    changes[0].generation = 4;
    changes[0].fitness = started.fitness;
    evo::LoopVerifySettings v;
    v.every_generations = 2;
    v.top_k = 1;
    v.policy = evo::VerifyPolicy::Penalise;
    changes[0].verify = v;
    CHECK(describe_rule_change(started, started.fitness, changes, 0) ==
          "CalculiX checks every 2 generations, top 1, policy penalise, tolerance 0.1");
    changes[0].fitness.constraints.min_fill_fraction = 0.05;
    CHECK(describe_rule_change(started, started.fitness, changes, 0) ==
          "min fill 0.05; CalculiX checks every 2 generations, top 1, policy penalise, "
          "tolerance 0.1");
    v.every_generations = 0;
    CHECK(describe_verify_settings(v) == "CalculiX checks off");
}

TEST_CASE("studio loop checks: the checks' settings go to the live run as a rule change; a "
          "refusal is the status's error and sends nothing") {
    const auto dir = fs::absolute(testing::fresh_dir("loop-checks-switch"));
    auto e = testing::tiny_experiment();
    e.evolution.generations = 30;  // stopped long before
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 1400);  // tall: the editor's Evolution section opened
    testing::run_script_patiently(session,
                                  json::parse(R"([{"click": "header Evolution"}, {"frames": 2},
                                                  {"click": "Start"},
                                                  {"wait_generations": 1},
                                                  {"click": "Pause"},
                                                  {"wait_run": "paused"},
                                                  {"frames": 2}])"));
    CHECK_FALSE(drawn_now(studio, "Apply checks to run"));  // nothing edited yet
    run_script(session, json::parse(R"([{"set": "evolution.verify.every_generations", "value": 1},
                                        {"set": "evolution.verify.top_k", "value": 1},
                                        {"frames": 2}])"));
    CHECK(verify_differs_from_run(studio));
    CHECK(drawn_now(studio, "edited rules"));
    CHECK(drawn_now(studio, "Apply checks to run"));
    CHECK(describe_rules_to_send(studio) ==
          "CalculiX checks every 1 generation, top 1, policy flag, tolerance 0.1");
    {
        // Checks where CalculiX cannot run: the run's own reason, as an error; nothing is sent.
        PathWithoutCcx no_ccx(dir / "empty-bin");
        CHECK_THROWS_WITH_AS(run_script(session, json::parse(R"([{"apply_rules": true}])")),
                             doctest::Contains("CalculiX (ccx) is not on the PATH"), ScriptError);
        CHECK(studio.ui.status_is_error);
        CHECK_MESSAGE(
            studio.ui.status.find("continuum checks were not changed") != std::string::npos,
            studio.ui.status);
        CHECK(studio.run.evolution.sent_verify() == nullptr);
        CHECK(verify_differs_from_run(studio));  // the edits wait in the editor
    }
    // Checks off, policy reject: nothing needs CalculiX, and the run takes it between
    // generations as a rule change, pending in the Run panel until then.
    run_script(session, json::parse(R"([{"set": "evolution.verify.every_generations", "value": 0},
                                        {"set": "evolution.verify.policy", "value": "reject"},
                                        {"apply_rules": true},
                                        {"frames": 2}])"));
    INFO("status: " << studio.ui.status);
    CHECK_FALSE(studio.ui.status_is_error);
    REQUIRE(studio.run.evolution.sent_verify());
    CHECK(studio.run.evolution.sent_verify()->policy == evo::VerifyPolicy::Reject);
    CHECK_FALSE(rules_differ_from_run(studio));
    CHECK_FALSE(drawn_now(studio, "edited rules"));
    CHECK_FALSE(drawn_now(studio, "Apply checks to run"));
    // Nothing left to send: the script step says so rather than pass silently.
    CHECK_THROWS_AS(run_script(session, json::parse(R"([{"apply_rules": true}])")), ScriptError);
    CHECK(drawn_now(studio, "loop checks pending"));
    const int at = studio.run.evolution.snapshot()->generation;
    CHECK(studio.run.evolution.snapshot()->experiment.evolution.verify.policy ==
          evo::VerifyPolicy::Flag);  // not before the next generation
    // The frozen generation finishes under the old settings; the next one is under the new.
    testing::run_script_patiently(
        session,
        json::array({{{"click", "Resume"}}, {{"wait_generations", at + 2}}, {{"frames", 2}}}));
    const auto run = studio.run.evolution.snapshot();
    CHECK(run->experiment.evolution.verify.policy == evo::VerifyPolicy::Reject);
    REQUIRE_FALSE(run->rule_changes.empty());
    CHECK(run->rule_changes.back().description == "CalculiX checks off");
    CHECK_FALSE(drawn_now(studio, "loop checks pending"));
    testing::run_script_patiently(session,
                                  json::parse(R"([{"click": "Stop"}, {"wait_run": "stopped"}])"));
    // run.json keeps the change with its "verify" block: a resumed run goes on under it.
    const evo::RunInfo info = evo::read_run_info((dir / "run").string());
    REQUIRE_FALSE(info.rule_changes.empty());
    REQUIRE(info.rule_changes.back().verify.has_value());
    CHECK(info.rule_changes.back().verify->policy == evo::VerifyPolicy::Reject);
    CHECK(info.current().evolution.verify.policy == evo::VerifyPolicy::Reject);
}

TEST_CASE("studio loop checks with CalculiX: checks turned on mid-run mark the checked bodies in "
          "the Run panel, the tables and the 3D view") {
    if (bhm::test::skip_without_ccx()) return;
    const auto dir = fs::absolute(testing::fresh_dir("loop-checks-ccx"));
    auto e = testing::tiny_experiment({4, 2, 2});
    e.evolution.generations = 6;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1280, 900);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                 {"wait_generations": 1},
                                 {"click": "Pause"},
                                 {"wait_run": "paused"},
                                 {"set": "evolution.verify.every_generations", "value": 1},
                                 {"set": "evolution.verify.top_k", "value": 1},
                                 {"frames": 2}])"));
    CHECK_FALSE(drawn_now(studio, "loop checks"));  // a run without checks has no line
    // Resume sends the edited checks, as it sends edited fitness rules.
    testing::run_script_patiently(session, json::parse(R"([{"click": "Resume"},
                                 {"wait_run": "finished"},
                                 {"click": "tab Population"}, {"frames": 3}])"));
    const auto run = studio.run.evolution.snapshot();
    REQUIRE(run);
    INFO("status: " << studio.ui.status << "; message: " << run->message);
    CHECK(run->experiment.evolution.verify.every_generations == 1);
    REQUIRE_FALSE(run->loop_checks.empty());
    CHECK(drawn_now(studio, "loop checks"));
    // Every checked member has its badge in the Population table, the others none.
    std::int64_t checked_id = -1;
    for (const auto& m : run->population) {
        const std::string name = "check #" + std::to_string(m.id);
        const evo::LoopCheck* check = loop_check_of(*run, m.id);
        CHECK(drawn_now(studio, name) == (check != nullptr));
        CHECK(m.check.has_value() == (check != nullptr));
        if (!check) continue;
        CHECK(*m.check == check->outcome);
        CHECK(m.check_worst == check->worst);
        if (checked_id < 0) checked_id = m.id;
    }
    // The best bodies are picked: one of them is still in the population.
    REQUIRE(checked_id >= 0);
    // Champions: the newest champion's row has the champion's badge.
    run_script(session, json::parse(R"([{"click": "tab Champions"}, {"frames": 40}])"));
    int champion_badges = 0;
    for (const auto& entry : studio.run.champion_history.entries()) {
        const bool checked = loop_check_of(*run, entry.id) != nullptr;
        CHECK(drawn_now(studio, "champion check gen " + std::to_string(entry.generation)) ==
              checked);
        champion_badges += checked;
    }
    CHECK(champion_badges >= 1);
    // The 3D view: a checked member shown with its badge over it; an unchecked one without.
    run_script(session, json::parse(R"([{"click": "tab Population"}, {"frames": 2}])"));
    REQUIRE(select_individual(studio, checked_id));
    testing::run_script_patiently(session, json::parse(R"([{"mode": "simulation"},
                                                           {"wait_simulation": true},
                                                           {"frames": 2}])"));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->id == checked_id);
    CHECK(drawn_now(studio, "view check badge"));
    for (const auto& m : run->population) {
        if (loop_check_of(*run, m.id)) continue;
        REQUIRE(select_individual(studio, m.id));
        testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                                               {"frames": 2}])"));
        CHECK(studio.bodies.shown->id == m.id);
        CHECK_FALSE(drawn_now(studio, "view check badge"));
        break;
    }
    // The change is kept as a rule change with its settings.
    const evo::RunInfo info = evo::read_run_info((dir / "run").string());
    CHECK(info.current().evolution.verify.every_generations == 1);
}
