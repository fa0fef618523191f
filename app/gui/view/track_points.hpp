#pragma once
// A measured track drawn over the simulated body (the Calibrate tab's overlay in the 3D view):
// where its points are at a time of the replay, measured and simulated.
#include <array>
#include <cstddef>
#include <optional>

#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_simulation.hpp"

namespace bhm::app::gui {

//! Where the measured point `point` of the track is at time t_s in the simulation's frame:
//! the simulated point at the track's first row plus the measured displacement since that row,
//! on the axes the track gives; on the others the simulated point at t_s. Nothing outside the
//! track's time span.
std::optional<std::array<double, 3>> measured_point_at(const evo::MeasuredTrack& track,
                                                       const evo::SimulatedTrack& preview,
                                                       std::size_t point, double t_s);
//! The simulated point at t_s (interpolated between the preview's rows), over the same span.
std::optional<std::array<double, 3>> simulated_point_at(const evo::MeasuredTrack& track,
                                                        const evo::SimulatedTrack& preview,
                                                        std::size_t point, double t_s);

}  // namespace bhm::app::gui
