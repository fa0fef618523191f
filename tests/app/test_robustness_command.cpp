// `bhm robustness` end to end on tiny bodies: the CSV's shape and its agreement with a plain
// evaluation and to bhm simulate, the heatmap's layout and colours, and one clear line and exit 1
// for bad input.
#include <doctest/doctest.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/commands.hpp"
#include "app/cli/png_encode.hpp"
#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "support/captured_command.hpp"
#include "support/scratch.hpp"

#ifdef BHM_WITH_GUI  // render::read_png, to look at the heatmap
#include "app/cli/robustness_plot.hpp"
#include "render/image.hpp"
#endif

namespace fs = std::filesystem;
using namespace bhm;

namespace {

// Paper Table 1 materials on a 3x2x2 workspace held at x-, 0.02 s settle + 0.03 s evaluation.
evo::Experiment tiny_experiment() {
    evo::Experiment e;
    e.name = "tiny";
    e.workspace_size = {3, 2, 2};
    evo::MaterialEntry passive;
    passive.name = "passive";
    evo::MaterialEntry active = passive;
    active.name = "active";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(evo::Face::XMin)] = evo::BoundaryKind::Fixed;
    e.actuation.frequency_hz = 25.0;
    e.simulation.settle_s = 0.02;
    e.simulation.evaluate_s = 0.03;
    e.simulation.record_fps = 100.0;
    e.fitness.measure = evo::FitnessMeasure::ComMax3d;
    return e;
}

// x = 0 passive (held), the rest active; `length` cells along x.
evo::Body bar(int length) {
    evo::Body b;
    b.size = {3, 2, 2};
    b.cells.assign(12, 0);
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < length; ++x)
                b.cells[b.index(x, y, z)] = x == 0 ? 1 : 2;
    return b;
}

test::CapturedRun run(const std::vector<std::string>& args) {
    return test::run_captured(app::cmd_robustness, args);
}

}  // namespace

TEST_CASE("bhm robustness writes a bodies x controllers CSV equal to plain evaluations") {
    const fs::path dir = test::scratch_dir("robustness-cli");
    const std::string experiment = (dir / "e.json").string();
    evo::save_experiment(experiment, tiny_experiment());
    evo::save_body((dir / "a.json").string(), bar(3));
    evo::save_body((dir / "b.json").string(), bar(2));
    const std::string out = (dir / "out").string();
    const auto r = run({experiment, (dir / "a.json").string(), (dir / "b.json").string(),
                        "--controllers", "uniform,wave,random:5", "--out", out, "--threads", "2"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("6/6 evaluated") != std::string::npos);
    const auto table = evo::parse_robustness_csv(test::read_file(fs::path(out) / "robustness.csv"));
    CHECK(table.controllers == std::vector<std::string>{"uniform", "wave", "random:5"});
    REQUIRE(table.bodies.size() == 2);
    CHECK(table.bodies[1] == (dir / "b.json").string());
    // Cell (a, wave) against the evaluation of the same pair, from the files.
    const evo::Experiment e = evo::load_experiment(experiment);
    const evo::Body painted = evo::robustness_cell_body(
        e, evo::load_body((dir / "a.json").string()),
        evo::resolve_robustness_controller("wave", e.evolution.cppn.weight_range).entry);
    CHECK(table.at(0, 1) == evo::fitness_under(evo::evaluate_body(e, painted), e.fitness));
    if (app::png_available()) {
        CHECK(fs::file_size(fs::path(out) / "robustness.png") > 0);
    }
}

TEST_CASE("bhm robustness refuses bad input with one line naming the file or item") {
    const fs::path dir = test::scratch_dir("robustness-cli-errors");
    const std::string experiment = (dir / "e.json").string();
    evo::save_experiment(experiment, tiny_experiment());
    evo::save_body((dir / "a.json").string(), bar(3));
    const std::string body = (dir / "a.json").string();
    const std::string out = (dir / "out").string();

    auto r = run({experiment, body, "--controllers", "uniform,unifrom", "--out", out});
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("--controllers: unifrom: neither a built-in controller") != std::string::npos);
    CHECK_FALSE(fs::exists(fs::path(out) / "robustness.csv"));

    r = run(
        {experiment, (dir / "missing.json").string(), "--controllers", "uniform", "--out", out});
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("missing.json") != std::string::npos);

    r = run({experiment, body, "--controllers", (dir / "nope").string(), "--out", out});
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("nope: neither") != std::string::npos);

    r = run({experiment, body, "--out", out});  // no --controllers: a usage error
    CHECK(r.exit_code == 2);
    r = run({experiment, "--controllers", "uniform", "--out", out});  // no body
    CHECK(r.exit_code == 2);
}

#ifdef BHM_WITH_GUI
TEST_CASE("the robustness heatmap puts each cell where the CSV has it, coloured by fitness") {
    if (!app::png_available()) return;
    const fs::path dir = test::scratch_dir("robustness-heatmap");
    evo::RobustnessTable t;
    t.bodies = {"a", "b"};
    t.controllers = {"c1", "c2", "c3"};
    t.fitness = {0.0, 2.0, 1.0, -1.0, 0.5, -2.0};
    const auto scale = app::write_robustness_heatmap((dir / "h.png").string(), t);
    CHECK(scale.lo == 0.0);
    CHECK(scale.hi == 2.0);
    const render::Image image = render::read_png((dir / "h.png").string());
    // 10-pixel margin, 40-pixel cells, then a 12-pixel gap and a 16-pixel colour bar.
    CHECK(image.width == 2 * 10 + 3 * 40 + 12 + 16);
    CHECK(image.height == 2 * 10 + 2 * 40);
    auto centre = [&](int row, int col) {
        const std::uint8_t* p = image.pixel(10 + col * 40 + 12, 10 + row * 40 + 20);
        return std::array<int, 3>{p[0], p[1], p[2]};
    };
    CHECK(centre(0, 1)[0] > 200);  // the highest fitness: yellow
    CHECK(centre(0, 1)[1] > 200);
    CHECK(centre(0, 0)[2] > centre(0, 0)[0]);                  // the lowest: dark blue
    CHECK(centre(1, 0) == std::array<int, 3>{150, 150, 150});  // diverged: grey
    CHECK(centre(1, 2) == std::array<int, 3>{150, 150, 150});  // rejected: grey
}
#endif
