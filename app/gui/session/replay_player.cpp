#include "app/gui/session/replay_player.hpp"

#include <algorithm>
#include <cmath>

namespace bhm::app::gui {

void ReplayClock::set_duration(double duration) {
    duration_s = std::max(0.0, duration);
    time_s = std::clamp(time_s, 0.0, duration_s);
}

void ReplayClock::advance(double wall_dt_s) {
    if (!playing || duration_s <= 0.0) return;
    time_s += wall_dt_s * speed;
    if (time_s >= duration_s) {
        if (loop) {
            time_s = std::fmod(time_s, duration_s);
        } else {
            time_s = duration_s;
            playing = false;
        }
    } else if (time_s < 0.0) {
        time_s = loop ? duration_s + std::fmod(time_s, duration_s) : 0.0;
    }
}

void ReplayClock::seek(double t_s) {
    time_s = std::clamp(t_s, 0.0, duration_s);
}

void ReplayClock::step_frames(int frames, double frame_dt_s) {
    playing = false;
    seek(time_s + frames * frame_dt_s);
}

int frame_index_at(const engine::Replay& replay, double t_s) {
    const auto& frames = replay.frames;
    if (frames.empty()) return -1;
    // First frame with time > t, minus one. Sample times come from summed steps: allow 1 ns.
    const auto it = std::upper_bound(
        frames.begin(), frames.end(), t_s + 1e-9,
        [](double t, const engine::VoxelPoses& frame) { return t < frame.time_s; });
    return std::max(0, static_cast<int>(it - frames.begin()) - 1);
}

engine::VoxelPoses poses_at(const engine::Replay& replay, double t_s) {
    const int i = frame_index_at(replay, t_s);
    if (i < 0) return {};
    const auto& a = replay.frames[static_cast<std::size_t>(i)];
    if (i + 1 >= static_cast<int>(replay.frames.size()) || t_s <= a.time_s) return a;
    const auto& b = replay.frames[static_cast<std::size_t>(i) + 1];
    const double span = b.time_s - a.time_s;
    const float w =
        span > 0.0 ? static_cast<float>(std::clamp((t_s - a.time_s) / span, 0.0, 1.0)) : 0.0f;
    engine::VoxelPoses out = a;
    out.time_s = t_s;
    for (std::size_t k = 0; k < out.position_m.size(); ++k)
        out.position_m[k] = a.position_m[k] + w * (b.position_m[k] - a.position_m[k]);
    for (std::size_t k = 0; k < out.size_m.size(); ++k)
        out.size_m[k] = a.size_m[k] + w * (b.size_m[k] - a.size_m[k]);
    for (std::size_t v = 0; v + 3 < out.orientation.size(); v += 4) {
        float dot = 0.0f;
        for (int c = 0; c < 4; ++c)
            dot += a.orientation[v + c] * b.orientation[v + c];
        const float sign = dot < 0.0f ? -1.0f : 1.0f;  // q and -q are the same rotation
        float norm = 0.0f;
        for (int c = 0; c < 4; ++c) {
            const float q =
                a.orientation[v + c] + w * (sign * b.orientation[v + c] - a.orientation[v + c]);
            out.orientation[v + c] = q;
            norm += q * q;
        }
        norm = std::sqrt(norm);
        if (norm > 0.0f)
            for (int c = 0; c < 4; ++c)
                out.orientation[v + c] /= norm;
    }
    return out;
}

std::vector<glm::vec3> centre_of_mass_per_frame(const engine::Replay& replay,
                                                const std::vector<double>& material_density) {
    std::vector<glm::vec3> com;
    com.reserve(replay.frames.size());
    for (const auto& frame : replay.frames) {
        const int n = frame.voxel_count();
        double mass = 0.0, sum[3] = {0.0, 0.0, 0.0};
        for (int v = 0; v < n; ++v) {
            const std::size_t m = v < static_cast<int>(replay.voxel_material.size())
                                      ? replay.voxel_material[static_cast<std::size_t>(v)]
                                      : 0;
            const double density =
                (m >= 1 && m <= material_density.size()) ? material_density[m - 1] : 1.0;
            double volume = 1.0;
            if (frame.size_m.size() >= 3 * static_cast<std::size_t>(n))
                for (int c = 0; c < 3; ++c)
                    volume *= frame.size_m[3 * static_cast<std::size_t>(v) + c];
            const double w = density * volume;
            mass += w;
            for (int c = 0; c < 3; ++c)
                sum[c] += w * frame.position_m[3 * static_cast<std::size_t>(v) + c];
        }
        if (mass <= 0.0) mass = 1.0;
        com.emplace_back(sum[0] / mass, sum[1] / mass, sum[2] / mass);
    }
    return com;
}

}  // namespace bhm::app::gui
