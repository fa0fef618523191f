#pragma once
// A replay: every voxel's pose at a fixed frame rate, enough to redraw a simulation exactly.
// CONTRACT used by render/ and app/: keep these declarations; the format is documented in
// docs/replay-format.md.
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

//! Writes atomically (temp file + rename). Throws std::runtime_error naming the path on failure.
void write_replay(const std::string& path, const Replay& replay);
//! Throws std::runtime_error naming the path and what is wrong (missing, truncated, bad magic).
Replay read_replay(const std::string& path);

}  // namespace bhm::engine
