#pragma once
// From a recorded simulation (engine::Replay) to what the renderer draws: the body, its poses at
// any time, the centre-of-mass trail.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/replay.hpp"
#include "render/camera.hpp"
#include "render/scene.hpp"

namespace bhm::render {

//! The replay's body with the poses of frame 0 (rest poses when it has no frames).
BodyView body_view_from_replay(const engine::Replay& replay);

//! Centre of mass of each frame up to and including time_s (engine::centre_of_mass; voxel_mass
//! from engine::voxel_mass_weights, empty = all equal).
std::vector<glm::vec3> centre_of_mass_trail(const engine::Replay& replay, double time_s,
                                            const std::vector<double>& voxel_mass = {});

//! Bounds of every voxel over every frame (for framing a whole sequence without jumps).
Bounds replay_bounds(const engine::Replay& replay);

//! Per-voxel scalars for ColorMode::Scalar.
//! Distance of each voxel's centre from its rest position (metres).
std::vector<float> voxel_displacement_m(const engine::VoxelPoses& poses,
                                        const engine::VoxelPoses& rest);
//! Volumetric strain of each voxel: current volume / rest volume - 1 (rest edge = voxel size).
std::vector<float> voxel_volume_strain(const engine::VoxelPoses& poses, double voxel_size_m);

}  // namespace bhm::render
