#include "app/gui/view/track_points.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace bhm::app::gui {

namespace {

std::optional<std::array<double, 3>> point_at(const evo::MeasuredTrack& track,
                                              const evo::SimulatedTrack& preview,
                                              std::size_t point, double t_s, bool measured_axes) {
    const auto& t = track.t_s;
    if (point >= track.points.size() || point >= preview.position_m.size() || t.empty() ||
        t_s < t.front() || t_s > t.back())
        return std::nullopt;
    const auto& sim = preview.position_m[point];
    // The preview stops early when it diverged: only its rows can be placed.
    const std::size_t rows = std::min(t.size(), sim.size());
    if (rows == 0 || t_s > t[rows - 1]) return std::nullopt;
    const std::size_t hi = static_cast<std::size_t>(
        std::max<std::ptrdiff_t>(1, std::upper_bound(t.begin(), t.begin() + rows, t_s) - t.begin()));
    const std::size_t k1 = std::min(hi, rows - 1), k0 = k1 - (k1 > 0 ? 1 : 0);
    const double w = t[k1] > t[k0] ? std::clamp((t_s - t[k0]) / (t[k1] - t[k0]), 0.0, 1.0) : 0.0;
    const auto& measured = track.points[point].position_m;
    std::array<double, 3> out{};
    for (std::size_t a = 0; a < 3; ++a) {
        auto lerp = [&](const std::vector<std::array<double, 3>>& v) {
            return v[k0][a] + w * (v[k1][a] - v[k0][a]);
        };
        out[a] = measured_axes && track.points[point].axes[a] ? sim[0][a] + lerp(measured) - measured[0][a]
                                             : lerp(sim);
    }
    return out;
}

}  // namespace

std::optional<std::array<double, 3>> measured_point_at(const evo::MeasuredTrack& track,
                                                       const evo::SimulatedTrack& preview,
                                                       std::size_t point, double t_s) {
    return point_at(track, preview, point, t_s, true);
}

std::optional<std::array<double, 3>> simulated_point_at(const evo::MeasuredTrack& track,
                                                        const evo::SimulatedTrack& preview,
                                                        std::size_t point, double t_s) {
    return point_at(track, preview, point, t_s, false);
}

}  // namespace bhm::app::gui
