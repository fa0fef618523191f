#pragma once
// One simulation of a body at the times of a measured track, and the misfit between the two.
// Tracks are compared up to a constant offset per point and axis (fitted), so a tracker's origin
// (a corner of the video frame) does not matter, only that its axes are the simulation's.
#include <array>
#include <atomic>
#include <string>
#include <vector>

#include "evo/calibrate/fit_parameters.hpp"
#include "evo/calibrate/measured_track.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct SimulatedTrack {
    //! (points) (times) positions in metres, the measured track's points in its order
    std::vector<std::vector<std::array<double, 3>>> position_m;
    bool diverged = false;
    std::string divergence_reason;
    double wall_s = 0.0;
};

//! Simulates the framed body (apply_frame_and_overrides) under point.experiment, sampling the
//! track's points at its times (interpolated between the steps either side of each). Throws
//! std::runtime_error for a point the body does not have (a voxel:N cell that is empty, a tip of
//! a single-layer body) and EvaluationCancelled when cancel is raised. Parameters outside the
//! engine's envelope (engine/limits.hpp) give a diverged track with the engine's reason.
SimulatedTrack simulate_track(const FitPoint& point, const Body& framed_body,
                              const MeasuredTrack& track,
                              const std::atomic<bool>* cancel = nullptr);

//! The residuals, simulated minus measured position less their mean difference (per point and
//! axis: the tracker's origin, fitted), over every row and present axis (metres); a diverged
//! simulation gives an empty vector. Every row's tracking error counts alike: taken from the
//! first row, that row's error was in every residual.
std::vector<double> track_residuals(const MeasuredTrack& track, const SimulatedTrack& sim);
//! RMS of the residuals (metres); +infinity for a diverged simulation.
double track_misfit(const MeasuredTrack& track, const SimulatedTrack& sim);
//! RMS of the measured displacements from the first row (metres): the scale a misfit is judged by.
double track_motion_rms(const MeasuredTrack& track);

}  // namespace bhm::evo
