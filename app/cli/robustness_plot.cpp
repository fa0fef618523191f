// bhm robustness's heatmap (robustness_plot.hpp), rasterised here and encoded by png_encode.
#include "app/cli/robustness_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "app/cli/png_encode.hpp"
#include "app/cli/rgb_canvas.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

namespace {

constexpr int kCell = 40, kMargin = 10, kBarWidth = 16, kBarGap = 12;
constexpr Rgb kInvalid{150, 150, 150}, kCross{60, 60, 60}, kBackground{255, 255, 255};

// Dark blue -> teal -> yellow (the studio's sequential map's ends), linear between stops.
Rgb sequential(double t) {
    constexpr std::array<std::array<double, 3>, 3> stops{
        {{0.10, 0.12, 0.45}, {0.10, 0.60, 0.60}, {0.98, 0.90, 0.15}}};
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    const double s = t * 2.0;
    const int i = std::min(1, static_cast<int>(s));
    const double f = s - i;
    Rgb out{};
    for (int c = 0; c < 3; ++c)
        out[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround(
            255.0 * (stops[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] * (1.0 - f) +
                     stops[static_cast<std::size_t>(i) + 1][static_cast<std::size_t>(c)] * f)));
    return out;
}

}  // namespace

bool robustness_cell_valid(double fitness) {
    return std::isfinite(fitness) && fitness >= 0.0;
}

HeatmapScale robustness_scale(const evo::RobustnessTable& table) {
    HeatmapScale scale{INFINITY, -INFINITY};
    for (const double f : table.fitness)
        if (robustness_cell_valid(f))
            scale.lo = std::min(scale.lo, f), scale.hi = std::max(scale.hi, f);
    if (!(scale.lo <= scale.hi)) scale = {0.0, 0.0};
    return scale;
}

Rgb robustness_color(double fitness, const HeatmapScale& scale) {
    if (!robustness_cell_valid(fitness)) return kInvalid;
    const double span = scale.hi - scale.lo;
    return sequential(span > 0.0 ? (fitness - scale.lo) / span : 0.5);
}

Rgb robustness_bar_color(double t) {
    return sequential(t);
}

HeatmapScale write_robustness_heatmap(const std::string& path, const evo::RobustnessTable& table) {
    const int rows = static_cast<int>(table.bodies.size());
    const int cols = static_cast<int>(table.controllers.size());
    if (rows == 0 || cols == 0) throw std::runtime_error(path + ": an empty table has no heatmap");
    const HeatmapScale scale = robustness_scale(table);

    const int grid_h = rows * kCell;
    RgbCanvas canvas(2 * kMargin + cols * kCell + kBarGap + kBarWidth, 2 * kMargin + grid_h);
    canvas.fill(0, 0, canvas.width, canvas.height, kBackground);
    for (int b = 0; b < rows; ++b)
        for (int c = 0; c < cols; ++c) {
            const double f = table.at(static_cast<std::size_t>(b), static_cast<std::size_t>(c));
            const int x0 = kMargin + c * kCell, y0 = kMargin + b * kCell;
            const bool valid = robustness_cell_valid(f);
            // One pixel of white between cells.
            canvas.fill(x0 + 1, y0 + 1, kCell - 2, kCell - 2, robustness_color(f, scale));
            if (!valid)
                for (int k = 4; k < kCell - 4; ++k)
                    canvas.put(x0 + k, y0 + k, kCross),
                        canvas.put(x0 + kCell - 1 - k, y0 + k, kCross);
        }
    // The colour bar: the table's highest fitness at the top.
    const int bar_x = kMargin + cols * kCell + kBarGap;
    for (int y = 0; y < grid_h; ++y)
        canvas.fill(bar_x, kMargin + y, kBarWidth, 1,
                    sequential(1.0 - static_cast<double>(y) / std::max(1, grid_h - 1)));
    write_rgb_png(path, canvas.width, canvas.height, canvas.rgb);
    return scale;
}

}  // namespace bhm::app
