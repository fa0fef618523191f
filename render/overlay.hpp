#pragma once
// Screen-space decorations computed on the CPU in pixel coordinates (origin lower left):
// the axes gizmo in the lower-left corner and the colour bar of scalar colouring.
#include <vector>

#include "render/camera.hpp"
#include "render/draw_list.hpp"

namespace bhm::render {

struct Overlay {
    std::vector<LineVertex> lines;          //!< pairs, pixel coordinates, z = 0
    std::vector<TriangleVertex> triangles;  //!< pixel coordinates, z = 0
};

//! The overlay of a draw list seen by camera in a viewport of width x height pixels.
Overlay build_overlay(const DrawList& list, const Camera& camera, int width_px, int height_px);

//! Axis colours of the gizmo: x red, y green, z blue.
glm::vec4 axis_color(int axis);

}  // namespace bhm::render
