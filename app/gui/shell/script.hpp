#pragma once
// Scripted sessions for headless runs and tests: a JSON list of steps, each driving the studio
// through the same mouse and keyboard paths a person uses (documented in docs/studio.md).
// Each kind of step is one row of script_steps(): its key, the function that runs it, an example
// and what it does. docs/studio.md's table of steps is that table's text (script_reference();
// tests/app/test_studio_script_reference.cpp fails when they differ and prints it).
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/gui/shell/headless_studio.hpp"

namespace bhm::app::gui {

struct ScriptError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

//! Reads a script file (a JSON array of step objects); throws ScriptError naming the file.
nlohmann::json load_script(const std::string& path);

//! Runs every step; throws ScriptError "step N (kind): reason" when one fails. after_step, when
//! given, is called after each step with its index (tests check the state there).
void run_script(HeadlessStudio& session, const nlohmann::json& steps,
                const std::function<void(int, const nlohmann::json&)>& after_step = {});

//! One step (exposed for tests): the first kind of script_steps() the object has a key of runs
//! it; throws ScriptError for a step of no known kind.
void run_step(HeadlessStudio& session, const nlohmann::json& step);

//! One kind of step.
struct ScriptStep {
    const char* name;  //!< the step's key, e.g. "load"
    void (*run)(HeadlessStudio& session, const nlohmann::json& step);
    const char* example;  //!< a whole step, as docs/studio.md shows it
    const char* help;     //!< what it does (Markdown, one table cell)
};
//! Every kind of step, in the order docs/studio.md lists them.
const std::vector<ScriptStep>& script_steps();
//! docs/studio.md's table of steps: its header and one row per kind, each line ending in "\n".
std::string script_reference();

//! Sets one experiment field by a dotted path ("materials[1].poisson_ratio") through the JSON
//! form, the parser and apply_edit; throws ScriptError with the validator's message when refused.
void set_experiment_field(Studio& studio, const std::string& path, const nlohmann::json& value);

//! Mouse helpers: move, press and release over three frames at a window position.
//! fast: the pointer arrives, presses and releases in one event batch (one frame), as a quick
//! click or xdotool does; otherwise it hovers a frame first and holds the button a frame.
void click_at(HeadlessStudio& session, glm::vec2 position, bool shift = false, bool fast = false);
//! Presses over a widget, moves by `by` pixels over several frames, releases (splitters).
void drag_widget(HeadlessStudio& session, const std::string& name, glm::vec2 by);
//! Presses a chord. fast: the key and its modifiers go down and up before the next frame (a
//! quick Ctrl+Z); otherwise they are held for one frame. repeats > 0: held for that many of the
//! system's key repeats (GLFW_REPEAT events, one a frame, through the window's key path).
void press_key(HeadlessStudio& session, const std::string& chord, bool fast = false,
               int repeats = 0);

}  // namespace bhm::app::gui
