// Evaluations that end when the motion repeats (evo/evaluate/periodic_end.hpp): the extrapolation
// against signals whose future is known exactly, and the accuracy gate of issue 23 against the
// full 11 s evaluation on the smallest bodies of the corpus (tests/bench/corpus/; the whole corpus
// is bench_periodic_end's job).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/model.hpp"
#include "engine/muscle.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/fitness_json.hpp"
#include "evo/evaluate/periodic_end.hpp"
#include "evo/evaluate/settle_rest.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

namespace {

//! A 2 Hz drive sampled at 30 fps, 1 s settle + 10 s: the paper presets' schedule.
Experiment paper_schedule() {
    auto e = test::tiny_experiment({2, 1, 1});
    e.actuation.frequency_hz = 2.0;
    e.simulation.settle_s = 1.0;
    e.simulation.evaluate_s = 10.0;
    e.simulation.record_fps = 30.0;
    return e;
}

ExploitGroups unit_mass() {
    ExploitGroups g;
    g.total_mass_kg = 1.0;
    return g;
}

//! Every track follows x(t) (voxel lengths, along x and, halved, along y).
TrackSample sample_of(double t, double x_voxels, double voxel_m) {
    TrackSample s;
    s.t_s = t;
    for (int k = 0; k < TrackSample::kTracks; ++k) {
        // With a unit total mass the moments (kg m) read as metres too.
        s.track(k) = {x_voxels * voxel_m, 0.5 * x_voxels * voxel_m, 0.0};
    }
    s.bend_tip_m[2] += 3.0 * voxel_m;  // a bend line 3 voxels long, along z
    return s;
}

//! Feeds x(k / 30 s) until the detector stops; returns the sample index it stopped at (-1: never)
//! and checks every extrapolated sample against x itself.
template <class Signal>
int run_signal(const Experiment& e, const Signal& x, double* worst_error = nullptr,
               bool held = false) {
    const double dt = 1e-4;
    PeriodicEnd end(e, dt, unit_mass(), held);
    REQUIRE(end.enabled());
    const int last = 330;
    for (int k = 0; k <= last; ++k) {
        const double t = k / 30.0;
        if (!end.observe(sample_of(t, x(t), e.voxel_size_m))) continue;
        int rest = 0;
        double worst = 0.0;
        end.extrapolate([&](const TrackSample& s) {
            ++rest;
            const double truth = x(s.t_s) * e.voxel_size_m;
            worst = std::max(worst, std::abs(s.com_m[0] - truth) / e.voxel_size_m);
        });
        CHECK(rest == last - k);
        if (worst_error) *worst_error = worst;
        return k;
    }
    return -1;
}

}  // namespace

TEST_CASE("a pure repeat stops after two settled periods and extrapolates to the end exactly") {
    const auto e = paper_schedule();
    const auto x = [](double t) {
        return t < 1.0 ? 0.0 : 0.3 * std::sin(2.0 * std::numbers::pi * 2.0 * (t - 1.0));
    };
    double error = 1.0;
    const int stopped = run_signal(e, x, &error);
    CHECK(stopped == 30 + 2 * 15);  // reference at 1 s, two whole periods of 15 samples
    // Sample times land on the first 1e-4 s step at or past k / 30 s: within a step of x.
    CHECK(error < 0.3 * 2.0 * std::numbers::pi * 2.0 * 1e-4 * 1.01);
}

TEST_CASE("a repeat plus a constant drift is extrapolated with the drift") {
    const auto e = paper_schedule();
    const auto x = [](double t) {
        if (t < 1.0) return 0.0;
        return 0.2 * std::sin(2.0 * std::numbers::pi * 2.0 * (t - 1.0)) + 0.084 * 2.0 * (t - 1.0);
    };
    double error = 1.0;
    CHECK(run_signal(e, x, &error) == 60);
    // Within a 1e-4 s step of x, as above: |x'| <= 0.2 * 4 pi + 0.168 voxel lengths per second.
    CHECK(error < (0.2 * 4.0 * std::numbers::pi + 0.168) * 1e-4 * 1.01);
}

