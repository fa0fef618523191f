// Issue 43: the Experiment panel draws a muscle material's stimulus and activation. The curves are
// checked against the first-order activation's closed forms (Zajac 1989): a single twitch peaks at
// 1 - exp(-w / rise) at the end of its pulse of width w; a fast train settles into a periodic
// state whose trough solves a = e_d (1 - (1 - a) e_r), e_r = exp(-w / rise), e_d = exp(-(T - w) /
// decay). Only the plot's sampling is ours here: a grid alone would step over a 10 ms pulse.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "app/gui/panels/twitch_plot.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;

namespace {

engine::Muscle twitching(double frequency_hz) {
    engine::Muscle m;
    m.contraction_strain = 0.1;
    m.rise_s = 0.03;
    m.decay_s = 0.06;
    m.pulse_width_s = 0.01;
    m.frequency_hz = frequency_hz;
    return m;
}

}  // namespace

TEST_CASE("twitch plot: a single twitch's peak and decay are on the plotted curve") {
    const engine::Muscle m = twitching(0.5);  // three pulses 2 s apart: three separate twitches
    const TwitchCurves c = twitch_curves(m);
    REQUIRE(c.t_s.size() == c.activation.size());
    REQUIRE(c.t_s.size() == c.stimulus.size());
    CHECK(std::is_sorted(c.t_s.begin(), c.t_s.end()));
    CHECK(c.t_s.back() >= m.pulse_width_s + 5.0 * (m.rise_s + m.decay_s));
    const auto peak = std::max_element(c.activation.begin(), c.activation.end());
    const double t_peak = c.t_s[static_cast<std::size_t>(peak - c.activation.begin())];
    CHECK(*peak == doctest::Approx(1.0 - std::exp(-m.pulse_width_s / m.rise_s)).epsilon(1e-6));
    CHECK(t_peak == doctest::Approx(m.pulse_width_s).epsilon(1e-6));
    // 0.2 s on, the twitch has decayed by exp(-(0.2 - w) / decay) from its peak.
    const auto at = std::lower_bound(c.t_s.begin(), c.t_s.end(), 0.2);
    const double a = c.activation[static_cast<std::size_t>(at - c.t_s.begin())];
    const double t = *at;
    CHECK(a == doctest::Approx(*peak * std::exp(-(t - m.pulse_width_s) / m.decay_s)).epsilon(1e-6));
    // The stimulus is on for the pulses only: three rectangles of width w.
    double on = 0.0;
    for (std::size_t k = 1; k < c.t_s.size(); ++k)
        if (c.stimulus[k - 1] > 0.5 && c.stimulus[k] > 0.5) on += c.t_s[k] - c.t_s[k - 1];
    CHECK(c.t_s.back() == doctest::Approx(3.0 / m.frequency_hz));
    CHECK(on == doctest::Approx(3.0 * m.pulse_width_s).epsilon(1e-6));
}

TEST_CASE("twitch plot: a fast train fuses toward tetanus at the analytic trough") {
    const engine::Muscle m = twitching(50.0);
    const TwitchCurves c = twitch_curves(m);
    const double period = 1.0 / m.frequency_hz;
    const double er = std::exp(-m.pulse_width_s / m.rise_s);
    const double ed = std::exp(-(period - m.pulse_width_s) / m.decay_s);
    const double trough = ed * (1.0 - er) / (1.0 - ed * er);
    const double crest = 1.0 - (1.0 - trough) * er;
    // The last full period of the span: settled (each period shrinks the distance from the
    // periodic state by e_r e_d = exp(-0.5) here, so 20 periods leave exp(-10)).
    const double from = c.t_s.back() - 1.5 * period, to = c.t_s.back() - 0.5 * period;
    REQUIRE(from > 20.0 * period);
    double lo = 1.0, hi = 0.0;
    for (std::size_t k = 0; k < c.t_s.size(); ++k)
        if (c.t_s[k] >= from && c.t_s[k] <= to) {
            lo = std::min(lo, c.activation[k]);
            hi = std::max(hi, c.activation[k]);
        }
    CHECK(lo == doctest::Approx(trough).epsilon(1e-4));
    CHECK(hi == doctest::Approx(crest).epsilon(1e-4));
    CHECK(lo > 0.5);  // fused: the activation never falls back toward rest between pulses
}

TEST_CASE("twitch plot: a scheduled train spans one burst and its rest") {
    engine::Muscle m = twitching(20.0);
    m.train_on_s = 0.5;
    m.train_off_s = 1.0;
    CHECK(twitch_plot_span_s(m) == doctest::Approx(1.5));
    const TwitchCurves c = twitch_curves(m);
    for (std::size_t k = 0; k < c.t_s.size(); ++k)
        if (c.t_s[k] > 0.5 + 1e-6 && c.t_s[k] < 1.5 - 1e-6)
            CHECK(c.stimulus[k] == 0.0);  // the rest: no pulse (1.5 s starts the next burst)
    m.train_off_s = 0.05;                 // a rest shorter than the decay: the decay is shown whole
    CHECK(twitch_plot_span_s(m) == doctest::Approx(0.5 + 5.0 * m.decay_s));
}

TEST_CASE("twitch plot: the Experiment panel draws it for a muscle material only") {
    const auto preset =
        std::filesystem::path(BHM_SOURCE_DIR) / "assets" / "experiments" / "muscle-catheter.json";
    evo::Experiment e = evo::load_experiment(preset.string());
    std::size_t muscles = 0;
    for (const auto& m : e.materials)
        if (m.physics.actuation_model == engine::ActuationModel::Muscle) ++muscles;
    REQUIRE(muscles >= 1);
    REQUIRE(muscles < e.materials.size());
    Studio studio;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1600, 1000);
    run_script(session, json::parse(R"([{"click": "tab Experiment"}, {"frames": 2},
                                        {"click": "header Materials"}, {"frames": 3}])"));
    for (std::size_t k = 0; k < e.materials.size(); ++k) {
        const bool muscle =
            e.materials[k].physics.actuation_model == engine::ActuationModel::Muscle;
        const auto it = studio.ui.widgets.find("twitch plot " + std::to_string(k + 1));
        const bool drawn = it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame;
        const std::string which =
            "material " + std::to_string(k + 1) + (muscle ? " (muscle)" : " (not muscle)");
        INFO(which);
        CHECK(drawn == muscle);
    }
}
