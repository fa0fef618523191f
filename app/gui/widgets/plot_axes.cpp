#include "app/gui/widgets/plot_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace bhm::app::gui {

AxisRange fit_range(const std::vector<double>& values, double padding) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : values) {
        if (!std::isfinite(v)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    if (!std::isfinite(lo)) return {0.0, 1.0};
    if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) return {lo - 0.5, hi + 0.5};
    const double pad = padding * (hi - lo);
    return {lo - pad, hi + pad};
}

namespace {

double nice_step(double span, int target) {
    const double raw = span / std::max(1, target);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double fraction = raw / magnitude;
    const double nice = fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0;
    return nice * magnitude;
}

}  // namespace

std::vector<double> nice_ticks(const AxisRange& range, int target) {
    std::vector<double> ticks;
    const double span = range.span();
    if (!(span > 0.0) || !std::isfinite(span)) return ticks;
    const double step = nice_step(span, target);
    const double first = std::ceil(range.min / step - 1e-9) * step;
    for (double t = first; t <= range.max + 1e-9 * step; t += step) {
        ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
        if (ticks.size() > 100) break;
    }
    return ticks;
}

std::vector<double> spaced_ticks(const AxisRange& range, float length_px, float min_gap_px,
                                 int most) {
    const double span = range.span();
    if (!(span > 0.0) || !std::isfinite(span) || !(length_px > 0.0f)) return {};
    const double gap = std::max(1.0f, min_gap_px);
    // nice_step may round the step down (by up to 1.5x, 0..2000 in 6 gives 11 ticks): try fewer
    // ticks until they fit and number at most `most` + 1.
    for (int target = std::clamp(static_cast<int>(length_px / gap), 1, std::max(1, most));
         target >= 1; --target) {
        auto ticks = nice_ticks(range, target);
        if (ticks.size() < 2) return ticks;
        if ((ticks[1] - ticks[0]) / span * length_px >= gap &&
            ticks.size() <= static_cast<std::size_t>(most) + 1)
            return ticks;
    }
    // Even one step is too short: the tick nearest the middle alone.
    const double middle = 0.5 * (range.min + range.max);
    double nearest = middle;
    double distance = std::numeric_limits<double>::infinity();
    for (double t : nice_ticks(range, 1))
        if (std::abs(t - middle) < distance) {
            distance = std::abs(t - middle);
            nearest = t;
        }
    return {nearest};
}

std::string format_tick(double value, double step) {
    char text[32];
    const double magnitude = std::abs(value) > std::abs(step) ? std::abs(value) : std::abs(step);
    if (magnitude >= 1e6 || (step > 0.0 && step < 1e-4)) {
        std::snprintf(text, sizeof text, "%.3g", value);
    } else {
        const int decimals =
            step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
        std::snprintf(text, sizeof text, "%.*f", std::clamp(decimals, 0, 6), value);
    }
    return text;
}

double median_of(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const std::size_t mid = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + static_cast<long>(mid), values.end());
    const double upper = values[mid];
    if (values.size() % 2 == 1) return upper;
    const double lower = *std::max_element(values.begin(), values.begin() + static_cast<long>(mid));
    return 0.5 * (lower + upper);
}

}  // namespace bhm::app::gui
