#pragma once
// Playback of a replay: a clock over the simulated time (play, pause, speed, step, scrub, loop)
// and the poses at any time, interpolated between the recorded frames. No GL, no ImGui.
#include <vector>

#include <glm/vec3.hpp>

#include "engine/replay.hpp"

namespace bhm::app::gui {

struct ReplayClock {
    double time_s = 0.0;      //!< simulated time shown
    double duration_s = 0.0;  //!< time of the last frame
    bool playing = false;
    bool loop = true;
    double speed = 1.0;  //!< simulated seconds per wall second

    //! A new replay length; the time is kept (clamped), so a new champion continues in step.
    void set_duration(double duration);
    //! Moves the time by wall_dt_s x speed while playing; at the end it wraps (loop) or stops.
    void advance(double wall_dt_s);
    void seek(double t_s);  //!< clamped to [0, duration]
    //! Moves by whole frames of a replay recorded at frame_dt_s (pauses playback).
    void step_frames(int frames, double frame_dt_s);
};

//! Index of the last frame at or before t (0 before the first frame); -1 for an empty replay.
int frame_index_at(const engine::Replay& replay, double t_s);

//! Centre of mass of each frame (engine::centre_of_mass): voxels weighted by their mass, i.e. by
//! density (an actuated voxel keeps its mass). material_density holds the density of material k
//! at index k-1; empty means equal densities.
std::vector<glm::vec3> centre_of_mass_per_frame(const engine::Replay& replay,
                                                const std::vector<double>& material_density);

}  // namespace bhm::app::gui
