#include "evo/search/volume_front.hpp"

namespace bhm::evo {

std::vector<bool> volume_front(const std::vector<VolumePoint>& points, VolumeObjective direction) {
    const int sign = direction == VolumeObjective::Maximize ? -1 : 1;  // volume as minimised
    auto beats = [&](const VolumePoint& a, const VolumePoint& b) {
        const int va = sign * a.voxels, vb = sign * b.voxels;
        return a.fitness >= b.fitness && va <= vb && (a.fitness > b.fitness || va < vb);
    };
    // O(n^2): a population or an archive of a few hundred at most.
    std::vector<bool> on_front(points.size(), true);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t j = 0; j < points.size() && on_front[i]; ++j)
            on_front[i] = !(j != i && beats(points[j], points[i]));
    return on_front;
}

}  // namespace bhm::evo
