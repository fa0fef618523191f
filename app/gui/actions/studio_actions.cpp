#include "app/gui/actions/studio_actions.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>

#include "app/gui/actions/calibration_actions.hpp"
#include "app/gui/actions/robustness_actions.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/run_directory.hpp"

namespace bhm::app::gui {

void set_status(Studio& studio, const std::string& message, bool is_error) {
    studio.ui.status = message;
    studio.ui.status_is_error = is_error;
}

std::string describe_problems(const std::string& prefix,
                              const std::vector<evo::Problem>& problems) {
    // Every problem, not only the first: a user fixing one at a time would meet them in turns.
    std::string text = prefix;
    for (std::size_t i = 0; i < problems.size(); ++i)
        text += (i == 0 ? "" : "; ") + problems[i].field + ": " + problems[i].message;
    if (problems.size() > 1) text += " (" + std::to_string(problems.size()) + " problems)";
    return text;
}

// --- Document ------------------------------------------------------------------------------

bool apply_edit(Studio& studio, const evo::Experiment& next, const std::string& label) {
    auto problems = studio.document.edit(next, label);
    studio.ui.edit_problems = problems;
    if (!problems.empty()) {
        set_status(studio, describe_problems("refused: ", problems), true);
        return false;
    }
    if (!label.empty()) set_status(studio, label);
    return true;
}

std::string material_library_warning(const evo::MaterialLibrary& library) {
    const auto warnings = library.warnings();
    if (warnings.empty()) return "";
    std::string text = "material library: " + warnings.front();
    if (warnings.size() > 1) text += " (and " + std::to_string(warnings.size() - 1) + " more)";
    return text;
}

const evo::MaterialLibrary* studio_material_library(Studio& studio) {
    if (!studio.library.materials && studio.library.materials_error.empty()) {
        try {
            studio.library.materials = evo::load_material_library(studio.library.materials_dir);
            // A skipped entry or a damaged file is said where the library is first used (issue
            // 41 R10); the picker lists every one.
            if (auto warning = material_library_warning(*studio.library.materials);
                !warning.empty())
                set_status(studio, warning);
        } catch (const evo::ValidationError& e) {
            studio.library.materials_error =
                e.problems.empty() ? std::string(e.what()) : e.problems[0].to_string();
        }
    }
    return studio.library.materials ? &*studio.library.materials : nullptr;
}

bool choose_library_material(Studio& studio, std::size_t slot, const std::string& id) {
    const evo::MaterialLibrary* library = studio_material_library(studio);
    const evo::LibraryMaterial* m = library ? library->find(id) : nullptr;
    auto next = studio.document.experiment();
    if (!m || slot >= next.materials.size()) {
        set_status(studio, "no library material '" + id + "'", true);
        return false;
    }
    auto& entry = next.materials[slot];
    entry.name.clear();  // the library's name: the slot now holds another material
    evo::apply_library_material(*m, next.actuation.temperature_amplitude_c, entry);
    return apply_edit(studio, next,
                      "material " + std::to_string(slot + 1) + " from library: " + m->name);
}

void new_experiment(Studio& studio) {
    studio.document = ExperimentDocument();
    studio.view.camera_needs_framing = true;
    studio.ui.edit_problems.clear();
    set_status(studio, "new experiment");
}

bool open_experiment(Studio& studio, const std::string& path) {
    try {
        auto experiment = evo::load_experiment(path);
        studio.document.reset(experiment, path);
        studio.settings.remember(path);
        studio.path_field = path;
        studio.view.camera_needs_framing = true;
        studio.ui.edit_problems.clear();
        set_view_mode(studio, ViewMode::Workspace);
        std::string status = "opened " + path;
        // Filled from a library with a damaged file or a skipped entry: it loaded, and says so.
        const bool uses_library =
            std::any_of(experiment.materials.begin(), experiment.materials.end(),
                        [](const auto& m) { return !m.library.empty(); });
        if (const evo::MaterialLibrary* library =
                uses_library ? studio_material_library(studio) : nullptr)
            if (auto warning = material_library_warning(*library); !warning.empty())
                status += "; " + warning;
        set_status(studio, status);
        return true;
    } catch (const evo::ValidationError& e) {
        studio.ui.edit_problems = e.problems;
        set_status(studio,
                   e.problems.empty()
                       ? std::string(e.what())
                       : describe_problems(e.problems.front().file + ":", e.problems),
                   true);
    } catch (const std::exception& e) {
        set_status(studio, path + ": " + e.what(), true);
    }
    return false;
}

bool open_welcome(Studio& s) {
    s.ui.welcome_open = true;
    s.ui.welcome_cards = read_preset_cards(s.library.presets_dir);
    const auto& cards = s.ui.welcome_cards;
    const auto demo = std::find_if(cards.begin(), cards.end(),
                                   [](const PresetCard& c) { return c.stem == kStartHerePreset; });
    if (demo == cards.end()) {
        set_status(
            s, std::string("welcome: no ") + kStartHerePreset + ".json in " + s.library.presets_dir,
            true);
        return false;
    }
    const auto recent = s.settings.recent_files;
    const bool opened = open_experiment(s, demo->path);
    s.settings.recent_files = recent;  // opened for the user, not by them
    if (opened) set_status(s, "welcome: choose an experiment to start from");
    return opened;
}

bool save_experiment_as(Studio& studio, const std::string& path) {
    if (path.empty()) {
        set_status(studio, "save: type a file name in the path field first", true);
        return false;
    }
    if (is_shipped_preset(path, studio.library.presets_dir)) {
        // The gallery's presets stay as shipped: propose a name of the user's own instead.
        const auto stem = std::filesystem::path(path).stem().string();
        studio.path_field = (std::filesystem::path(default_runs_root()).parent_path() /
                             "experiments" / (stem + "-edited.json"))
                                .string();
        set_status(studio,
                   path +
                       " is a shipped preset and is not overwritten: Save As under a new name "
                       "(proposed in the path field)",
                   true);
        return false;
    }
    try {
        std::error_code ec;
        const auto parent = std::filesystem::path(path).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent, ec);
        evo::save_experiment(path, studio.document.experiment());
        studio.document.mark_saved(path);
        studio.settings.remember(path);
        set_status(studio, "saved " + path);
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

bool save_experiment(Studio& studio) {
    const std::string path =
        studio.document.path().empty() ? studio.path_field : studio.document.path();
    return save_experiment_as(studio, path);
}

bool undo(Studio& studio) {
    const std::string label = studio.document.undo_label();
    if (!studio.document.undo()) {
        set_status(studio, "nothing to undo");
        return false;
    }
    set_status(studio, "undo: " + label);
    return true;
}

bool redo(Studio& studio) {
    const std::string label = studio.document.redo_label();
    if (!studio.document.redo()) {
        set_status(studio, "nothing to redo");
        return false;
    }
    set_status(studio, "redo: " + label);
    return true;
}

// --- Painter -------------------------------------------------------------------------------

bool cycle_face(Studio& studio, evo::Face face) {
    const auto& e = studio.document.experiment();
    const auto kind = next_face_kind(e.boundary.faces[static_cast<int>(face)]);
    return apply_edit(studio, with_face_kind(e, face, kind), face_edit_label(face, kind));
}

bool set_enclosure_thickness(Studio& studio, evo::Face face, int voxels) {
    const auto& e = studio.document.experiment();
    return apply_edit(studio, with_enclosure_thickness(e, face, voxels),
                      std::string("enclosure ") + evo::kFaceNames[static_cast<int>(face)] + " " +
                          std::to_string(voxels) + " voxels");
}

bool paint_cell(Studio& studio, const std::array<int, 3>& cell) {
    const auto& p = studio.painter;
    return apply_edit(studio,
                      with_override(studio.document.experiment(), cell, p.brush, p.brush_material),
                      paint_edit_label(cell, p.brush, p.brush_material));
}

// --- Evolution -----------------------------------------------------------------------------

namespace {

std::string fresh_run_dir(const evo::Experiment& e, const std::string& runs_root) {
    const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    localtime_r(&now, &tm);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
    std::string name = e.name.empty() ? std::string("run") : e.name;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '-';
    return (std::filesystem::path(runs_root) / (name + "-" + stamp)).string();
}

}  // namespace

void forget_shown_bodies(Studio& studio) {
    studio.bodies.simulator.cancel();
    studio.bodies.compare_simulator.cancel();
    studio.bodies.shown.reset();
    studio.bodies.shown_version = studio.bodies.simulator.version();
    studio.bodies.compared.reset();
    studio.bodies.compared_version = studio.bodies.compare_simulator.version();
    studio.run.selected_id = -1;
}

namespace {

// A run was launched (it has published its first, running, snapshot): the action's own word on
// the status line, and whatever way the run ends is news, even the way the last one ended. The
// line heard only of a change of phase, so a second resume that failed as the first had, before
// a frame saw it running (one slow frame), left "resumed ..." standing (issue 39, a low).
void report_run_launched(Studio& studio, const std::string& message) {
    set_status(studio, message);
    studio.ui.status_run_phase = RunPhase::Running;
}

}  // namespace

bool start_run(Studio& studio) {
    if (run_is_live(studio.run.evolution.phase())) {
        set_status(studio, "a run is already going: stop it first", true);
        return false;
    }
    if (studio.ui.welcome_open) {  // F5 too: the newcomer chooses an experiment first
        set_status(studio, "choose an experiment in the welcome first (or close it)", true);
        return false;
    }
    // Absolute, so the run is found again whatever folder the studio was started from.
    std::string dir = studio.run.dir_field.empty()
                          ? fresh_run_dir(studio.document.experiment(), default_runs_root())
                          : absolute_path(studio.run.dir_field);
    try {
        studio.run.evolution.start(studio.document.experiment(), dir);
        close_run_directory(studio);
        forget_shown_bodies(studio);
        studio.run.dir_field.clear();
        studio.run.document_id = studio.document.identity();
        studio.run.adopt_experiment = false;
        studio.bodies.follow_champion = true;
        studio.bodies.requested_champion = -1;
        report_run_launched(studio, "evolution started: " + dir);
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

bool pause_run(Studio& studio) {
    if (studio.run.evolution.phase() != RunPhase::Running) return false;
    studio.run.evolution.pause();
    set_status(studio, "pausing: the generation in progress is interrupted and re-run on resume");
    return true;
}

bool resume_run(Studio& studio) {
    const auto phase = studio.run.evolution.phase();
    if (phase != RunPhase::Paused && phase != RunPhase::Pausing) return false;
    // A refused change (the status says why) does not hold the run: it goes on under the rules
    // it has, and the edits wait in the editor.
    const bool refused = rules_differ_from_run(studio) && !apply_rules_to_run(studio);
    studio.run.evolution.resume();
    if (!refused) set_status(studio, "evolution resumed");
    return true;
}

bool stop_run(Studio& studio) {
    if (!run_is_live(studio.run.evolution.phase())) return false;
    studio.run.evolution.stop();
    const int done =
        studio.run.snapshot && studio.run.snapshot->loaded ? studio.run.snapshot->generation : 0;
    // Resume run (Run directory) goes on from this folder without its path typed (issue 39, M1).
    if (done > 0 && !studio.run.snapshot->run_dir.empty())
        studio.run.open_field = studio.run.snapshot->run_dir;
    set_status(studio, done > 0 ? "stopping: the generation in progress is abandoned, the "
                                  "checkpoint of generation " +
                                      std::to_string(done - 1) + " is kept"
                                : std::string("stopping: no generation is complete yet, so "
                                              "there will be no checkpoint to resume"));
    return true;
}

std::string stopped_run_folder(const Studio& studio) {
    if (studio.run.showing_directory || studio.run.evolution.phase() != RunPhase::Stopped)
        return "";
    const auto run = studio.run.evolution.snapshot();
    // Generation 0 stopped leaves no checkpoint (and no folder): nothing to go on from.
    if (!run || !run->loaded || run->generation < 1) return "";
    return run->run_dir;
}

bool resume_stopped_run(Studio& studio) {
    const std::string folder = stopped_run_folder(studio);
    if (folder.empty()) return false;
    return resume_run_directory(studio, folder);
}

bool resume_run_directory(Studio& studio, const std::string& run_dir) {
    if (run_is_live(studio.run.evolution.phase())) {
        set_status(studio, "a run is already going: stop it first", true);
        return false;
    }
    if (run_dir.empty()) {
        set_status(studio, "resume run: type or browse for a run directory first", true);
        return false;
    }
    try {
        studio.run.evolution.resume_from(absolute_path(run_dir));
        close_run_directory(studio);
        forget_shown_bodies(studio);
        // The editor takes the run's experiment once its checkpoint is loaded (when it holds
        // no unsaved edits); until then no document of the editor belongs to the run.
        studio.run.document_id = 0;
        studio.run.adopt_experiment = true;
        studio.bodies.follow_champion = true;
        studio.bodies.requested_champion = -1;
        report_run_launched(studio, "resumed " + run_dir);
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

bool restart_from_run_info(Studio& studio) {
    const auto run = studio.run.evolution.snapshot();
    if (!run || run->run_dir.empty() || run_is_live(studio.run.evolution.phase())) return false;
    if (studio.document.dirty()) {
        set_status(studio, "the editor holds unsaved edits: save or undo them first", true);
        return false;
    }
    try {
        const evo::RunInfo info = evo::read_run_info(run->run_dir);
        studio.document.reset(info.started, "");
        studio.view.camera_needs_framing = true;
        studio.run.dir_field.clear();  // a new folder: the damaged one is left as it is
    } catch (const std::exception& e) {
        set_status(studio, std::string("cannot start again: ") + e.what(), true);
        return false;
    }
    return start_run(studio);
}

bool editing_run_document(const Studio& studio) {
    return studio.run.document_id != 0 && studio.run.document_id == studio.document.identity() &&
           run_is_live(studio.run.evolution.phase());
}

std::optional<evo::Fitness> run_fitness_rules(const Studio& studio) {
    if (const evo::Experiment* sent = studio.run.evolution.sent_rules()) return sent->fitness;
    const auto snapshot = studio.run.evolution.snapshot();
    if (!snapshot || !snapshot->loaded) return std::nullopt;
    return snapshot->experiment.fitness;
}

std::optional<evo::LoopVerifySettings> run_verify_settings(const Studio& studio) {
    if (const evo::LoopVerifySettings* sent = studio.run.evolution.sent_verify()) return *sent;
    const auto snapshot = studio.run.evolution.snapshot();
    if (!snapshot || !snapshot->loaded) return std::nullopt;
    return snapshot->experiment.evolution.verify;
}

namespace {

bool fitness_differs_from_run(const Studio& studio) {
    if (!editing_run_document(studio)) return false;
    const auto rules = run_fitness_rules(studio);
    return rules && !(*rules == studio.document.experiment().fitness);
}

}  // namespace

bool verify_differs_from_run(const Studio& studio) {
    if (!editing_run_document(studio)) return false;
    const auto verify = run_verify_settings(studio);
    return verify && !(*verify == studio.document.experiment().evolution.verify);
}

bool rules_differ_from_run(const Studio& studio) {
    return fitness_differs_from_run(studio) || verify_differs_from_run(studio);
}

std::string describe_rules_to_send(const Studio& studio) {
    std::string what;
    if (fitness_differs_from_run(studio))
        what = describe_fitness_change(*run_fitness_rules(studio),
                                       studio.document.experiment().fitness);
    if (verify_differs_from_run(studio))
        what += (what.empty() ? "" : "; ") +
                describe_verify_settings(studio.document.experiment().evolution.verify);
    return what;
}

bool apply_rules_to_run(Studio& studio) {
    const auto snapshot = studio.run.evolution.snapshot();
    if (!snapshot || !run_is_live(studio.run.evolution.phase())) {
        set_status(studio, "no run to change", true);
        return false;
    }
    if (!editing_run_document(studio)) {
        // The run owns its experiment: another document's rules never reach it.
        set_status(studio,
                   "the editor shows another experiment than the run's: its rules do not apply "
                   "to the run",
                   true);
        return false;
    }
    const auto& doc = studio.document.experiment();
    const bool fitness = fitness_differs_from_run(studio);
    const bool verify = verify_differs_from_run(studio);
    if (!fitness && !verify) return false;
    // The checks first: they are the part the run may refuse (CalculiX missing, a setting out of
    // range), and a refusal then sends nothing, so the edits stay to be fixed and sent again.
    if (verify) {
        try {
            studio.run.evolution.change_verify(doc.evolution.verify);
        } catch (const std::exception& e) {
            set_status(studio,
                       std::string("the run's continuum checks were not changed: ") + e.what(),
                       true);
            return false;
        }
    }
    if (fitness) {
        evo::Experiment rules = snapshot->experiment;
        rules.fitness = doc.fitness;
        studio.run.evolution.change_rules(rules);
    }
    set_status(studio, fitness && verify ? "fitness rules and CalculiX checks changed: the "
                                           "population is re-scored before the next generation"
                       : fitness ? "fitness rules changed: the population is re-scored before "
                                   "the next generation"
                                 : "CalculiX checks changed: " +
                                       describe_verify_settings(doc.evolution.verify) +
                                       " from the next generation");
    return true;
}

bool boundary_differs_from_run(const Studio& studio) {
    const auto snapshot = studio.run.evolution.snapshot();
    if (!snapshot || !snapshot->loaded || !editing_run_document(studio)) return false;
    return !(snapshot->experiment.boundary == studio.document.experiment().boundary);
}

// --- Run directory -------------------------------------------------------------------------

bool open_run_directory(Studio& studio, const std::string& run_dir) {
    try {
        studio.run.directory.open(run_dir);
        studio.run.directory.refresh();
        studio.run.showing_directory = true;
        forget_shown_bodies(studio);
        studio.bodies.follow_champion = true;
        studio.bodies.requested_champion = -1;
        studio.run.snapshot = studio.run.directory.snapshot();
        // The hidden folders of verifications a crash interrupted (never a finished report).
        remove_stale_partials(run_dir);
        std::string note;
        if (studio.run.snapshot && !studio.document.dirty()) {
            // Show the run's experiment in the editor (a copy; the run directory is never
            // written). It is untitled, and so is the path field: Save must never write the
            // run's experiment over the file the editor held before (issue 39, H1).
            const std::string previous = studio.document.path();
            studio.document.reset(studio.run.snapshot->experiment, "");
            studio.path_field.clear();
            studio.view.camera_needs_framing = true;
            note = previous.empty() ? std::string(" (the editor shows its experiment, untitled)")
                                    : " (the editor shows its experiment, untitled; " + previous +
                                          " is unchanged)";
        } else if (studio.run.snapshot) {
            note = " (the editor keeps your unsaved experiment)";
        }
        set_status(studio, "watching run directory " + run_dir + note);
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

void close_run_directory(Studio& studio) {
    studio.run.directory.close();
    if (studio.run.showing_directory) {
        // Back to the live session's run: the directory's bodies are not its own.
        forget_shown_bodies(studio);
        studio.bodies.follow_champion = true;
        studio.bodies.requested_champion = -1;
    }
    studio.run.showing_directory = false;
}

// --- Bodies and replay ---------------------------------------------------------------------

namespace {

const PopulationMember* find_member(const EvolutionSnapshot& run, std::int64_t id) {
    if (run.has_champion && run.champion.id == id) return &run.champion;
    for (const auto& m : run.population)
        if (m.id == id) return &m;
    return nullptr;
}

void request_simulation(Studio& studio, const EvolutionSnapshot& run, const PopulationMember& m,
                        const std::string& label) {
    if (!m.body) return;
    SimulationRequest request;
    request.id = m.id;
    request.label = label;
    request.experiment = run.experiment;
    request.framed_body = m.body;
    studio.bodies.simulator.request(std::move(request));
}

}  // namespace

bool select_individual(Studio& studio, std::int64_t id) {
    if (!studio.run.snapshot) return false;
    const PopulationMember* m = find_member(*studio.run.snapshot, id);
    // A watched run directory lists its population without bodies (population.csv): they are
    // developed from its checkpoint on the first click that needs one.
    if (m && !m->body && studio.run.showing_directory &&
        studio.run.snapshot == studio.run.directory.snapshot() &&
        studio.run.directory.load_bodies()) {
        studio.run.snapshot = studio.run.directory.snapshot();
        m = find_member(*studio.run.snapshot, id);
    }
    if (m && !m->body) {
        set_status(studio,
                   "individual #" + std::to_string(id) + ": its body is not at hand (" +
                       (studio.run.directory.error().empty() ? std::string("no checkpoint")
                                                             : studio.run.directory.error()) +
                       ")",
                   true);
        return false;
    }
    if (!m) {
        set_status(studio, "individual #" + std::to_string(id) + " is not in the population", true);
        return false;
    }
    studio.run.selected_id = id;
    const bool champion =
        studio.run.snapshot->has_champion && studio.run.snapshot->champion.id == id;
    studio.bodies.follow_champion = champion;
    if (champion) studio.bodies.requested_champion = id;
    request_simulation(
        studio, *studio.run.snapshot, *m,
        (champion ? "champion #" : "individual #") + std::to_string(id) +
            (champion ? ", generation " + std::to_string(studio.run.snapshot->champion_generation)
                      : ""));
    set_status(studio,
               std::string(champion ? "simulating the champion #" : "simulating individual #") +
                   std::to_string(id));
    return true;
}

SimulationRequest champion_request(const Studio& studio, const ChampionEntry& entry) {
    SimulationRequest request;
    request.id = entry.id;
    request.label = "champion #" + std::to_string(entry.id) + " of generation " +
                    std::to_string(entry.generation);
    request.experiment = studio.run.snapshot->experiment;
    request.experiment.fitness.measure = entry.measure;
    request.framed_body = load_champion_body(entry.path);
    return request;
}

bool replay_champion(Studio& studio, const ChampionEntry& entry, bool beside) {
    if (!studio.run.snapshot) return false;
    try {
        SimulationRequest request = champion_request(studio, entry);
        if (beside) {
            studio.bodies.compare_simulator.request(std::move(request));
            set_status(studio, "simulating the champion of generation " +
                                   std::to_string(entry.generation) + " to show beside");
        } else {
            studio.bodies.follow_champion = false;
            studio.run.selected_id = entry.id;
            studio.bodies.simulator.request(std::move(request));
            set_status(studio,
                       "simulating the champion of generation " + std::to_string(entry.generation));
        }
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

const evo::ExploitReport* shown_exploits(const Studio& studio) {
    if (!studio.bodies.shown) return nullptr;
    const auto id = studio.bodies.shown->id;
    if (studio.run.snapshot) {
        if (studio.run.snapshot->has_champion && studio.run.snapshot->champion.id == id)
            return &studio.run.snapshot->champion.exploits;
        for (const auto& m : studio.run.snapshot->population)
            if (m.id == id) return &m.exploits;
    }
    for (const auto& e : studio.run.champion_history.entries())
        if (e.id == id) return &e.exploits;
    return nullptr;
}

void clear_compared_body(Studio& studio) {
    studio.bodies.compare_simulator.cancel();  // a compared body still being simulated goes too
    studio.bodies.compared.reset();
    studio.bodies.compared_version = studio.bodies.compare_simulator.version();
}

bool add_compared_run(Studio& studio, const std::string& run_dir) {
    const std::string dir = absolute_path(run_dir);
    for (const auto& c : studio.run.compared)
        if (c.dir == dir) return true;
    try {
        RunDirectoryWatch watch;
        watch.open(dir);
        watch.refresh();
        if (!watch.snapshot()) throw std::runtime_error(dir + ": " + watch.error());
        ComparedRun run;
        run.dir = dir;
        run.label = std::filesystem::path(dir).filename().string();
        run.snapshot = watch.snapshot();
        studio.run.compared.push_back(std::move(run));
        set_status(studio, "comparing with " + dir);
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

void remove_compared_run(Studio& studio, std::size_t index) {
    if (index < studio.run.compared.size())
        studio.run.compared.erase(studio.run.compared.begin() + static_cast<long>(index));
}

void follow_champion(Studio& studio) {
    studio.bodies.follow_champion = true;
    studio.bodies.requested_champion = -1;  // update_studio requests it again
}

void set_view_mode(Studio& studio, ViewMode mode) {
    if (studio.view.mode != mode) studio.view.camera_needs_framing = true;
    studio.view.mode = mode;
}

void toggle_playback(Studio& studio) {
    if (!studio.bodies.shown) return;
    if (!studio.clock.playing && studio.clock.time_s >= studio.clock.duration_s)
        studio.clock.time_s = 0.0;
    studio.clock.playing = !studio.clock.playing;
}

void step_replay(Studio& studio, int frames) {
    if (!studio.bodies.shown) return;
    const double fps = studio.bodies.shown->experiment.simulation.record_fps;
    studio.clock.step_frames(frames, fps > 0.0 ? 1.0 / fps : 1.0 / 30.0);
}

void set_named_view(Studio& studio, render::NamedView view) {
    render::Bounds unit;
    unit.add(glm::vec3(0.0f));
    unit.add(glm::vec3(1.0f));
    const auto named = render::named_view(view, unit, 1.0f);
    studio.view.camera.yaw_rad = named.yaw_rad;
    // The renderer's front looks from +y onto the paper's front section (a cut hides y beyond
    // it); the studio shows no cut, so from +y its Front looked at the back of what the iso view
    // shows. Here Front looks from -y, x to the right as in the iso view.
    if (view == render::NamedView::Front) studio.view.camera.yaw_rad = -named.yaw_rad;
    studio.view.camera.pitch_rad = named.pitch_rad;
    studio.view.camera.orthographic = named.orthographic;
    studio.view.zoom = 1.0f;
    studio.view.camera_needs_framing = true;
}

// --- Per frame -----------------------------------------------------------------------------

namespace {

bool simulating_status(const Studio& studio) {
    return !studio.ui.status_is_error && studio.ui.status.starts_with("simulating");
}

// The run shown this frame: a watched run directory (re-read twice a second), else the live
// session, whose end the status line then reports.
void take_run_snapshot(Studio& studio) {
    // The snapshot to show: a watched run directory, else the live (or last) session.
    if (studio.run.showing_directory) {
        // Twice a second is enough for a run that writes once per generation; stat() is cheap.
        const auto now = std::chrono::steady_clock::now();
        if (now - studio.run.last_directory_check > std::chrono::milliseconds(500)) {
            studio.run.last_directory_check = now;
            if (studio.run.directory.refresh())
                studio.run.snapshot = studio.run.directory.snapshot();
        }
    } else {
        studio.run.evolution.collect_ended();
        studio.run.progress = studio.run.evolution.progress();
        studio.run.snapshot = studio.run.evolution.snapshot();
        // The run ended: the status line says how, instead of the last action's word.
        const RunPhase phase = studio.run.snapshot ? studio.run.snapshot->phase : RunPhase::Idle;
        const bool ended =
            phase == RunPhase::Finished || phase == RunPhase::Stopped || phase == RunPhase::Failed;
        if (ended && phase != studio.ui.status_run_phase && !studio.run.snapshot->message.empty())
            set_status(studio, studio.run.snapshot->message, phase == RunPhase::Failed);
        studio.ui.status_run_phase = phase;
    }
}

// A resumed run's experiment goes into the editor once its checkpoint is loaded.
void adopt_resumed_run_experiment(Studio& studio) {
    // A resumed run's experiment, once loaded, becomes the editor's document (the run's own),
    // unless the editor holds unsaved edits of another one.
    if (studio.run.adopt_experiment && studio.run.snapshot && studio.run.snapshot->loaded &&
        !studio.run.showing_directory) {
        studio.run.adopt_experiment = false;
        if (!studio.document.dirty()) {
            studio.document.reset(studio.run.snapshot->experiment, "");
            studio.run.document_id = studio.document.identity();
            studio.view.camera_needs_framing = true;
        }
    }
}

// A new champion of the run shown is simulated for the 3D view (when following champions).
void follow_new_champion(Studio& studio) {
    // A new champion: simulate it for the live view.
    if (studio.bodies.follow_champion && studio.run.snapshot && studio.run.snapshot->has_champion &&
        studio.run.snapshot->champion.id != studio.bodies.requested_champion) {
        studio.bodies.requested_champion = studio.run.snapshot->champion.id;
        request_simulation(studio, *studio.run.snapshot, studio.run.snapshot->champion,
                           "champion #" + std::to_string(studio.run.snapshot->champion.id) +
                               ", generation " +
                               std::to_string(studio.run.snapshot->champion_generation));
    }
}

// The simulators' newest bodies: the one shown and the one beside it; their failures.
void take_simulated_bodies(Studio& studio) {
    // A finished simulation: show it (the clock keeps its time, so playback continues in step).
    if (studio.bodies.simulator.version() != studio.bodies.shown_version) {
        studio.bodies.shown_version = studio.bodies.simulator.version();
        auto next = studio.bodies.simulator.latest();
        if (next && (!studio.bodies.shown || next->id != studio.bodies.shown->id)) {
            if (!studio.bodies.shown) {  // the first body of a session: start playing it
                studio.clock.playing = true;
                set_view_mode(studio, ViewMode::Simulation);
            }
        }
        studio.bodies.shown = next;
        // The "simulating ..." line would go stale now: say what is shown.
        if (next && simulating_status(studio)) set_status(studio, "showing " + next->label);
    }
    if (studio.bodies.compare_simulator.version() != studio.bodies.compared_version) {
        studio.bodies.compared_version = studio.bodies.compare_simulator.version();
        studio.bodies.compared = studio.bodies.compare_simulator.latest();
        studio.view.camera_needs_framing = true;  // two bodies: frame both
        if (studio.bodies.compared && simulating_status(studio))
            set_status(studio, std::string(studio.view.split ? "beside it (the right pane): "
                                                             : "beside it (+y): ") +
                                   studio.bodies.compared->label);
    }
    for (const BodySimulator* sim : {&studio.bodies.simulator, &studio.bodies.compare_simulator})
        if (!sim->busy() && !sim->last_error().empty() && simulating_status(studio))
            set_status(studio, "simulation failed: " + sim->last_error(), true);
}

// The replay clock spans the body shown and moves on by this frame's time.
void advance_replay_clock(Studio& studio) {
    if (studio.bodies.shown) {
        const auto& frames = studio.bodies.shown->replay.frames;
        studio.clock.set_duration(frames.empty() ? 0.0 : frames.back().time_s);
    }
    studio.clock.advance(studio.ui.frame_dt_s);
}

}  // namespace

void update_studio(Studio& studio) {
    take_run_snapshot(studio);
    adopt_resumed_run_experiment(studio);
    follow_new_champion(studio);
    take_simulated_bodies(studio);
    update_calibration(studio);
    update_verification(studio);
    update_robustness(studio);
    advance_replay_clock(studio);
}

}  // namespace bhm::app::gui
