#include "render/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/glm.hpp>

namespace bhm::render {

namespace {

using Stops = std::array<glm::vec3, 5>;

// Our own control points, evenly spaced in t, interpolated linearly in sRGB. The sequential map
// rises monotonically in lightness so magnitudes read correctly in greyscale prints too.
constexpr Stops kSequential = {glm::vec3{0.13f, 0.10f, 0.38f}, glm::vec3{0.16f, 0.36f, 0.64f},
                               glm::vec3{0.13f, 0.60f, 0.60f}, glm::vec3{0.50f, 0.79f, 0.36f},
                               glm::vec3{0.99f, 0.91f, 0.22f}};
// Symmetric about the white middle so zero strain is neutral.
constexpr Stops kDiverging = {glm::vec3{0.15f, 0.30f, 0.70f}, glm::vec3{0.55f, 0.70f, 0.90f},
                              glm::vec3{0.97f, 0.97f, 0.97f}, glm::vec3{0.93f, 0.60f, 0.50f},
                              glm::vec3{0.72f, 0.13f, 0.15f}};

//! t clamped to [0, 1], NaN to 0: a float-to-int conversion of NaN or infinity is undefined.
float unit(float t) {
    if (!(t > 0.0f)) return 0.0f;  // NaN included
    return t < 1.0f ? t : 1.0f;
}

glm::vec3 interpolate(const Stops& stops, float t) {
    const float x = unit(t) * static_cast<float>(stops.size() - 1);
    const int i = std::min(static_cast<int>(x), static_cast<int>(stops.size()) - 2);
    const float f = x - static_cast<float>(i);
    return stops[i] * (1.0f - f) + stops[i + 1] * f;
}

// A hue wheel of moderate saturation: phase 0 and 2 pi get the same colour.
glm::vec3 hue_wheel(float t) {
    if (!std::isfinite(t)) t = 0.0f;
    const float h = (t - std::floor(t)) * 6.0f;
    const float c = 0.75f, m = 0.18f;
    const float x = c * (1.0f - std::fabs(std::fmod(h, 2.0f) - 1.0f));
    glm::vec3 rgb;
    switch (static_cast<int>(h) % 6) {
        case 0:
            rgb = {c, x, 0};
            break;
        case 1:
            rgb = {x, c, 0};
            break;
        case 2:
            rgb = {0, c, x};
            break;
        case 3:
            rgb = {0, x, c};
            break;
        case 4:
            rgb = {x, 0, c};
            break;
        default:
            rgb = {c, 0, x};
            break;
    }
    return rgb + glm::vec3(m);
}

// Categories, not a scale: the three lattice axes as the axes gizmo draws them.
glm::vec3 axis_colour(float t) {
    if (!(t >= 1.0f / 3.0f)) return {0.84f, 0.26f, 0.20f};  // x (NaN included)
    if (t < 2.0f / 3.0f) return {0.24f, 0.64f, 0.30f};      // y
    return {0.22f, 0.42f, 0.86f};                           // z
}

}  // namespace

float ScalarRange::normalize(float value) const {
    // Any input, finite or not, gives a number in [0, 1]: 0.5 where nothing sensible exists (an
    // empty, infinite or NaN range; a NaN value). In double: the span of two finite floats is
    // finite there (-3.4e38 to 3.4e38 overflows a float).
    const double span = static_cast<double>(max) - static_cast<double>(min);
    if (!std::isfinite(span) || !(std::fabs(span) > 0.0) || std::isnan(value)) return 0.5f;
    const double t = (static_cast<double>(value) - min) / span;  // +-inf for an infinite value
    if (std::isnan(t)) return 0.5f;
    return static_cast<float>(std::clamp(t, 0.0, 1.0));
}

ScalarRange ScalarExtent::range(bool symmetric, double fallback) const {
    const double m = largest_ > 0.0 ? std::min(largest_, kMaxScaleMagnitude) : fallback;
    return {symmetric ? -static_cast<float>(m) : 0.0f, static_cast<float>(m)};
}

glm::vec4 sample_color_map(ColorMapName map, float t) {
    switch (map) {
        case ColorMapName::Diverging:
            return glm::vec4(interpolate(kDiverging, t), 1.0f);
        case ColorMapName::Cyclic:
            return glm::vec4(hue_wheel(t), 1.0f);
        case ColorMapName::Axes:
            return glm::vec4(axis_colour(t), 1.0f);
        case ColorMapName::Sequential:
        default:
            return glm::vec4(interpolate(kSequential, t), 1.0f);
    }
}

std::optional<ColorMapName> parse_color_map(const std::string& name) {
    if (name == "sequential") return ColorMapName::Sequential;
    if (name == "diverging") return ColorMapName::Diverging;
    if (name == "cyclic") return ColorMapName::Cyclic;
    if (name == "axes") return ColorMapName::Axes;
    return std::nullopt;
}

const char* color_map_name(ColorMapName map) {
    switch (map) {
        case ColorMapName::Diverging:
            return "diverging";
        case ColorMapName::Cyclic:
            return "cyclic";
        case ColorMapName::Axes:
            return "axes";
        case ColorMapName::Sequential:
        default:
            return "sequential";
    }
}

}  // namespace bhm::render
