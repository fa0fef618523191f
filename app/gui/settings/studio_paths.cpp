#include "app/gui/settings/studio_paths.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace bhm::app::gui {

namespace fs = std::filesystem;

std::string absolute_path(const std::string& path) {
    if (path.empty()) return path;
    std::error_code ec;
    const fs::path p = fs::absolute(path, ec);
    return ec ? path : p.lexically_normal().string();
}

std::string default_runs_root() {
    const char* xdg = std::getenv("XDG_DATA_HOME");
    if (xdg && *xdg && fs::path(xdg).is_absolute())
        return (fs::path(xdg) / "bhm-studio" / "runs").string();
    const char* home = std::getenv("HOME");
    if (home && *home)
        return (fs::path(home) / ".local" / "share" / "bhm-studio" / "runs").string();
    return absolute_path("runs");
}

std::string default_screenshots_dir() {
    return (fs::path(default_runs_root()).parent_path() / "screenshots").string();
}

std::string default_export_path(const std::string& name) {
    return (fs::path(default_runs_root()).parent_path() / "exports" / name).string();
}

std::string next_numbered_path(const std::string& path) {
    const fs::path base(absolute_path(path));
    std::error_code ec;
    for (int n = 1;; ++n) {
        char number[16];
        std::snprintf(number, sizeof number, "-%03d", n);
        const fs::path candidate =
            base.parent_path() / (base.stem().string() + number + base.extension().string());
        if (!fs::exists(candidate, ec)) return candidate.string();
    }
}

std::string default_presets_dir() {
    if (const char* env = std::getenv("BHM_PRESETS_DIR"); env && *env) return absolute_path(env);
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed =
            exe.parent_path().parent_path() / "share" / "bhm" / "experiments";
        if (fs::is_directory(installed, ec)) return installed.lexically_normal().string();
    }
    return (fs::path(BHM_STUDIO_ASSETS_DIR) / "experiments").lexically_normal().string();
}

bool is_shipped_preset(const std::string& path, const std::string& presets_dir) {
    if (path.empty() || presets_dir.empty()) return false;
    std::error_code ec;
    const fs::path file = fs::weakly_canonical(fs::absolute(path, ec), ec);
    const fs::path dir = fs::weakly_canonical(fs::absolute(presets_dir, ec), ec);
    if (ec) return false;
    const auto rel = file.lexically_relative(dir);
    return !rel.empty() && *rel.begin() != ".." && rel.is_relative() && rel != ".";
}

std::vector<std::string> list_experiment_files(const std::string& dir) {
    std::vector<std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code type_ec;
        if (it->is_regular_file(type_ec) && it->path().extension() == ".json")
            files.push_back(absolute_path(it->path().string()));
    }
    std::sort(files.begin(), files.end());
    return files;
}

FileListing read_file_listing(const std::string& dir) {
    FileListing out;
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) {
        out.error = dir + ": " + ec.message();
        return out;
    }
    for (fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
        std::error_code type_ec;
        const auto& p = it->path();
        if (p.filename().string().starts_with(".")) continue;  // hidden
        if (it->is_directory(type_ec)) {
            const bool run = fs::exists(p / "run.json", type_ec);
            out.folders.emplace_back(absolute_path(p.string()), run);
        } else if (it->is_regular_file(type_ec) && p.extension() == ".json") {
            out.experiments.push_back(absolute_path(p.string()));
        } else if (it->is_regular_file(type_ec) && p.extension() == ".csv") {
            out.tracks.push_back(absolute_path(p.string()));
        }
    }
    std::sort(out.folders.begin(), out.folders.end());
    std::sort(out.experiments.begin(), out.experiments.end());
    std::sort(out.tracks.begin(), out.tracks.end());
    return out;
}

}  // namespace bhm::app::gui