TEST_CASE("a drift that still changes, or motion that does not repeat, runs the full time") {
    const auto e = paper_schedule();
    // Accelerating: consecutive periods differ by a growing drift.
    CHECK(run_signal(e, [](double t) { return t < 1.0 ? 0.0 : 0.05 * (t - 1.0) * (t - 1.0); }) ==
          -1);
    // Two incommensurate tones: no period of the drive repeats.
    CHECK(run_signal(e, [](double t) {
              return t < 1.0 ? 0.0
                             : 0.3 * std::sin(2.0 * std::numbers::pi * 2.0 * t) +
                                   0.2 * std::sin(2.0 * std::numbers::pi * 0.7071 * t);
          }) == -1);
}

TEST_CASE("a decaying transient ends only once what is left is within the tolerance") {
    // x = periodic + A exp(-t / tau): the residual falls by exp(-P / tau) a period; the stop is
    // where residual * (periods left + 1) meets the tolerance, and the extrapolation error there
    // (the transient still to decay) is within the gate.
    auto e = paper_schedule();
    const auto x = [](double t) {
        if (t < 1.0) return 0.0;
        const double s = t - 1.0;
        return 0.3 * std::sin(2.0 * std::numbers::pi * 2.0 * s) + 0.5 * (1.0 - std::exp(-s / 0.4));
    };
    double error = 1.0;
    const int stopped = run_signal(e, x, &error);
    REQUIRE(stopped > 60);
    CHECK(stopped < 330);
    CHECK(error <= std::max(0.005 * 0.5, 1e-3));
    // Tenfold looser, it stops earlier, where the transient left is over the gate.
    e.simulation.periodic_tolerance *= 10.0;
    double loose_error = 0.0;
    const int loose_stop = run_signal(e, x, &loose_error);
    CHECK(loose_stop < stopped);
}

TEST_CASE("a held body's decaying transient ends once what it has left is within the tolerance") {
    // The same signal as above, a clamped body's: it cannot drift, so only the transient still to
    // decay (0.5 exp(-s / 0.4), falling by 0.29 a period) separates the last period from the orbit.
    auto e = paper_schedule();
    const auto x = [](double t) {
        if (t < 1.0) return 0.0;
        const double s = t - 1.0;
        return 0.3 * std::sin(2.0 * std::numbers::pi * 2.0 * s) + 0.5 * (1.0 - std::exp(-s / 0.4));
    };
    double free_error = 1.0, held_error = 1.0;
    const int free_stop = run_signal(e, x, &free_error, false);
    const int held_stop = run_signal(e, x, &held_error, true);
    REQUIRE(held_stop > 60);
    CHECK(held_stop < free_stop);  // no drift to keep up over the periods left
    CHECK(held_error <= std::max(0.005 * 0.5, 1e-3));
    // The rest of the run repeats the last period, whose transient is largest at its start,
    // a = e(start) (1 / r - 1) against the period before; r / (1 - r) < 1 here, so the stop is the
    // first sample where a meets the tolerance (sqrt(1.25) a along the tracks, which move by x
    // along x and x / 2 along y).
    const double r = std::exp(-0.5 / 0.4);
    auto a = [&](int k) {
        return std::sqrt(1.25) * 0.5 * std::exp(-(k / 30.0 - 1.5) / 0.4) * (1.0 / r - 1.0);
    };
    CHECK(a(held_stop) <= 1e-3);
    CHECK(a(held_stop - 1) > 1e-3);
    // A transient that decays too slowly to trust (r = 0.95 a period) and is too large to keep up
    // over the periods left never ends early, nor does a growing one.
    const auto slow = [](double t) {
        if (t < 1.0) return 0.0;
        return 0.3 * std::sin(2.0 * std::numbers::pi * 2.0 * (t - 1.0)) +
               0.05 * std::pow(0.95, 2.0 * (t - 1.0));
    };
    CHECK(run_signal(e, slow, nullptr, true) == -1);
    const auto growing = [](double t) {
        if (t < 1.0) return 0.0;
        return (0.3 + 1e-3 * (t - 1.0)) * std::sin(2.0 * std::numbers::pi * 2.0 * (t - 1.0));
    };
    CHECK(run_signal(e, growing, nullptr, true) == -1);
}

