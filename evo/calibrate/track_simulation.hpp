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

//! How far a track's end may lie from the experiment's settle_s + evaluate_s, either way, before
//! track_span_warning speaks: 10 catches a t_s in milliseconds (1000 times) or minutes (1/60)
//! and leaves a track of a few periods of a longer experiment alone.
inline constexpr double kTrackSpanWarningFactor = 10.0;

//! One line naming the track's file and the field that set its end (t_s, or time_offset_s where
//! the offset is most of it) when the track ends more than kTrackSpanWarningFactor times after or
//! before the experiment's settle_s + evaluate_s; empty otherwise. Every simulation of a fit runs
//! from 0 to the track's end, so a track in the wrong unit costs 1000 times the time, or fits a
//! fraction of a period (issue 41 R1).
std::string track_span_warning(const MeasuredTrack& track, const Experiment& experiment);
//! The field of the track's file that set its end, for messages: "time_offset_s" where the header's
//! offset is more of it than the last row's own time, else "t_s".
const char* track_end_field(const MeasuredTrack& track);

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
