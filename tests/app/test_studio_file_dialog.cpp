// The studio's file dialog (Open..., Save As..., Open run..., Compare...): folders first, filtered
// by what the purpose can use, driven by Up / Down / Enter / Backspace / Escape, a typed path
// still taken; and through the UI, as a person presses the keys.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/file_dialog_widget.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/widgets/file_dialog.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// dir/{a/, b/, run1/ (run.json), x.json, y.json, notes.txt}
fs::path make_tree(const std::string& name) {
    const auto dir = testing::fresh_dir(name);
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    fs::create_directories(dir / "run1");
    std::ofstream(dir / "run1" / "run.json") << "{}";
    auto e = testing::tiny_experiment();
    e.name = "x";
    evo::save_experiment((dir / "x.json").string(), e);
    e.name = "y";
    evo::save_experiment((dir / "y.json").string(), e);
    std::ofstream(dir / "notes.txt") << "not an experiment";
    return fs::canonical(dir);
}

std::vector<std::string> names(const FileDialog& d) {
    std::vector<std::string> out;
    for (const auto& e : d.entries)
        out.push_back(e.name);
    return out;
}

}  // namespace

TEST_CASE("studio file dialog: folders first, filtered by what the purpose can use") {
    const auto dir = make_tree("dialog-listing");
    FileDialog d;
    open_file_dialog(d, FileDialogPurpose::OpenExperiment, dir.string());
    CHECK(d.open);
    CHECK(names(d) == std::vector<std::string>{"..", "a/", "b/", "run1/", "x.json", "y.json"});
    CHECK(d.entries[3].kind == FileDialogEntry::Kind::Run);
    CHECK(d.selected == 1);  // the first entry after ".."
    open_file_dialog(d, FileDialogPurpose::OpenRun, dir.string());
    CHECK(names(d) == std::vector<std::string>{"..", "a/", "b/", "run1/"});
    // A folder that cannot be read says so.
    open_file_dialog(d, FileDialogPurpose::OpenExperiment, dir.string());
    file_dialog_go(d, (dir / "missing").string());
    CHECK_FALSE(d.error.empty());
}

TEST_CASE("studio file dialog: Up, Down, Enter, Backspace and Escape") {
    const auto dir = make_tree("dialog-keys");
    FileDialog d;
    open_file_dialog(d, FileDialogPurpose::OpenExperiment, dir.string());
    // Down to x.json: a, b, run1, x.json
    for (int k = 0; k < 3; ++k)
        CHECK_FALSE(file_dialog_key(d, FileDialogKey::Down));
    CHECK(d.entries[static_cast<std::size_t>(d.selected)].name == "x.json");
    for (int k = 0; k < 10; ++k)
        file_dialog_key(d, FileDialogKey::Down);  // stops at the last
    CHECK(d.entries[static_cast<std::size_t>(d.selected)].name == "y.json");
    file_dialog_key(d, FileDialogKey::Up);
    const auto chosen = file_dialog_key(d, FileDialogKey::Enter);
    REQUIRE(chosen);
    CHECK(*chosen == (dir / "x.json").string());
    CHECK_FALSE(d.open);

    // Enter on a folder opens it; Backspace goes back up; for experiments a run is a folder.
    open_file_dialog(d, FileDialogPurpose::OpenExperiment, dir.string());
    CHECK(d.entries[static_cast<std::size_t>(d.selected)].name == "a/");
    CHECK_FALSE(file_dialog_key(d, FileDialogKey::Enter));
    CHECK(d.dir == (dir / "a").string());
    CHECK(names(d) == std::vector<std::string>{".."});
    file_dialog_key(d, FileDialogKey::Backspace);
    CHECK(d.dir == dir.string());
    // Backspace edits a typed name instead of leaving the folder.
    d.name = "x";
    file_dialog_key(d, FileDialogKey::Backspace);
    CHECK(d.dir == dir.string());
    d.name.clear();
    file_dialog_key(d, FileDialogKey::Escape);
    CHECK_FALSE(d.open);

    // For the run purposes a run directory is chosen, not entered.
    open_file_dialog(d, FileDialogPurpose::CompareRun, dir.string());
    file_dialog_key(d, FileDialogKey::Down);
    file_dialog_key(d, FileDialogKey::Down);
    const auto run = file_dialog_key(d, FileDialogKey::Enter);
    REQUIRE(run);
    CHECK(*run == (dir / "run1").string());
}

TEST_CASE("studio file dialog: a typed path is still taken") {
    const auto dir = make_tree("dialog-typed");
    FileDialog d;
    open_file_dialog(d, FileDialogPurpose::OpenExperiment, dir.string());
    d.name = "a";  // a folder, relative to the one shown: shown
    CHECK_FALSE(file_dialog_key(d, FileDialogKey::Enter));
    CHECK(d.dir == (dir / "a").string());
    CHECK(d.name.empty());
    d.name = "../missing.json";
    CHECK_FALSE(file_dialog_key(d, FileDialogKey::Enter));
    CHECK(d.open);
    CHECK(d.error.find("no such file") != std::string::npos);
    d.name = (dir / "y.json").string();  // absolute
    const auto open = file_dialog_key(d, FileDialogKey::Enter);
    REQUIRE(open);
    CHECK(*open == (dir / "y.json").string());

    open_file_dialog(d, FileDialogPurpose::SaveExperimentAs, dir.string(), "new-one");
    const auto saved = file_dialog_key(d, FileDialogKey::Enter);
    REQUIRE(saved);
    CHECK(*saved == (dir / "new-one.json").string());  // .json added
    // A new folder is the save's to make (the data folder's experiments/ on first use).
    open_file_dialog(d, FileDialogPurpose::SaveExperimentAs, dir.string(), "new/z.json");
    const auto deeper = file_dialog_key(d, FileDialogKey::Enter);
    REQUIRE(deeper);
    CHECK(*deeper == (dir / "new" / "z.json").string());

    open_file_dialog(d, FileDialogPurpose::OpenRun, dir.string(), "b");
    CHECK_FALSE(file_dialog_key(d, FileDialogKey::Enter));  // a plain folder: shown
    CHECK(d.dir == (dir / "b").string());
    d.name = "../x.json";
    CHECK_FALSE(file_dialog_key(d, FileDialogKey::Enter));
    CHECK(d.error.find("not a run directory") != std::string::npos);
}