TEST_CASE("a held body's slow decay under a jitter is not taken for a fast one") {
    // A transient falling by 0.9 a period whose size wobbles by 20 % (as a period's largest change
    // does when the creep goes on at one phase of the cycle: paper-exp3 random-05). Judged from
    // one pair of periods it looked like r = 0.6 and stopped at sample 119 with 2.9x the allowed
    // error; the ratio over up to three periods, the largest of the last half period's, waits
    // until what is left is within the tolerance.
    const auto e = paper_schedule();
    const auto x = [](double t) {
        if (t < 1.0) return 0.0;
        const double p = 2.0 * (t - 1.0);  // periods since settling
        return 0.3 * std::sin(2.0 * std::numbers::pi * p) +
               0.005 * (1.0 - std::pow(0.9, p) * (1.0 + 0.2 * std::sin(2.0 * std::numbers::pi *
                                                                         0.61 * p)));
    };
    double error = 1.0;
    const int stopped = run_signal(e, x, &error, true);
    CHECK(stopped > 119);
    if (stopped > 0) CHECK(error <= 1e-3);
}

TEST_CASE("a body is held when every part of it holds a fixed voxel") {
    auto spec_of = [](std::vector<std::uint8_t> cells, std::vector<std::uint8_t> fixed) {
        bhm::engine::BodySpec spec;
        spec.nx = static_cast<int>(cells.size());
        spec.ny = spec.nz = 1;
        spec.material = std::move(cells);
        spec.fixed = std::move(fixed);
        spec.materials = {bhm::engine::Material{}};
        return spec;
    };
    using bhm::engine::Model;
    CHECK(every_part_held(*Model::build(spec_of({1, 1, 1, 1}, {1, 0, 0, 0}))));
    // A gap splits off a free part: it can fall and drift.
    CHECK_FALSE(every_part_held(*Model::build(spec_of({1, 1, 0, 1}, {1, 0, 0, 0}))));
    CHECK(every_part_held(*Model::build(spec_of({1, 1, 0, 1}, {1, 0, 0, 1}))));
    CHECK_FALSE(every_part_held(*Model::build(spec_of({1, 1, 1, 1}, {0, 0, 0, 0}))));
}

namespace {

//! Feeds x(k / 30 s) from t = 0 to a held body's SettleRest; the sample index where it says at
//! rest (-1: never).
template <class Signal>
int rest_at(const Experiment& e, const Signal& x, bool held = true) {
    SettleRest rest(e, unit_mass(), held);
    for (int k = 0; k <= 330; ++k)
        if (rest.observe(sample_of(k / 30.0, x(k / 30.0), e.voxel_size_m))) return k;
    return -1;
}

}  // namespace

