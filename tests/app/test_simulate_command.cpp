// `bhm simulate` end to end on a tiny body: the three files, their agreement, and the exit codes.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/commands.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "support/captured_command.hpp"
#include "support/relative_approx.hpp"
#include "support/scratch.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    return bhm::test::output_dir("simulate", name);
}

// Paper Table 1 materials on a 3x2x2 workspace held at x-; settle 0.05 s so a 0.1 s run has both
// a settle phase and an actuated phase.
bhm::evo::Experiment tiny_experiment() {
    bhm::evo::Experiment e;
    e.name = "tiny";
    e.workspace_size = {3, 2, 2};
    bhm::evo::MaterialEntry passive;
    passive.name = "passive";
    passive.physics.cte_per_c = 0.0;
    bhm::evo::MaterialEntry active = passive;
    active.name = "active";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(bhm::evo::Face::XMin)] = bhm::evo::BoundaryKind::Fixed;
    e.simulation.settle_s = 0.05;
    e.simulation.evaluate_s = 0.05;
    e.simulation.record_fps = 30.0;
    return e;
}

// x = 0 passive (held), x = 1..2 active.
bhm::evo::Body tiny_body() {
    bhm::evo::Body b;
    b.size = {3, 2, 2};
    b.cells.assign(12, 2);
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            b.cells[b.index(0, y, z)] = 1;
    return b;
}

using bhm::test::CapturedRun;

CapturedRun run_simulate(const std::vector<std::string>& args) {
    return bhm::test::run_captured(bhm::app::cmd_simulate, args);
}

std::vector<std::vector<double>> read_csv_rows(const fs::path& path, std::string& header) {
    std::ifstream in(path);
    std::getline(in, header);
    std::vector<std::vector<double>> rows;
    std::string line;
    while (std::getline(in, line)) {
        std::vector<double> row;
        std::istringstream cells(line);
        std::string cell;
        while (std::getline(cells, cell, ','))
            row.push_back(std::strtod(cell.c_str(), nullptr));
        rows.push_back(row);
    }
    return rows;
}

}  // namespace

TEST_CASE("simulate writes summary, trajectory and replay that agree with each other") {
    const fs::path dir = fresh_dir("tiny");
    const fs::path experiment = dir / "experiment.json", body = dir / "body.json";
    bhm::evo::save_experiment(experiment.string(), tiny_experiment());
    bhm::evo::save_body(body.string(), tiny_body());
    const fs::path out = dir / "out" / "nested";  // created if missing

    const CapturedRun run = run_simulate(
        {experiment.string(), "--body", body.string(), "--seconds", "0.1", "--out", out.string()});
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.out.find(out.string()) != std::string::npos);
    REQUIRE(fs::exists(out / "summary.json"));
    REQUIRE(fs::exists(out / "trajectory.csv"));
    REQUIRE(fs::exists(out / "replay.bin"));

    std::string header;
    const auto rows = read_csv_rows(out / "trajectory.csv", header);
    CHECK(header == "t_s,com_x_m,com_y_m,com_z_m,tip_x_m,tip_y_m,tip_z_m");
    REQUIRE(rows.size() == 4);  // 30 fps x 0.1 s + the sample at t = 0
    for (const auto& row : rows)
        REQUIRE(row.size() == 7);
    CHECK(rows.front()[0] == 0.0);
    CHECK(rows.back()[0] == bhm::test::relative(0.1, 1e-3));

    std::ifstream summary_file(out / "summary.json");
    const nlohmann::json s = nlohmann::json::parse(summary_file);
    CHECK(s["voxels"] == 12);
    CHECK(s["links"].get<int>() == 20);  // 3x2x2 lattice: 2*2*2 (x) + 3*1*2 (y) + 3*2*1 (z)
    CHECK(s["diverged"] == false);
    CHECK(s["sim_time_s"].get<double>() == bhm::test::relative(0.1, 1e-3));
    const double dt = s["dt_s"].get<double>();
    CHECK(dt > 0.0);
    CHECK(s["steps"].get<double>() ==
          bhm::test::relative(s["sim_time_s"].get<double>() / dt, 0.01));
    CHECK(s["voxel_steps_per_s"].get<double>() > 0.0);
    // Exploit flags (docs/evolution.md): the x = 0 layer (4 voxels) is held and holds the rest;
    // every voxel of a 3x2x2 block has at least 3 neighbours, so none is thin.
    const auto& x = s["exploits"];
    CHECK(x["checked"] == true);
    CHECK(x["held_voxels"] == 4);
    CHECK(x["unanchored_fraction"] == 0.0);
    CHECK(x["escaped"] == false);
    CHECK(x["thin_voxels"] == 0);
    CHECK(x["tentacle"] == false);

    // com_start is the first sample at or after settle_s = 0.05 (t = 2/30), com_end the last one.
    const auto& start_row = rows[2];
    CHECK(start_row[0] >= 0.05);
    CHECK(rows[1][0] < 0.05);
    for (int i = 0; i < 3; ++i) {
        CHECK(s["com_start_m"][i].get<double>() == start_row[1 + i]);
        CHECK(s["com_end_m"][i].get<double>() == rows.back()[1 + i]);
        CHECK(s["tip_position_m"][i].get<double>() == rows.back()[4 + i]);
    }
    const double L = 0.01;
    const double dx = rows.back()[1] - start_row[1], dy = rows.back()[2] - start_row[2],
                 dz = rows.back()[3] - start_row[3];
    CHECK(s["displacement_3d_voxels"].get<double>() ==
          bhm::test::relative(std::sqrt(dx * dx + dy * dy + dz * dz) / L));
    CHECK(s["displacement_yz_voxels"].get<double>() ==
          bhm::test::relative(std::sqrt(dy * dy + dz * dz) / L));
    CHECK(s["max_displacement_3d_voxels"].get<double>() >=
          s["displacement_3d_voxels"].get<double>());
    // At t = 0 the body is at rest on its lattice: uniform density puts the centre of mass on the
    // middle x layer, one voxel behind the tip layer, and on the tip's y and z by symmetry.
    CHECK(rows.front()[4] - rows.front()[1] == bhm::test::relative(L));
    CHECK(rows.front()[5] == bhm::test::relative(rows.front()[2]));
    CHECK(rows.front()[6] == bhm::test::relative(rows.front()[3]));

    const bhm::engine::Replay replay = bhm::engine::read_replay((out / "replay.bin").string());
    CHECK(replay.voxel_cell.size() == 12);
    CHECK(replay.nx == 3);
    CHECK(replay.settle_s == 0.05);
    REQUIRE(replay.frames.size() == rows.size());
    for (std::size_t f = 0; f < rows.size(); ++f) {
        CHECK(replay.frames[f].voxel_count() == 12);
        CHECK(replay.frames[f].time_s == rows[f][0]);
    }
    // Held voxels are the x = 0 layer, in passive material.
    int held = 0;
    for (std::size_t v = 0; v < replay.voxel_cell.size(); ++v)
        if (replay.voxel_fixed[v]) {
            ++held;
            CHECK(replay.voxel_cell[v] % 3 == 0);
            CHECK(replay.voxel_material[v] == 1);
        }
    CHECK(held == 4);
}

