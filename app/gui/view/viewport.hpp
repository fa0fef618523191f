#pragma once
// The 3D view's scene and mouse handling, apart from the ImGui window that hosts it so scripts and
// tests can use the same picking: what is drawn, what is under a pixel, what a click does.
#include <array>
#include <optional>
#include <string>

#include <glm/vec2.hpp>

#include "app/gui/studio.hpp"
#include "render/draw_list.hpp"

namespace bhm::app::gui {

//! The painter's draw list of an experiment's workspace: faces (fixed ones tinted green again),
//! frame, overrides and the context body (the 3D view in Workspace mode, the welcome's thumbnails).
render::DrawList workspace_draw_list(const evo::Experiment& experiment,
                                     const PainterState& painter, const evo::Body* context_body,
                                     bool show_edges);

//! The draw list of the 3D view in its current mode (painter highlights included).
render::DrawList build_view_draw_list(const Studio& studio);

//! The split view shows the compared body in a pane of its own (Simulation mode, a compared body
//! and split on).
bool split_view_active(const Studio& studio);
//! The verification of the body shown, with its shapes, when it is drawn in the 3D view now
//! (Simulation mode, ghost on); null otherwise.
const FemVerification* fem_overlay(const Studio& studio);
//! The compared body's draw list for the split view's second pane (no offset); empty without one.
render::DrawList compared_view_draw_list(const Studio& studio);

//! Frames the camera on the view's bounds when asked (camera_needs_framing), keeping its angles.
void frame_view_camera(Studio& studio, const render::DrawList& list, float aspect);

//! The body shown for context inside the workspace in painter mode (the champion), or null.
const evo::Body* painter_context_body(const Studio& studio);

//! Updates painter.hovered_face / hovered_cell for the mouse at `pixel` (view coordinates).
void update_hover(Studio& studio, std::optional<glm::vec2> pixel);

//! The clicked voxel at the replay time: what the colour modes show for it (body_analysis.hpp).
struct VoxelReading {
    int voxel = -1;
    std::array<int, 3> cell{0, 0, 0};  //!< lattice cell of the body
    int material = 0;                  //!< 1-based
    std::string material_name;
    bool held = false;
    float displacement_vox = 0.0f;  //!< from t = 0, voxel lengths
    float strain = 0.0f;            //!< volumetric
    float actuation = 0.0f;         //!< the signal, -1 .. 1 (0 for passive voxels, settling)
    int fibre_axis = -1;            //!< 0..2 = x..z for a muscle voxel, -1 otherwise
};
//! Empty when no voxel is inspected or the body shown is no longer the one it was picked on.
std::optional<VoxelReading> inspected_voxel(const Studio& studio);

}  // namespace bhm::app::gui
