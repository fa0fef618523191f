#include "app/gui/widgets/file_dialog.hpp"

#include <filesystem>

#include "app/gui/settings/studio_paths.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;

namespace {

bool is_run_dir(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec) && fs::exists(p / "run.json", ec);
}

std::optional<std::string> choose(FileDialog& d, const std::string& path) {
    d.open = false;
    d.error.clear();
    return path;
}

}  // namespace

const char* file_dialog_title(FileDialogPurpose purpose) {
    switch (purpose) {
        case FileDialogPurpose::OpenExperiment:
            return "Open experiment";
        case FileDialogPurpose::SaveExperimentAs:
            return "Save experiment as";
        case FileDialogPurpose::OpenRun:
            return "Open run directory";
        case FileDialogPurpose::CompareRun:
            return "Compare with run directory";
        case FileDialogPurpose::ShowBody:
            return "Show a body file";
        case FileDialogPurpose::LoadTrack:
            return "Load a measured track";
    }
    return "";
}

bool purpose_wants_run(FileDialogPurpose purpose) {
    return purpose == FileDialogPurpose::OpenRun || purpose == FileDialogPurpose::CompareRun;
}

std::vector<FileDialogEntry> file_dialog_entries(const std::string& dir, FileDialogPurpose purpose,
                                                 std::string* error) {
    std::vector<FileDialogEntry> out;
    const fs::path here(dir);
    if (here.has_parent_path() && here.parent_path() != here)
        out.push_back({FileDialogEntry::Kind::Parent, "..", here.parent_path().string()});
    const FileListing listing = read_file_listing(dir);
    if (error) *error = listing.error;
    for (const auto& [path, run] : listing.folders)
        out.push_back({run ? FileDialogEntry::Kind::Run : FileDialogEntry::Kind::Folder,
                       fs::path(path).filename().string() + "/", path});
    if (purpose == FileDialogPurpose::LoadTrack) {
        for (const auto& path : listing.tracks)
            out.push_back({FileDialogEntry::Kind::Track, fs::path(path).filename().string(), path});
    } else if (!purpose_wants_run(purpose)) {
        for (const auto& path : listing.experiments)
            out.push_back(
                {FileDialogEntry::Kind::Experiment, fs::path(path).filename().string(), path});
    }
    return out;
}

void file_dialog_go(FileDialog& d, const std::string& dir) {
    d.dir = absolute_path(dir);
    d.entries = file_dialog_entries(d.dir, d.purpose, &d.error);
    // On the first real entry (".." is first where there is a parent), not on "..".
    d.selected = !d.entries.empty() && d.entries.front().kind == FileDialogEntry::Kind::Parent &&
                         d.entries.size() > 1
                     ? 1
                     : 0;
    d.scroll_to_selected = true;
}

void open_file_dialog(FileDialog& d, FileDialogPurpose purpose, const std::string& start_dir,
                      const std::string& name) {
    d.open = true;
    d.purpose = purpose;
    d.name = name;
    std::error_code ec;
    file_dialog_go(d, !start_dir.empty() && fs::is_directory(start_dir, ec) ? start_dir : ".");
}

std::optional<std::string> file_dialog_activate(FileDialog& d, std::size_t index) {
    if (index >= d.entries.size()) return std::nullopt;
    const FileDialogEntry e = d.entries[index];
    switch (e.kind) {
        case FileDialogEntry::Kind::Parent:
        case FileDialogEntry::Kind::Folder:
            file_dialog_go(d, e.path);
            return std::nullopt;
        case FileDialogEntry::Kind::Run:
            if (purpose_wants_run(d.purpose)) return choose(d, e.path);
            file_dialog_go(d, e.path);
            return std::nullopt;
        case FileDialogEntry::Kind::Experiment:
        case FileDialogEntry::Kind::Track:
            return choose(d, e.path);
    }
    return std::nullopt;
}

std::optional<std::string> file_dialog_accept_typed(FileDialog& d) {
    if (d.name.empty()) return std::nullopt;
    fs::path p(d.name);
    if (p.is_relative()) p = fs::path(d.dir) / p;
    const std::string path = absolute_path(p.string());
    std::error_code ec;
    if (purpose_wants_run(d.purpose)) {
        if (is_run_dir(path)) return choose(d, path);
        if (fs::is_directory(path, ec)) {
            d.name.clear();
            file_dialog_go(d, path);
            return std::nullopt;
        }
        d.error = path + ": not a run directory (it has no run.json)";
        return std::nullopt;
    }
    if (fs::is_directory(path, ec)) {
        d.name.clear();
        file_dialog_go(d, path);
        return std::nullopt;
    }
    if (d.purpose == FileDialogPurpose::SaveExperimentAs) {
        // A folder that does not exist yet is made by the save (as for the name proposed
        // for an edited preset in the data folder).
        fs::path out(path);
        if (!out.has_extension()) out += ".json";
        return choose(d, out.string());
    }
    if (!fs::is_regular_file(path, ec)) {
        d.error = path + ": no such file";
        return std::nullopt;
    }
    return choose(d, path);
}

std::optional<std::string> file_dialog_key(FileDialog& d, FileDialogKey key) {
    const int n = static_cast<int>(d.entries.size());
    switch (key) {
        case FileDialogKey::Up:
            if (d.selected > 0) --d.selected;
            d.scroll_to_selected = true;
            return std::nullopt;
        case FileDialogKey::Down:
            if (d.selected + 1 < n) ++d.selected;
            d.scroll_to_selected = true;
            return std::nullopt;
        case FileDialogKey::Backspace:
            if (d.name.empty() && fs::path(d.dir).has_parent_path() &&
                fs::path(d.dir).parent_path() != fs::path(d.dir))
                file_dialog_go(d, fs::path(d.dir).parent_path().string());
            return std::nullopt;
        case FileDialogKey::Escape:
            d.open = false;
            return std::nullopt;
        case FileDialogKey::Enter: {
            // A typed name wins unless it is the selected file's own name (Save As fills it).
            const bool typed =
                !d.name.empty() && (d.selected < 0 || d.selected >= n ||
                                    d.entries[static_cast<std::size_t>(d.selected)].name != d.name);
            if (typed) return file_dialog_accept_typed(d);
            if (d.selected >= 0 && d.selected < n)
                return file_dialog_activate(d, static_cast<std::size_t>(d.selected));
            return std::nullopt;
        }
    }
    return std::nullopt;
}

}  // namespace bhm::app::gui
