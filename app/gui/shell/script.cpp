#include "app/gui/shell/script.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#define GLFW_INCLUDE_NONE  // GL comes from glad only
#include <GLFW/glfw3.h>
#include <imgui_internal.h>  // ImTextCharFromUtf8

#include "app/gui/actions/calibration_actions.hpp"
#include "app/gui/actions/export_actions.hpp"
#include "app/gui/actions/key_bindings.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/view/scene.hpp"
#include "app/gui/view/viewport.hpp"
#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_fields.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"

namespace bhm::app::gui {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Draws frames until done() holds; between frames the UI thread sleeps a little so the workers
// get the cores (as a person's studio would wait for vsync).
void frames_until(HeadlessStudio& session, double timeout_s, const std::function<bool()>& done,
                  const std::string& what) {
    const auto start = Clock::now();
    while (!done()) {
        if (std::chrono::duration<double>(Clock::now() - start).count() > timeout_s)
            throw ScriptError("timed out after " + std::to_string(timeout_s) + " s waiting for " +
                              what);
        session.frame();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    session.frame();
}

glm::vec2 widget_centre(HeadlessStudio& session, const std::string& name) {
    auto& widgets = session.studio().ui.widgets;
    auto it = widgets.find(name);
    if (it == widgets.end() || it->second.frame < session.studio().ui.frame - 1) {
        session.frame();  // it may appear once the UI caught up with the state
        it = widgets.find(name);
    }
    if (it == widgets.end() || it->second.frame < session.studio().ui.frame - 1)
        throw ScriptError("no widget named '" + name + "' on screen");
    return 0.5f * (it->second.min + it->second.max);
}

std::optional<evo::Face> parse_face(const std::string& name) {
    for (int f = 0; f < 6; ++f)
        if (name == evo::kFaceNames[static_cast<std::size_t>(f)]) return static_cast<evo::Face>(f);
    return std::nullopt;
}

double timeout_of(const json& step, double fallback) {
    return step.contains("timeout_s") ? step.at("timeout_s").get<double>() : fallback;
}

void click_face(HeadlessStudio& session, const std::string& name, bool fast) {
    const auto face = parse_face(name);
    if (!face) throw ScriptError("unknown face '" + name + "' (x-, x+, y-, y+, z-, z+)");
    Studio& s = session.studio();
    run_action(s, Action::ToolFaces);
    session.frame();  // lays the view out in workspace mode
    const auto& e = s.document.experiment();
    const LatticeBox box{e.workspace_size, e.voxel_size_m};
    const auto pixel = project_to_pixel(s.view.camera, face_centre_m(box, *face), s.view.size_px);
    const auto hit =
        pixel ? pick_box_face(ray_through_pixel(s.view.camera, *pixel, s.view.size_px), box)
              : std::nullopt;
    if (!hit || hit->face != *face)
        throw ScriptError("face " + name +
                          " is not visible from the current view (orbit or pick another view)");
    click_at(session, s.view.origin_px + *pixel, false, fast);
}

void click_cell(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const auto cell = step.at("click_cell").get<std::array<int, 3>>();
    if (step.contains("brush")) {
        const std::string brush = step.at("brush").get<std::string>();
        bool known = false;
        for (std::size_t k = 0; k < kPaintKindNames.size(); ++k)
            if (brush == kPaintKindNames[k]) {
                s.painter.brush = static_cast<PaintKind>(k);
                known = true;
            }
        if (!known)
            throw ScriptError("unknown brush '" + brush + "' (fixed, forbidden, material, clear)");
    }
    if (step.contains("material")) s.painter.brush_material = step.at("material").get<int>();
    run_action(s, Action::ToolVoxels);
    session.frame();
    // Try the centres of the cell's six faces: the first one whose ray picks this cell.
    const auto& e = s.document.experiment();
    const LatticeBox box{e.workspace_size, e.voxel_size_m};
    if (!box.contains_cell(cell)) throw ScriptError("cell is outside the workspace");
    const auto occupied = painter_occupancy(e, painter_context_body(s));
    const float L = static_cast<float>(e.voxel_size_m);
    for (int f = 0; f < 6; ++f) {
        glm::vec3 p{(cell[0] + 0.5f) * L, (cell[1] + 0.5f) * L, (cell[2] + 0.5f) * L};
        p[f / 2] += (f % 2 ? 0.499f : -0.499f) * L;
        const auto pixel = project_to_pixel(s.view.camera, p, s.view.size_px);
        if (!pixel || pixel->x < 1 || pixel->y < 1 || pixel->x > s.view.size_px.x - 1 ||
            pixel->y > s.view.size_px.y - 1)
            continue;
        const auto hit = pick_cell(
            ray_through_pixel(s.view.camera, *pixel, s.view.size_px), box, s.painter.slice,
            [&](const std::array<int, 3>& c) {
                return occupied[static_cast<std::size_t>(
                           c[0] + e.workspace_size[0] * (c[1] + e.workspace_size[1] * c[2]))] != 0;
            });
        if (hit && hit->cell == cell) {
            click_at(session, s.view.origin_px + *pixel, step.value("shift", false),
                     step.value("fast", false));
            return;
        }
    }
    throw ScriptError("cell (" + std::to_string(cell[0]) + ", " + std::to_string(cell[1]) + ", " +
                      std::to_string(cell[2]) +
                      ") is hidden from this view (use a slice or another view)");
}

// One function per kind of step (the table script_steps() names them).

void step_load(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    if (!open_experiment(s, step.at("load").get<std::string>())) throw ScriptError(s.ui.status);
}

void step_set(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    set_experiment_field(s, step.at("set").get<std::string>(), step.at("value"));
}

void step_click(HeadlessStudio& session, const json& step) {
    click_at(session, widget_centre(session, step.at("click").get<std::string>()), false,
             step.value("fast", false));
}

void step_click_face(HeadlessStudio& session, const json& step) {
    click_face(session, step.at("click_face").get<std::string>(), step.value("fast", false));
}

void step_drag(HeadlessStudio& session, const json& step) {
    const auto by = step.at("by").get<std::array<float, 2>>();
    drag_widget(session, step.at("drag").get<std::string>(), {by[0], by[1]});
}

void step_resize(HeadlessStudio& session, const json& step) {
    const auto size = step.at("resize").get<std::array<int, 2>>();
    if (!session.set_display_size(size[0], size[1]))
        throw ScriptError("resize: 1..the starting size in each direction");
    session.frame();
}

void step_click_cell(HeadlessStudio& session, const json& step) {
    click_cell(session, step);
}

void step_key(HeadlessStudio& session, const json& step) {
    press_key(session, step.at("key").get<std::string>(), step.value("fast", false),
              step.value("hold", 0));
}

void step_type(HeadlessStudio& session, const json& step) {
    // Characters as a window's char callback gets them, all in one event batch.
    const std::string text = step.at("type").get<std::string>();
    for (const char* c = text.c_str(); *c;) {
        unsigned int codepoint = 0;
        const int used = ImTextCharFromUtf8(&codepoint, c, nullptr);
        if (used <= 0) break;
        session.input().keys.character(codepoint);
        c += used;
    }
    session.frame();
}

void step_view(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const auto view = render::parse_named_view(step.at("view").get<std::string>());
    if (!view) throw ScriptError("unknown view (iso, front, top, side)");
    set_named_view(s, *view);
}

void step_mode(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const std::string mode = step.at("mode").get<std::string>();
    if (mode != "workspace" && mode != "simulation")
        throw ScriptError("mode is workspace or simulation");
    set_view_mode(s, mode == "workspace" ? ViewMode::Workspace : ViewMode::Simulation);
}

void step_wait_generations(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const int n = step.at("wait_generations").get<int>();
    frames_until(
        session, timeout_of(step, 300.0),
        [&] {
            const auto run = s.run.evolution.snapshot();
            if (run && run->phase == RunPhase::Failed)
                throw ScriptError("the run failed: " + run->message);
            return run && (run->generation >= n ||
                           (!run_is_live(run->phase) && run->phase != RunPhase::Idle));
        },
        std::to_string(n) + " generations");
    const auto run = s.run.evolution.snapshot();
    if (!run || run->generation < n)
        throw ScriptError("the run ended after " + std::to_string(run ? run->generation : 0) +
                          " generations");
}

void step_wait_run(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const std::string want = step.at("wait_run").get<std::string>();
    frames_until(
        session, timeout_of(step, 300.0),
        [&] {
            const auto phase = s.run.evolution.phase();
            return run_phase_name(phase) == want;
        },
        "the run to be " + want);
}

void step_select(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    if (step.at("select") != "champion")
        throw ScriptError("select: only \"champion\" is supported");
    frames_until(
        session, timeout_of(step, 30.0),
        [&] { return s.run.snapshot && s.run.snapshot->has_champion; }, "a champion");
    const auto id = s.run.snapshot->champion.id;
    click_at(session, widget_centre(session, "individual #" + std::to_string(id)));
    if (s.bodies.simulator.pending_id() != id && !(s.bodies.shown && s.bodies.shown->id == id))
        throw ScriptError("the click did not select the champion #" + std::to_string(id));
}

void step_wait_simulation(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    frames_until(
        session, timeout_of(step, 120.0),
        [&] {
            if (!s.bodies.simulator.last_error().empty())
                throw ScriptError(s.bodies.simulator.last_error());
            return !s.bodies.simulator.busy() && s.bodies.shown != nullptr;
        },
        "the simulation");
}

void step_show_body(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    if (!show_body_file(s, step.at("show_body").get<std::string>())) throw ScriptError(s.ui.status);
}

void step_load_track(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    if (!load_track(s, step.at("load_track").get<std::string>())) throw ScriptError(s.ui.status);
}

void step_calibrate(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    // The fit list as --fit names it; the boxes of the Calibrate tab follow it.
    const std::string list = step.at("calibrate").get<std::string>();
    auto& c = s.calibration;
    for (std::size_t i = 0; i < c.fit_names.size(); ++i)
        c.fit_on[i] = ("," + list + ",").find("," + c.fit_names[i] + ",") != std::string::npos;
    if (step.contains("max_simulations")) c.max_simulations = step.at("max_simulations").get<int>();
    if (!start_calibration(s)) throw ScriptError(s.ui.status);
}

void step_wait_calibration(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    frames_until(
        session, timeout_of(step, 600.0),
        [&] {
            const auto snap = s.calibration.session.snapshot();
            return !s.calibration.session.running() && snap &&
                   snap->phase != CalibrationPhase::Running;
        },
        "the calibration");
    const auto snap = s.calibration.session.snapshot();
    if (snap->phase == CalibrationPhase::Failed) throw ScriptError(snap->error);
}

void step_apply_rules(HeadlessStudio& session, const json&) {
    Studio& s = session.studio();
    // What Apply to run does (Constraints, or the checks' own button): the edits the live run
    // can take between generations. Nothing to send is an error too: the script expected some.
    if (!rules_differ_from_run(s))
        throw ScriptError("apply_rules: the editor's rules and checks are the live run's");
    if (!apply_rules_to_run(s)) throw ScriptError(s.ui.status);
    session.frame();
}

void step_wait_verify(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    // Verify in FEM: until the worker has ended (finished, failed or cancelled).
    frames_until(
        session, timeout_of(step, 120.0), [&] { return !s.verify.worker.running(); },
        "the verification");
    session.frame();  // the frame that takes its last state
}

void step_replay(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const json& r = step.at("replay");
    if (!s.bodies.shown) throw ScriptError("replay: no simulated body is shown");
    if (r.contains("playing")) s.clock.playing = r.at("playing").get<bool>();
    if (r.contains("time_s")) s.clock.seek(r.at("time_s").get<double>());
    set_view_mode(s, ViewMode::Simulation);
    session.frame(0.0);
}

void step_frames(HeadlessStudio& session, const json& step) {
    for (int i = step.at("frames").get<int>(); i > 0; --i)
        session.frame();
}

void step_screenshot(HeadlessStudio& session, const json& step) {
    render::write_png(step.at("screenshot").get<std::string>(), session.capture());
}

void step_export_view(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    const auto size = step.value("size", std::array<int, 2>{1280, 720});
    if (!export_screenshot(s, session.app().renderer(),
                           step.at("export_view").get<std::string>(), size[0], size[1]))
        throw ScriptError(s.ui.status);
}

void step_save(HeadlessStudio& session, const json& step) {
    Studio& s = session.studio();
    if (!save_experiment_as(s, step.at("save").get<std::string>())) throw ScriptError(s.ui.status);
}

}  // namespace

json load_script(const std::string& path) {
    std::string text;
    try {
        text = engine::read_text(path, engine::kTextFileCap);
    } catch (const engine::FileReadError& e) {
        throw ScriptError(e.what());
    }
    json steps;
    try {
        steps = json::parse(text);
    } catch (const json::exception& e) {
        throw ScriptError(path + ": not valid JSON: " + evo::without_json_tags(e.what()));
    }
    if (!steps.is_array()) throw ScriptError(path + ": a script is a JSON array of steps");
    return steps;
}

void click_at(HeadlessStudio& session, glm::vec2 position, bool shift, bool fast) {
    auto& in = session.input();
    in.mouse = position;
    in.shift = shift;
    if (fast) {  // move, press and release all before the next frame
        in.pressed_in_batch[0] = true;
        session.frame();
        session.frame();
        in.shift = false;
        session.frame();
        return;
    }
    session.frame();  // hover first, as a real pointer arrives before it clicks
    in.buttons[0] = true;
    session.frame();
    in.buttons[0] = false;
    session.frame();  // the release acts after this frame's 3D view was drawn
    in.shift = false;
    session.frame();  // so draw once more: a screenshot next shows the result
}

void drag_widget(HeadlessStudio& session, const std::string& name, glm::vec2 by) {
    auto& in = session.input();
    const glm::vec2 start = widget_centre(session, name);
    in.mouse = start;
    session.frame();
    in.buttons[0] = true;
    session.frame();
    constexpr int kSteps = 6;
    for (int k = 1; k <= kSteps; ++k) {
        in.mouse = start + by * (static_cast<float>(k) / kSteps);
        session.frame();
    }
    in.buttons[0] = false;
    session.frame();
    session.frame();
}

void press_key(HeadlessStudio& session, const std::string& chord_text, bool fast, int repeats) {
    const auto chord = parse_key_chord(chord_text);
    if (!chord) throw ScriptError("unknown key '" + chord_text + "'");
    if (repeats < 0) throw ScriptError("hold: a number of key repeats, 0 or more");
    if (fast && repeats > 0) throw ScriptError("a key is either fast or held, not both");
    auto& in = session.input();
    // The events a window's key callback gets: a press, then one repeat per beat while held.
    const int mods = (chord->ctrl ? GLFW_MOD_CONTROL : 0) | (chord->shift ? GLFW_MOD_SHIFT : 0);
    if (const auto press = key_event_chord(chord->key, GLFW_PRESS, mods))
        in.key_presses.push_back(*press);
    if (fast) {  // pressed and released (Ctrl too) before the next frame: nothing is held
        in.keys.key(chord->key, GLFW_PRESS, mods);
        in.keys.key(chord->key, GLFW_RELEASE, mods);
        session.frame();
        return;
    }
    in.ctrl = chord->ctrl;
    in.shift = chord->shift;
    in.key = chord->key;
    session.frame();
    for (int k = 0; k < repeats; ++k) {
        if (const auto repeat = key_event_chord(chord->key, GLFW_REPEAT, mods))
            in.key_presses.push_back(*repeat);
        session.frame();
    }
    if (const auto release = key_event_chord(chord->key, GLFW_RELEASE, mods))
        in.key_presses.push_back(*release);
    in.key = 0;
    in.ctrl = in.shift = false;
    session.frame();
}

void set_experiment_field(Studio& studio, const std::string& path, const json& value) {
    json doc = evo::experiment_to_json(studio.document.experiment());
    // "a.b[2].c" -> JSON pointer /a/b/2/c
    std::string pointer;
    std::string token;
    auto flush = [&] {
        if (!token.empty()) pointer += "/" + token;
        token.clear();
    };
    for (char c : path) {
        if (c == '.' || c == '[' || c == ']')
            flush();
        else
            token += c;
    }
    flush();
    // A field of the experiment's table may be absent from its JSON (experiment_to_json leaves
    // out blocks at their defaults, such as evolution.verify): it is added, as the editor would.
    const auto fields = evo::experiment_fields();
    const bool in_table = std::any_of(fields.begin(), fields.end(),
                                      [&](const evo::ExperimentField& f) { return path == f.path; });
    bool done = false;
    try {
        const json::json_pointer at(pointer);
        if (in_table || doc.contains(at)) {
            doc[at] = value;
            done = true;
        }
    } catch (const json::exception&) {
    }
    if (!done) throw ScriptError("set: the experiment has no field '" + path + "'");
    evo::Experiment next;
    try {
        next = evo::parse_experiment(doc, document_label(studio.document));
    } catch (const evo::ValidationError& e) {
        studio.ui.edit_problems = e.problems;
        set_status(studio, describe_problems("refused: ", e.problems), true);
        throw ScriptError(std::string("set ") + path +
                          " refused: " + e.problems.front().to_string());
    }
    if (!apply_edit(studio, next, "set " + path))
        throw ScriptError("set " + path +
                          " refused: " + studio.ui.edit_problems.front().to_string());
}

const std::vector<ScriptStep>& script_steps() {
    static const std::vector<ScriptStep> steps = {
        {"load", step_load,
         R"({"load": "exp.json"})",
         "File > Open"},
        {"save", step_save,
         R"({"save": "exp.json"})",
         "File > Save As"},
        {"set", step_set,
         R"({"set": "simulation.settle_s", "value": 0.2})",
         "edits one experiment field by its JSON path (as in `bhm validate` messages, "
         "e.g. `materials[1].poisson_ratio`); validated and undoable; a refused value "
         "fails the step with the validator's message"},
        {"click", step_click,
         R"({"click": "Start", "fast": true})",
         "clicks a widget by its label (`fast`: the pointer arrives, presses and "
         "releases in one event batch, as a quick click or xdotool does; also on "
         "`click_face` and `click_cell`): buttons (Start, Pause, Resume, Stop, Undo, "
         "Redo, Open..., Save As..., Save PNG, Write frames, Save VXA, Iso, ...), `face "
         "x+` (Constraints panel), `welcome preset quick-demo` (a welcome card), `dialog "
         "entry x.json`, `dialog ok` (the file dialog), `3d view compared` (the split "
         "view's second pane), `individual #12` (Population row), `timeline`, `3d view`, "
         "`design strip` (the folded left column's button), `fitness tab com_final_3d` "
         "(a measure's tab)"},
        {"click_face", step_click_face,
         R"({"click_face": "x+"})",
         "selects the Faces tool and clicks the face's centre in the 3D view (it must "
         "face the camera)"},
        {"click_cell", step_click_cell,
         R"({"click_cell": [x, y, z], "brush": "fixed", "material": 2, "shift": false})",
         "selects the Voxels tool (and brush) and clicks the cell where it can be seen"},
        {"type", step_type,
         R"({"type": "runs/a"})",
         "types characters into the text field that has the keyboard, as a window's char "
         "callback gets them (one event batch)"},
        {"key", step_key,
         R"({"key": "ctrl+z", "fast": true})",
         "presses a shortcut (`ctrl+`, `shift+`, letters, digits, `f1`..`f12`, `space`, "
         "`left`, `right`, `up`, `down`, `home`, `end`, `tab`, `enter`, `escape`, "
         "`backspace`, `delete`); `fast`: pressed and released, Ctrl too, before the "
         "next frame; `{\"key\": \"down\", \"hold\": 3}`: held for 3 of the system's key "
         "repeats (one a frame, as the window's key callback gets them) before the "
         "release"},
        {"view", step_view,
         R"({"view": "iso"})",
         "named view: iso, front, top, side"},
        {"mode", step_mode,
         R"({"mode": "simulation"})",
         "3D view mode: workspace or simulation"},
        {"wait_generations", step_wait_generations,
         R"({"wait_generations": 2, "timeout_s": 120})",
         "draws frames until the run has completed that many generations (fails if it "
         "ends first)"},
        {"wait_run", step_wait_run,
         R"({"wait_run": "finished"})",
         "draws frames until the run is `running`, `paused`, `stopped`, `finished` or "
         "`failed`"},
        {"select", step_select,
         R"({"select": "champion"})",
         "clicks the champion's row in the Population panel"},
        {"wait_simulation", step_wait_simulation,
         R"({"wait_simulation": true})",
         "draws frames until the body asked for is simulated and shown"},
        {"show_body", step_show_body,
         R"({"show_body": "body.json"})",
         "Calibrate > Show body"},
        {"load_track", step_load_track,
         R"({"load_track": "tip.csv"})",
         "Calibrate > Load track onto the body shown"},
        {"calibrate", step_calibrate,
         R"({"calibrate": "E,amplitude", "max_simulations": 100})",
         "ticks those parameters (the others off) and presses Calibrate"},
        {"wait_calibration", step_wait_calibration,
         R"({"wait_calibration": true, "timeout_s": 600})",
         "draws frames until the calibration (or the track's simulation) has ended; a "
         "failed one fails the step"},
        {"apply_rules", step_apply_rules,
         R"({"apply_rules": true})",
         "Apply to run: sends the editor's fitness rules and CalculiX checks "
         "(`evolution.verify`, e.g. after `{\"set\": \"evolution.verify.policy\", "
         "\"value\": \"reject\"}`) to the live run, from its next generation; fails when "
         "nothing differs or the run refuses them (the status's message)"},
        {"wait_verify", step_wait_verify,
         R"({"wait_verify": true, "timeout_s": 120})",
         "draws frames until Verify in FEM has ended (finished, failed or cancelled)"},
        {"replay", step_replay,
         R"({"replay": {"time_s": 5.0, "playing": false}})",
         "sets the replay clock (and shows the simulation)"},
        {"frames", step_frames,
         R"({"frames": 10})",
         "draws frames"},
        {"drag", step_drag,
         R"({"drag": "splitter right", "by": [-100, 0]})",
         "presses on a widget, moves by that many pixels over several frames, releases "
         "(`splitter left`, `splitter right`, `splitter replay`, `splitter run`, "
         "`splitter plot`)"},
        {"resize", step_resize,
         R"({"resize": [640, 400]})",
         "the window's size from now on (at most the size it started with)"},
        {"screenshot", step_screenshot,
         R"({"screenshot": "ui.png"})",
         "the whole window as drawn"},
        {"export_view", step_export_view,
         R"({"export_view": "view.png", "size": [1920, 1080]})",
         "the 3D view rendered off-screen at that size"},
    };
    return steps;
}

void run_step(HeadlessStudio& session, const json& step) {
    if (!step.is_object() || step.empty())
        throw ScriptError("a step is a JSON object such as {\"frames\": 3}");
    for (const ScriptStep& kind : script_steps())
        if (step.contains(kind.name)) return kind.run(session, step);
    throw ScriptError("unknown step " + step.dump());
}

std::string script_reference() {
    std::string out = "| step | does |\n|---|---|\n";
    for (const ScriptStep& kind : script_steps())
        out += std::string("| `") + kind.example + "` | " + kind.help + " |\n";
    return out;
}

void run_script(HeadlessStudio& session, const json& steps,
                const std::function<void(int, const json&)>& after_step) {
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const json& step = steps[i];
        try {
            run_step(session, step);
        } catch (const ScriptError& e) {
            // The kind run_step ran, not the object's first key: keys come in alphabetical
            // order, so {"wait_run": ..., "timeout_s": 60} would read as "timeout_s".
            std::string kind = step.is_object() && !step.empty() ? step.begin().key() : "?";
            for (const ScriptStep& k : script_steps())
                if (step.is_object() && step.contains(k.name)) {
                    kind = k.name;
                    break;
                }
            throw ScriptError("step " + std::to_string(i + 1) + " (" + kind + "): " + e.what());
        } catch (const json::exception& e) {
            throw ScriptError("step " + std::to_string(i + 1) +
                              ": malformed: " + evo::without_json_tags(e.what()));
        }
        if (after_step) after_step(static_cast<int>(i), step);
    }
}

}  // namespace bhm::app::gui
