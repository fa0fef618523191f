#pragma once
// The heatmap PNG of bhm robustness: one square per cell of the table, rows the bodies and
// columns the controllers in the CSV's order, coloured by fitness on a sequential map (dark blue
// at the table's lowest valid fitness, yellow at its highest); diverged or rejected cells
// (negative fitness) grey with a dark cross; a colour bar on the right. No text: the numbers and
// labels are in robustness.csv beside it.
#include <string>

#include "app/cli/rgb_canvas.hpp"
#include "evo/evaluate/robustness.hpp"

namespace bhm::app {

struct HeatmapScale {
    double lo = 0.0, hi = 0.0;  //!< the fitness at the bottom and top of the colour bar
};

//! A cell with a fitness to colour (not diverged, not rejected: finite and >= 0).
bool robustness_cell_valid(double fitness);
//! The colour bar's ends: the table's lowest and highest valid fitness (0, 0 when none is).
HeatmapScale robustness_scale(const evo::RobustnessTable& table);
//! A cell's colour in the heatmap (grey when not valid): the studio's Robustness tab draws the
//! same colours as the PNG.
Rgb robustness_color(double fitness, const HeatmapScale& scale);
//! The colour bar at t in [0, 1] (0 the lowest fitness).
Rgb robustness_bar_color(double t);

//! Writes PATH atomically. Throws std::runtime_error naming the path (also where bhm was built
//! without libpng).
HeatmapScale write_robustness_heatmap(const std::string& path, const evo::RobustnessTable& table);

}  // namespace bhm::app
