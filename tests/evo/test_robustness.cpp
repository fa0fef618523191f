// Robustness tables (issue 44; evo/evaluate/robustness.hpp): a cell is exactly the evaluation of
// its body file (the painted, framed body saved and read back, as `bhm simulate` reads it), the
// table does not depend on the thread count, the CSV reads back bit for bit, and bad controller
// items are refused naming the item, file and field.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/controller.hpp"
#include "evo_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

namespace {

//! A controller without hidden nodes: phase output = w_phase * x, amplitude = w_amp * bias.
Genome x_controller(double w_phase, double w_amplitude) {
    Genome g;
    g.output_count = kControllerOutputCount;
    g.edges = {{kInputX, kInputCount, w_phase}, {kInputBias, kInputCount + 1, w_amplitude}};
    return g;
}

//! A 4 x 3 x 3 workspace: a stalk held at x- (passive at x = 0) and active beyond.
Body stalk(int length) {
    Body b;
    b.size = {4, 3, 3};
    b.cells.assign(static_cast<std::size_t>(b.cell_count()), 0);
    for (int x = 0; x < length; ++x)
        for (int y = 0; y < 3; ++y)
            b.cells[static_cast<std::size_t>(b.index(x, y, 1))] = x == 0 ? 1 : 2;
    return b;
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

std::string error_of(const std::string& item) {
    try {
        resolve_robustness_controller(item, 3.0);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a robustness cell is bit for bit the evaluation of its body file") {
    const Experiment e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("robustness-cells");
    write_text(dir / "c.json", controller_to_json(x_controller(0.9, 0.4)).dump());
    std::vector<RobustnessController> controllers;
    for (const std::string& item :
         std::vector<std::string>{"uniform", "wave", "random:3", (dir / "c.json").string()})
        controllers.push_back(resolve_robustness_controller(item, e.evolution.cppn.weight_range));
    const std::vector<Body> bodies = {stalk(4), stalk(3)};
    const RobustnessTable table = evaluate_robustness(e, bodies, {"long", "short"}, controllers, 2);
    REQUIRE(table.fitness.size() == 8);
    CHECK(table.controllers[2] == "random:3");

    for (std::size_t b = 0; b < bodies.size(); ++b)
        for (std::size_t c = 0; c < controllers.size(); ++c) {
            CAPTURE(b);
            CAPTURE(c);
            // What `bhm simulate` does with the painted body's file: load, frame, evaluate.
            const fs::path file = dir / "cell.body.json";
            save_body(file.string(), robustness_cell_body(e, bodies[b], controllers[c].entry));
            const Body loaded = load_body(file.string());
            REQUIRE(loaded.has_controller());
            const FitnessReport plain = evaluate_body(e, apply_frame_and_overrides(e, loaded));
            CHECK(table.at(b, c) == fitness_under(plain, e.fitness));
            CHECK(table.reports[b * 4 + c].measures == plain.measures);
        }
    // The controllers do drive differently: the long stalk's uniform and wave cells differ.
    CHECK(table.at(0, 0) != table.at(0, 1));
    // One thread gives the same table.
    const RobustnessTable serial =
        evaluate_robustness(e, bodies, {"long", "short"}, controllers, 1);
    CHECK(serial.fitness == table.fitness);
}

TEST_CASE("robustness.csv has a row per body and a column per controller and reads back exactly") {
    RobustnessTable t;
    t.bodies = {"a.json", "dir, with comma/b.json", "q\"uote.json"};
    t.controllers = {"uniform", "runs/x,y"};
    t.fitness = {0.1, 1.0 / 3.0, -1.0, -2.0, 1e-300, std::nextafter(2.5, 3.0)};
    const std::string csv = robustness_csv(t);
    CHECK(csv.substr(0, csv.find('\n')) == "body,uniform,\"runs/x,y\"");
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 4);
    const RobustnessTable back = parse_robustness_csv(csv);
    CHECK(back.bodies == t.bodies);
    CHECK(back.controllers == t.controllers);
    CHECK(back.fitness == t.fitness);  // bit for bit: 17 significant digits
    CHECK_THROWS_WITH_AS(parse_robustness_csv("body,a\nx,1,2\n"),
                         "robustness.csv line 2: 3 fields, expected 2", std::invalid_argument);
    CHECK_THROWS_AS(parse_robustness_csv("body,a\nx,one\n"), std::invalid_argument);
}

TEST_CASE("bad robustness controllers are refused naming the item, file and field") {
    const fs::path dir = bhm::test::scratch_dir("robustness-errors");
    CHECK(error_of("unifrom").find("unifrom: neither a built-in controller") == 0);
    CHECK(error_of("random:x").find("random:x: the seed") == 0);
    CHECK(error_of("").find("empty") != std::string::npos);
    CHECK(error_of((dir / "missing.json").string()).find("missing.json: neither") !=
          std::string::npos);
    // A run directory whose champion has no controller.
    CHECK(error_of(dir.string()) == (dir / "controller.json").string() +
                                        ": missing (a run writes controller.json only when its "
                                        "champion has a controller: evolution.controller mode "
                                        "coevolve or fixed_body)");
    // A controller file with one output, and a file that is not JSON.
    Genome one = x_controller(1.0, 1.0);
    one.output_count = 1;
    one.edges.pop_back();
    nlohmann::json j = controller_to_json(x_controller(1.0, 1.0));
    j["genome"] = genome_to_json(one);
    write_text(dir / "one.json", j.dump());
    const std::string one_error = error_of((dir / "one.json").string());
    CHECK(one_error.find((dir / "one.json").string() + ": ") == 0);
    CHECK(one_error.find("outputs") != std::string::npos);
    write_text(dir / "bad.json", "{not json");
    CHECK(error_of((dir / "bad.json").string()).find("bad.json: not a controller file") !=
          std::string::npos);
    // The run directory with its champion's controller is accepted.
    write_text(dir / "controller.json", controller_to_json(x_controller(1.0, 1.0)).dump());
    const RobustnessController run = resolve_robustness_controller(dir.string(), 3.0);
    CHECK(run.label == dir.string());
    CHECK_FALSE(run.entry.genome_json.empty());
    const RobustnessController seeded = resolve_robustness_controller("random:42", 3.0);
    CHECK(seeded.entry.name == "random");
    CHECK(seeded.entry.seed == 42);
}