TEST_CASE("settling ends once a held body is at rest, never while it still moves") {
    auto e = paper_schedule();
    // A sag that creeps to 0.3 voxel lengths with a 50 ms time constant: at rest once the creep
    // left, 0.3 exp(-t / 0.05), is within a tenth of the tolerance (sqrt(1.25) of it along the
    // tracks). That is at t = 0.05 ln(0.3 sqrt(1.25) / 1e-4) = 0.41 s, within a window (0.1 s).
    const auto sag = [](double t) { return 0.3 * (1.0 - std::exp(-t / 0.05)); };
    const int k = rest_at(e, sag);
    REQUIRE(k > 0);
    CHECK(k < 30);
    // The last window's spread, the creep of its 0.1 s, c(t - W) (1 - exp(-W / 0.05)), is within
    // the tenth (the decay ratio exp(-2) adds nothing: r / (1 - r) < 1), and so is what is left.
    const auto creep_left = [](double t) { return 0.3 * std::sqrt(1.25) * std::exp(-t / 0.05); };
    CHECK(creep_left(k / 30.0 - 0.1) * (1.0 - std::exp(-2.0)) <= 1e-4 * 1.0001);
    CHECK(creep_left(k / 30.0) <= 1e-4);
    CHECK(k / 30.0 >= 0.41 - 0.1);
    // A slow swing (period 0.8 s) never reads as rest, nor a creep that hardly decays.
    CHECK(rest_at(e, [](double t) { return 0.01 * std::sin(2.0 * std::numbers::pi * t / 0.8); }) ==
          -1);
    CHECK(rest_at(e, [](double t) { return 0.01 * std::exp(-t / 3.0); }) == -1);
    // A sag still going at the last sample before settle_s leaves nothing to skip.
    CHECK(rest_at(e, [](double t) { return 0.3 * (1.0 - std::exp(-t / 0.2)); }) == -1);
    // Off for free bodies and with the early end switched off.
    CHECK(rest_at(e, sag, false) == -1);
    e.simulation.end_when_periodic = false;
    CHECK(rest_at(e, sag) == -1);
}

TEST_CASE("no early end when switched off or when a period is not a whole number of samples") {
    auto e = paper_schedule();
    e.simulation.end_when_periodic = false;
    CHECK_FALSE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());
    e = paper_schedule();
    e.actuation.frequency_hz = 7.0;  // 30 / 7 samples a period
    CHECK_FALSE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());
    e = paper_schedule();
    e.simulation.evaluate_s = 10.01;  // the last sample is not on the 30 fps grid
    CHECK_FALSE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());
}

TEST_CASE("a muscle body's period is its stimulus's, not the sine's frequency") {
    // Issue 43: a muscle ignores actuation.frequency_hz, so comparing its motion at the sine's
    // period would call a tetanic plateau "periodic" at the wrong period. The muscle catheter's
    // burst (0.3 s on, 0.2 s off) happens to equal its 2 Hz sine; move it off.
    auto e =
        load_experiment(std::string(BHM_SOURCE_DIR) + "/assets/experiments/muscle-catheter.json");
    CHECK(drive_period_s(e) == doctest::Approx(0.5));
    bhm::engine::Muscle& u = e.materials[1].physics.muscle;
    REQUIRE(e.materials[1].physics.actuation_model == bhm::engine::ActuationModel::Muscle);
    u.train_off_s = 0.4;  // a burst every 0.7 s: 21 samples at 30 fps, not the sine's 15
    CHECK(drive_period_s(e) == doctest::Approx(0.7));
    e.simulation.settle_s = 0.5;  // the run a whole number of samples, with or without the settle
    e.simulation.evaluate_s = 2.0;
    CHECK(PeriodicEnd(e, 1e-4, unit_mass()).samples_per_period() == 21);
    u.train_off_s = 0.0;  // one endless 50 Hz train: its pulse period (not a whole number of
    CHECK(drive_period_s(e) == doctest::Approx(0.02));  // 30 fps samples: no early end)
    CHECK_FALSE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());
    u.stimulus = bhm::engine::MuscleStimulus::Beating;
    u.frequency_hz = 1.5;
    u.train_on_s = 0.3;  // a beating muscle has no schedule
    CHECK(drive_period_s(e) == doctest::Approx(1.0 / 1.5));
    CHECK(PeriodicEnd(e, 1e-4, unit_mass()).samples_per_period() == 20);
    // Two muscles on different periods: no common period is sought, the run goes the full time.
    e.materials.push_back(e.materials[1]);
    e.materials[2].physics.muscle.frequency_hz = 1.0;
    CHECK(drive_period_s(e) == 0.0);
    CHECK_FALSE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());
    // The sine model keeps its own.
    CHECK(drive_period_s(paper_schedule()) ==
          doctest::Approx(1.0 / paper_schedule().actuation.frequency_hz));
}

