// HyperNEAT (evolution.algorithm = "hyperneat", issue 44): the substrate's weights are exactly its
// CPPN's outputs at each connection's two ends, thresholded; its activation is the documented one
// (docs/hyperneat.md), checked against values worked out by hand; runs evolve controllers and
// bodies through it and resume into their uninterrupted twins; a controller run's controller.json
// drives its body as the run did and other bodies through their own substrate; bad fields are
// named.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/body_ops.hpp"
#include "evo/genome/controller.hpp"
#include "evo/genome/hyperneat_substrate.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"

using namespace bhm::evo;

namespace {

enum Query : int { kXa = 0, kYa, kZa, kXb, kYb, kZb, kD, kBias };

//! A HyperNEAT CPPN with no hidden node: output j = sum of weight * input over `edges` {input,
//! output j, weight}; outputs = 2 + output sheets.
Genome hand_cppn(int outputs, std::vector<std::array<double, 3>> edges) {
    Genome g;
    g.input_count = kHyperNeatInputCount;
    g.output_count = outputs;
    for (const auto& e : edges)
        g.edges.push_back(
            {static_cast<int>(e[0]), kHyperNeatInputCount + static_cast<int>(e[1]), e[2]});
    return g;
}

Experiment hyperneat_experiment(ControllerMode mode) {
    auto e = test::tiny_experiment();
    e.evolution.algorithm = Algorithm::HyperNeat;
    e.evolution.population = 4;
    e.evolution.controller.mode = mode;
    if (mode == ControllerMode::FixedBody) {
        Body b;  // a 3 x 3 x 2 body: an active core on a passive slab
        b.size = {3, 3, 2};
        b.cells = {1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 1, 2, 1};
        e.evolution.controller.body = b;
    }
    return e;
}

}  // namespace

TEST_CASE("HyperNEAT's substrate weights follow its CPPN: weight = x_a - x_b, thresholded") {
    // Four cells along x: node coordinates -1, -1/3, 1/3, 1; radius 1 connects each node to
    // itself and its neighbours: 2 + 3 + 3 + 2 connections.
    HyperNeatSettings s;
    s.radius = 1;
    s.weight_threshold = 0.5;
    const HyperNeatSubstrate substrate({4, 1, 1}, 2, s);
    REQUIRE(substrate.connection_count() == 10u);
    // Output 0 = x_a - x_b, output 2 = y_b + 0.3 (always 0.3: one cell along y), others 0.
    const Genome cppn =
        hand_cppn(4, {{kXa, 0, 1.0}, {kXb, 0, -1.0}, {kYb, 2, 1.0}, {kBias, 2, 0.3}});
    const SubstrateWeights w = substrate.weights(cppn);
    REQUIRE(w.weights.size() == 4u);
    int expressed = 0;
    for (std::size_t p = 0; p < w.source.size(); ++p) {
        const int a = w.source[p], b = w.target[p];
        CHECK(std::abs(a - b) <= 1);
        const double xa = -1.0 + 2.0 * a / 3.0, xb = -1.0 + 2.0 * b / 3.0;
        const double expected = std::fabs(xa - xb) >= 0.5 ? xa - xb : 0.0;
        CHECK(w.weights[0][p] == doctest::Approx(expected).epsilon(1e-15));
        CHECK(w.weights[1][p] == 0.0);
        CHECK(w.weights[2][p] == 0.0);  // 0.3 < 0.5: below the threshold, no connection
        CHECK(w.weights[3][p] == 0.0);
        expressed += w.weights[0][p] != 0.0;
    }
    CHECK(expressed == 6);  // every neighbour pair (|dx| = 2/3), never a node to itself

    s.weight_threshold = 0.7;  // above 2/3: nothing is expressed
    const SubstrateWeights none = HyperNeatSubstrate({4, 1, 1}, 2, s).weights(cppn);
    for (double v : none.weights[0])
        CHECK(v == 0.0);
    s.weight_threshold = 0.25;  // below 0.3: output 2 is expressed everywhere
    const SubstrateWeights all = HyperNeatSubstrate({4, 1, 1}, 2, s).weights(cppn);
    for (double v : all.weights[2])
        CHECK(v == doctest::Approx(0.3).epsilon(1e-15));
}

