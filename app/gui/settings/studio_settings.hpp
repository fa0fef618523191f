#pragma once
// What the studio remembers between sessions: window size, panel layout, camera, recent files and
// the HiDPI scale. A small JSON file in $XDG_CONFIG_HOME/bhm-studio/ (or ~/.config/bhm-studio/),
// written atomically; a missing or damaged file falls back to the defaults with a warning.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace bhm::app::gui {

struct PanelLayout {
    float left_px = 360.0f;    //!< experiment / constraints column
    float right_px = 400.0f;   //!< run, fitness plot, population column
    float bottom_px = 132.0f;  //!< replay timeline under the 3D view
    float run_px = 270.0f;     //!< run control panel height in the right column
    float plot_px = 250.0f;    //!< fitness plot height
    bool operator==(const PanelLayout&) const = default;
};

struct CameraSettings {
    float yaw_rad = -0.9425f;  //!< the renderer's iso view
    float pitch_rad = 0.534f;
    float zoom = 1.0f;  //!< distance relative to the framed distance (1 = framed)
    bool orthographic = false;
    bool operator==(const CameraSettings&) const = default;
};

struct StudioSettings {
    int window_width = 1600;
    int window_height = 960;
    float ui_scale = 1.0f;  //!< HiDPI: multiplies fonts and sizes, in [0.5, 3]
    PanelLayout layout;
    CameraSettings camera;
    std::vector<std::string> recent_files;  //!< newest first, at most kMaxRecent
    bool operator==(const StudioSettings&) const = default;

    static constexpr std::size_t kMaxRecent = 10;
    //! Moves path, made absolute, to the front of recent_files (no duplicates, capped).
    void remember(const std::string& path);
};

//! $XDG_CONFIG_HOME/bhm-studio/settings.json, else $HOME/.config/bhm-studio/settings.json; empty
//! when neither variable is set.
std::string default_settings_path();

nlohmann::json settings_to_json(const StudioSettings& settings);
//! Reads what it recognises, keeps defaults for the rest and clamps values into range.
StudioSettings settings_from_json(const nlohmann::json& json);

//! Defaults when the file does not exist; a damaged file gives the defaults and a one-line
//! warning naming the file in *warning.
StudioSettings load_settings(const std::string& path, std::string* warning = nullptr);
//! Creates the folder if needed and writes atomically; throws std::runtime_error naming the path.
void save_settings(const std::string& path, const StudioSettings& settings);

}  // namespace bhm::app::gui
