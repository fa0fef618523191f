#pragma once
// The continuum's deformed voxels as engine poses, so that a view that draws our engine's voxels
// (render::, which knows engine state types only) can draw the FEM's shape the same way: each
// voxel's centre moved by the FEM's centre displacement, its orientation the rotation part of
// the mean edge vectors of its 8 corner nodes (Gram-Schmidt on x, then y), its edge lengths
// their lengths.
#include <array>
#include <vector>

#include "engine/poses.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/fem_model.hpp"

namespace bhm::evo {

//! `rest_position_m`: each voxel's centre at rest in the frame to draw in (the engine's), in the
//! FemModel's voxel order. Throws std::runtime_error when a node has no displacement.
engine::VoxelPoses fem_voxel_shape(const FemModel& model, const NodalDisplacements& u,
                                   const std::vector<std::array<double, 3>>& rest_position_m);

}  // namespace bhm::evo
