#pragma once
// When the window loop draws a frame. Evolving, playing a replay, simulating a body, exporting
// frames or dragging: every frame. Otherwise (idle, or a run paused or ended) the loop waits for
// input, and a wake-up draws only when something changed: input, a new snapshot of the run or of
// a simulated body; after a change a few frames let ImGui settle (hover, popups), and once a
// second a frame picks up what changes without telling (a watched run directory, file lists).
// A paused run was drawn at full rate, half a core for a still picture.
#include <cstdint>

namespace bhm::app::gui {

struct Studio;

//! Something moves on screen by itself: draw every frame.
bool needs_animation(const Studio& studio);

class RedrawGate {
  public:
    //! The user did something (key, character, button, wheel, pointer moved, resize, focus).
    void input() { input_ = true; }
    //! Whether to draw now (now_s: a steady clock in seconds). Call once per loop iteration.
    bool should_draw(const Studio& studio, double now_s);

    static constexpr int kSettleFrames = 3;
    static constexpr double kQuietPeriodS = 1.0;  //!< longest gap between frames when idle

  private:
    bool input_ = true;
    std::uint64_t stamp_ = 0;
    int settle_ = kSettleFrames;
    double last_draw_s_ = -1e30;
};

}  // namespace bhm::app::gui
