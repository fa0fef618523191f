#include "app/gui/settings/key_chord.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>

namespace bhm::app::gui {

std::optional<KeyChord> parse_key_chord(const std::string& text) {
    std::string s;
    for (char c : text)
        s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    KeyChord chord;
    for (;;) {
        if (s.rfind("ctrl+", 0) == 0) {
            chord.ctrl = true;
            s = s.substr(5);
        } else if (s.rfind("shift+", 0) == 0) {
            chord.shift = true;
            s = s.substr(6);
        } else {
            break;
        }
    }
    static const std::pair<const char*, int> named[] = {
        {"space", GLFW_KEY_SPACE},   {"left", GLFW_KEY_LEFT},   {"right", GLFW_KEY_RIGHT},
        {"home", GLFW_KEY_HOME},     {"end", GLFW_KEY_END},     {"tab", GLFW_KEY_TAB},
        {"escape", GLFW_KEY_ESCAPE}, {"enter", GLFW_KEY_ENTER}, {"delete", GLFW_KEY_DELETE},
        {"up", GLFW_KEY_UP},         {"down", GLFW_KEY_DOWN},   {"backspace", GLFW_KEY_BACKSPACE},
    };
    for (const auto& [name, key] : named)
        if (s == name) {
            chord.key = key;
            return chord;
        }
    if (s.size() == 1 && std::isalnum(static_cast<unsigned char>(s[0]))) {
        chord.key = std::toupper(static_cast<unsigned char>(s[0]));  // GLFW letters/digits = ASCII
        return chord;
    }
    if (s.size() >= 2 && s[0] == 'f' && std::all_of(s.begin() + 1, s.end(), ::isdigit)) {
        const int n = std::stoi(s.substr(1));
        if (n >= 1 && n <= 25) {
            chord.key = GLFW_KEY_F1 + n - 1;
            return chord;
        }
    }
    return std::nullopt;
}

std::optional<KeyChord> key_event_chord(int key, int action, int mods) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return std::nullopt;
    return KeyChord{key, (mods & GLFW_MOD_CONTROL) != 0, (mods & GLFW_MOD_SHIFT) != 0,
                    action == GLFW_REPEAT};
}

}  // namespace bhm::app::gui
