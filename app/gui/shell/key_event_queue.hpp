#pragma once
// Key presses, releases and typed characters handed to ImGui in the order they came, so a quick
// keystroke is never lost at a low frame rate (issue 39, M2). ImGui 1.86 reads keys as a state
// (io.KeysDown) when a frame begins, and a text field acts on one key per frame: at 5-20 fps a
// key pressed and released between two frames was never seen (Ctrl+A, End, Backspace did
// nothing) and characters typed after it were inserted before it took effect (a typed path
// spliced into the proposed one). Here each press is held down for the frame that takes it,
// at most one key (besides modifiers) per frame, and characters typed after a key wait for the
// next frame. The window's GLFW callbacks and the headless studio's fast keys both feed it.
#include <deque>
#include <vector>

struct ImGuiIO;

namespace bhm::app::gui {

class KeyEventQueue {
  public:
    //! A GLFW key event (GLFW_PRESS, GLFW_REPEAT or GLFW_RELEASE, GLFW_MOD_* bits).
    void key(int key, int action, int mods);
    //! A typed character (GLFW's char callback).
    void character(unsigned int codepoint);
    //! Before ImGui::NewFrame: lets go of the keys held for the last frame whose release has
    //! come, then hands ImGui the events up to the second key press (or a character after a
    //! key press), which wait for the next frame.
    void deliver(ImGuiIO& io);
    //! Events still waiting for a frame (a reason to draw another).
    bool pending() const { return !events_.empty(); }

  private:
    struct Event {
        enum class Kind { Press, Release, Character } kind = Kind::Press;
        int key = 0;
        int mods = 0;
        unsigned int codepoint = 0;
    };
    std::deque<Event> events_;
    std::vector<int> down_;    //!< keys whose press ImGui has been given and not yet the release
    std::vector<int> let_go_;  //!< released, to be let go of before the next frame's events
};

}  // namespace bhm::app::gui
