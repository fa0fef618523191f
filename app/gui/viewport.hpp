#pragma once
// The 3D view's scene and mouse handling, apart from the ImGui window that hosts it so scripts and
// tests can use the same picking: what is drawn, what is under a pixel, what a click does.
#include <optional>

#include <glm/vec2.hpp>

#include "app/gui/studio.hpp"
#include "render/draw_list.hpp"

namespace bhm::app::gui {

//! The draw list of the 3D view in its current mode (painter highlights included).
render::DrawList build_view_draw_list(const Studio& studio);

//! Frames the camera on the view's bounds when asked (camera_needs_framing), keeping its angles.
void frame_view_camera(Studio& studio, const render::DrawList& list, float aspect);

//! The body shown for context inside the workspace in painter mode (the champion), or null.
const evo::Body* painter_context_body(const Studio& studio);

//! Updates painter.hovered_face / hovered_cell for the mouse at `pixel` (view coordinates).
void update_hover(Studio& studio, std::optional<glm::vec2> pixel);

//! What a left click at `pixel` (view coordinates, top-left origin) does: cycle a face or paint a
//! cell in Workspace mode. Returns true when it changed the experiment.
bool click_in_view(Studio& studio, glm::vec2 pixel, bool shift);

}  // namespace bhm::app::gui
