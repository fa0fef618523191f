#include "render/overlay.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "render/stroke_font.hpp"

namespace bhm::render {

namespace {

constexpr glm::vec4 kInk{0.18f, 0.19f, 0.22f, 1.0f};

void add_axes_gizmo(Overlay& overlay, const Camera& camera, int height_px) {
    const float length = std::clamp(0.06f * static_cast<float>(height_px), 18.0f, 56.0f);
    const float letter = std::clamp(0.35f * length, 7.0f, 16.0f);
    const glm::vec2 origin{1.6f * length, 1.6f * length};
    const glm::vec3 right = camera.right(), up = camera.up(), forward = camera.forward();
    // Axes pointing away from the viewer first, so nearer ones are drawn over them.
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return forward[a] > forward[b]; });
    for (int axis : order) {
        const glm::vec2 dir{right[axis], up[axis]};
        const glm::vec2 tip = origin + length * dir;
        const glm::vec4 color = axis_color(axis);
        overlay.lines.push_back({{origin, 0.0f}, color, 2.5f});
        overlay.lines.push_back({{tip, 0.0f}, color, 2.5f});
        // The letter just beyond the tip, centred on the axis direction.
        const float n = glm::length(dir);
        const glm::vec2 away = n > 1e-3f ? dir / n : glm::vec2(0.7f, 0.7f);
        const glm::vec2 centre = tip + away * (0.9f * letter);
        const char name[2] = {static_cast<char>('X' + axis), '\0'};
        add_text(overlay.lines, name, centre - glm::vec2(0.25f * letter, 0.5f * letter), letter,
                 color, 1.5f);
    }
}

std::string format_value(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", static_cast<double>(value));
    return text;
}

void add_legend(Overlay& overlay, const Legend& legend, int width_px, int height_px) {
    const float w = static_cast<float>(width_px), h = static_cast<float>(height_px);
    const float bar_width = std::clamp(0.018f * w, 8.0f, 20.0f);
    const float x1 = w - std::clamp(0.03f * w, 10.0f, 40.0f), x0 = x1 - bar_width;
    const float y0 = 0.22f * h, y1 = 0.78f * h;
    constexpr int kSteps = 48;
    for (int i = 0; i < kSteps; ++i) {
        const float t0 = static_cast<float>(i) / kSteps, t1 = static_cast<float>(i + 1) / kSteps;
        const float ya = y0 + t0 * (y1 - y0), yb = y0 + t1 * (y1 - y0);
        // Flat colour per step: the cyclic map must not be blended across its stops.
        const glm::vec4 c = sample_color_map(legend.map, 0.5f * (t0 + t1));
        for (const glm::vec2 p : {glm::vec2{x0, ya}, glm::vec2{x1, ya}, glm::vec2{x1, yb},
                                  glm::vec2{x0, ya}, glm::vec2{x1, yb}, glm::vec2{x0, yb}})
            overlay.triangles.push_back({{p, 0.0f}, c});
    }
    const glm::vec2 corners[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int i = 0; i < 4; ++i) {
        overlay.lines.push_back({{corners[i], 0.0f}, kInk, 1.0f});
        overlay.lines.push_back({{corners[(i + 1) % 4], 0.0f}, kInk, 1.0f});
    }
    const float text_h = std::clamp(0.022f * h, 7.0f, 14.0f);
    const float values[3] = {legend.range.min, 0.5f * (legend.range.min + legend.range.max),
                             legend.range.max};
    for (int i = 0; i < 3; ++i) {
        const float y = y0 + 0.5f * static_cast<float>(i) * (y1 - y0);
        overlay.lines.push_back({{x0 - 4.0f, y, 0.0f}, kInk, 1.0f});
        overlay.lines.push_back({{x0, y, 0.0f}, kInk, 1.0f});
        const std::string label = format_value(values[i]);
        const float tw = text_width_px(label, text_h);
        add_text(overlay.lines, label, {x0 - 8.0f - tw, y - 0.5f * text_h}, text_h, kInk, 1.25f);
    }
}

}  // namespace

glm::vec4 axis_color(int axis) {
    switch (axis) {
        case 0:
            return {0.85f, 0.20f, 0.18f, 1.0f};
        case 1:
            return {0.20f, 0.65f, 0.22f, 1.0f};
        default:
            return {0.20f, 0.38f, 0.88f, 1.0f};
    }
}

Overlay build_overlay(const DrawList& list, const Camera& camera, int width_px, int height_px) {
    Overlay overlay;
    if (list.axes_gizmo) add_axes_gizmo(overlay, camera, height_px);
    if (list.legend) add_legend(overlay, *list.legend, width_px, height_px);
    return overlay;
}

}  // namespace bhm::render
