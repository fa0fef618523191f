// The controller genome (issue 44; evo/genome/controller.hpp): its JSON round trip, the output
// maps and the built-in controllers against values worked out by hand, a body's controller through
// the body file, the hash, the engine input and the MPI wire, fixed_controllers' mean, and the
// experiment file's evolution.controller with one line per bad field.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/evaluation_wire.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/body_ops.hpp"
#include "evo/genome/controller.hpp"
#include "evo/run/cached_evaluation.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;
using nlohmann::json;

namespace {

constexpr double kPi = std::numbers::pi;

//! A controller without hidden nodes: phase output = w_phase * bias, amplitude = w_amp * bias.
Genome bias_controller(double w_phase, double w_amplitude) {
    Genome g;
    g.output_count = kControllerOutputCount;
    g.edges = {{kInputBias, kInputCount, w_phase}, {kInputBias, kInputCount + 1, w_amplitude}};
    return g;
}

//! A 4 x 1 x 1 bar: active, active, passive, active.
Body bar() {
    Body b;
    b.size = {4, 1, 1};
    b.cells = {2, 2, 1, 2};
    return b;
}

std::vector<Problem> problems_of(const json& j) {
    try {
        parse_experiment(j, "e.json");
    } catch (const ValidationError& e) {
        return e.problems;
    }
    return {};
}

bool names(const std::vector<Problem>& problems, const std::string& field) {
    for (const auto& p : problems)
        if (p.field == field) return true;
    return false;
}

}  // namespace

TEST_CASE("a controller genome round-trips through controller.json") {
    Rng rng(11);
    CppnSettings settings;
    for (int k = 0; k < 5; ++k) {
        const Genome g = random_controller(settings, rng);
        CHECK(g.output_count == 2);
        const std::string text = controller_to_json(g).dump(2);
        const json parsed = json::parse(text);
        CHECK(parsed["format"] == "bhm-controller");
        CHECK(parsed["genome"]["outputs"] == json({"phase", "amplitude"}));
        CHECK(controller_from_json(parsed, settings.weight_range) == g);
    }
    SUBCASE("a body genome or a wrong format is refused naming the field") {
        json j = controller_to_json(bias_controller(0.1, 0.2));
        j["genome"] = genome_to_json(random_genome(settings, rng, 3));  // a body's, 3 outputs
        CHECK_THROWS_WITH_AS(controller_from_json(j, 1.0), doctest::Contains("outputs"),
                             std::invalid_argument);
        j = controller_to_json(bias_controller(0.1, 0.2));
        j["format"] = "bhm-genome";
        CHECK_THROWS_WITH_AS(controller_from_json(j, 1.0), doctest::Contains("controller.format"),
                             std::invalid_argument);
    }
}

TEST_CASE("the controller's outputs map onto phase and amplitude as documented") {
    // phase = pi o wrapped onto [-pi, pi]; amplitude = clamp((1 + o) / 2, 0, 1).
    CHECK(controller_phase(0.5) == doctest::Approx(kPi / 2));
    CHECK(controller_phase(-0.25) == doctest::Approx(-kPi / 4));
    CHECK(controller_phase(1.5) == doctest::Approx(-kPi / 2));  // 3 pi / 2 is -pi / 2
    CHECK(controller_amplitude(-0.2) == doctest::Approx(0.4));
    CHECK(controller_amplitude(-3.0) == 0.0f);
    CHECK(controller_amplitude(2.0) == 1.0f);

    const auto e = test::tiny_experiment();
    Body b = bar();
    paint_controller(bias_controller(0.5, -0.2), e.materials, b);
    REQUIRE(b.phase.size() == 4u);
    REQUIRE(b.amplitude.size() == 4u);
    for (int c : {0, 1, 3}) {  // active: the bias's outputs
        CHECK(b.phase[c] == doctest::Approx(kPi / 2));
        CHECK(b.amplitude[c] == doctest::Approx(0.4));
    }
    CHECK(b.phase[2] == 0.0f);  // passive: not driven
    CHECK(b.amplitude[2] == 1.0f);
}

