// The byte messages the MPI front end carries: rules, jobs and results come back bit-identical
// (doubles included), and anything of another version, kind or length is refused by name.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/evaluation_wire.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

TEST_CASE("rules round-trip exactly, the paper experiments included") {
    RulesMessage m;
    m.rules_id = 0x0123456789abcdefULL;
    m.rules = test::tiny_experiment();
    m.rules.simulation.dt_fraction = 0.1 + 0.2;  // not exactly representable: must stay the same
    const auto back = decode_rules(encode_rules(m));
    CHECK(back.rules_id == m.rules_id);
    CHECK(back.rules == m.rules);
    for (const char* name : {"paper-exp1.json", "paper-exp1-attached.json", "paper-exp2.json",
                             "paper-exp3.json", "quick-demo.json", "biohybrid-catheter.json"}) {
        CAPTURE(name);
        m.rules = load_experiment(std::string(BHM_SOURCE_DIR) + "/assets/experiments/" + name);
        CHECK(decode_rules(encode_rules(m)).rules == m.rules);
    }
}

TEST_CASE("jobs carry the body cell for cell") {
    JobMessage m;
    m.batch_id = 42;
    m.rules_id = 7;
    m.index = 50;
    m.body.size = {3, 2, 2};
    m.body.cells = {0, 1, 2, 255, 0, 1, 1, 2, 0, 0, 3, 1};
    const auto back = decode_job(encode_job(m));
    CHECK(back.batch_id == 42);
    CHECK(back.rules_id == 7);
    CHECK(back.index == 50);
    CHECK(back.body == m.body);
    CHECK(back.body.fibre.empty());

    // Per-voxel fibre axes (issue 43) travel with the cells, byte for byte.
    m.body.fibre = {255, 0, 1, 2, 255, 2, 1, 0, 255, 255, 1, 2};
    CHECK(decode_job(encode_job(m)).body == m.body);
    m.body.fibre.pop_back();  // fibres and cells disagree
    CHECK_THROWS_AS(encode_job(m), WireError);
    m.body.fibre.clear();

    m.body.cells.pop_back();  // size and cells disagree
    CHECK_THROWS_AS(encode_job(m), WireError);
}

TEST_CASE("results keep every double bit for bit") {
    ResultMessage m;
    m.batch_id = 3;
    m.index = 9;
    m.report.fitness = 0.1 + 0.2;
    m.report.measures = {1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(), 1e300,
                         std::nextafter(2.0, 3.0)};
    m.report.diverged = true;
    m.report.divergence_reason = "voxel 12: \"speed\" > limit\n";
    m.report.simulated_s = 0.75;
    m.report.steps = 123456789012LL;
    m.report.sim_wall_s = 1.25;
    m.report.exploits.checked = true;  // issue 13's flags travel with the result too
    m.report.exploits.escaped = true;
    m.report.exploits.unanchored_fraction = 1.0 / 7.0;
    m.report.exploits.held_voxels = 12;
    m.report.exploits.tentacle = true;
    m.report.exploits.thin_share = 0.1 + 0.7;
    m.report.exploits.thin_voxels = 5;
    for (int k = 0; k < kBehaviourLength; ++k)  // novelty search needs it from every rank
        m.report.behaviour.push_back(std::nextafter(0.1 * k - 1.0, 5.0));
    const auto back = decode_result(encode_result(m));
    CHECK(back.report.exploits == m.report.exploits);
    CHECK(back.report.behaviour == m.report.behaviour);
    CHECK(back.batch_id == 3);
    CHECK(back.index == 9);
    CHECK(back.report.fitness == m.report.fitness);
    for (std::size_t k = 0; k < m.report.measures.size(); ++k) {
        CHECK(back.report.measures[k] == m.report.measures[k]);
        CHECK(std::signbit(back.report.measures[k]) == std::signbit(m.report.measures[k]));
    }
    CHECK(back.report.diverged);
    CHECK(back.report.divergence_reason == m.report.divergence_reason);
    CHECK(back.report.simulated_s == 0.75);
    CHECK(back.report.steps == 123456789012LL);
}

TEST_CASE("other versions, kinds, truncations and garbage are refused by name") {
    JobMessage job;
    job.body.size = {1, 1, 1};
    job.body.cells = {1};
    std::string bytes = encode_job(job);

    std::string other_version = bytes;
    other_version[4] = static_cast<char>(kEvaluationWireVersion + 1);
    CHECK_THROWS_WITH_AS(decode_job(other_version), doctest::Contains("wire version"), WireError);
    // Version 1 results had no behaviour descriptor: a rank of that build is refused, not misread.
    static_assert(kEvaluationWireVersion == 3);
    std::string version_1 = encode_result(ResultMessage{});
    version_1[4] = 1;
    CHECK_THROWS_WITH_AS(decode_result(version_1), doctest::Contains("wire version 1"), WireError);
    CHECK_THROWS_WITH_AS(decode_result(bytes), doctest::Contains("kind"), WireError);
    CHECK_THROWS_WITH_AS(decode_job(bytes.substr(0, bytes.size() - 1)),
                         doctest::Contains("truncated"), WireError);
    CHECK_THROWS_WITH_AS(decode_job(bytes + "x"), doctest::Contains("trailing"), WireError);
    CHECK_THROWS_WITH_AS(decode_job("hello"), doctest::Contains("not a BHM"), WireError);

    ResultMessage result;
    std::string text = encode_result(result);
    CHECK_THROWS_WITH_AS(decode_result(text.substr(0, text.size() - 2)),
                         doctest::Contains("bad JSON"), WireError);
    RulesMessage rules;
    rules.rules = test::tiny_experiment();
    text = encode_rules(rules);
    const auto at = text.find("\"population\":6");
    REQUIRE(at != std::string::npos);
    text.replace(at, 14, "\"population\":0");  // parses, but is not a valid experiment
    CHECK_THROWS_WITH_AS(decode_rules(text), doctest::Contains("population"), WireError);
}
