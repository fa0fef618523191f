#pragma once
// Where the studio reads and writes, independent of the folder it was started from: recent files
// and run folders are absolute paths; new runs go under the user's data folder; the shipped
// presets are found next to the executable or in the source tree and are never overwritten.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace bhm::app::gui {

//! `path` made absolute against the current folder and normalised ("" stays "").
std::string absolute_path(const std::string& path);

//! Folder new runs go to when the Run panel's field is empty:
//! $XDG_DATA_HOME/bhm-studio/runs, else $HOME/.local/share/bhm-studio/runs, else an absolute
//! runs/ in the current folder (the last resort only when neither variable is set).
std::string default_runs_root();

//! Folder F12 screenshots go to when the Export panel's path is empty: a screenshots/ folder
//! beside default_runs_root() (not the folder the studio was started from).
std::string default_screenshots_dir();

//! Where the Export panel's files go unless another path is typed: an exports/ folder beside
//! default_runs_root(), so `name` never lands in the folder the studio was started from (the
//! source checkout, when started from there). Absolute.
std::string default_export_path(const std::string& name);

//! The first of `stem-001.ext`, `stem-002.ext`, ... beside `path` that does not exist yet,
//! absolute: each F12 keeps the earlier screenshots.
std::string next_numbered_path(const std::string& path);

//! The shipped presets: $BHM_PRESETS_DIR when set, else <exe>/../share/bhm/experiments when it
//! exists, else the source tree's assets/experiments. Absolute; may not exist.
std::string default_presets_dir();

//! `path` is a file inside presets_dir (a shipped preset: Save asks for a new name instead).
bool is_shipped_preset(const std::string& path, const std::string& presets_dir);

//! The *.json experiments of a folder, sorted by name (absolute paths; empty if unreadable).
std::vector<std::string> list_experiment_files(const std::string& dir);

//! What the file browser shows of one folder.
struct FileListing {
    std::vector<std::pair<std::string, bool>> folders;  //!< absolute path, is a run directory
    std::vector<std::string> experiments;               //!< *.json (absolute), by name
    std::vector<std::string> tracks;  //!< *.csv measured tracks (absolute), by name
    std::string error;                                  //!< the folder cannot be read
    std::chrono::steady_clock::time_point read_at{};
    bool valid = false;
};
FileListing read_file_listing(const std::string& dir);

}  // namespace bhm::app::gui
