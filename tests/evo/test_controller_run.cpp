// evolution.controller's modes end to end on the tiny workspace (issue 44): a fixed-body run
// leaves the body bit-identical and writes its champion's controller.json; a coevolve run carries
// a controller per member; fixed_controllers' fitness is the mean of plain evaluations under each
// controller; the GA keeps its elite; and each mode's stopped-then-resumed run equals its
// uninterrupted twin.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/controller.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

namespace {

//! A 3 x 3 x 2 body: an active core on a passive slab, on the tiny workspace's x- face.
Body fixed_body() {
    Body b;
    b.size = {3, 3, 2};
    b.cells = {1, 1, 1, 1, 1, 1, 1, 1, 1,  // z = 0
               2, 2, 2, 2, 2, 2, 1, 2, 1};
    return b;
}

Experiment fixed_body_experiment() {
    auto e = test::tiny_experiment();
    e.evolution.controller.mode = ControllerMode::FixedBody;
    e.evolution.controller.body = fixed_body();
    e.evolution.population = 4;
    return e;
}

Experiment coevolve_experiment() {
    auto e = test::tiny_experiment();
    e.evolution.controller.mode = ControllerMode::Coevolve;
    e.evolution.population = 4;
    return e;
}

Experiment fixed_controllers_experiment() {
    auto e = test::tiny_experiment();
    e.evolution.controller.mode = ControllerMode::FixedControllers;
    e.evolution.controller.controllers = {{"uniform", 1, ""}, {"wave", 1, ""}};
    e.evolution.population = 4;
    return e;
}

void check_twins(const Experiment& e, const std::string& name) {
    const fs::path whole = test::fresh_dir("controller", name + "-whole"),
                   parts = test::fresh_dir("controller", name + "-parts");
    test::check_twins_equal(test::run_twins(e, whole.string(), parts.string(), 3, 2, 1));
}

}  // namespace

TEST_CASE("a fixed-body run evolves only the controller: the body stays bit-identical") {
    const auto e = fixed_body_experiment();
    const fs::path dir = test::fresh_dir("controller", "fixed-body");
    EvolutionRun run(e, test::run_options(3, 2, dir.string()));
    run.run();
    const Body framed = apply_frame_and_overrides(e, fixed_body());
    const auto reference = make_body_spec(e, framed);
    auto members = run.state().population;
    members.push_back(run.state().champion->individual);
    bool phases_differ = false;
    for (const Individual& m : members) {
        CHECK(m.genome.output_count == kControllerOutputCount);
        CHECK(m.phenotype.body.cells == framed.cells);
        CHECK(m.phenotype.body.fibre == framed.fibre);
        const auto spec = make_body_spec(e, m.phenotype.body);
        // The engine input's bytes of the body itself: cells, held cells, fibres, materials.
        CHECK(spec.material == reference.material);
        CHECK(spec.fixed == reference.fixed);
        CHECK(spec.fibre_axis == reference.fibre_axis);
        CHECK(spec.materials == reference.materials);
        REQUIRE(m.phenotype.body.has_controller());
        phases_differ = phases_differ || m.phenotype.body.phase != members[0].phenotype.body.phase;
    }
    CHECK(phases_differ);  // what evolved is the controller

    // controller.json: the champion's genome, reusable: it paints another body.
    std::ifstream in(dir / kControllerFile);
    REQUIRE(in);
    const auto controller = controller_from_json(nlohmann::json::parse(in), 1.0);
    CHECK(controller == run.state().champion->individual.genome);
    Body other;
    other.size = {4, 1, 1};
    other.cells = {2, 2, 2, 2};
    paint_controller(controller, e.materials, other);
    CHECK(other.phase.size() == 4u);
    // champion.json's body carries the controller the champion was simulated with.
    std::ifstream champion(dir / "champion.json");
    const auto record = nlohmann::json::parse(champion);
    const Body saved = parse_body(record["phenotype"], "champion.json");
    CHECK(saved == run.state().champion->individual.phenotype.body);
}