TEST_CASE("built-in controllers: uniform, wave along x and a seeded random") {
    const auto e = test::tiny_experiment();
    Body b = bar();
    paint_builtin_controller("wave", 1, e.materials, b);
    // x = 0..3 over a length of 4: 0, pi/2, (passive), 3 pi/2 = -pi/2.
    CHECK(b.phase[0] == doctest::Approx(0.0));
    CHECK(b.phase[1] == doctest::Approx(kPi / 2));
    CHECK(b.phase[2] == 0.0f);
    CHECK(b.phase[3] == doctest::Approx(-kPi / 2));
    for (float a : b.amplitude)
        CHECK(a == 1.0f);
    paint_builtin_controller("uniform", 1, e.materials, b);
    for (float p : b.phase)
        CHECK(p == 0.0f);
    Body r1 = bar(), r2 = bar(), r3 = bar();
    paint_builtin_controller("random", 5, e.materials, r1);
    paint_builtin_controller("random", 5, e.materials, r2);
    paint_builtin_controller("random", 6, e.materials, r3);
    CHECK(r1.phase == r2.phase);
    CHECK(r1.phase != r3.phase);
    for (float p : r1.phase)
        CHECK((p >= -kPi && p < kPi));
    CHECK_THROWS_AS(paint_builtin_controller("sine", 1, e.materials, b), std::invalid_argument);
}

TEST_CASE("a body's controller: body file, hash, engine input and wire keep it bit for bit") {
    auto e = test::tiny_experiment();
    Body b = bar();
    paint_controller(bias_controller(0.3, 0.1), e.materials, b);
    b.phase[1] = -2.9f;
    b.amplitude[3] = 0.123456789f;

    const Body read = parse_body(json::parse(body_to_json(b).dump()), "b.json");
    CHECK(read == b);

    Body plain = bar();
    CHECK(hash_body(plain) != hash_body(b));
    Body other = b;
    other.amplitude[3] = 0.5f;
    CHECK(hash_body(other) != hash_body(b));

    e.workspace_size = {4, 1, 1};
    e.actuation.phase_offset_rad = 0.25;
    const auto framed = apply_frame_and_overrides(e, b);
    const auto spec = make_body_spec(e, framed);
    REQUIRE(spec.phase_rad.size() == 4u);
    CHECK(spec.phase_rad[1] == doctest::Approx(-2.9 + 0.25));
    CHECK(spec.amplitude_scale == b.amplitude);
    // Without a controller: the experiment's uniform phase and no amplitude scale, as before.
    const auto plain_spec = make_body_spec(e, apply_frame_and_overrides(e, plain));
    CHECK(plain_spec.amplitude_scale.empty());

    JobMessage job;
    job.body = b;
    CHECK(decode_job(encode_job(job)).body == b);
    job.body = plain;
    CHECK(decode_job(encode_job(job)).body == plain);

    SUBCASE("a controller out of range in a body file names the field") {
        json j = body_to_json(b);
        j["controller"]["amplitude"][0] = 1.5;
        CHECK_THROWS_WITH_AS(parse_body(j, "b.json"), doctest::Contains("controller.amplitude[0]"),
                             ValidationError);
        j = body_to_json(b);
        j["controller"]["phase_rad"] = json::array({0.0});
        CHECK_THROWS_WITH_AS(parse_body(j, "b.json"), doctest::Contains("controller.phase_rad"),
                             ValidationError);
    }
}

TEST_CASE("fixed_controllers' result is the mean over the controllers") {
    FitnessReport a, b;
    a.measures = {1, 2, 3, 4, 5};
    b.measures = {3, 2, 1, 0, 15};
    a.steps = 10;
    b.steps = 30;
    Fitness rules;
    rules.measure = FitnessMeasure::BendAngleDeg;
    const FitnessReport reports[] = {a, b};
    const FitnessReport mean = mean_over_controllers(reports, rules);
    CHECK(mean.measures[0] == 2.0);
    CHECK(mean.measures[4] == 10.0);
    CHECK(mean.fitness == 10.0);
    CHECK(mean.steps == 40);
    CHECK_FALSE(mean.diverged);
    b.diverged = true;
    const FitnessReport with_diverged[] = {a, b};
    CHECK(mean_over_controllers(with_diverged, rules).fitness == kDivergedFitness);
}

