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

std::vector<glm::vec3> centre_of_mass_per_frame(const engine::Replay& replay,
                                                const std::vector<double>& material_density) {
    const std::vector<double> mass = engine::voxel_mass_weights(replay, material_density);
    std::vector<glm::vec3> com;
    com.reserve(replay.frames.size());
    for (const auto& frame : replay.frames) {
        const auto c = engine::centre_of_mass(frame, mass);
        com.emplace_back(c[0], c[1], c[2]);
    }
    return com;
}

}  // namespace bhm::app::gui