TEST_CASE("HyperNEAT's substrate activates as documented: steps of tanh, identity outputs") {
    // Two cells along x, every pair connected (2 x 2), threshold 0 (all expressed).
    HyperNeatSettings s;
    s.radius = 1;
    s.steps = 2;
    s.weight_threshold = 0.0;
    const HyperNeatSubstrate substrate({2, 1, 1}, 2, s);
    REQUIRE(substrate.connection_count() == 4u);
    // w_IH = 0.5, w_HH = 0.25, w_HO0 = 1, w_HO1 = x_a.
    const Genome cppn =
        hand_cppn(4, {{kBias, 0, 0.5}, {kBias, 1, 0.25}, {kBias, 2, 1.0}, {kXa, 3, 1.0}});
    // By hand: each hidden node sums two inputs of 1 x 0.5; h1 = tanh(1); h2 = tanh(1 + 2 x 0.25
    // h1); o0 = 2 h2 at both nodes; o1 = (-1 + 1) h2 = 0.
    const double h1 = std::tanh(1.0), h2 = std::tanh(1.0 + 0.5 * h1);
    const auto out = substrate.activate(cppn);
    REQUIRE(out.size() == 2u);
    for (int c = 0; c < 2; ++c) {
        CHECK(out[0][static_cast<std::size_t>(c)] == doctest::Approx(2.0 * h2).epsilon(1e-14));
        CHECK(out[1][static_cast<std::size_t>(c)] == doctest::Approx(0.0));
    }
    CHECK_THROWS_AS(substrate.activate(hand_cppn(3, {})), std::invalid_argument);  // 1 sheet short
}

TEST_CASE("a HyperNEAT CPPN round-trips through JSON with its eight inputs") {
    const Genome g = hand_cppn(4, {{kXa, 0, 1.0}, {kD, 3, -0.5}});
    const auto json = genome_to_json(g);
    CHECK(json["inputs"].size() == 8u);
    CHECK(json["outputs"][1] == "w_hidden_hidden");
    CHECK(genome_from_json(json, 1.0) == g);
    auto bad = json;
    bad["inputs"] = {"x", "y"};
    CHECK_THROWS_WITH_AS(genome_from_json(bad, 1.0), doctest::Contains("genome.inputs"),
                         std::invalid_argument);
    // It paints a substrate, not a lattice: not a controller file.
    CHECK_THROWS_WITH_AS(controller_from_json(genome_to_json(hand_cppn(2, {})), 1.0),
                         doctest::Contains("controller.genome.inputs"), std::invalid_argument);
}

TEST_CASE("HyperNEAT evolves controllers for a fixed body and bodies, through its substrate") {
    {
        const auto e = hyperneat_experiment(ControllerMode::FixedBody);
        const Developer developer(e);
        CHECK(developer.cppn_input_count() == kHyperNeatInputCount);
        CHECK(developer.cppn_output_count() == 2 + kControllerOutputCount);
        EvolutionRun run(e, test::run_options(3, 2));
        run.run();
        const Body framed = apply_frame_and_overrides(e, *e.evolution.controller.body);
        for (const Individual& m : run.state().population) {
            CHECK(m.genome.input_count == kHyperNeatInputCount);
            CHECK(m.phenotype.body.cells == framed.cells);  // the body is left bit-identical
            // The controller is the substrate's two outputs, mapped as a controller CPPN's.
            Body expected = framed;
            const auto out = developer.substrate()->activate(m.genome);
            paint_controller_outputs(out[0], out[1], e.materials, expected);
            CHECK(m.phenotype.body.phase == expected.phase);
            CHECK(m.phenotype.body.amplitude == expected.amplitude);
        }
    }
    {
        const auto e = hyperneat_experiment(ControllerMode::None);
        const Developer developer(e);
        CHECK(developer.cppn_output_count() == 2 + kOutputCount);
        EvolutionRun run(e, test::run_options(3, 2));
        run.run();
        for (const Individual& m : run.state().population) {
            CHECK(m.genome.input_count == kHyperNeatInputCount);
            CHECK(m.phenotype == developer.develop(m.genome));
        }
    }
}

TEST_CASE("HyperNEAT runs resume into their uninterrupted twins (controller and body)") {
    for (ControllerMode mode : {ControllerMode::FixedBody, ControllerMode::None}) {
        const std::string name = kControllerModeNames[static_cast<std::size_t>(mode)];
        CAPTURE(name);
        const auto whole = test::fresh_dir("hyperneat", name + "-whole"),
                   parts = test::fresh_dir("hyperneat", name + "-parts");
        test::check_twins_equal(
            test::run_twins(hyperneat_experiment(mode), whole.string(), parts.string(), 3, 2, 1));
        // controller.json holds the champion's HyperNEAT CPPN and its substrate, for a controller
        // run only ("a HyperNEAT controller file drives ..." below).
        CHECK(std::filesystem::exists(whole / kControllerFile) ==
              (mode == ControllerMode::FixedBody));
        CHECK(std::filesystem::exists(whole / "champion.json"));
    }
}

