// Settings persistence: round trip, clamping, damaged files, atomic writes, recent files, and the
// XDG location.
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>

#include "app/gui/settings/studio_settings.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm::app::gui;
namespace fs = std::filesystem;

TEST_CASE("studio settings: what is saved is read back") {
    const auto dir = testing::fresh_dir("settings");
    StudioSettings s;
    s.window_width = 1700;
    s.window_height = 1000;
    s.ui_scale = 1.5f;
    s.layout.left_px = 333.0f;
    s.layout.plot_px = 222.0f;
    s.camera.yaw_rad = 0.25f;
    s.camera.pitch_rad = -0.5f;
    s.camera.zoom = 2.0f;
    s.camera.orthographic = true;
    s.remember("b.json");
    s.remember("a.json");
    const auto path = (dir / "nested" / "settings.json").string();
    save_settings(path, s);
    CHECK(fs::exists(path));
    CHECK_FALSE(fs::exists(path + ".tmp"));
    std::string warning;
    CHECK(load_settings(path, &warning) == s);
    CHECK(warning.empty());
}

TEST_CASE("studio settings: missing, damaged and out-of-range files fall back safely") {
    const auto dir = testing::fresh_dir("settings-bad");
    std::string warning;
    CHECK(load_settings((dir / "none.json").string(), &warning) == StudioSettings{});
    CHECK(warning.empty());
    const auto damaged = (dir / "damaged.json").string();
    std::ofstream(damaged) << "{\"window\": {\"width\": 1";
    CHECK(load_settings(damaged, &warning) == StudioSettings{});
    CHECK(warning.find(damaged) == 0);
    const auto wild = settings_from_json(nlohmann::json::parse(
        R"({"ui_scale": 40, "window": {"width": -5, "height": "tall"}, "camera": {"pitch_rad": 9},
            "recent_files": ["/d/x.json", 7, "relative.json", "/d/y.json"]})"));
    CHECK(wild.ui_scale == 3.0f);
    CHECK(wild.window_width == 320);
    CHECK(wild.window_height == StudioSettings{}.window_height);
    CHECK(wild.camera.pitch_rad == doctest::Approx(1.55f));
    // Relative entries name no file reliably (they depended on the folder the studio ran in).
    CHECK(wild.recent_files == std::vector<std::string>{"/d/x.json", "/d/y.json"});
}

TEST_CASE("studio settings: recent files are absolute, newest first, unique and capped") {
    StudioSettings s;
    for (int i = 0; i < 15; ++i)
        s.remember("f" + std::to_string(i) + ".json");
    s.remember((std::filesystem::current_path() / "sub" / ".." / "f12.json").string());
    const auto abs = [](const char* name) {
        return (std::filesystem::current_path() / name).string();
    };
    REQUIRE(s.recent_files.size() == StudioSettings::kMaxRecent);
    CHECK(s.recent_files[0] == abs("f12.json"));
    CHECK(s.recent_files[1] == abs("f14.json"));
    CHECK(s.recent_files[2] == abs("f13.json"));
    CHECK(s.recent_files.back() == abs("f5.json"));
    for (const auto& path : s.recent_files)
        CHECK(std::filesystem::path(path).is_absolute());
}

TEST_CASE("studio settings: the file lives under XDG_CONFIG_HOME, else ~/.config") {
    const char* old_xdg = std::getenv("XDG_CONFIG_HOME");
    const std::string saved = old_xdg ? old_xdg : "";
    setenv("XDG_CONFIG_HOME", "/tmp/xdg-test", 1);
    CHECK(default_settings_path() == "/tmp/xdg-test/bhm-studio/settings.json");
    unsetenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    if (home)
        CHECK(default_settings_path() == std::string(home) + "/.config/bhm-studio/settings.json");
    if (old_xdg) setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
}
