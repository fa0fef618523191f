// bhm studio: the desktop application (app/gui/), in a window or headless on OSMesa for scripts,
// tests and CI. See docs/studio.md.
#include <filesystem>
#include <iostream>
#include <string>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"

#if BHM_WITH_GUI
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/shell/window_runner.hpp"
#include "app/gui/studio.hpp"
#include "app/gui/studio_app.hpp"
#endif

namespace bhm::app {

namespace {

#if BHM_WITH_GUI
// "1280x800" -> width, height; UsageError otherwise.
void parse_size(const std::string& text, int& width, int& height) {
    const auto x = text.find('x');
    try {
        if (x == std::string::npos) throw std::invalid_argument("no x");
        std::size_t used = 0;
        width = std::stoi(text.substr(0, x), &used);
        if (used != x) throw std::invalid_argument("width");
        height = std::stoi(text.substr(x + 1), &used);
        if (used != text.size() - x - 1) throw std::invalid_argument("height");
    } catch (const std::exception&) {
        throw UsageError("--size: expected WIDTHxHEIGHT such as 1280x800, got '" + text + "'");
    }
    if (width < 64 || height < 64 || width > 8192 || height > 8192)
        throw UsageError("--size: each side must be in 64..8192 pixels, got '" + text + "'");
}

int studio_main(ArgParser& p) {
    gui::Studio studio;
    if (p.has("--settings-dir")) {
        studio.settings_path = p.get("--settings-dir") + "/settings.json";
    } else if (!p.has("--headless")) {
        studio.settings_path = gui::default_settings_path();
    }
    std::error_code exists_ec;
    const bool settings_existed = !studio.settings_path.empty() &&
                                  std::filesystem::exists(studio.settings_path, exists_ec);
    if (!studio.settings_path.empty()) {
        std::string warning;
        studio.settings = gui::load_settings(studio.settings_path, &warning);
        if (!warning.empty()) std::cerr << "bhm studio: " << warning << "\n";
    }
    gui::restore_view_settings(studio);

    if (!p.positionals().empty()) {
        const std::string& target = p.positionals().front();
        std::error_code ec;
        const bool ok = std::filesystem::is_directory(target, ec)
                            ? gui::open_run_directory(studio, target)
                            : gui::open_experiment(studio, target);
        if (!ok) {
            std::cerr << "bhm studio: " << studio.ui.status << "\n";
            return 1;
        }
    }
    // A first start (no settings file, or no recent experiment): the welcome, over the quick
    // demo instead of an untitled paper-sized experiment.
    if (p.positionals().empty() &&
        gui::is_first_start(studio.settings_path, settings_existed, studio.settings))
        gui::open_welcome(studio);
    const long long frames = p.get_int("--frames", 0);
    if (frames < 0 || frames > 10'000'000) throw UsageError("--frames: expected 0..10000000");

    if (p.has("--headless")) {
        gui::HeadlessOptions options;
        if (p.has("--size")) parse_size(p.get("--size"), options.width, options.height);
        options.frames = frames > 0 ? static_cast<int>(frames) : 3;
        options.screenshot = p.get("--screenshot");
        options.script = p.get("--script");
        return gui::run_headless(studio, options);
    }
    if (p.has("--screenshot") || p.has("--script"))
        throw UsageError("--screenshot and --script need --headless");
    gui::WindowOptions options;
    if (p.has("--size")) parse_size(p.get("--size"), options.width, options.height);
    options.max_frames = static_cast<int>(frames);
    return gui::run_window(studio, options);
}
#endif

}  // namespace

int cmd_studio(const Args& args) {
    ArgParser parser(
        "studio", "[EXPERIMENT.json | RUN_DIR] [OPTIONS]",
        "Open BHM Studio: edit an experiment, paint its constraints, run evolution and "
        "watch the champion, replay and export. --headless runs the same UI off-screen "
        "(OSMesa) for scripts and CI.");
    parser
        .positional("FILE", "an experiment file to edit, or a run directory to view", false, false)
        .flag("--headless", "no window: draw off-screen (needs no display)")
        .option("--frames", "N",
                "draw at least N frames (window: close after N; default 3 headless)")
        .option("--screenshot", "PNG", "headless: write the last frame to PNG",
                PathRole::OutputFile)
        .option("--size", "WxH", "window or off-screen size in pixels, e.g. 1280x800")
        .option("--script", "JSON", "headless: run the steps of a script (docs/studio.md)")
        .option("--settings-dir", "DIR",
                "read and write settings.json there (default: $XDG_CONFIG_HOME/bhm-studio; "
                "headless runs keep no settings unless this is given)",
                PathRole::OutputDir);
    return run_command(parser, args, [](ArgParser& p) -> int {
#if BHM_WITH_GUI
        return studio_main(p);
#else
        (void)p;
        std::cerr << "bhm studio: this build has no GUI (configured with -DBHM_BUILD_GUI=OFF)\n";
        return 1;
#endif
    });
}

}  // namespace bhm::app
