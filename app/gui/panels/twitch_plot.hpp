#pragma once
// The Experiment panel's picture of a muscle material's drive (issue 43): its stimulus u(t) and its
// activation a(t) from the start of the actuation, so a designer sees a twitch, summation toward
// tetanus and the on/off schedule while typing the time constants and the pulse train.
#include <vector>

#include "app/gui/studio.hpp"
#include "engine/body_spec.hpp"

namespace bhm::app::gui {

//! Sampled curves over [0, span]: a uniform grid plus both ends of every pulse, so that the
//! stimulus's edges and the activation's peaks (at a pulse's end) are samples, not aliased away.
struct TwitchCurves {
    std::vector<double> t_s;
    std::vector<double> stimulus;    //!< u in {0, 1}
    std::vector<double> activation;  //!< a in [0, 1]
};

//! The time the plot spans: one burst and its rest for a scheduled train; otherwise three stimulus
//! periods, at least long enough for a twitch to rise and decay (5 time constants each); within
//! 0.05 to 20 s.
double twitch_plot_span_s(const engine::Muscle& m);
TwitchCurves twitch_curves(const engine::Muscle& m);

//! Draws the plot for material slot `slot` (0-based), recorded for scripts as "twitch plot N".
void draw_twitch_plot(Studio& studio, std::size_t slot, const engine::Muscle& m);

}  // namespace bhm::app::gui