TEST_CASE("a HyperNEAT controller file drives its run's body as the run did, and other bodies") {
    const auto e = hyperneat_experiment(ControllerMode::FixedBody);
    const auto dir = test::fresh_dir("hyperneat", "controller-file");
    RunOptions options = test::run_options(3, 2);
    options.out_dir = dir.string();
    EvolutionRun run(e, options);
    run.run();
    REQUIRE(run.state().champion);
    const auto& champion = run.state().champion->individual;

    // The run directory is a controller item of `bhm robustness`, read from its controller.json.
    const RobustnessController item =
        resolve_robustness_controller(dir.string(), e.evolution.cppn.weight_range);
    const auto program = controller_program_from_json(nlohmann::json::parse(item.entry.genome_json),
                                                      e.evolution.cppn.weight_range);
    REQUIRE(program.substrate);
    CHECK(*program.substrate == e.evolution.hyperneat);
    CHECK(program.genome == champion.genome);
    // On the run's own body: the champion's phases and amplitudes, bit for bit.
    const Body cell = robustness_cell_body(e, *e.evolution.controller.body, item.entry);
    CHECK(cell.phase == champion.phenotype.body.phase);
    CHECK(cell.amplitude == champion.phenotype.body.amplitude);

    // On a body of another size: the substrate laid over that body's lattice.
    Body other;
    other.size = {4, 2, 2};
    other.cells = {2, 2, 1, 1, 2, 2, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    Body painted = apply_frame_and_overrides(e, other);
    Body expected = painted;
    paint_controller_program(program, e.materials, painted);
    const HyperNeatSubstrate substrate(expected.size, kControllerOutputCount,
                                       e.evolution.hyperneat);
    const auto out = substrate.activate(program.genome);
    paint_controller_outputs(out[0], out[1], e.materials, expected);
    CHECK(painted.phase == expected.phase);
    CHECK(painted.amplitude == expected.amplitude);

    // A coevolved controller is a lattice CPPN: its reader refuses a substrate's CPPN.
    const auto json = nlohmann::json::parse(item.entry.genome_json);
    CHECK_THROWS_WITH_AS(controller_from_json(json, 1.0),
                         doctest::Contains("controller.genome.inputs"), std::invalid_argument);
    // Bad substrate fields are named.
    const auto refused = [&](const char* field, nlohmann::json value) {
        auto j = json;
        j["substrate"][field] = value;
        const std::string named = std::string("controller.substrate.") + field;
        CHECK_THROWS_WITH_AS(controller_program_from_json(j, 1.0),
                             doctest::Contains(named.c_str()), std::invalid_argument);
    };
    refused("radius", 0);
    refused("steps", "three");
    refused("weight_threshold", -1.0);
    auto lattice_cppn = json;
    Rng rng(3);
    lattice_cppn["genome"] = genome_to_json(random_controller(e.evolution.cppn, rng));
    CHECK_THROWS_WITH_AS(controller_program_from_json(lattice_cppn, 1.0),
                         doctest::Contains("controller.genome.inputs"), std::invalid_argument);
}

TEST_CASE("evolution.hyperneat round-trips and its bad fields are named") {
    auto e = hyperneat_experiment(ControllerMode::None);
    e.evolution.hyperneat.radius = 2;
    e.evolution.hyperneat.steps = 4;
    e.evolution.hyperneat.weight_threshold = 0.1;
    const auto json = experiment_to_json(e);
    CHECK(json["evolution"]["algorithm"] == "hyperneat");
    CHECK(parse_experiment(json, "x.json") == e);
    // Other algorithms' files stay as they were: no hyperneat block at its defaults.
    CHECK_FALSE(experiment_to_json(test::tiny_experiment())["evolution"].contains("hyperneat"));

    const auto refused = [&](const char* field, nlohmann::json value, const char* named) {
        auto j = json;
        j["evolution"]["hyperneat"][field] = value;
        try {
            parse_experiment(j, "exp.json");
            FAIL("accepted evolution.hyperneat." << field << " = " << value.dump());
        } catch (const ValidationError& error) {
            const std::string message = error.what();
            CHECK(message.find('\n') == std::string::npos);
            CHECK(message.find(named) != std::string::npos);
        }
    };
    refused("radius", 0, "exp.json:evolution.hyperneat.radius");
    refused("steps", 0, "exp.json:evolution.hyperneat.steps");
    refused("weight_threshold", -0.5, "exp.json:evolution.hyperneat.weight_threshold");
    refused("radius", "wide", "exp.json:evolution.hyperneat.radius");
    // The cost limit: a 40 x 40 x 40 workspace at radius 2 is 64000 x 125 = 8e6 connections.
    auto big = json;
    big["workspace"]["size"] = {40, 40, 40};
    big["evolution"]["hyperneat"]["radius"] = 2;
    CHECK_THROWS_WITH_AS(parse_experiment(big, "exp.json"),
                         doctest::Contains("evolution.hyperneat.radius"), ValidationError);
}
