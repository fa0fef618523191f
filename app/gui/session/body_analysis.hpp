#pragma once
// Per-element and per-time quantities of a simulated body, for the 3D view's colour modes and the
// Analysis plots (compare Polyscope's per-element quantities, VoxCAD's colour modes, MuJoCo's
// simulate plots). Computed once per simulated body on the simulator's worker thread (the frames
// are immutable after that) except the per-frame colours, which are cheap.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/replay.hpp"
#include "evo/experiment/experiment.hpp"
#include "render/colormap.hpp"

namespace bhm::app::gui {

enum class ColorBy { Material, Displacement, Strain, Actuation, Phase, FibreAxis };
inline constexpr std::array<const char*, 6> kColorByNames = {
    "material", "displacement", "strain", "actuation", "phase", "fibre axis"};

//! Time series over the replay frames, from the end of settling as the fitness measures are:
//! centre-of-mass displacement per axis and the tip's displacement in voxel lengths, and the
//! bend angle (the angle between the settled and the current base-to-tip direction; base = the
//! layer of the first fixed face, x- when none is fixed; tip = the filled layer farthest from it,
//! as evo/evaluate/fitness.hpp defines them) in degrees. Before settle_s every value is 0.
struct BodyTimeSeries {
    std::vector<double> t_s;
    std::array<std::vector<double>, 3> com_vox;
    std::vector<double> tip_vox;
    std::vector<double> bend_deg;
    //! Largest per-voxel displacement (voxel lengths) and |volumetric strain| over all frames: the
    //! colour ranges, fixed for the whole replay so colours compare across time.
    float max_displacement_vox = 0.0f;
    float max_abs_strain = 0.0f;
};

//! com_m: centre of mass per frame (SimulatedBody::com_m).
BodyTimeSeries body_time_series(const evo::Experiment& experiment, const engine::Replay& replay,
                                const std::vector<glm::vec3>& com_m);

//! One value per replay voxel at frame `frame` and how to map it:
//!  - displacement: |p(t) - p(0)| in voxel lengths (sequential, 0 .. the replay's maximum);
//!  - strain: volumetric strain sx*sy*sz / L^3 - 1 (diverging, symmetric range);
//!  - actuation: the actuation signal sin(2 pi f (t - settle) + phase) of active voxels, 0 for
//!    passive ones and while settling (diverging, -1 .. 1);
//!  - phase: each active voxel's actuation phase in radians, the controller drawn over the body
//!    (an evolved controller's, or the experiment's uniform or random one; issue 44), 0 for
//!    passive ones (cyclic, -pi .. pi);
//!  - fibre axis: 0, 1, 2 (x, y, z) for a muscle voxel, its own axis or its material's (issue 43:
//!    fibres per voxel); voxels that are not muscle keep their material colour (without).
struct VoxelScalars {
    std::vector<float> values;
    std::vector<std::uint8_t> without;  //!< empty, or 1 where a voxel has no value (see above)
    render::ScalarRange range;
    render::ColorMapName map = render::ColorMapName::Sequential;
    const char* unit = "";
};
//! What drives each replay voxel, from its body spec (static over the replay).
struct VoxelDrive {
    std::vector<float> phase_rad;  //!< actuation phase (0 for uniform phases)
    //! fibre axis 0..2 of a muscle voxel (its own, else its material's); -1 for any other voxel
    std::vector<std::int8_t> fibre_axis;
};

VoxelScalars voxel_scalars(ColorBy by, const evo::Experiment& experiment,
                           const engine::Replay& replay, int frame, const BodyTimeSeries& series,
                           const VoxelDrive& drive);

//! Phase and fibre axis per replay voxel, as evo::make_body_spec draws them.
VoxelDrive voxel_drive(const evo::Experiment& experiment, const evo::Body& framed_body,
                       const engine::Replay& replay);

}  // namespace bhm::app::gui
