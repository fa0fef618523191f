// `bhm calibrate` end to end: a track the command's own --simulate-only writes for an experiment
// with a known amplitude is fitted back from another amplitude; the files it leaves; bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/commands.hpp"
#include "evo/calibrate/calibrator.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "support/captured_command.hpp"
#include "support/scratch.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    return bhm::test::output_dir("calibrate", name);
}

using bhm::test::CapturedRun;

CapturedRun run_calibrate(const std::vector<std::string>& args) {
    return bhm::test::run_captured(bhm::app::cmd_calibrate, args);
}

// A 4x1x2 bilayer cantilever held at x-, active on top; 6 Hz drive, 0.2 s.
bhm::evo::Experiment bilayer_experiment() {
    bhm::evo::Experiment e;
    e.name = "bilayer";
    e.workspace_size = {4, 1, 2};
    bhm::evo::MaterialEntry passive;
    passive.name = "passive";
    bhm::evo::MaterialEntry active = passive;
    active.name = "active";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(bhm::evo::Face::XMin)] = bhm::evo::BoundaryKind::Fixed;
    e.actuation.frequency_hz = 6.0;
    e.simulation.settle_s = 0.02;
    e.simulation.evaluate_s = 0.18;
    return e;
}

void write_files(const fs::path& dir, double amplitude_c) {
    auto e = bilayer_experiment();
    e.actuation.temperature_amplitude_c = amplitude_c;
    bhm::evo::save_experiment((dir / "experiment.json").string(), e);
    bhm::evo::Body b;
    b.size = {4, 1, 2};
    b.cells = {1, 1, 1, 1, 2, 2, 2, 2};
    bhm::evo::save_body((dir / "body.json").string(), b);
    std::ofstream times(dir / "times.csv");
    times << "t_s,tip.x,tip.z,com.z\n";
    for (int k = 0; k <= 20; ++k) times << 0.01 * k << ",0,0,0\n";
}

}  // namespace

TEST_CASE("bhm calibrate fits back the amplitude of a track simulated with a known one") {
    if (!bhm::evo::calibration_available()) return;
    const fs::path truth = fresh_dir("truth"), dir = fresh_dir("fit");
    write_files(truth, 10.0);
    const auto sim = run_calibrate({(truth / "experiment.json").string(), "--body",
                                    (truth / "body.json").string(), "--track",
                                    (truth / "times.csv").string(), "--simulate-only", "--out",
                                    (truth / "out").string()});
    REQUIRE_MESSAGE(sim.exit_code == 0, sim.err);
    write_files(dir, 14.47);
    const auto run = run_calibrate({(dir / "experiment.json").string(), "--body",
                                    (dir / "body.json").string(), "--track",
                                    (truth / "out" / "simulated.csv").string(), "--fit",
                                    "amplitude", "--threads", "2", "--out", (dir / "out").string()});
    REQUIRE_MESSAGE(run.exit_code == 0, run.err);
    std::ifstream in(dir / "out" / "report.json");
    const auto report = nlohmann::json::parse(in);
    CHECK(report["fit"][0]["name"] == "amplitude");
    CHECK(std::abs(report["fit"][0]["initial"].get<double>() - 14.47) < 1e-9);
    // The CSV keeps 9 significant digits, so the fit is close to exact.
    CHECK(std::abs(report["fit"][0]["fitted"].get<double>() / 10.0 - 1.0) < 0.01);
    CHECK(report["good_fit"] == true);
    CHECK(report["misfit_after_m"].get<double>() < 0.05 * report["misfit_before_m"].get<double>());
    CHECK(report["simulations"]["total"].get<int>() ==
          report["simulations"]["optimiser"].get<int>() + 2 + 2);
    const auto calibrated =
        bhm::evo::load_experiment((dir / "out" / "calibrated-experiment.json").string());
    CHECK(std::abs(calibrated.actuation.temperature_amplitude_c -
                   report["fit"][0]["fitted"].get<double>()) < 1e-6);
    CHECK(fs::exists(dir / "out" / "simulated-before.csv"));
    CHECK(fs::exists(dir / "out" / "simulated-after.csv"));
    if (report["plot"].is_string()) {
        std::ifstream png(dir / "out" / "tracks.png", std::ios::binary);
        char magic[8] = {};
        png.read(magic, 8);
        CHECK(std::string(magic + 1, 3) == "PNG");
    }
}

TEST_CASE("bhm calibrate refuses a bad track with the row and a bad --fit as a usage error") {
    const fs::path dir = fresh_dir("bad");
    write_files(dir, 14.47);
    std::ofstream(dir / "bad.csv") << "t_s,tip.x\n0,0\n0.02,0.001\n0.01,0.002\n";
    const auto bad_track =
        run_calibrate({(dir / "experiment.json").string(), "--body", (dir / "body.json").string(),
                       "--track", (dir / "bad.csv").string(), "--fit", "amplitude", "--out",
                       (dir / "out").string()});
    CHECK(bad_track.exit_code == 1);
    CHECK(bad_track.err.find("bad.csv: row 3 (line 4): time 0.01 s is not after the previous "
                             "row's") != std::string::npos);
    const auto bad_fit =
        run_calibrate({(dir / "experiment.json").string(), "--body", (dir / "body.json").string(),
                       "--track", (dir / "times.csv").string(), "--fit", "stiffness", "--out",
                       (dir / "out").string()});
    CHECK(bad_fit.exit_code == 2);
    CHECK(bad_fit.err.find("unknown parameter 'stiffness'") != std::string::npos);
    const auto no_track = run_calibrate({(dir / "experiment.json").string(), "--body",
                                         (dir / "body.json").string(), "--fit", "amplitude"});
    CHECK(no_track.exit_code == 2);
    CHECK(no_track.err.find("missing --track") != std::string::npos);
}
