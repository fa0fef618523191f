// bhm calibrate's fit (evo/calibrate/calibrator.hpp) against tracks our own engine made from
// known parameters: the truth is the parameters the track was simulated with, not the fit's own
// output. Bodies are 8 voxels and tracks a fraction of a second, so each case takes seconds.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <numbers>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "evo/calibrate/calibrator.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/test_support_calibrate.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::evo;
using bhm::evo::test::bilayer;
using bhm::evo::test::calibration_experiment;
using bhm::evo::test::synthetic_track;
using bhm::test::relative;

namespace {

bool trades_off(const CalibrationResult& r, int a, int b) {
    for (const auto& g : r.identifiability.trade_offs)
        if (std::count(g.begin(), g.end(), a) && std::count(g.begin(), g.end(), b)) return true;
    return false;
}

}  // namespace

TEST_CASE("a synthetic track with noise gives back E, amplitude and global damping") {
    if (!calibration_available()) return;
    const Experiment e = calibration_experiment();
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    const auto ps = parse_fit_list("E,amplitude,global_damping", e);
    // The truth: E x 1.25, amplitude x 0.85, global damping x 1.4, then noise of +-0.5 % of the
    // motion. (Bond damping at 0.1 of critical barely moves this tip: 65 % more of it changes
    // the track by a tenth of this noise, so it is not what this case fits.)
    const std::vector<double> truth = {std::log(1.25), std::log(0.85), std::log(1.4)};
    const MeasuredTrack track = synthetic_track(apply_fit(e, ps, truth), body, 0.005);
    CalibrationOptions o;
    o.threads = 2;
    const CalibrationResult r = calibrate(e, body, track, ps, o);
    MESSAGE("simulations ", r.optimiser_simulations, " + ", r.jacobian_simulations, ", misfit ",
            r.misfit_before_m, " -> ", r.misfit_after_m, " m, motion ", r.motion_rms_m, " m; E ",
            r.fitted[0].value, " +- ", r.fitted[0].sigma, " amplitude ", r.fitted[1].value,
            " global damping ", r.fitted[2].value);
    // E is the least determined (sigma 1.8 % of it under this noise, and the fit noise-limited:
    // 483 simulations give the same E as 200): the truth must lie within 3 sigma of it, and
    // sigma itself be small.
    CHECK(std::fabs(r.fitted[0].value - 5e6 * 1.25) < 3.0 * r.fitted[0].sigma);
    CHECK(r.fitted[0].sigma < 0.03 * 5e6 * 1.25);
    CHECK(r.fitted[1].value == relative(14.47 * 0.85, 0.02));
    CHECK(r.fitted[2].value == relative(0.01 * 1.4, 0.10));
    CHECK(r.good_fit);
    CHECK(r.misfit_after_m < 0.1 * r.misfit_before_m);
    CHECK(r.identifiability.trade_offs.empty());
    for (const auto& f : r.fitted) {
        CHECK(std::isfinite(f.sigma));
        CHECK(f.sigma > 0.0);
    }
    // The calibrated experiment holds the fitted values.
    CHECK(r.calibrated.experiment.materials[1].physics.youngs_modulus_pa ==
          relative(r.fitted[0].value, 1e-12));
    CHECK(r.calibrated.experiment.actuation.temperature_amplitude_c ==
          relative(r.fitted[1].value, 1e-12));
}

TEST_CASE("a track of a different body is reported as a poor fit") {
    if (!calibration_available()) return;
    const Experiment e = calibration_experiment();
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    // The other body has its active layer below: it bends the other way.
    const Body other = apply_frame_and_overrides(e, bilayer(true));
    const auto ps = parse_fit_list("E,amplitude", e);
    const MeasuredTrack track = synthetic_track(FitPoint{e, 0.0}, other, 0.0);
    CalibrationOptions o;
    o.threads = 2;
    o.max_simulations = 60;
    const CalibrationResult r = calibrate(e, body, track, ps, o);
    CHECK_FALSE(r.good_fit);
    CHECK(r.misfit_after_m > 0.5 * r.motion_rms_m);
    CHECK(std::any_of(r.warnings.begin(), r.warnings.end(),
                      [](const std::string& w) { return w.rfind("poor fit", 0) == 0; }));
}