TEST_CASE("a coevolve run carries a body and a controller per member") {
    const auto e = coevolve_experiment();
    EvolutionRun run(e, test::run_options(3, 2));
    run.run();
    for (const Individual& m : run.state().population) {
        CHECK(m.genome.output_count == kOutputCount);
        CHECK(m.controller.output_count == kControllerOutputCount);
        CHECK_FALSE(m.controller.edges.empty());
        // The phenotype is the body CPPN's body painted by the controller CPPN.
        Body expected = m.phenotype.body;
        paint_controller(m.controller, e.materials, expected);
        CHECK(m.phenotype.body == expected);
        CHECK(m.phenotype.body.has_controller());
    }
}

TEST_CASE("fixed_controllers: a body's fitness is the mean of its plain evaluations") {
    const auto e = fixed_controllers_experiment();
    EvolutionRun run(e, test::run_options(2, 2));
    run.run();
    const Individual& champion = run.state().champion->individual;
    CHECK_FALSE(champion.phenotype.body.has_controller());
    double sum = 0.0;
    for (const auto& entry : e.evolution.controller.controllers) {
        Body painted = champion.phenotype.body;
        paint_controller_entry(entry, 1.0, e.materials, painted);
        sum += evaluate_body(e, painted).fitness;
    }
    CHECK(champion.report.fitness == doctest::Approx(sum / 2.0).epsilon(1e-12));
}

TEST_CASE("the GA keeps its elite: the best fitness never drops") {
    auto e = test::tiny_experiment();
    e.evolution.algorithm = Algorithm::Ga;
    e.evolution.population = 5;
    EvolutionRun run(e, test::run_options(4, 2));
    run.run();
    const auto& h = run.state().history;
    REQUIRE(h.size() == 4u);
    for (std::size_t g = 1; g < h.size(); ++g)
        CHECK(h[g].best_fitness >= h[g - 1].best_fitness);
    CHECK(run.state().population.size() == 5u);
}

TEST_CASE("each controller mode and the GA resume into their uninterrupted twins") {
    SUBCASE("fixed_body") {
        check_twins(fixed_body_experiment(), "fixed-body");
    }
    SUBCASE("coevolve") {
        check_twins(coevolve_experiment(), "coevolve");
    }
    SUBCASE("fixed_controllers") {
        check_twins(fixed_controllers_experiment(), "fixed-controllers");
    }
    SUBCASE("ga") {
        auto e = test::tiny_experiment();
        e.evolution.algorithm = Algorithm::Ga;
        e.evolution.population = 4;
        check_twins(e, "ga");
    }
}

TEST_CASE("NEAT, novelty search and the GA evolve controllers too, in fixed_body and coevolve") {
    for (Algorithm algorithm : {Algorithm::Neat, Algorithm::Novelty, Algorithm::Ga}) {
        CAPTURE(kAlgorithmNames[static_cast<std::size_t>(algorithm)]);
        auto fixed = fixed_body_experiment();
        fixed.evolution.algorithm = algorithm;
        fixed.evolution.novelty.k = 2;
        EvolutionRun run(fixed, test::run_options(3, 2));
        run.run();
        const Body framed = apply_frame_and_overrides(fixed, fixed_body());
        for (const Individual& m : run.state().population) {
            CHECK(m.genome.output_count == kControllerOutputCount);
            CHECK(m.phenotype.body.cells == framed.cells);
            CHECK(m.phenotype.body.has_controller());
        }
        auto coevolve = coevolve_experiment();
        coevolve.evolution.algorithm = algorithm;
        coevolve.evolution.novelty.k = 2;
        EvolutionRun co(coevolve, test::run_options(3, 2));
        co.run();
        for (const Individual& m : co.state().population) {
            CHECK(m.controller.output_count == kControllerOutputCount);
            CHECK(m.phenotype.body.has_controller());
        }
    }
}

TEST_CASE("a controller file with a bad genome is refused before any simulation, naming it") {
    auto e = fixed_controllers_experiment();
    nlohmann::json bad = controller_to_json(Genome{});
    bad["genome"]["edges"] = nlohmann::json::array({nlohmann::json::array({0, 99, 0.5})});
    e.evolution.controller.controllers.push_back({"bad.json", 1, bad.dump()});
    CHECK_THROWS_WITH_AS(Developer{e}, doctest::Contains("evolution.controller.controllers[2]"),
                         std::invalid_argument);
}
