#pragma once
// Private to the engine: the second pass of a step. Each voxel gathers the forces of its (up to
// six) links in a fixed order, adds gravity, its external force, floor contact and friction, and
// is integrated with semi-implicit (symplectic) Euler.
#include "engine/internal/model_data.hpp"
#include "engine/internal/world_state.hpp"

namespace bhm::engine {

struct VoxelPassInput {
    double sin_t = 0.0, cos_t = 0.0;  //!< actuation phase of the step (see Model::Data::act_sin)
    double gravity_m_s2 = 0.0;
    double floor_z = 0.0;  //!< height of the floor: 0, or -1e300 without one (never touched)
    //! The implicit bond damping follows: write only the velocities (also as VoxelState's v*),
    //! not the pose; damping_voxel_pass's last sweep moves it
    bool velocity_only = false;
    //! Per voxel slot, the force besides the links' and gravity (N): the external force plus the
    //! springs' across edges (EdgeScratch::force); null: VoxelState::ext_force alone
    const std::array<std::vector<double>, 3>* applied_force = nullptr;
};

//! Integrates every voxel by one dt and returns how many voxels' new state is insane: moved more
//! than one voxel or turned more than one radian in the step, or non-finite (non-zero = diverged;
//! VoxelState::refused marks them).
int voxel_pass(const Model::Data& model, VoxelState& voxels,
               const std::array<LinkScratch, 3>& links, const VoxelPassInput& in);

//! The voxel half of one sweep of the implicit bond damping (damping_pass.hpp) on every voxel:
//! v = v* plus dt M^-1 times the damping loads of damping_link_pass in the link scratch; `last`: then integrates the pose
//! and returns the count of insane voxels as voxel_pass does (0 otherwise).
int damping_voxel_pass(const Model::Data& model, VoxelState& voxels,
                       const std::array<LinkScratch, 3>& links, bool last);

//! The first voxel the last voxel_pass marked as refused, or -1.
int first_refused_voxel(const Model::Data& model, const VoxelState& voxels);

}  // namespace bhm::engine
