#pragma once
// Fixtures of the calibration tests: a 4-voxel-long bilayer cantilever (8 voxels) and tracks our
// own engine makes from it.
#include <cmath>
#include <cstdint>

#include "evo/calibrate/fit_parameters.hpp"
#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_simulation.hpp"
#include "evo/evo_test_support.hpp"

namespace bhm::evo::test {

//! 4 x 1 x 2 workspace fixed at x-, 0.3 s simulated. A 15 Hz drive and bonds at 0.1 of critical
//! damping, so E (the ringing), the amplitude (the bend) and the damping (the decay) each leave
//! their own mark: at bond_damping_ratio 1 the bond damping has no effect on the track at all,
//! and at 2 Hz E changes the tip's path ten times less (gravity sag only).
inline Experiment calibration_experiment() {
    Experiment e = tiny_experiment({4, 1, 2});
    e.actuation.frequency_hz = 15.0;
    e.simulation.bond_damping_ratio = 0.1;
    // No floor: a cantilever whose lower layer rests on the floor has a misfit made rugged by
    // stick-slip contact, where a local search stops short of the truth.
    e.environment.floor = false;
    e.simulation.settle_s = 0.02;
    e.simulation.evaluate_s = 0.28;
    return e;
}

//! Passive layer over an active one (active_below) or the other way round.
inline Body bilayer(bool active_below) {
    Body b;
    b.size = {4, 1, 2};
    b.cells.assign(8, 1);
    for (int x = 0; x < 4; ++x) b.cells[static_cast<std::size_t>(b.index(x, 0, active_below ? 0 : 1))] = 2;
    return b;
}

//! The tip's x and z every 10 ms from 0 to the end, simulated at point, plus uniform noise of
//! +-noise x the motion's RMS (a fixed linear congruential sequence).
inline MeasuredTrack synthetic_track(const FitPoint& point, const Body& framed, double noise) {
    MeasuredTrack track;
    track.source = "synthetic";
    const double end_s = point.experiment.simulation.settle_s + point.experiment.simulation.evaluate_s;
    for (double t = 0.0; t <= end_s + 1e-9; t += 0.01) track.t_s.push_back(t);
    TrackPoint tip;
    tip.name = "tip";
    tip.axes = {true, false, true};
    track.points = {tip};
    const SimulatedTrack sim = simulate_track(point, framed, track);
    track.points[0].position_m = sim.position_m[0];
    const double rms = track_motion_rms(track);
    std::uint64_t state = 12345;
    for (auto& p : track.points[0].position_m)
        for (double& v : p) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            const double u = static_cast<double>(state >> 11) * 0x1.0p-53;  // [0, 1)
            v += noise * rms * (2.0 * u - 1.0);
        }
    return track;
}

}  // namespace bhm::evo::test