TEST_CASE("a muscle body whose controller delays its stimuli ends early within the gate") {
    // Issue 44: a controller's phase delays a muscle voxel's train by less than its period, so
    // the body still repeats with the stimulus period; the early end must give the full run's
    // measures. A held 4 x 3 x 2 body, half muscle (10 Hz twitches), under one wave of delays
    // along x.
    Experiment on = test::tiny_experiment();
    bhm::engine::Material& muscle = on.materials[1].physics;
    muscle.cte_per_c = 0.0;
    muscle.actuation_model = bhm::engine::ActuationModel::Muscle;
    muscle.muscle.contraction_strain = 0.05;
    muscle.muscle.frequency_hz = 10.0;
    muscle.muscle.pulse_width_s = 0.02;
    muscle.muscle.rise_s = 0.01;
    muscle.muscle.decay_s = 0.02;
    on.simulation.settle_s = 0.05;
    on.simulation.evaluate_s = 1.95;  // 2 s: 400 samples, 20 a period
    on.fitness.measure = FitnessMeasure::ComMax3d;
    Experiment off = on;
    off.simulation.end_when_periodic = false;
    Body body;
    body.size = {4, 3, 2};
    body.cells.assign(24, 1);
    for (std::size_t c = 12; c < 24; ++c)
        body.cells[c] = 2;  // the top layer is muscle
    body = apply_frame_and_overrides(on, body);
    body.phase.assign(body.cells.size(), 0.0f);
    body.amplitude.assign(body.cells.size(), 1.0f);
    for (int z = 0; z < body.size[2]; ++z)
        for (int y = 0; y < body.size[1]; ++y)
            for (int x = 0; x < body.size[0]; ++x)
                body.phase[static_cast<std::size_t>(body.index(x, y, z))] =
                    static_cast<float>(std::remainder(2.0 * std::numbers::pi * x / body.size[0],
                                                      2.0 * std::numbers::pi));
    const FitnessReport e = evaluate_body(on, body);
    const FitnessReport f = evaluate_body(off, body);
    Body plain = body;
    plain.phase.assign(plain.cells.size(), 0.0f);
    CHECK(evaluate_body(off, plain).fitness != f.fitness);  // the delays do act
    MESSAGE("delayed muscle body: "
            << std::string(e.ended_early ? "ended early" : "ran the full time") << " at "
            << e.simulated_s << " s, gate error "
            << (e.ended_early ? periodic_end_error(e, f) : 0.0));
    CHECK(e.ended_early);
    CHECK(e.steps < f.steps);
    CHECK(periodic_end_error(e, f) <= 1.0);
}

TEST_CASE("a fatiguing muscle is never called periodic: its force fades over the stimulus") {
    auto e =
        load_experiment(std::string(BHM_SOURCE_DIR) + "/assets/experiments/muscle-catheter.json");
    e.simulation.settle_s = 0.5;
    e.simulation.evaluate_s = 2.0;
    REQUIRE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());  // fresh: its 0.5 s burst repeats
    bhm::engine::Muscle& u = e.materials[1].physics.muscle;
    u.fatigue_s = 5.0;
    u.recovery_s = 20.0;
    u.fatigue_floor = 0.5;
    CHECK(drive_period_s(e) == 0.0);
    CHECK_FALSE(PeriodicEnd(e, 1e-4, unit_mass()).enabled());
    // The force left after each burst falls: the motion does not repeat at the burst's period.
    const double burst = u.train_on_s + u.train_off_s;
    const double f1 = bhm::engine::muscle::activation(u, burst).fatigue;
    const double f2 = bhm::engine::muscle::activation(u, 2.0 * burst).fatigue;
    CHECK(f2 < f1);
    CHECK(f1 < 1.0);
    // Fatigue fields without a fatigue time do nothing: the period stays.
    u.fatigue_s = 0.0;
    CHECK(drive_period_s(e) == doctest::Approx(0.5));
}

