#include "render/replay_view.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/glm.hpp>

namespace bhm::render {

BodyView body_view_from_replay(const engine::Replay& replay) {
    BodyView body;
    body.nx = replay.nx, body.ny = replay.ny, body.nz = replay.nz;
    body.voxel_size_m = replay.voxel_size_m;
    body.voxel_cell = replay.voxel_cell;
    body.voxel_material = replay.voxel_material;
    body.voxel_fixed = replay.voxel_fixed;
    body.poses = replay.frames.empty() ? rest_poses(body) : replay.frames.front();
    return body;
}

std::vector<glm::vec3> centre_of_mass_trail(const engine::Replay& replay, double time_s,
                                            const std::vector<double>& voxel_mass) {
    std::vector<glm::vec3> trail;
    for (const auto& frame : replay.frames) {
        if (frame.time_s > time_s) break;
        const auto com = engine::centre_of_mass(frame, voxel_mass);
        trail.emplace_back(com[0], com[1], com[2]);
    }
    return trail;
}

Bounds replay_bounds(const engine::Replay& replay) {
    Bounds bounds;
    for (const auto& frame : replay.frames) {
        for (int v = 0; v < frame.voxel_count(); ++v) {
            const std::size_t i = static_cast<std::size_t>(v);
            const glm::vec3 c{frame.position_m[3 * i], frame.position_m[3 * i + 1],
                              frame.position_m[3 * i + 2]};
            const glm::vec3 s{frame.size_m.size() > 3 * i + 2 ? frame.size_m[3 * i] : 0.0f,
                              frame.size_m.size() > 3 * i + 2 ? frame.size_m[3 * i + 1] : 0.0f,
                              frame.size_m.size() > 3 * i + 2 ? frame.size_m[3 * i + 2] : 0.0f};
            const glm::vec3 half(0.5f * glm::length(s));
            bounds.add(c - half);
            bounds.add(c + half);
        }
    }
    return bounds;
}

std::vector<float> voxel_displacement_m(const engine::VoxelPoses& poses,
                                        const engine::VoxelPoses& rest) {
    const int n = std::min(poses.voxel_count(), rest.voxel_count());
    std::vector<float> out(static_cast<std::size_t>(poses.voxel_count()), 0.0f);
    for (int v = 0; v < n; ++v) {
        const std::size_t i = 3 * static_cast<std::size_t>(v);
        // In double: the square of a float near its largest (3.4e38) overflows.
        const glm::dvec3 d =
            glm::dvec3(poses.position_m[i], poses.position_m[i + 1], poses.position_m[i + 2]) -
            glm::dvec3(rest.position_m[i], rest.position_m[i + 1], rest.position_m[i + 2]);
        out[static_cast<std::size_t>(v)] = static_cast<float>(glm::length(d));
    }
    return out;
}

std::vector<float> voxel_volume_strain(const engine::VoxelPoses& poses, double voxel_size_m) {
    const double rest_volume = voxel_size_m * voxel_size_m * voxel_size_m;
    std::vector<float> out(static_cast<std::size_t>(poses.voxel_count()), 0.0f);
    if (!(rest_volume > 0.0)) return out;
    for (std::size_t v = 0; v < out.size() && 3 * v + 2 < poses.size_m.size(); ++v) {
        const double volume = static_cast<double>(poses.size_m[3 * v]) * poses.size_m[3 * v + 1] *
                              poses.size_m[3 * v + 2];
        out[v] = static_cast<float>(volume / rest_volume - 1.0);
    }
    return out;
}

}  // namespace bhm::render
