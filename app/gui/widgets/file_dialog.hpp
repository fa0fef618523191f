#pragma once
// The studio's own file dialog (Open..., Save As..., Open run..., Compare...): Debian packages
// no ImGui file dialog and no native dialog library that fits (apt-cache search: imgui,
// file dialog, nativefiledialog, tinyfiledialogs, portable-file-dialogs give only libimgui-dev
// and a Perl/Tk widget), so this is a small one. The model is plain data over
// std::filesystem (testable without ImGui); panels/file_dialog_widget.cpp draws it.
// Folders first, then the files the purpose can use (*.json experiments, or run directories);
// Up / Down move, Enter opens a folder or chooses, Backspace goes to the parent folder (when
// the name field is empty), Escape cancels; a typed path (absolute, or relative to the folder
// shown) is still taken.
#include <optional>
#include <string>
#include <vector>

namespace bhm::app::gui {

//! ShowBody and LoadTrack: the Calibrate tab's body file (*.json) and measured track (*.csv).
enum class FileDialogPurpose {
    OpenExperiment,
    SaveExperimentAs,
    OpenRun,
    CompareRun,
    ShowBody,
    LoadTrack
};

struct FileDialogEntry {
    //! Experiment: a *.json file (an experiment, or a body for ShowBody); Track: a *.csv track.
    enum class Kind { Parent, Folder, Run, Experiment, Track } kind = Kind::Folder;
    std::string name;  //!< as listed ("..", "runs/", "quick-demo.json")
    std::string path;  //!< absolute
};

enum class FileDialogKey { Up, Down, Enter, Backspace, Escape };

struct FileDialog {
    bool open = false;
    FileDialogPurpose purpose = FileDialogPurpose::OpenExperiment;
    std::string dir;   //!< absolute folder shown
    std::string name;  //!< the name field: a file name or a typed path
    int selected = 0;  //!< index into entries
    std::vector<FileDialogEntry> entries;
    std::string error;  //!< the folder cannot be read, or a typed path is no use
    //! Scroll the selected row into view on the next draw (after a key moved it).
    bool scroll_to_selected = false;
};

//! "Open experiment", "Save experiment as", "Open run directory", "Compare with run directory".
const char* file_dialog_title(FileDialogPurpose purpose);
//! Runs are chosen; experiments are chosen.
bool purpose_wants_run(FileDialogPurpose purpose);

//! The listing of `dir` for a purpose: ".." (unless at the root), folders (run directories as
//! Run) by name, then *.json experiments by name for the experiment purposes. *error: why the
//! folder cannot be read.
std::vector<FileDialogEntry> file_dialog_entries(const std::string& dir, FileDialogPurpose purpose,
                                                 std::string* error = nullptr);

//! Opens the dialog in `start_dir` (made absolute; the current folder when empty or missing),
//! with `name` in the name field (Save As: the document's file name).
void open_file_dialog(FileDialog& dialog, FileDialogPurpose purpose, const std::string& start_dir,
                      const std::string& name = "");
//! Shows another folder (re-reads it, selection on its first entry).
void file_dialog_go(FileDialog& dialog, const std::string& dir);
//! Opens the entry (a folder) or chooses it (a file, or a run for the run purposes). A chosen
//! path closes the dialog and is returned.
std::optional<std::string> file_dialog_activate(FileDialog& dialog, std::size_t index);
//! Takes the name field: a folder is shown, a file (Save: any new name, ".json" added when it
//! has no extension, its folder made by the save; Open: an existing file) or a run directory
//! is chosen.
std::optional<std::string> file_dialog_accept_typed(FileDialog& dialog);
//! One key; Enter takes a typed name first, else the selected entry.
std::optional<std::string> file_dialog_key(FileDialog& dialog, FileDialogKey key);

}  // namespace bhm::app::gui
