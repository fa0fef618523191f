#include "app/gui/settings/studio_settings.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/gui/settings/studio_paths.hpp"
#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app::gui {

namespace {

template <class T>
void read_number(const nlohmann::json& j, const char* key, T& out, T lo, T hi) {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number()) return;
    out = std::clamp(it->get<T>(), lo, hi);
}

}  // namespace

void StudioSettings::remember(const std::string& relative_or_absolute) {
    if (relative_or_absolute.empty()) return;
    // Absolute: the list must mean the same files whatever folder the studio starts from.
    const std::string path = absolute_path(relative_or_absolute);
    std::erase(recent_files, path);
    recent_files.insert(recent_files.begin(), path);
    if (recent_files.size() > kMaxRecent) recent_files.resize(kMaxRecent);
}

std::string default_settings_path() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    if (xdg && *xdg) return std::string(xdg) + "/bhm-studio/settings.json";
    const char* home = std::getenv("HOME");
    if (home && *home) return std::string(home) + "/.config/bhm-studio/settings.json";
    return "";
}

nlohmann::json settings_to_json(const StudioSettings& s) {
    return {
        {"format_version", 1},
        {"window", {{"width", s.window_width}, {"height", s.window_height}}},
        {"ui_scale", s.ui_scale},
        {"layout",
         {{"left_px", s.layout.left_px},
          {"right_px", s.layout.right_px},
          {"bottom_px", s.layout.bottom_px},
          {"run_px", s.layout.run_px},
          {"plot_px", s.layout.plot_px}}},
        {"camera",
         {{"yaw_rad", s.camera.yaw_rad},
          {"pitch_rad", s.camera.pitch_rad},
          {"zoom", s.camera.zoom},
          {"orthographic", s.camera.orthographic}}},
        {"recent_files", s.recent_files},
    };
}

StudioSettings settings_from_json(const nlohmann::json& j) {
    StudioSettings s;
    if (!j.is_object()) return s;
    if (auto w = j.find("window"); w != j.end() && w->is_object()) {
        read_number(*w, "width", s.window_width, 320, 16384);
        read_number(*w, "height", s.window_height, 240, 16384);
    }
    read_number(j, "ui_scale", s.ui_scale, 0.5f, 3.0f);
    if (auto l = j.find("layout"); l != j.end() && l->is_object()) {
        read_number(*l, "left_px", s.layout.left_px, 120.0f, 4000.0f);
        read_number(*l, "right_px", s.layout.right_px, 120.0f, 4000.0f);
        read_number(*l, "bottom_px", s.layout.bottom_px, 60.0f, 2000.0f);
        read_number(*l, "run_px", s.layout.run_px, 80.0f, 2000.0f);
        read_number(*l, "plot_px", s.layout.plot_px, 80.0f, 2000.0f);
    }
    if (auto c = j.find("camera"); c != j.end() && c->is_object()) {
        read_number(*c, "yaw_rad", s.camera.yaw_rad, -100.0f, 100.0f);
        read_number(*c, "pitch_rad", s.camera.pitch_rad, -1.55f, 1.55f);
        read_number(*c, "zoom", s.camera.zoom, 0.05f, 50.0f);
        if (auto o = c->find("orthographic"); o != c->end() && o->is_boolean())
            s.camera.orthographic = o->get<bool>();
    }
    if (auto r = j.find("recent_files"); r != j.end() && r->is_array()) {
        for (const auto& entry : *r)
            // Relative entries (older files) name no file reliably: dropped.
            if (entry.is_string() && s.recent_files.size() < StudioSettings::kMaxRecent &&
                std::filesystem::path(entry.get<std::string>()).is_absolute())
                s.recent_files.push_back(entry.get<std::string>());
    }
    return s;
}

StudioSettings load_settings(const std::string& path, std::string* warning) {
    std::error_code ec;
    if (path.empty() || !std::filesystem::exists(path, ec)) return {};
    try {
        const std::string text = engine::read_text(path, engine::kTextFileCap);
        return settings_from_json(nlohmann::json::parse(text));
    } catch (const std::exception& e) {
        if (warning) *warning = path + ": ignoring damaged settings file (" + e.what() + ")";
        return {};
    }
}

void save_settings(const std::string& path, const StudioSettings& settings) {
    const std::filesystem::path p(path);
    std::error_code ec;
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
    if (ec) throw std::runtime_error(path + ": cannot create the folder: " + ec.message());
    evo::write_file_atomically(path, settings_to_json(settings).dump(2) + "\n");
}

}  // namespace bhm::app::gui
