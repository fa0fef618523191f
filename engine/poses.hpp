#pragma once
// A snapshot of every voxel's pose: what the renderer draws and what a replay stores.
#include <cstdint>
#include <vector>

namespace bhm::engine {

struct VoxelPoses {
    double time_s = 0.0;
    std::vector<float> position_m;   //!< (n x 3) centre of each voxel, world frame
    std::vector<float> orientation;  //!< (n x 4) unit quaternion w, x, y, z
    std::vector<float> size_m;       //!< (n x 3) current edge lengths along the voxel's own axes
    int voxel_count() const { return static_cast<int>(position_m.size() / 3); }
};

}  // namespace bhm::engine