TEST_CASE("the misfit fits the tracker's origin: one row's tracking error stays one row's") {
    const Experiment e = calibration_experiment();
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    const MeasuredTrack clean = synthetic_track(FitPoint{e, 0.0}, body, 0.0);
    const SimulatedTrack sim = simulate_track(FitPoint{e, 0.0}, body, clean);
    // Another origin for the whole track (a corner of the video frame): no misfit at all.
    MeasuredTrack moved = clean;
    for (auto& p : moved.points[0].position_m) p[0] += 0.3, p[2] -= 0.1;
    CHECK(track_misfit(moved, sim) < 1e-12);
    // An error of d in the first row's x only. Worked by hand, with n rows and 2 axes: the fitted
    // offset is -d/n, so the residuals are d/n - d once and d/n n-1 times: RMS
    // d sqrt((n-1) / (2 n^2)). Taken from the first row, every other row was off by d:
    // d sqrt((n-1) / (2 n)), sqrt(n) times more, which is what biased E on the floor.
    const double d = 1e-3;
    MeasuredTrack first_off = clean;
    first_off.points[0].position_m[0][0] += d;
    const double n = static_cast<double>(clean.t_s.size());
    CHECK(track_misfit(first_off, sim) == relative(d * std::sqrt((n - 1.0) / (2.0 * n * n)), 1e-6));
}

TEST_CASE("a fitted phase lag goes into the calibrated experiment, which then needs no report") {
    if (!calibration_available()) return;
    const Experiment e = calibration_experiment();
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    const auto ps = parse_fit_list("phase_lag", e);
    // The truth: the prototype lags its drive by 0.6 rad.
    Experiment lagging = e;
    lagging.actuation.phase_offset_rad = -0.6;
    const MeasuredTrack track = synthetic_track(FitPoint{lagging, 0.0}, body, 0.005);
    CalibrationOptions o;
    o.threads = 2;
    o.max_simulations = 60;
    const CalibrationResult r = calibrate(e, body, track, ps, o);
    CHECK(r.fitted[0].value == doctest::Approx(-0.6).epsilon(0.02));
    CHECK(r.calibrated.experiment.actuation.phase_offset_rad == r.fitted[0].value);
    // The calibrated experiment alone, saved and read back, moves as the track does.
    const Experiment back =
        parse_experiment(experiment_to_json(r.calibrated.experiment), "calibrated.json");
    CHECK(back.actuation.phase_offset_rad == r.calibrated.experiment.actuation.phase_offset_rad);
    const double alone = track_misfit(track, simulate_track(FitPoint{back, 0.0}, body, track));
    MESSAGE("phase lag ", r.fitted[0].value, " rad, misfit ", r.misfit_before_m, " -> ",
            r.misfit_after_m, " m, alone ", alone, " m");
    CHECK(alone == relative(r.misfit_after_m, 1e-9));
    CHECK(alone < 0.05 * r.misfit_before_m);
    // Added to an offset already there, and wrapped into [-pi, pi].
    Experiment near_pi = e;
    near_pi.actuation.phase_offset_rad = 3.0;
    CHECK(apply_fit(near_pi, ps, {0.5}).experiment.actuation.phase_offset_rad ==
          doctest::Approx(3.5 - 2.0 * std::numbers::pi));
}

