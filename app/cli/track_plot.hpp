#pragma once
// The PNG of bhm calibrate: measured against simulated displacements, one panel per compared
// coordinate, drawn by a small rasteriser of its own (no display, no GL) and written with libpng.
#include <string>

#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_simulation.hpp"

namespace bhm::app {

//! False where bhm was built without libpng: write_track_plot then throws.
bool track_plot_available();

//! Writes PATH atomically: per point and axis a panel of displacement from the first row against
//! time; measured = black dots, before = orange line, after = blue line, zero = grey line.
//! Throws std::runtime_error naming the path.
void write_track_plot(const std::string& path, const evo::MeasuredTrack& track,
                      const evo::SimulatedTrack& before, const evo::SimulatedTrack& after);

}  // namespace bhm::app
