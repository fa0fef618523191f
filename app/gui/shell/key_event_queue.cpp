#include "app/gui/shell/key_event_queue.hpp"

#include <algorithm>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

namespace bhm::app::gui {

namespace {

bool is_modifier(int key) {
    switch (key) {
        case GLFW_KEY_LEFT_CONTROL:
        case GLFW_KEY_RIGHT_CONTROL:
        case GLFW_KEY_LEFT_SHIFT:
        case GLFW_KEY_RIGHT_SHIFT:
        case GLFW_KEY_LEFT_ALT:
        case GLFW_KEY_RIGHT_ALT:
        case GLFW_KEY_LEFT_SUPER:
        case GLFW_KEY_RIGHT_SUPER:
            return true;
        default:
            return false;
    }
}

bool in_range(const ImGuiIO& io, int key) { return key >= 0 && key < IM_ARRAYSIZE(io.KeysDown); }

}  // namespace

void KeyEventQueue::key(int key, int action, int mods) {
    if (action == GLFW_REPEAT) return;  // ImGui repeats a held key itself
    events_.push_back({action == GLFW_RELEASE ? Event::Kind::Release : Event::Kind::Press, key,
                       mods, 0});
}

void KeyEventQueue::character(unsigned int codepoint) {
    events_.push_back({Event::Kind::Character, 0, 0, codepoint});
}

void KeyEventQueue::deliver(ImGuiIO& io) {
    for (int k : let_go_)
        if (in_range(io, k)) io.KeysDown[k] = false;
    // ImGui must see a key up for a frame between two presses, or it takes them for one held.
    std::vector<int> up_for_this_frame;
    up_for_this_frame.swap(let_go_);
    bool key_given = false;  // a key (not a modifier) went down this frame
    int key_mods = 0;        // with these modifiers (GLFW_MOD_*)
    std::vector<int> pressed_now;
    while (!events_.empty()) {
        const Event e = events_.front();
        const bool modifier = e.kind != Event::Kind::Character && is_modifier(e.key);
        // A text field acts on one key per frame, and on characters before keys.
        if (key_given && !modifier && e.kind != Event::Kind::Release) break;
        const auto seen = [&](const std::vector<int>& keys) {
            return std::find(keys.begin(), keys.end(), e.key) != keys.end();
        };
        if (e.kind == Event::Kind::Press && (seen(up_for_this_frame) || seen(pressed_now)))
            break;
        events_.pop_front();
        if (e.kind == Event::Kind::Character) {
            io.AddInputCharacter(e.codepoint);
        } else if (e.kind == Event::Kind::Press) {
            if (in_range(io, e.key)) io.KeysDown[e.key] = true;
            if (std::find(down_.begin(), down_.end(), e.key) == down_.end())
                down_.push_back(e.key);
            pressed_now.push_back(e.key);
            if (!modifier) {
                key_given = true;
                key_mods = e.mods;
            }
        } else {
            down_.erase(std::remove(down_.begin(), down_.end(), e.key), down_.end());
            // Released in the batch it was pressed in: held down for this frame all the same.
            if (std::find(pressed_now.begin(), pressed_now.end(), e.key) != pressed_now.end())
                let_go_.push_back(e.key);
            else if (in_range(io, e.key))
                io.KeysDown[e.key] = false;
        }
    }
    // The modifiers as they were when this frame's key went down (a quick Ctrl+A lets go of Ctrl
    // before the frame); otherwise those held now.
    int mods = key_given ? key_mods : 0;
    if (!key_given)
        for (int k : down_)
            mods |= k == GLFW_KEY_LEFT_CONTROL || k == GLFW_KEY_RIGHT_CONTROL ? GLFW_MOD_CONTROL
                    : k == GLFW_KEY_LEFT_SHIFT || k == GLFW_KEY_RIGHT_SHIFT   ? GLFW_MOD_SHIFT
                    : k == GLFW_KEY_LEFT_ALT || k == GLFW_KEY_RIGHT_ALT       ? GLFW_MOD_ALT
                    : k == GLFW_KEY_LEFT_SUPER || k == GLFW_KEY_RIGHT_SUPER   ? GLFW_MOD_SUPER
                                                                              : 0;
    io.KeyCtrl = (mods & GLFW_MOD_CONTROL) != 0;
    io.KeyShift = (mods & GLFW_MOD_SHIFT) != 0;
    io.KeyAlt = (mods & GLFW_MOD_ALT) != 0;
    io.KeySuper = (mods & GLFW_MOD_SUPER) != 0;
}

}  // namespace bhm::app::gui
