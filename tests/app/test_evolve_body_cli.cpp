// `bhm evolve E.json --body B.json` (issue 44): evolves only a controller for B. The champion's
// body is B framed, cell for cell; controller.json is written; run.json keeps the body so that
// --resume needs no --body; --body beside --resume, or a body that does not fit, is one line
// naming the option or the field, and a non-zero exit.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "shell_run.hpp"
#include "support/scratch.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bhm;

const std::string kBhm = std::string(BHM_BINARY_DIR) + "/bin/bhm";

// A 4 x 3 x 3 workspace held at x-, 0.06 s simulated at 25 Hz: a generation takes milliseconds.
evo::Experiment tiny_experiment() {
    evo::Experiment e =
        evo::load_experiment(std::string(BHM_SOURCE_DIR) + "/assets/experiments/quick-demo.json");
    e.workspace_size = {4, 3, 3};
    e.simulation.settle_s = 0.01;
    e.simulation.evaluate_s = 0.05;
    e.simulation.record_fps = 200.0;
    e.actuation.frequency_hz = 25.0;
    e.evolution.population = 4;
    e.evolution.generations = 2;
    e.evolution.threads = 1;
    return e;
}

evo::Body body_of(std::array<int, 3> size) {
    evo::Body b;
    b.size = size;
    b.cells.assign(static_cast<std::size_t>(b.cell_count()), 2);
    for (int y = 0; y < size[1]; ++y)
        for (int x = 0; x < size[0]; ++x)
            b.cells[static_cast<std::size_t>(b.index(x, y, 0))] = 1;  // a passive bottom layer
    return b;
}

}  // namespace

TEST_CASE("bhm evolve --body evolves a controller for that body, which stays cell for cell") {
    const fs::path dir = test::scratch_dir("evolve-body-cli", false);
    fs::create_directories(dir);
    const auto e = tiny_experiment();
    evo::save_experiment((dir / "E.json").string(), e);
    const evo::Body body = body_of({3, 3, 2});
    evo::save_body((dir / "B.json").string(), body);
    const std::string out = (dir / "run").string();

    const auto run = test::run_shell(kBhm + " evolve " + (dir / "E.json").string() + " --body " +
                                     (dir / "B.json").string() + " --out " + out);
    CAPTURE(run.output);
    REQUIRE(run.status == 0);
    const auto champion = nlohmann::json::parse(test::read_file(fs::path(out) / "champion.json"));
    const evo::Body saved = evo::parse_body(champion["phenotype"], "champion.json");
    const evo::Body framed = evo::apply_frame_and_overrides(e, body);
    CHECK(saved.cells == framed.cells);
    CHECK(saved.has_controller());
    CHECK(fs::is_regular_file(fs::path(out) / "controller.json"));
    const auto info = nlohmann::json::parse(test::read_file(fs::path(out) / "run.json"));
    CHECK(info["experiment"]["evolution"]["controller"]["mode"] == "fixed_body");

    // The run keeps its body: --resume alone continues it; --body with --resume is refused.
    const auto refused =
        test::run_shell(kBhm + " evolve " + (dir / "E.json").string() + " --body " +
                        (dir / "B.json").string() + " --out " + out + " --resume");
    CHECK(refused.status != 0);
    CHECK(refused.output.find("--body") != std::string::npos);
    const auto resumed = test::run_shell(kBhm + " evolve " + (dir / "E.json").string() + " --out " +
                                         out + " --resume --generations 3");
    CAPTURE(resumed.output);
    CHECK(resumed.status == 0);

    // A body larger than the workspace: one line naming the field.
    evo::save_body((dir / "Big.json").string(), body_of({9, 3, 2}));
    const auto big =
        test::run_shell(kBhm + " evolve " + (dir / "E.json").string() + " --body " +
                        (dir / "Big.json").string() + " --out " + (dir / "run-big").string());
    CHECK(big.status != 0);
    CHECK(big.output.find("evolution.controller.body.size[0]") != std::string::npos);
    fs::remove_all(dir);
}
