// The measuring behind `bhm simulate` on hand-made samples whose answers are known exactly.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/simulate_progress.hpp"
#include "app/cli/simulation_report.hpp"
#include "support/relative_approx.hpp"

using bhm::app::DisplacementSummary;
using bhm::app::TrajectorySample;

namespace {

constexpr double L = 0.01;  // voxel size (m)

TrajectorySample sample(double t, bhm::app::Vec3 com, bhm::app::Vec3 tip = {0, 0, 0}) {
    return {t, com, tip};
}

}  // namespace

TEST_CASE("displacements start at the end of settling and are measured in voxel lengths") {
    // Before settling the body falls a long way: none of that may count.
    // After: start (1, 2, 3) L; a peak 6 L in y and 8 L in z away (10 L, YZ 10 L);
    // the end 3 L in x and 4 L in z away (5 L in 3-D, 4 L on the YZ plane).
    const std::vector<TrajectorySample> samples = {
        sample(0.0, {1 * L, 2 * L, 50 * L}),
        sample(0.5, {1 * L, 2 * L, 20 * L}),
        sample(1.0 - 1e-12, {1 * L, 2 * L, 3 * L}),  // sample time short of 1.0 by rounding only
        sample(1.5, {1 * L, 8 * L, 11 * L}),
        sample(2.0, {4 * L, 2 * L, 7 * L}, {0.2, 0.3, 0.4}),
    };
    const DisplacementSummary d = bhm::app::summarize_displacements(samples, 1.0, L);
    CHECK(d.settled);
    CHECK(d.com_start_t_s == bhm::test::relative(1.0));
    CHECK(d.com_start_m[2] == bhm::test::relative(3 * L));
    CHECK(d.com_end_m[0] == bhm::test::relative(4 * L));
    CHECK(d.displacement_3d_voxels == bhm::test::relative(5.0));
    CHECK(d.displacement_yz_voxels == bhm::test::relative(4.0));
    CHECK(d.max_displacement_3d_voxels == bhm::test::relative(10.0));
    CHECK(d.max_displacement_yz_voxels == bhm::test::relative(10.0));
    CHECK(d.tip_position_m[0] == 0.2);
    CHECK(d.tip_position_m[2] == 0.4);
}

TEST_CASE("the first sample after settle_s is the start when none lands on it") {
    const std::vector<TrajectorySample> samples = {
        sample(0.0, {0, 0, 0}),
        sample(0.9, {0, 0, 1 * L}),
        sample(1.2, {0, 3 * L, 0}),
        sample(1.8, {0, 3 * L, 2 * L}),
    };
    const DisplacementSummary d = bhm::app::summarize_displacements(samples, 1.0, L);
    CHECK(d.com_start_t_s == 1.2);
    CHECK(d.displacement_3d_voxels == bhm::test::relative(2.0));
    CHECK(d.displacement_yz_voxels == bhm::test::relative(2.0));
    CHECK(d.max_displacement_3d_voxels == bhm::test::relative(2.0));
}

TEST_CASE("a run that ends before settling reports no displacement") {
    const std::vector<TrajectorySample> samples = {sample(0.0, {0, 0, 0}), sample(0.5, {L, L, L})};
    const DisplacementSummary d = bhm::app::summarize_displacements(samples, 1.0, L);
    CHECK_FALSE(d.settled);
    CHECK(d.displacement_3d_voxels == 0.0);
    CHECK(d.max_displacement_yz_voxels == 0.0);
    CHECK(d.com_end_m[0] == L);
    CHECK(bhm::app::summarize_displacements({}, 1.0, L).settled == false);
}

TEST_CASE("settle_s = 0 starts at the first sample") {
    const std::vector<TrajectorySample> samples = {sample(0.0, {0, 0, 0}), sample(0.1, {0, 0, -L})};
    const DisplacementSummary d = bhm::app::summarize_displacements(samples, 0.0, L);
    CHECK(d.com_start_t_s == 0.0);
    CHECK(d.displacement_yz_voxels == bhm::test::relative(1.0));
}

TEST_CASE("trajectory CSV has the header and round-trips every double") {
    const std::vector<TrajectorySample> samples = {
        sample(0.0, {0.1, -0.2, 1.0 / 3.0}, {0.7, 0.8, 0.9}),
        sample(1.0 / 30.0, {1e-300, 12345.678901234567, -0.0}, {2, 3, 4}),
    };
    const std::string csv = bhm::app::trajectory_csv(samples);
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);
    CHECK(line == "t_s,com_x_m,com_y_m,com_z_m,tip_x_m,tip_y_m,tip_z_m");
    for (const auto& s : samples) {
        REQUIRE(std::getline(in, line));
        std::vector<double> values;
        std::istringstream row(line);
        std::string cell;
        while (std::getline(row, cell, ','))
            values.push_back(std::strtod(cell.c_str(), nullptr));
        REQUIRE(values.size() == 7);
        CHECK(values[0] == s.t_s);
        for (int i = 0; i < 3; ++i) {
            CHECK(values[1 + i] == s.com_m[i]);
            CHECK(values[4 + i] == s.tip_m[i]);
        }
    }
    CHECK_FALSE(std::getline(in, line));
}

TEST_CASE("summary JSON holds the documented fields with the values given") {
    bhm::app::RunStats stats;
    stats.voxels = 100;
    stats.links = 250;
    stats.steps = 2000;
    stats.wall_s = 4.0;
    stats.diverged = true;
    stats.divergence_reason = "voxel 3 left the world";
    DisplacementSummary d;
    d.com_start_m = {1, 2, 3};
    d.displacement_yz_voxels = 0.25;
    const auto j = bhm::app::summary_json(stats, d);
    for (const char* key :
         {"voxels", "links", "steps", "dt_s", "sim_time_s", "wall_s", "voxel_steps_per_s",
          "diverged", "divergence_reason", "com_start_m", "com_end_m", "displacement_3d_voxels",
          "displacement_yz_voxels", "max_displacement_3d_voxels", "max_displacement_yz_voxels",
          "tip_position_m"}) {
        CAPTURE(key);
        CHECK(j.contains(key));
    }
    CHECK(j["voxel_steps_per_s"].get<double>() == 100.0 * 2000.0 / 4.0);
    CHECK(j["diverged"].get<bool>());
    CHECK(j["divergence_reason"] == "voxel 3 left the world");
    CHECK(j["com_start_m"][2].get<double>() == 3.0);
    CHECK(j["displacement_yz_voxels"].get<double>() == 0.25);
}

TEST_CASE("progress line shows percent, simulated time, rate and ETA") {
    CHECK(bhm::app::format_progress(5.5, 11.0, 3.21e6, 6.2) ==
          " 50.0%  t 5.50/11.00 s  3.21e+06 voxel-steps/s  ETA 7 s");
    CHECK(bhm::app::format_progress(0.0, 11.0, 0.0, -1.0).find("ETA ?") != std::string::npos);
    CHECK(bhm::app::format_progress(12.0, 11.0, 1.0, 0.0).rfind("100.0%", 0) == 0);
}
