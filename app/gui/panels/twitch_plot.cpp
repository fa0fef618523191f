#include "app/gui/panels/twitch_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "app/gui/widgets/mini_plot.hpp"
#include "app/gui/widgets/ui_widgets.hpp"
#include "engine/muscle.hpp"

namespace bhm::app::gui {

namespace {

constexpr int kGridSamples = 600;
// Past this many pulses in the span the pulses fuse on screen anyway: the grid alone is drawn.
constexpr int kMostPulseEdges = 4000;

}  // namespace

double twitch_plot_span_s(const engine::Muscle& m) {
    const double period = m.frequency_hz > 0.0 ? 1.0 / m.frequency_hz : 1.0;
    const double twitch = m.pulse_width_s + 5.0 * (m.rise_s + m.decay_s);
    double span = std::max(3.0 * period, twitch);
    if (m.stimulus == engine::MuscleStimulus::PulseTrain && m.train_on_s > 0.0 &&
        m.train_off_s > 0.0)
        span = m.train_on_s + std::max(m.train_off_s, 5.0 * m.decay_s);
    return std::clamp(span, 0.05, 20.0);
}

TwitchCurves twitch_curves(const engine::Muscle& m) {
    const double span = twitch_plot_span_s(m);
    std::vector<double> t;
    t.reserve(kGridSamples + 1);
    for (int k = 0; k <= kGridSamples; ++k)
        t.push_back(span * k / kGridSamples);
    // The pulses start at tau = 0, n / f (engine/muscle.cpp); each edge is sampled on both sides
    // by a hair, so the drawn stimulus is a rectangle and the activation's peak is exact.
    if (m.frequency_hz > 0.0 && span * m.frequency_hz < kMostPulseEdges) {
        const double period = 1.0 / m.frequency_hz;
        const double hair = 1e-9 * span;
        for (double start = 0.0; start < span; start += period)
            for (double edge : {start, start + m.pulse_width_s})
                for (double at : {edge - hair, edge + hair})
                    if (at > 0.0 && at < span) t.push_back(at);
        std::sort(t.begin(), t.end());
    }
    TwitchCurves c;
    c.t_s = std::move(t);
    for (double tau : c.t_s) {
        // The stimulus at tau = 0 is the first pulse's start: drawn as on.
        c.stimulus.push_back(engine::muscle::stimulated(m, std::max(tau, 1e-12)) ? 1.0 : 0.0);
        c.activation.push_back(engine::muscle::activation(m, tau).a);
    }
    return c;
}

void draw_twitch_plot(Studio& studio, std::size_t slot, const engine::Muscle& m) {
    const TwitchCurves c = twitch_curves(m);
    const float width = std::max(ImGui::GetContentRegionAvail().x, 60.0f);
    const std::string id = "twitch plot " + std::to_string(slot + 1);
    draw_time_plot(id.c_str(), c.t_s,
                   {{&c.stimulus, IM_COL32(150, 150, 150, 255), "stimulus"},
                    {&c.activation, IM_COL32(200, 60, 40, 255), "activation"}},
                   -1.0, "after the settle", "0-1", ImVec2(width, 6.5f * ImGui::GetFontSize()));
    record_widget(studio, id);
    if (ImGui::IsItemHovered())
        wrapped_tooltip(
            "The muscle's stimulus (grey) and its activation (red) from the start of the "
            "actuation: a(t) rises toward 1 with the rise time while stimulated and decays with "
            "the decay time between pulses; pulses closer than the decay sum toward a fused "
            "tetanus. Its voxels contract along the fibre by the contraction strain times a(t).");
}

}  // namespace bhm::app::gui