TEST_CASE("the option is read, written and checked with the experiment") {
    auto e = paper_schedule();
    e.simulation.end_when_periodic = false;
    e.simulation.periodic_tolerance = 2e-4;
    const auto back = parse_experiment(experiment_to_json(e), "round trip");
    CHECK(back.simulation.end_when_periodic == false);
    CHECK(back.simulation.periodic_tolerance == 2e-4);
    e.simulation.periodic_tolerance = 0.0;
    const auto problems = validate_experiment(e, "tolerance.json");
    bool named = false;
    for (const auto& p : problems)
        named = named || p.field == "simulation.periodic_tolerance";
    CHECK(named);
}

TEST_CASE("a report says where it stopped, reports written before early ends still read") {
    FitnessReport r;
    r.simulated_s = 2.0;
    r.ended_early = true;
    r.periodic_residual = 1.5e-6;
    const auto back = report_from_json(report_to_json(r), "report");
    CHECK(back.ended_early);
    CHECK(back.simulated_s == 2.0);
    CHECK(back.periodic_residual == 1.5e-6);
    auto old = report_to_json(r);
    old.erase("ended_early");
    old.erase("periodic_residual");
    const auto read = report_from_json(old, "old report");
    CHECK_FALSE(read.ended_early);
    CHECK(read.periodic_residual == 0.0);
}

TEST_CASE("on corpus bodies an early end gives the full 11 s measures") {
    // The gate of issue 23 on a few small paper-exp1 bodies of the corpus (bench_periodic_end runs
    // them all): every fitness measure within max(0.5 %, 1e-3 voxels or degrees) of the full run,
    // or the run went the full length. random-39 drifts slowly sideways (its com_final_yz is the
    // closest to the gate, 0.45 of it) and the champion bends by only 0.05 degrees: at a tenfold
    // looser tolerance both end early and miss the gate (2.2 and 2.4 times the allowed error).
    const std::string root = BHM_SOURCE_DIR;
    const std::string path = root + "/tests/bench/corpus/";
    const Experiment on = load_experiment(root + "/assets/experiments/paper-exp1.json");
    Experiment off = on;
    off.simulation.end_when_periodic = false;
    int early = 0;
    double worst = 0.0;
    for (const auto& [file, name] : std::vector<std::pair<std::string, std::string>>{
             {"paper-exp1-champions", "champion-seed1"},
             {"paper-exp1", "random-39"},
             {"paper-exp1", "random-00"},
             {"paper-exp1", "random-09"}}) {
        std::ifstream in(path + file + ".json");
        REQUIRE(in);
        const auto corpus = nlohmann::json::parse(in);
        for (const auto& entry : corpus.at("bodies")) {
            if (entry.at("name").get<std::string>() != name) continue;
            const Body body = apply_frame_and_overrides(on, parse_body(entry.at("body"), file));
            const FitnessReport e = evaluate_body(on, body);
            MESSAGE(file << "/" << name
                         << std::string(e.ended_early ? " ended early" : " ran the full length"));
            if (!e.ended_early) continue;  // the full length: nothing extrapolated
            const FitnessReport f = evaluate_body(off, body);
            CHECK(e.steps < f.steps);
            CHECK_FALSE(f.ended_early);
            const double error = periodic_end_error(e, f);
            INFO(file << "/" << name << " stopped at " << e.simulated_s << " s: gate error "
                      << error);
            CHECK(error <= 1.0);
            worst = std::max(worst, error);
            ++early;
        }
    }
    MESSAGE(early << " of 4 bodies ended early; largest gate error " << worst);
    // 3 of 4 until issue 24 gave the lattice's shear mode G instead of E / 2 (docs/physics.md):
    // since, the champion and random-39 (the two nearest the gate, above) ran the full length,
    // which is the safe side. With samples at their exact due times (issue 42, evo/evaluate/
    // tracks.hpp) their residuals lost the step's jitter and all four end early within the gate
    // (the champion at 10 s, 0.32 of the allowed error; random-39 at 8.03 s, 0.57). At the
    // presets' longer step (dt_fraction 1.2, rotary_inertia_scale 1.5, issue 42) all four still
    // do: the champion at 10.5 s, 0.071 of it; random-39 at 7.77 s, 0.0044.
    CHECK(early >= 2);
}
