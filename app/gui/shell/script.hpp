#pragma once
// Scripted sessions for headless runs and tests: a JSON list of steps, each driving the studio
// through the same mouse and keyboard paths a person uses (documented in docs/studio.md).
//   {"load": "exp.json"}                       open an experiment (File > Open)
//   {"set": "simulation.settle_s", "value": 0.2}  edit one field (validated, undoable)
//   {"click": "Start"}                        click a widget by its label (buttons, rows)
//   {"click_face": "x+"}                      Faces tool, click the face in the 3D view
//   {"click_cell": [x, y, z], "brush": "fixed"|"forbidden"|"material"|"clear", "material": k}
//   {"key": "ctrl+z"}                         press a shortcut (key_bindings.hpp)
//   {"type": "runs/a"}                        type characters into the text field with the keyboard
//   {"view": "iso"|"front"|"top"|"side"}     named camera view (keys 1-4)
//   {"mode": "workspace"|"simulation"}
//   {"wait_generations": 2, "timeout_s": 120}  frames until the run has completed that many
//   {"wait_run": "finished"|"paused"|"stopped", "timeout_s": 60}
//   {"select": "champion"}                    click the champion's row in the Population panel
//   {"wait_simulation": true, "timeout_s": 60}  frames until the body asked for is shown
//   {"wait_verify": true, "timeout_s": 60}      frames until Verify in FEM has ended
//   {"replay": {"time_s": 5.0, "playing": false}}  scrub the replay
//   {"frames": 10}                            draw that many frames
//   {"screenshot": "ui.png"}                  the whole window, as drawn
//   {"export_view": "view.png", "size": [w, h]}  off-screen render of the 3D view
//   {"save": "exp.json"}                      File > Save As
//   {"drag": "splitter right", "by": [-100, 0]}  press on a widget, move, release
//   {"resize": [w, h]}                        the window's size (at most the one it started with)
//   "fast": true on click, click_face, click_cell, key: press and release in one event batch
#include <functional>
#include <stdexcept>
#include <string>

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

//! One step (exposed for tests).
void run_step(HeadlessStudio& session, const nlohmann::json& step);

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
