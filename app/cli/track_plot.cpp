#include "app/cli/track_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "app/cli/png_encode.hpp"
#include "app/cli/rgb_canvas.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

namespace {

constexpr Rgb kMeasured{0, 0, 0}, kBefore{230, 120, 20}, kAfter{30, 90, 220}, kGrid{200, 200, 200},
    kFrame{120, 120, 120};
constexpr int kWidth = 900, kPanelHeight = 200, kMargin = 12;

}  // namespace

bool track_plot_available() { return png_available(); }

void write_track_plot(const std::string& path, const evo::MeasuredTrack& track,
                      const evo::SimulatedTrack& before, const evo::SimulatedTrack& after) {
    if (!png_available())
        throw std::runtime_error(path + ": bhm was built without libpng, so it cannot plot");
    struct Panel {
        std::size_t point, axis;
    };
    std::vector<Panel> panels;
    for (std::size_t i = 0; i < track.points.size(); ++i)
        for (std::size_t a = 0; a < 3; ++a)
            if (track.points[i].axes[a]) panels.push_back({i, a});
    RgbCanvas canvas(kWidth, static_cast<int>(panels.size()) * kPanelHeight);
    const double t0 = track.t_s.front(), t1 = track.t_s.back();
    const std::size_t rows = track.t_s.size();
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const auto [pi, a] = panels[k];
        const auto& measured = track.points[pi].position_m;
        auto disp = [&](const std::vector<std::array<double, 3>>& s, std::size_t r) {
            return s[r][a] - s[0][a];
        };
        const evo::SimulatedTrack* sims[2] = {&before, &after};
        auto usable = [&](const evo::SimulatedTrack* s) {
            return !s->diverged && s->position_m.size() > pi && s->position_m[pi].size() == rows;
        };
        double lo = 0.0, hi = 0.0;
        for (std::size_t r = 0; r < rows; ++r) {
            lo = std::min(lo, disp(measured, r)), hi = std::max(hi, disp(measured, r));
            for (auto* s : sims)
                if (usable(s))
                    lo = std::min(lo, disp(s->position_m[pi], r)),
                    hi = std::max(hi, disp(s->position_m[pi], r));
        }
        if (hi - lo <= 0.0) hi = lo + 1e-6;
        const int top = static_cast<int>(k) * kPanelHeight + kMargin;
        const int bottom = static_cast<int>(k + 1) * kPanelHeight - kMargin;
        auto px = [&](double t) {
            return kMargin + static_cast<int>(std::lround((t - t0) / (t1 - t0) * (kWidth - 2 * kMargin)));
        };
        auto py = [&](double v) {
            return bottom - static_cast<int>(std::lround((v - lo) / (hi - lo) * (bottom - top)));
        };
        canvas.line(kMargin, top, kWidth - kMargin, top, kFrame);
        canvas.line(kMargin, bottom, kWidth - kMargin, bottom, kFrame);
        canvas.line(kMargin, top, kMargin, bottom, kFrame);
        canvas.line(kWidth - kMargin, top, kWidth - kMargin, bottom, kFrame);
        canvas.line(kMargin, py(0.0), kWidth - kMargin, py(0.0), kGrid);
        const Rgb colors[2] = {kBefore, kAfter};
        for (int s = 0; s < 2; ++s) {
            if (!usable(sims[s])) continue;
            const auto& series = sims[s]->position_m[pi];
            for (std::size_t r = 1; r < rows; ++r)
                canvas.line(px(track.t_s[r - 1]), py(disp(series, r - 1)), px(track.t_s[r]),
                            py(disp(series, r)), colors[s]);
        }
        for (std::size_t r = 0; r < rows; ++r) canvas.dot(px(track.t_s[r]), py(disp(measured, r)), kMeasured);
    }
    write_rgb_png(path, canvas.width, canvas.height, canvas.rgb);
}

}  // namespace bhm::app
