#pragma once
// The real studio UI on an OSMesa (llvmpipe) context with no display: synthetic mouse and keyboard
// go into ImGui exactly where the GLFW backend would put them, each frame is drawn off-screen and
// can be read back. Scripts (script.hpp), tests and the benchmark drive the studio through this.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "app/gui/shell/key_event_queue.hpp"
#include "app/gui/studio.hpp"
#include "app/gui/studio_app.hpp"
#include "render/image.hpp"

namespace bhm::app::gui {

//! Keeps freed heap memory in the process instead of returning it to the kernel at once. llvmpipe
//! allocates and frees megabytes of binned scene data every frame; with glibc's defaults that
//! memory goes back and forth through brk/munmap and page faults, about a quarter of a frame's
//! CPU time (measured with perf, tests/bench/bench_studio.cpp). Process-wide, so app/ only.
void keep_freed_memory_for_rendering();

//! Input state held between frames, copied into ImGuiIO before each NewFrame.
struct SyntheticInput {
    glm::vec2 mouse{-1.0f, -1.0f};
    std::array<bool, 3> buttons{};
    //! A press (and maybe its release) that came in the same event batch as this frame: the
    //! button reads as down for this one frame, as the GLFW backend latches a press it saw
    //! released before the frame began. Cleared by the frame.
    std::array<bool, 3> pressed_in_batch{};
    float wheel = 0.0f;  //!< consumed by the next frame
    bool ctrl = false, shift = false;
    int key = 0;  //!< GLFW key code held down (0 = none)
    //! Presses since the last frame, as the window's key callback records them (a press and its
    //! release may both come before the frame). Moved into studio.ui.key_presses by the frame.
    std::vector<KeyChord> key_presses;
    //! What ImGui's text fields get: the same events a window's key and char callbacks queue
    //! (a fast key's press and release, typed characters), handed over a frame at a time.
    KeyEventQueue keys;
};

class HeadlessStudio {
  public:
    //! Creates the off-screen context, an ImGui context with the studio style and the app.
    //! Throws std::runtime_error when OSMesa or the shaders fail.
    HeadlessStudio(Studio& studio, int width, int height);
    ~HeadlessStudio();
    HeadlessStudio(const HeadlessStudio&) = delete;
    HeadlessStudio& operator=(const HeadlessStudio&) = delete;

    //! One full frame (input, UI, 3D view, ImGui drawing). dt_s advances the replay clock.
    void frame(double dt_s = 1.0 / 60.0);
    //! Pixels of the last frame, top row first.
    render::Image capture();

    SyntheticInput& input() { return input_; }
    //! The window's logical size (as a resize would make it); at most the size it was created
    //! with (the off-screen target keeps that size). False when out of range.
    bool set_display_size(int width, int height);
    Studio& studio() { return studio_; }
    StudioApp& app() { return *app_; }
    int width() const { return width_; }
    int height() const { return height_; }
    const std::string& font() const { return font_; }
    std::string gl_renderer() const;

  private:
    struct Gl;
    Studio& studio_;
    int width_, height_;
    int target_width_, target_height_;
    std::unique_ptr<Gl> gl_;
    std::unique_ptr<StudioApp> app_;
    SyntheticInput input_;
    std::string font_;
};

}  // namespace bhm::app::gui