TEST_CASE("simulate reports bad input as file:field: message and exits 1") {
    const fs::path dir = fresh_dir("bad");
    const fs::path experiment = dir / "experiment.json", body = dir / "body.json";
    bhm::evo::save_experiment(experiment.string(), tiny_experiment());

    SUBCASE("missing body file") {
        const auto run = run_simulate({experiment.string(), "--body", (dir / "nope.json").string(),
                                       "--out", (dir / "out").string()});
        CHECK(run.exit_code == 1);
        CHECK(run.err.find((dir / "nope.json").string() + ":") != std::string::npos);
        CHECK_FALSE(fs::exists(dir / "out"));
    }
    SUBCASE("experiment that is not JSON: one line naming it") {
        std::ofstream(experiment) << "{ not json";
        bhm::evo::save_body(body.string(), tiny_body());
        const auto run = run_simulate({experiment.string(), "--body", body.string()});
        CHECK(run.exit_code == 1);
        CHECK(run.err.rfind(experiment.string() + ":", 0) == 0);
        CHECK(run.err.find('\n') == run.err.size() - 1);
    }
    SUBCASE("bad experiment and missing body: both reported") {
        std::ofstream(experiment) << "{ not json";
        const auto run = run_simulate({experiment.string(), "--body", body.string()});
        CHECK(run.exit_code == 1);
        CHECK(run.err.find(experiment.string() + ":") != std::string::npos);
        CHECK(run.err.find(body.string() + ":") != std::string::npos);
    }
    SUBCASE("body larger than the workspace") {
        bhm::evo::Body big = tiny_body();
        big.size = {3, 2, 3};
        big.cells.assign(18, 1);
        bhm::evo::save_body(body.string(), big);
        const auto run = run_simulate(
            {experiment.string(), "--body", body.string(), "--out", (dir / "out").string()});
        CHECK(run.exit_code == 1);
        CHECK(run.err.find(body.string() + ":size[2]:") != std::string::npos);
    }
    SUBCASE("usage errors exit 2") {
        CHECK(run_simulate({experiment.string()}).exit_code == 2);  // no --body
        CHECK(
            run_simulate({experiment.string(), "--body", "b.json", "--seconds", "-1"}).exit_code ==
            2);
        CHECK(run_simulate({experiment.string(), "--body", "b.json", "--bogus"}).exit_code == 2);
    }
}