TEST_CASE("Cancel during the optimiser says cancelled, and the scan reports its progress") {
    if (!calibration_available()) return;
    const Experiment e = calibration_experiment();
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    const auto ps = parse_fit_list("E,amplitude", e);
    const MeasuredTrack track =
        synthetic_track(apply_fit(e, ps, {std::log(1.25), std::log(0.85)}), body, 0.0);
    std::atomic<bool> cancel{false};
    std::vector<int> counts;
    CalibrationOptions o;
    o.threads = 2;
    o.max_simulations = 500;
    o.cancel = &cancel;
    o.progress = [&](int simulations, double) {
        counts.push_back(simulations);
        // Past the scan (16 simulations for 2 parameters): inside BOBYQA's objective.
        if (simulations >= 24) cancel.store(true);
    };
    // NLopt's C++ wrapper turns an exception of the objective into its own "nlopt failure":
    // the calibrator must still say that it was cancelled.
    CHECK_THROWS_AS(calibrate(e, body, track, ps, o), EvaluationCancelled);
    // One report per simulation, the scan's included, counting up by one.
    REQUIRE(counts.size() >= 24);
    for (std::size_t k = 0; k < 16; ++k) CHECK(counts[k] == static_cast<int>(k) + 1);
}

TEST_CASE("expansion coefficient and amplitude, which only act as a product, are reported as trading off") {
    if (!calibration_available()) return;
    const Experiment e = calibration_experiment();
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    const auto ps = parse_fit_list("cte,amplitude", e);
    const MeasuredTrack track =
        synthetic_track(apply_fit(e, ps, {std::log(1.2), std::log(1.1)}), body, 0.01);
    CalibrationOptions o;
    o.threads = 2;
    o.max_simulations = 60;
    const CalibrationResult r = calibrate(e, body, track, ps, o);
    CHECK(trades_off(r, 0, 1));
    // The product is what the track fixes: 1.2 x 1.1.
    CHECK(r.fitted[0].value * r.fitted[1].value ==
          relative(0.01 * 14.47 * 1.32, 0.02));
}

TEST_CASE("two parameters whose effects are nearly proportional are reported as trading off") {
    // In this engine E and the amplitude leave separate marks on a bending track (their
    // correlation stayed below 0.9 from 2 to 411 Hz, with and without gravity), so the E x
    // amplitude case of a pure bending track is checked on its Jacobian: column 2 is column 1
    // plus 1 % of another shape, so |corr| is near 1 by construction; column 3 is orthogonal.
    std::vector<std::vector<double>> jac;
    for (int k = 0; k < 40; ++k) {
        const double a = std::sin(0.3 * k), b = std::cos(0.7 * k + 0.2);
        jac.push_back({a, a + 0.01 * b, (k % 2 ? 1.0 : -1.0)});
    }
    const auto id = analyse_identifiability(jac, 1e-4);
    REQUIRE(id.trade_offs.size() == 1);
    CHECK(id.trade_offs[0] == std::vector<int>{0, 1});
    CHECK(std::abs(id.correlation[0][1]) > 0.99);
    CHECK(std::abs(id.correlation[0][2]) < 0.2);
    // Exactly proportional columns: near singular, still named as a trade-off.
    for (auto& row : jac) row[1] = 2.0 * row[0];
    const auto singular = analyse_identifiability(jac, 1e-4);
    CHECK(singular.near_singular);
    REQUIRE(singular.trade_offs.size() == 1);
    CHECK(singular.trade_offs[0] == std::vector<int>{0, 1});
}

