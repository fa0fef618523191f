#pragma once
// A replay: every voxel's pose at a fixed frame rate, enough to redraw a simulation exactly.
// CONTRACT used by render/ and app/: keep these declarations; the format is documented in
// docs/replay-format.md.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/poses.hpp"

namespace bhm::engine {

struct Replay {
    int nx = 0, ny = 0, nz = 0;         //!< lattice size of the body
    double voxel_size_m = 0.01;
    double settle_s = 0.0;              //!< end of the settle phase (actuation off before)
    std::vector<std::int32_t> voxel_cell;      //!< (n) lattice cell of each voxel
    std::vector<std::uint8_t> voxel_material;  //!< (n) 1-based material index
    std::vector<std::uint8_t> voxel_fixed;     //!< (n) 1 = held
    std::vector<VoxelPoses> frames;            //!< in time order
};

enum class PoseSampling { NearestBefore, Interpolate };

//! The poses at time_s, clamped to the recorded span: the last frame at or before time_s, or a
//! blend of the two frames around it (positions and sizes linearly, orientations by normalised
//! lerp along the shorter arc). The one home of "a replay at time t" for the renderer, the studio
//! and the exports. Throws std::invalid_argument when the replay has no frames or two frames
//! differ in voxel count.
VoxelPoses pose_at(const Replay& replay, double time_s,
                   PoseSampling sampling = PoseSampling::Interpolate);

//! The mass of each voxel up to a common factor: its material's density (material_density is
//! indexed by the 1-based voxel_material minus one; 1 where it has no entry). Every voxel has the
//! same rest volume and its mass does not change when it is actuated, as in the engine.
std::vector<double> voxel_mass_weights(const Replay& replay,
                                       const std::vector<double>& material_density);

//! The centre of mass of one frame, in metres: voxel centres weighted by voxel_mass (empty = all
//! equal), as World::centre_of_mass_m computes it during the simulation.
std::array<double, 3> centre_of_mass(const VoxelPoses& poses,
                                     const std::vector<double>& voxel_mass = {});

//! Writes atomically (temp file + rename). Throws std::runtime_error naming the path on failure.
void write_replay(const std::string& path, const Replay& replay);
//! Throws std::runtime_error naming the path and what is wrong (missing, truncated, bad magic).
Replay read_replay(const std::string& path);

}  // namespace bhm::engine
