// Screen-space overlay: the axes gizmo points where the world axes point; the legend appears
// with scalar colouring; the stroke font draws what it is asked.
#include <doctest/doctest.h>

#include <glm/glm.hpp>

#include "render/overlay.hpp"
#include "render/stroke_font.hpp"

using namespace bhm::render;

namespace {
// Gizmo axis lines are the 2.5 px wide pairs coloured like the axis.
glm::vec2 axis_direction(const Overlay& o, int axis) {
    for (std::size_t i = 0; i + 1 < o.lines.size(); i += 2)
        if (o.lines[i].color == axis_color(axis) && o.lines[i].width_px == 2.5f)
            return glm::vec2(o.lines[i + 1].position - o.lines[i].position);
    FAIL("no line for axis " << axis);
    return {};
}
}  // namespace

TEST_CASE("gizmo in the top view: x to the right, y up, z toward the viewer (no length)") {
    Bounds b;
    b.add(glm::vec3(0));
    b.add(glm::vec3(1));
    const Camera top = named_view(NamedView::Top, b, 1.0f);
    DrawList list;
    list.axes_gizmo = true;
    const Overlay o = build_overlay(list, top, 640, 480);
    const glm::vec2 x = axis_direction(o, 0), y = axis_direction(o, 1), z = axis_direction(o, 2);
    CHECK(x.x > 10.0f);
    CHECK(std::fabs(x.y) < 1e-3f);
    CHECK(y.y > 10.0f);
    CHECK(std::fabs(y.x) < 1e-3f);
    CHECK(glm::length(z) < 1e-3f);
    // Front view (looking along -y): x points left, z up.
    const Overlay f = build_overlay(list, named_view(NamedView::Front, b, 1.0f), 640, 480);
    CHECK(axis_direction(f, 0).x < -10.0f);
    CHECK(axis_direction(f, 2).y > 10.0f);
}

TEST_CASE("legend only with scalar colouring, a colour bar from the map") {
    DrawList list;
    Camera camera;
    CHECK(build_overlay(list, camera, 640, 480).triangles.empty());
    list.legend = Legend{ColorMapName::Sequential, {0.0f, 2.0f}};
    const Overlay o = build_overlay(list, camera, 640, 480);
    REQUIRE(!o.triangles.empty());
    // Lowest step has the map's low colour, highest its high colour (sampled at step centres).
    float lowest = 1e9f, highest = -1e9f;
    glm::vec4 low_color{}, high_color{};
    for (const auto& t : o.triangles) {
        if (t.position.y < lowest) lowest = t.position.y, low_color = t.color;
        if (t.position.y > highest) highest = t.position.y, high_color = t.color;
    }
    CHECK(glm::length(low_color - sample_color_map(ColorMapName::Sequential, 0.0f)) < 0.05f);
    CHECK(glm::length(high_color - sample_color_map(ColorMapName::Sequential, 1.0f)) < 0.05f);
    for (const auto& t : o.triangles)
        CHECK(t.position.x > 560.0f);  // at the right edge
}

TEST_CASE("stroke font: seven segments for 8, three for 7, nothing for unknown characters") {
    std::vector<LineVertex> lines;
    add_text(lines, "8", {0, 0}, 10.0f, glm::vec4(1));
    CHECK(lines.size() == 14);
    lines.clear();
    add_text(lines, "7", {0, 0}, 10.0f, glm::vec4(1));
    CHECK(lines.size() == 6);
    lines.clear();
    add_text(lines, "?", {0, 0}, 10.0f, glm::vec4(1));
    CHECK(lines.empty());
    // Glyphs stay inside their cell: height 10, width 5, advancing 7.5 px.
    lines.clear();
    add_text(lines, "0.5", {100, 50}, 10.0f, glm::vec4(1));
    for (const auto& v : lines) {
        CHECK(v.position.y >= 50.0f);
        CHECK(v.position.y <= 60.0f);
        CHECK(v.position.x >= 100.0f);
        CHECK(v.position.x <= 100.0f + text_width_px("0.5", 10.0f));
    }
}
