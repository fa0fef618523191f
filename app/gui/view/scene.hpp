#pragma once
// What the 3D view draws, as render::Scene / render::DrawList (plain data, testable without GL):
// the workspace with its boundary faces, enclosure frame and voxel overrides (the painter), or a
// simulated body at the replay clock's time with its centre-of-mass trail and start state.
#include <array>
#include <optional>
#include <vector>

#include <glm/vec4.hpp>

#include "app/gui/session/body_simulator.hpp"
#include "app/gui/studio.hpp"
#include "engine/poses.hpp"
#include "render/draw_list.hpp"
#include "render/scene.hpp"

namespace bhm::app::gui {

//! RGBA per material (index k-1 for material k): the experiment's colours, else the renderer's
//! palette by activity.
std::vector<glm::vec4> material_colors(const evo::Experiment& experiment);

//! Extra materials the painter appends after the experiment's palette to show constraints.
struct PainterMaterials {
    int frame = 0;      //!< enclosure cells (translucent)
    int forbidden = 0;  //!< "empty" overrides: evolution may never fill them
    int fixed = 0;      //!< "fixed" overrides on an empty cell (hatched marker)
};
PainterMaterials painter_materials(const evo::Experiment& experiment);

//! The painter's scene: workspace, faces marked fixed / free, the frame, the overrides and (when
//! given, and the same size as the workspace) a body at rest for context, minus the slice.
render::Scene workspace_scene(const evo::Experiment& experiment, const PainterState& painter,
                              const evo::Body* context_body);

//! Cells the painter draws as occupied (for picking): frame, overrides, context body.
std::vector<std::uint8_t> painter_occupancy(const evo::Experiment& experiment,
                                            const evo::Body* context_body);

//! A simulated body at time t: poses interpolated from its replay, COM trail up to t, and
//! optionally its start state as a ghost beside it.
render::Scene simulation_scene(const SimulatedBody& body, double t_s, const ViewState& view);

//! "Verify in FEM": the scene's body drawn at row `load` of a verification, ours at rest under
//! that load as the body and the FEM's deformed voxels as a ghost over it (voxels matched by
//! lattice cell; the trail and the start ghost go). False, the scene unchanged, when the
//! verification has no shapes for these voxels.
bool apply_fem_overlay(render::Scene& scene, const FemVerification& verification, int load);

//! Highlights for the painter drawn into an existing draw list: a wire box around a cell and a
//! tinted quad over a face (just outside it, see lift_face_tints).
void add_cell_highlight(render::DrawList& list, const std::array<int, 3>& cell, double voxel_size_m,
                        glm::vec4 color);
void add_face_highlight(render::DrawList& list, const std::array<int, 3>& workspace,
                        double voxel_size_m, evo::Face face, glm::vec4 color);
//! Simulation mode: the picked voxel (index into `poses`) as a wire box drawn over everything,
//! placed, turned and sized as it is posed, a little larger so its edges are not inside the
//! neighbours' faces. Nothing when the index is out of range.
void add_posed_voxel_highlight(render::DrawList& list, const engine::VoxelPoses& poses, int voxel,
                               glm::vec4 color);
//! Workspace mode: the renderer's face tints (translucent quads lying in a face of the
//! workspace) moved a twentieth of a voxel outside it, as add_face_highlight's are (the bottom
//! face's a twentieth of a voxel above it, over the floor at z = 0). In the face
//! the tint shared a plane with the voxels on that face (the frame, overrides, the champion) and
//! fought them in the depth buffer: a speckle that changed with each turn of the camera (the
//! faces flickered, issue 39). Their outlines stay on the workspace's edges.
void lift_face_tints(render::DrawList& list, const std::array<int, 3>& workspace,
                     double voxel_size_m);
//! Simulation mode: a fixed face as an opaque green outline with diagonal hatching, a tenth of a
//! voxel outside the workspace (no tint over the body, no z-fighting with the voxels on it).
void add_fixed_face_hatch(render::DrawList& list, const std::array<int, 3>& workspace,
                          double voxel_size_m, evo::Face face);

}  // namespace bhm::app::gui