TEST_CASE("the Gauss-Newton step of a linear model lands on its least-squares solution") {
    // r(x) = A x - b with A's columns strongly correlated (a narrow valley, as rise_s and the
    // contraction strain of a fused muscle train): from any x0 one step reaches the minimum,
    // which the normal equations give in closed form (Cramer's rule for two parameters).
    std::vector<std::vector<double>> a;
    std::vector<double> b;
    for (int k = 0; k < 30; ++k) {
        const double u = std::sin(0.4 * k), v = std::cos(1.1 * k);
        a.push_back({u, 0.9 * u + 0.1 * v});
        b.push_back(0.7 * u - 0.2 * v + 0.05 * std::sin(3.0 * k));
    }
    double h00 = 0, h01 = 0, h11 = 0, g0 = 0, g1 = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        h00 += a[k][0] * a[k][0];
        h01 += a[k][0] * a[k][1];
        h11 += a[k][1] * a[k][1];
        g0 += a[k][0] * b[k];
        g1 += a[k][1] * b[k];
    }
    const double det = h00 * h11 - h01 * h01;
    const double x0 = (g0 * h11 - g1 * h01) / det, x1 = (h00 * g1 - h01 * g0) / det;
    const std::vector<double> start = {2.0, -3.0};
    std::vector<double> r;
    for (std::size_t k = 0; k < a.size(); ++k)
        r.push_back(a[k][0] * start[0] + a[k][1] * start[1] - b[k]);
    const auto step = gauss_newton_step(a, r);
    REQUIRE(step.size() == 2);
    CHECK(start[0] + step[0] == doctest::Approx(x0).epsilon(1e-9));
    CHECK(start[1] + step[1] == doctest::Approx(x1).epsilon(1e-9));
    // At the minimum the step is nil; with proportional columns it is not defined.
    std::vector<double> at_min;
    for (std::size_t k = 0; k < a.size(); ++k)
        at_min.push_back(a[k][0] * x0 + a[k][1] * x1 - b[k]);
    const auto none = gauss_newton_step(a, at_min);
    REQUIRE(none.size() == 2);
    CHECK(std::abs(none[0]) < 1e-9);
    CHECK(std::abs(none[1]) < 1e-9);
    for (auto& row : a)
        row[1] = 2.0 * row[0];
    CHECK(gauss_newton_step(a, r).empty());
}

TEST_CASE("parameter names and points the body lacks are refused with one-line errors") {
    const Experiment e = calibration_experiment();
    CHECK_THROWS_WITH(parse_fit_list("E,youngs", e),
                      doctest::Contains("--fit: unknown parameter 'youngs'"));
    CHECK_THROWS_WITH(parse_fit_list("E:bone", e),
                      "--fit: 'E:bone': the experiment has no material 'bone'");
    CHECK_THROWS_WITH(parse_fit_list("E,E:active", e), "--fit: 'E:active' overlaps 'E'");
    const Body body = apply_frame_and_overrides(e, bilayer(false));
    const auto track = parse_measured_track("t_s,voxel:99.x\n0,0\n0.01,0\n0.02,0\n", "t.csv");
    CHECK_THROWS_WITH(simulate_track(FitPoint{e, 0.0}, body, track),
                      "t.csv: point 'voxel:99': that lattice cell holds no voxel in the body");
}

TEST_CASE("a track that ends far after or before the experiment's time is warned about by field") {
    const Experiment e = calibration_experiment();  // settle_s + evaluate_s = 0.3 s
    auto warning_of = [&](const std::string& text) {
        return track_span_warning(parse_measured_track(text, "t.csv"), e);
    };
    // t_s in milliseconds: every simulation of the fit would run 1000 times the experiment.
    CHECK(warning_of("t_s,tip.x\n0,0\n150,0\n300,0\n") ==
          "t.csv: t_s: the track ends at 300 s, 1000 times the experiment's settle_s + "
          "evaluate_s (0.3 s), and every simulation of the calibration runs to its end: is t_s "
          "in seconds?");
    // An offset that is most of the end is the field named.
    CHECK(warning_of("# time_offset_s: 1e6\nt_s,tip.x\n0,0\n0.1,0\n0.2,0\n") ==
          "t.csv: time_offset_s: the track ends at 1e+06 s, 3.333e+06 times the experiment's "
          "settle_s + evaluate_s (0.3 s), and every simulation of the calibration runs to its "
          "end: is time_offset_s in seconds?");
    // In minutes: far too short.
    CHECK(warning_of("t_s,tip.x\n0,0\n0.0025,0\n0.005,0\n")
              .starts_with("t.csv: t_s: the track ends at 0.005 s, 0.01667 times"));
    // Within 10 times either way, a track of a few periods or a longer film, nothing.
    CHECK(warning_of("t_s,tip.x\n0,0\n0.1,0\n0.3,0\n").empty());
    CHECK(warning_of("t_s,tip.x\n0,0\n1,0\n3,0\n").empty());
    CHECK(warning_of("# time_offset_s: 0.02\nt_s,tip.x\n0,0\n0.01,0\n0.02,0\n").empty());
}
