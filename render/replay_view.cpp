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

engine::VoxelPoses poses_at_time(const engine::Replay& replay, double time_s,
                                 PoseSampling sampling) {
    const auto& frames = replay.frames;
    if (frames.empty()) throw std::invalid_argument("replay has no frames");
    // First frame strictly after time_s; the one before it is at or before time_s.
    const auto after =
        std::upper_bound(frames.begin(), frames.end(), time_s,
                         [](double t, const engine::VoxelPoses& f) { return t < f.time_s; });
    if (after == frames.begin()) return frames.front();
    const auto& a = *(after - 1);
    if (after == frames.end() || sampling == PoseSampling::NearestBefore || a.time_s == time_s) {
        engine::VoxelPoses out = a;
        return out;
    }
    const auto& b = *after;
    if (a.position_m.size() != b.position_m.size() ||
        a.orientation.size() != b.orientation.size() || a.size_m.size() != b.size_m.size())
        throw std::invalid_argument("replay frames differ in voxel count");
    const float f = static_cast<float>((time_s - a.time_s) / (b.time_s - a.time_s));
    engine::VoxelPoses out = a;
    out.time_s = time_s;
    for (std::size_t i = 0; i < out.position_m.size(); ++i)
        out.position_m[i] = a.position_m[i] + f * (b.position_m[i] - a.position_m[i]);
    for (std::size_t i = 0; i < out.size_m.size(); ++i)
        out.size_m[i] = a.size_m[i] + f * (b.size_m[i] - a.size_m[i]);
    for (std::size_t i = 0; i + 3 < out.orientation.size(); i += 4) {
        glm::vec4 qa{a.orientation[i], a.orientation[i + 1], a.orientation[i + 2],
                     a.orientation[i + 3]};
        glm::vec4 qb{b.orientation[i], b.orientation[i + 1], b.orientation[i + 2],
                     b.orientation[i + 3]};
        if (glm::dot(qa, qb) < 0.0f) qb = -qb;  // q and -q are the same rotation
        glm::vec4 q = qa + f * (qb - qa);
        const float n = glm::length(q);
        q = n > 1e-8f ? q / n : qa;
        for (int k = 0; k < 4; ++k)
            out.orientation[i + static_cast<std::size_t>(k)] = q[k];
    }
    return out;
}

glm::vec3 center_of_mass(const engine::VoxelPoses& poses, const std::vector<float>& voxel_weight) {
    const int n = poses.voxel_count();
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (int v = 0; v < n; ++v) {
        const std::size_t i = static_cast<std::size_t>(v);
        const double w = voxel_weight.size() == static_cast<std::size_t>(n) ? voxel_weight[i] : 1.0;
        sum += w * glm::dvec3(poses.position_m[3 * i], poses.position_m[3 * i + 1],
                              poses.position_m[3 * i + 2]);
        total += w;
    }
    return total > 0.0 ? glm::vec3(sum / total) : glm::vec3(0.0f);
}

std::vector<glm::vec3> center_of_mass_trail(const engine::Replay& replay, double time_s,
                                            const std::vector<float>& voxel_weight) {
    std::vector<glm::vec3> trail;
    for (const auto& frame : replay.frames) {
        if (frame.time_s > time_s) break;
        trail.push_back(center_of_mass(frame, voxel_weight));
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
        const glm::vec3 d{poses.position_m[i] - rest.position_m[i],
                          poses.position_m[i + 1] - rest.position_m[i + 1],
                          poses.position_m[i + 2] - rest.position_m[i + 2]};
        out[static_cast<std::size_t>(v)] = glm::length(d);
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