TEST_CASE("studio file dialog: Open... and Save As... from the panel, with the keyboard only") {
    const auto dir = make_tree("dialog-ui");
    Studio studio;
    studio.library.browser_dir = dir.string();
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"click": "tab Experiment"}, {"frames": 1},
                                        {"click": "Open..."}, {"frames": 1}])"));
    REQUIRE(studio.ui.file_dialog.open);
    CHECK(studio.ui.widgets.at("file dialog").frame == studio.ui.frame);
    CHECK(studio.ui.widgets.count("dialog entry x.json"));
    CHECK_FALSE(studio.ui.widgets.count("dialog entry notes.txt"));
    // Shortcuts do not act behind the dialog: Ctrl+N here would ask about a new experiment.
    run_script(session, json::parse(R"([{"key": "ctrl+n"}, {"key": "down"}, {"key": "down"},
                                        {"key": "down"}, {"key": "enter"}, {"frames": 2}])"));
    CHECK_FALSE(studio.ui.file_dialog.open);
    CHECK(studio.document.experiment().name == "x");
    CHECK(studio.document.path() == (dir / "x.json").string());

    // Save As...: the dialog proposes the file's name; a new one typed, Enter saves there.
    run_script(session, json::parse(R"([{"click": "Save As..."}, {"frames": 1}])"));
    REQUIRE(studio.ui.file_dialog.open);
    CHECK(studio.ui.file_dialog.name == "x.json");
    studio.ui.file_dialog.name = "copy";
    run_script(session, json::parse(R"([{"key": "enter"}, {"frames": 1}])"));
    CHECK(fs::exists(dir / "copy.json"));
    CHECK(studio.document.path() == (dir / "copy.json").string());
    CHECK(evo::load_experiment((dir / "copy.json").string()).name == "x");

    // Escape closes it without a choice.
    run_script(session, json::parse(R"([{"click": "Open..."}, {"key": "escape"}, {"frames": 1}])"));
    CHECK_FALSE(studio.ui.file_dialog.open);
    CHECK(studio.document.path() == (dir / "copy.json").string());

    // Open run... and Compare... fill the Run panel's fields through the same dialog.
    show_file_dialog(studio, FileDialogPurpose::CompareRun);
    file_dialog_go(studio.ui.file_dialog, dir.string());
    run_script(session, json::parse(R"([{"key": "down"}, {"key": "down"}, {"key": "enter"},
                                        {"frames": 1}])"));
    CHECK_FALSE(studio.ui.file_dialog.open);
    CHECK(studio.run.compare_field == (dir / "run1").string());
}

TEST_CASE("studio file dialog: a held Down moves on with the key repeat, shortcuts act once") {
    const auto dir = make_tree("dialog-hold");
    Studio studio;
    studio.library.browser_dir = dir.string();
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"click": "tab Experiment"}, {"frames": 1},
                                        {"click": "Open..."}, {"frames": 1}])"));
    REQUIRE(studio.ui.file_dialog.open);
    file_dialog_go(studio.ui.file_dialog, dir.string());
    const auto listed = names(studio.ui.file_dialog);
    const auto x = std::find(listed.begin(), listed.end(), "x.json");
    REQUIRE(x != listed.end());
    const int target = static_cast<int>(x - listed.begin());
    const int start = studio.ui.file_dialog.selected;
    REQUIRE(target - start >= 3);  // a/, b/, run1/ come first
    // Down held for n of the system's repeats after its press: n + 1 rows down.
    json hold = json::array({{{"key", "down"}, {"hold", target - start - 1}}});
    run_script(session, hold);
    CHECK(studio.ui.file_dialog.selected == target);
    hold = json::array({{{"key", "up"}, {"hold", 1}}});
    run_script(session, hold);
    CHECK(studio.ui.file_dialog.selected == target - 2);
    run_script(session, json::parse(R"([{"key": "down"}, {"key": "down"}, {"key": "enter"},
                                        {"frames": 1}])"));
    CHECK_FALSE(studio.ui.file_dialog.open);
    CHECK(studio.document.experiment().name == "x");

    // Behind no dialog a held shortcut acts once per press: Ctrl+Z held undoes one edit.
    const int generations = studio.document.experiment().evolution.generations;
    run_script(session, json::parse(R"([{"set": "evolution.generations", "value": 7},
                                        {"set": "evolution.generations", "value": 8},
                                        {"key": "ctrl+z", "hold": 3}, {"frames": 1}])"));
    CHECK(generations != 7);
    CHECK(studio.document.experiment().evolution.generations == 7);
}