TEST_CASE("fixed_controllers: exploit flags are the union, behaviour the mean over controllers") {
    FitnessReport a, b, c;
    for (FitnessReport* r : {&a, &b, &c}) {
        r->exploits.checked = true;
        r->behaviour.assign(kBehaviourLength, 0.0);
    }
    // a: clean; b: detached motion (ratio 0.1); c: a tentacle (share 0.8) and the most motion.
    a.exploits.base_motion_ratio = 0.9, a.exploits.thin_share = 0.1, a.exploits.motion_voxels = 1;
    b.exploits.detached_motion = true, b.exploits.base_motion_ratio = 0.1;
    b.exploits.motion_voxels = 2;
    c.exploits.tentacle = true, c.exploits.thin_share = 0.8, c.exploits.thin_voxels = 3;
    c.exploits.motion_voxels = 4;
    a.behaviour[0] = 1.0, b.behaviour[0] = 2.0, c.behaviour[0] = 6.0;
    c.behaviour[5] = -3.0;
    Fitness rules;
    const FitnessReport reports[] = {a, b, c};
    const FitnessReport mean = mean_over_controllers(reports, rules);
    CHECK(mean.exploits.checked);
    CHECK_FALSE(mean.exploits.escaped);
    CHECK(mean.exploits.detached_motion);
    CHECK(mean.exploits.base_motion_ratio == 0.1);  // the measure of the run that raised it
    CHECK(mean.exploits.tentacle);
    CHECK(mean.exploits.thin_share == 0.8);
    CHECK(mean.exploits.thin_voxels == 3);
    CHECK(mean.exploits.motion_voxels == 4.0);
    REQUIRE(mean.behaviour.size() == static_cast<std::size_t>(kBehaviourLength));
    CHECK(mean.behaviour[0] == doctest::Approx(3.0));
    CHECK(mean.behaviour[5] == doctest::Approx(-1.0));
    CHECK(mean.behaviour[1] == 0.0);
    // A reject_* constraint sees the union: the body is invalid though the first run was clean.
    rules.constraints.reject_tentacle = true;
    CHECK(mean_over_controllers(reports, rules).fitness == kInvalidFitness);
    // A run without a descriptor (diverged): none for the body, as for one diverged run.
    c.behaviour.clear();
    const FitnessReport without[] = {a, b, c};
    CHECK(mean_over_controllers(without, rules).behaviour.empty());
    // One controller: its own report, bit for bit (the mode with a single controller unchanged).
    b.behaviour[3] = 0.1 + 0.2;
    const FitnessReport one[] = {b};
    const FitnessReport alone = mean_over_controllers(one, Fitness{});
    CHECK(alone.exploits == b.exploits);
    CHECK(alone.behaviour == b.behaviour);
    CHECK(alone.measures == b.measures);
}

TEST_CASE("evolution.controller in the experiment file: round trip and one line per bad field") {
    auto e = test::tiny_experiment();
    CHECK_FALSE(experiment_to_json(e)["evolution"].contains("controller"));  // none: as before

    e.evolution.controller.mode = ControllerMode::FixedControllers;
    e.evolution.controller.controllers = {{"uniform", 1, ""}, {"random", 9, ""}, {"wave", 1, ""}};
    ControllerEntry file;
    file.name = "c.json";
    file.genome_json = controller_to_json(bias_controller(0.2, 0.4)).dump();
    e.evolution.controller.controllers.push_back(file);
    const json j = experiment_to_json(e);
    CHECK(parse_experiment(json::parse(j.dump()), "e.json") == e);

    auto fixed = test::tiny_experiment();
    fixed.evolution.controller.mode = ControllerMode::FixedBody;
    fixed.evolution.controller.body = bar();
    const auto back = parse_experiment(experiment_to_json(fixed), "e.json");
    CHECK(back == fixed);

    json bad = experiment_to_json(test::tiny_experiment());
    bad["evolution"]["controller"] = {{"mode", "fixed_body"}};
    CHECK(names(problems_of(bad), "evolution.controller.body"));
    bad["evolution"]["controller"] = {{"mode", "fixed_controllers"}};
    CHECK(names(problems_of(bad), "evolution.controller.controllers"));
    bad["evolution"]["controller"] = {{"mode", "fixed_controllers"}, {"controllers", {"sine"}}};
    CHECK(names(problems_of(bad), "evolution.controller.controllers[0]"));
    bad["evolution"]["controller"] = {{"mode", "fixed_controllers"},
                                      {"controllers", {{{"builtin", "randm"}}}}};
    CHECK(names(problems_of(bad), "evolution.controller.controllers[0].builtin"));
    bad["evolution"]["controller"] = {{"mode", "coevolv"}};
    CHECK(names(problems_of(bad), "evolution.controller.mode"));
    bad["evolution"]["controller"] = {{"mode", "none"}, {"controllers", {"uniform"}}};
    CHECK(names(problems_of(bad), "evolution.controller.controllers"));
    bad["evolution"]["controller"] = {{"mode", "fixed_body"},
                                      {"body", {{"size", {9, 1, 1}}, {"layers", {"222222222"}}}}};
    const auto too_big = problems_of(bad);
    REQUIRE_FALSE(too_big.empty());
    CHECK(too_big.front().field.rfind("evolution.controller.body", 0) == 0);
    bad["evolution"]["controller"] = {{"mode", "none"}, {"colour", 1}};
    CHECK(names(problems_of(bad), "evolution.controller.colour"));
}