TEST_CASE("simulate --help documents the outputs and the diverged exit status") {
    const auto run = run_simulate({"--help"});
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("summary.json") != std::string::npos);
    CHECK(run.out.find("3 the simulation diverged") != std::string::npos);
}

TEST_CASE("simulate's summary says where an evaluation's settling would end at rest") {
    // The held 3x2x2 block settling for 1 s under gravity: at rest well before (windows of
    // 0.1 s, evo/evaluate/settle_rest.hpp), so an evaluation would stop integrating there and
    // resume at settle_s; bhm simulate runs it all and reports the stop.
    const fs::path dir = fresh_dir("settle_rest");
    const fs::path experiment = dir / "experiment.json", body = dir / "body.json";
    auto e = tiny_experiment();
    e.simulation.settle_s = 1.0;
    bhm::evo::save_experiment(experiment.string(), e);
    bhm::evo::save_body(body.string(), tiny_body());
    const CapturedRun run = run_simulate({experiment.string(), "--body", body.string(), "--seconds",
                                          "1.5", "--out", (dir / "out").string()});
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    std::ifstream summary_file(dir / "out" / "summary.json");
    const nlohmann::json r = nlohmann::json::parse(summary_file).at("settle_rest");
    CHECK(r.at("applies") == true);
    REQUIRE(r.at("ends_early") == true);
    CHECK(r.at("stop_s").get<double>() >= 0.2);  // two windows at least
    CHECK(r.at("stop_s").get<double>() < 1.0);
    CHECK(r.at("resume_s").get<double>() == 1.0);
    // Without the early ends nothing stops.
    e.simulation.end_when_periodic = false;
    bhm::evo::save_experiment(experiment.string(), e);
    const CapturedRun off = run_simulate({experiment.string(), "--body", body.string(), "--seconds",
                                          "1.5", "--out", (dir / "off").string()});
    REQUIRE(off.exit_code == 0);
    std::ifstream off_file(dir / "off" / "summary.json");
    const nlohmann::json o = nlohmann::json::parse(off_file).at("settle_rest");
    CHECK(o.at("applies") == false);
    CHECK(o.at("ends_early") == false);
    CHECK(o.at("stop_s").get<double>() == 1.0);
}

TEST_CASE("simulate's summary says where an evaluation would end and how far its extrapolation is") {
    // The held 3x2x2 block driven at 2 Hz, sampled at 30 fps (15 samples a period) for 3 s: its
    // motion repeats after a few periods. The summary's periodic_end block reports the stop, and
    // its extrapolated measures against the ones measured over the whole run (the gate of issue
    // 23, docs/experiment-format.md).
    const fs::path dir = fresh_dir("periodic");
    const fs::path experiment = dir / "experiment.json", body = dir / "body.json";
    auto e = tiny_experiment();
    e.actuation.frequency_hz = 2.0;
    e.simulation.settle_s = 0.2;
    bhm::evo::save_experiment(experiment.string(), e);
    bhm::evo::save_body(body.string(), tiny_body());
    const fs::path out = dir / "out";
    const CapturedRun run = run_simulate(
        {experiment.string(), "--body", body.string(), "--seconds", "3", "--out", out.string()});
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    std::ifstream summary_file(out / "summary.json");
    const nlohmann::json s = nlohmann::json::parse(summary_file);
    const auto& p = s.at("periodic_end");
    CHECK(p.at("applies") == true);
    REQUIRE(p.at("ends_early") == true);
    const double stop = p.at("stop_s").get<double>();
    CHECK(stop >= 0.2 + 2 * 0.5);  // two whole settled periods at least
    CHECK(stop < 3.0);
    CHECK(p.at("gate_error").get<double>() <= 1.0);
    // The extrapolated final displacement is the measured one within the gate.
    const double measured = s.at("displacement_3d_voxels").get<double>();
    const double extrapolated = p.at("extrapolated").at("com_final_3d").get<double>();
    CHECK(std::abs(extrapolated - measured) <= std::max(0.005 * std::abs(measured), 1e-3));
    CHECK(measured > 1e-3);  // it moved: the comparison is not of zeros
    // Switched off, the block reports that no early end applies.
    e.simulation.end_when_periodic = false;
    bhm::evo::save_experiment(experiment.string(), e);
    const CapturedRun off = run_simulate({experiment.string(), "--body", body.string(), "--seconds",
                                          "3", "--out", (dir / "off").string()});
    REQUIRE(off.exit_code == 0);
    std::ifstream off_file(dir / "off" / "summary.json");
    const nlohmann::json o = nlohmann::json::parse(off_file);
    CHECK(o.at("periodic_end").at("applies") == false);
    CHECK(o.at("periodic_end").at("ends_early") == false);
}
