#pragma once
// Experiment-aware scene building for the renderer: the one place that maps an evo::Experiment
// (materials, boundary faces, enclosure) onto render::Scene colours and face markings.
// render/ itself knows nothing of evo.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "engine/body_spec.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/experiment.hpp"
#include "render/scene.hpp"

namespace bhm::app {

//! One colour per material, index 0 = material 1: the material's own colour, else by activity.
std::vector<glm::vec4> experiment_material_colors(const evo::Experiment& experiment);

//! RGBA per material (index k-1 for material k): the experiment's colour, else muscle red for
//! active and tissue blue for passive materials; then one more entry, the translucent enclosure
//! colour, used for frame voxels (see mark_enclosure_voxels).
std::vector<glm::vec4> render_material_colors(const evo::Experiment& experiment);

//! Fixed faces green; a free face purple when the face opposite it is fixed (the free end of the
//! paper's Figure 2); other free faces unmarked, so they do not veil the body.
std::array<render::FaceMarking, 6> render_face_markings(const evo::Experiment& experiment);

//! Gives the voxels of the enclosure frame (in the frame layers and of the enclosure material)
//! the extra translucent colour entry. Lattice = the experiment's workspace.
void mark_enclosure_voxels(const evo::Experiment& experiment, render::BodyView& body);

//! The framed body (evo::make_body_spec's output) at rest in the experiment's workspace.
render::Scene rest_scene(const evo::Experiment& experiment, const engine::BodySpec& spec);

enum class ScalarColoring { Material, Displacement, Strain, Phase };
//! "material", "displacement", "strain", "phase"; throws std::invalid_argument otherwise.
ScalarColoring parse_scalar_coloring(const std::string& name);

struct ReplaySceneOptions {
    bool ghost = false;         //!< the t = 0 state as a translucent ghost
    bool ghost_beside = false;  //!< beside the body (one voxel apart) instead of over it
    int ghost_axis = 1;         //!< the axis it is moved along when beside: 0 = +x, 1 = +y
    bool trail = false;         //!< centre-of-mass trail up to the time shown
    bool interpolate = true;    //!< blend frames, or the last frame at or before the time
};

//! A replay's body at time_s in the experiment's workspace. Throws std::invalid_argument when the
//! replay's lattice is not the experiment's workspace.
render::Scene replay_scene(const evo::Experiment& experiment, const engine::Replay& replay,
                           double time_s, const ReplaySceneOptions& options = {});

//! Colours the scene's voxels by a scalar (sets colour map, range and legend). Displacement is
//! measured from rest (the replay's first frame when given, else the lattice) in voxel lengths,
//! range from zero to the largest value; strain is volumetric, symmetric around zero; phase
//! needs the per-cell phases of the body spec (radians, range [0, 2 pi)).
void apply_scalar_coloring(render::Scene& scene, ScalarColoring coloring,
                           const engine::VoxelPoses* rest_poses = nullptr,
                           const std::vector<float>* cell_phase_rad = nullptr);

//! The colour range of a scalar over every frame of a replay, so that a sequence or a video
//! keeps one scale (displacement from frame 0, in voxel lengths; volumetric strain, symmetric).
render::ScalarRange replay_scalar_range(const engine::Replay& replay, ScalarColoring coloring);

}  // namespace bhm::app
