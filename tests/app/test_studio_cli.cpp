// `bhm studio` from the command line: headless screenshots and scripts, usage errors, and the
// GLFW window path under Xvfb (skipped with a message when xvfb-run is not installed).
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>

#include "app/cli/commands.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "render/image.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
namespace fs = std::filesystem;

TEST_CASE("bhm studio --headless writes a screenshot of the requested size") {
    const auto dir = app::gui::testing::fresh_dir("cli");
    const auto png = (dir / "ui.png").string();
    const std::string preset = std::string(BHM_SOURCE_DIR) + "/assets/experiments/quick-demo.json";
    CHECK(app::cmd_studio({preset, "--headless", "--frames", "4", "--size", "800x500",
                           "--screenshot", png}) == 0);
    const auto image = render::read_png(png);
    CHECK(image.width == 800);
    CHECK(image.height == 500);
    CHECK_FALSE(fs::exists(dir / "settings.json"));  // headless keeps no settings by default
}

TEST_CASE("bhm studio: usage errors exit 2, failing scripts and files exit 1") {
    const auto dir = app::gui::testing::fresh_dir("cli-errors");
    CHECK(app::cmd_studio({"--headless", "--size", "12"}) == 2);
    CHECK(app::cmd_studio({"--screenshot", "x.png"}) == 2);  // needs --headless
    CHECK(app::cmd_studio({"--headless", "/nonexistent/experiment.json"}) == 1);
    const auto script = (dir / "bad.json").string();
    std::ofstream(script) << R"([{"frames": 1}, {"fly": true}])";
    CHECK(app::cmd_studio({"--headless", "--script", script}) == 1);
    std::ofstream(dir / "notjson.json") << "[{";
    CHECK(app::cmd_studio({"--headless", "--script", (dir / "notjson.json").string()}) == 1);
}

TEST_CASE("bhm studio --headless --settings-dir remembers the experiment it opened") {
    const auto dir = app::gui::testing::fresh_dir("cli-settings");
    const auto exp = (dir / "exp.json").string();
    evo::save_experiment(exp, app::gui::testing::tiny_experiment());
    CHECK(app::cmd_studio({exp, "--headless", "--settings-dir", dir.string()}) == 0);
    std::ifstream in(dir / "settings.json");
    REQUIRE(in);
    const auto settings = nlohmann::json::parse(in);
    REQUIRE(settings.at("recent_files").size() == 1);
    CHECK(settings.at("recent_files")[0] == exp);
}

TEST_CASE("bhm studio opens a GLFW window under Xvfb and closes after --frames") {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) {
        MESSAGE("skipped: xvfb-run is not installed (Debian package xvfb)");
        return;
    }
    const auto dir = app::gui::testing::fresh_dir("window");
    // The GL driver GLFW loads (libGL, swrast) keeps allocations until exit and is unloaded
    // before LeakSanitizer can name it; the studio's own code is leak-checked in-process by the
    // headless tests, so leak detection is off for this child process only.
    const std::string command =
        "ASAN_OPTIONS=detect_leaks=0 xvfb-run -a -s '-screen 0 1280x800x24' " +
        std::string(BHM_BINARY_DIR) + "/bin/bhm studio --frames 5 --size 1024x700 --settings-dir " +
        dir.string() + " " + BHM_SOURCE_DIR + "/assets/experiments/quick-demo.json > " +
        (dir / "log.txt").string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream log(dir / "log.txt");
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    CHECK_MESSAGE(status == 0, "bhm studio under xvfb-run failed: " << text);
    // Closing saved the window size and the recent file.
    std::ifstream in(dir / "settings.json");
    REQUIRE(in);
    const auto settings = nlohmann::json::parse(in);
    CHECK(settings.at("window").at("width") == 1024);
    CHECK(settings.at("recent_files").size() == 1);
}
