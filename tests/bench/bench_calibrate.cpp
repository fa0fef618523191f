// bench_calibrate: bhm calibrate's fit on the paper's 8x8x7 block (issue 28's benchmark target:
// 3 parameters in under 10 minutes on 2 cores). The block, fixed at x- as paper-exp1 holds it,
// has its upper half active (z >= 4) over a passive lower half, so it bends; a track of its tip
// and centre of mass is simulated with known parameters (E x 1.2, amplitude x 0.9, bond damping
// x 1.3) plus 1 % noise, then E, amplitude and bond_damping are fitted from the experiment's
// values. One CSV row on stdout: the truth, the fit, the simulations used and the wall time.
//
//   bench_calibrate [--assets DIR] [--seconds T] [--threads N] [--max-simulations N]
//                   [--profile N [--profile-span S]] [--noise F] [--clean-first-row]
// --seconds: actuated time of the track after the settling (default 1.5 s, 3 cycles at 2 Hz).
// --noise F: uniform noise of +-F x the motion's RMS on every position (default 0.01);
// --clean-first-row: none on the first row (the reference every displacement is taken from).
// --profile N: no fit; the misfit along E instead (N factors of E, log-spaced over truth x
// e^-S .. truth x e^S, default S = ln 5, the other parameters at their truth), one CSV row each:
// where the misfit has valleys besides the truth's (docs/calibration.md, "Bodies on the floor").
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "evo/calibrate/calibrator.hpp"
#include "evo/evaluate/worker_pool.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm::evo;

namespace {

int run(int argc, char** argv) {
    std::string assets = "assets/experiments";
    double seconds = 1.5;
    int threads = 2, max_sims = 200, profile = 0;
    double profile_span = std::log(5.0), noise_fraction = 0.01;
    bool clean_first_row = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--assets") assets = value();
        else if (a == "--seconds") seconds = std::stod(value());
        else if (a == "--threads") threads = std::stoi(value());
        else if (a == "--max-simulations") max_sims = std::stoi(value());
        else if (a == "--profile") profile = std::stoi(value());
        else if (a == "--profile-span") profile_span = std::stod(value());
        else if (a == "--noise") noise_fraction = std::stod(value());
        else if (a == "--clean-first-row") clean_first_row = true;
        else throw std::runtime_error("unknown argument " + a);
    }
    if (!calibration_available()) throw std::runtime_error("built without NLopt");
    Experiment e = load_experiment(assets + "/paper-exp1.json");
    Body block;
    block.size = e.workspace_size;
    block.cells.assign(static_cast<std::size_t>(block.cell_count()), 1);
    for (int z = block.size[2] / 2 + 1; z < block.size[2]; ++z)
        for (int y = 0; y < block.size[1]; ++y)
            for (int x = 0; x < block.size[0]; ++x)
                block.cells[static_cast<std::size_t>(block.index(x, y, z))] = 2;
    const Body framed = apply_frame_and_overrides(e, block);
    const auto ps = parse_fit_list("E,amplitude,bond_damping", e);
    const std::vector<double> truth = {std::log(1.2), std::log(0.9), std::log(1.3)};

    MeasuredTrack track;
    track.source = "bench";
    const double end_s = e.simulation.settle_s + seconds;
    for (double t = 0.0; t <= end_s + 1e-9; t += 1.0 / 30.0) track.t_s.push_back(t);
    TrackPoint tip, com;
    tip.name = "tip";
    tip.axes = {true, true, true};
    com.name = "com";
    com.kind = TrackPointKind::Com;
    com.axes = {true, true, true};
    track.points = {tip, com};
    const auto sim = simulate_track(apply_fit(e, ps, truth), framed, track);
    if (sim.diverged) throw std::runtime_error("the truth diverged: " + sim.divergence_reason);
    for (std::size_t i = 0; i < 2; ++i) track.points[i].position_m = sim.position_m[i];
    const double noise = noise_fraction * track_motion_rms(track);
    std::uint64_t state = 99;
    for (auto& p : track.points)
        for (std::size_t k = 0; k < p.position_m.size(); ++k)
            for (double& v : p.position_m[k]) {
                state = state * 6364136223846793005ULL + 1442695040888963407ULL;
                if (k > 0 || !clean_first_row)
                    v += noise * (2.0 * (static_cast<double>(state >> 11) * 0x1.0p-53) - 1.0);
            }
    if (profile > 1) {
        std::vector<double> misfit(static_cast<std::size_t>(profile));
        std::vector<std::vector<double>> xs;
        for (int k = 0; k < profile; ++k) {
            auto x = truth;
            x[0] += profile_span * (2.0 * k / (profile - 1) - 1.0);
            xs.push_back(x);
        }
        parallel_for(profile, threads, [&](int k) {
            const auto s = simulate_track(apply_fit(e, ps, xs[static_cast<std::size_t>(k)]), framed,
                                          track);
            misfit[static_cast<std::size_t>(k)] = track_misfit(track, s);
        });
        std::cout << "E_over_truth,E_pa,misfit_m,misfit_over_noise_rms\n";
        for (int k = 0; k < profile; ++k) {
            const auto& x = xs[static_cast<std::size_t>(k)];
            std::cout << std::exp(x[0] - truth[0]) << "," << fit_value(e, ps[0], x[0]) << ","
                      << misfit[static_cast<std::size_t>(k)] << ","
                      << (noise > 0 ? misfit[static_cast<std::size_t>(k)] / (noise / std::sqrt(3.0)) : 0.0)
                      << "\n";
        }
        return 0;
    }
    CalibrationOptions o;
    o.threads = threads;
    o.max_simulations = max_sims;
    o.progress = [](int n, double best) {
        std::fprintf(stderr, "\r%d simulations, best misfit %.4g m   ", n, best);
    };
    const auto r = calibrate(e, framed, track, ps, o);
    std::fprintf(stderr, "\n");
    std::cout << "voxels,track_s,threads,simulations,optimiser_simulations,wall_s,misfit_before_m,"
                 "misfit_after_m,E_truth,E_fit,E_sigma,amplitude_truth,amplitude_fit,"
                 "amplitude_sigma,bond_damping_truth,bond_damping_fit,bond_damping_sigma,"
                 "trade_offs\n";
    int voxels = 0;
    for (auto c : framed.cells) voxels += c != 0;
    std::cout << voxels << "," << end_s << "," << threads << ","
              << r.optimiser_simulations + r.jacobian_simulations + 2 << ","
              << r.optimiser_simulations << "," << r.wall_s << "," << r.misfit_before_m << ","
              << r.misfit_after_m;
    for (std::size_t i = 0; i < 3; ++i)
        std::cout << "," << fit_value(e, ps[i], truth[i]) << "," << r.fitted[i].value << ","
                  << r.fitted[i].sigma;
    std::cout << "," << r.identifiability.trade_offs.size() << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return bhm::bench::run_guarded("bench_calibrate", run, argc, argv);
}
