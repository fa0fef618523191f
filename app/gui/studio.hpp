#pragma once
// The studio's whole state, one struct (Dear ImGui's examples, Box2D's samples): the document
// being edited and the persisted settings, then one labelled section per job, each touched by
// its own actions and panels: the painter, the 3D view, the replay clock, the exports, the run
// shown (RunView), the library of materials, presets and files, the calibration, the bodies
// shown, Verify in FEM, and the window around them (UiState). Panels are free functions over it
// (panels.hpp); actions that the mouse, the keyboard and scripts share live in actions/.
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "app/gui/document/constraint_edits.hpp"
#include "app/gui/document/experiment_document.hpp"
#include "app/gui/session/body_simulator.hpp"
#include "app/gui/session/calibration_session.hpp"
#include "app/gui/session/champion_history.hpp"
#include "app/gui/session/evolution_session.hpp"
#include "app/gui/session/evolution_snapshot.hpp"
#include "app/gui/session/fem_verifier.hpp"
#include "app/gui/session/replay_player.hpp"
#include "app/gui/session/robustness_runner.hpp"
#include "app/gui/session/run_directory_watch.hpp"
#include "app/gui/settings/key_chord.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "app/gui/settings/studio_settings.hpp"
#include "app/gui/view/picking.hpp"
#include "app/gui/welcome/welcome.hpp"
#include "app/gui/widgets/file_dialog.hpp"
#include "app/gui/widgets/fitness_plot.hpp"
#include "app/gui/widgets/tile_layout.hpp"
#include "evo/experiment/material_library.hpp"
#include "render/camera.hpp"

namespace bhm::app {
class VideoWriter;
}

namespace bhm::app::gui {

//! What the 3D view shows.
enum class ViewMode {
    Workspace,   //!< the experiment's workspace: faces, frame, overrides (the painter)
    Simulation,  //!< a simulated body playing (live champion or a selected individual)
};

//! What a click in the 3D view does in Workspace mode.
enum class PainterTool { Faces, Voxels };

struct PainterState {
    PainterTool tool = PainterTool::Faces;
    PaintKind brush = PaintKind::Fixed;
    int brush_material = 1;  //!< 1-based, for PaintKind::Material
    Slice slice;
    bool show_champion = true;  //!< draw the champion's body at rest inside the workspace
    std::optional<std::array<int, 3>> hovered_cell;
    std::optional<evo::Face> hovered_face;
};

//! The renderer's iso view angles (render::NamedView::Iso), the studio's default camera.
inline render::Camera iso_camera() {
    render::Camera c;
    c.yaw_rad = -0.9425f;
    c.pitch_rad = 0.534f;
    c.fov_y_rad = 0.55f;
    return c;
}

struct ViewState {
    ViewMode mode = ViewMode::Workspace;
    render::Camera camera = iso_camera();
    bool camera_needs_framing = true;  //!< frame the scene on the next draw (new workspace, view)
    float zoom = 1.0f;                 //!< distance relative to the framed one
    glm::vec2 origin_px{0.0f};         //!< top-left of the 3D image on screen (ImGui coordinates)
    glm::vec2 size_px{0.0f};           //!< size of the 3D image (logical pixels)
    bool hovered = false;
    bool dragging = false;
    int drag_button = -1;
    float drag_distance_px = 0.0f;
    bool show_edges = true;
    bool show_trail = true;
    bool show_start_beside = false;        //!< the t = 0 state as a ghost beside the current one
    ColorBy color_by = ColorBy::Material;  //!< simulation mode: material or a scalar field
    int samples = 4;                       //!< MSAA samples of the 3D view
    //! A compared body (Analysis > Champions > beside) in a pane of its own right of the main
    //! one, with its own camera; off: drawn one workspace further along +y in the same view.
    bool split = true;
    //! The compared pane shows the main camera's view, and its gestures move both.
    bool link_cameras = true;
    struct Pane {
        render::Camera camera = iso_camera();
        bool needs_framing = true;
        float zoom = 1.0f;
        glm::vec2 origin_px{0.0f}, size_px{0.0f};
        bool dragging = false;
        int drag_button = -1;
    } second;
};

//! The Export panel's fields. Their defaults are absolute, in the data folder
//! (default_export_path), not relative names that land wherever the studio was started.
struct ExportState {
    std::string screenshot_path;  //!< empty: numbered files in default_screenshots_dir()
    int screenshot_width = 1920, screenshot_height = 1080;
    std::string frames_folder = default_export_path("bhm-frames");
    int frames_width = 1280, frames_height = 720;
    double frames_fps = 30.0;
    //! Burn a caption into frames and videos: experiment, body (generation), fitness, time.
    bool caption = true;
    std::string champion_vxa_path = default_export_path("champion.vxa");
    std::string champion_json_path = default_export_path("champion.json");
    //! The shown champion's controller CPPN (issue 44), and the controller to drive the body
    //! shown with (a controller file, a run directory, uniform, wave, random[:SEED]).
    std::string controller_path = default_export_path("controller.json");
    std::string controller_item;
    //! .stl or .obj (+ .mtl beside it)
    std::string mesh_path = default_export_path("champion.stl");
    bool mesh_deformed = false;  //!< at the replay time instead of at rest
    std::string vtk_folder = default_export_path("bhm-paraview");
    //! .mp4 (H.264) or .gif, through ffmpeg
    std::string video_path = default_export_path("bhm-replay.mp4");
    //! A frame sequence (or video) in progress: one frame is written per UI frame so the UI
    //! stays live.
    struct FrameJob {
        bool active = false;
        std::string folder;
        std::shared_ptr<VideoWriter> video;  //!< set: frames go to this video, not to PNGs
        std::string video_path;
        int width = 0, height = 0;
        double fps = 30.0;
        int next = 0, total = 0;
    } frame_job;
};

//! Screen rectangles of named widgets, recorded as they are drawn: scripts click them through the
//! same mouse path a person uses (script.hpp).
struct WidgetRect {
    glm::vec2 min{0.0f}, max{0.0f};
    int frame = -1;  //!< frame it was last drawn in
};

//! An action that would lose something (unsaved edits, the generation in progress) waits here
//! for the user's answer in a modal dialog (unsaved_guard.hpp).
struct PendingAction {
    enum class Kind { None, NewExperiment, OpenExperiment, Quit } kind = Kind::None;
    std::string path;                    //!< OpenExperiment: the file to open
    bool unsaved_answered = false;       //!< the unsaved-edits question is answered
    bool run_answered = false;           //!< Quit: the running-evolution question is answered
    bool quit_after_generation = false;  //!< Quit: once the generation in progress is saved
    std::string error;                   //!< why this question's Save failed ("" if it did not)
};

//! Another run's history overlaid on the fitness plots (Fitness > Compare).
struct ComparedRun {
    std::string dir;
    std::string label;
    std::shared_ptr<const EvolutionSnapshot> snapshot;
};

//! The Calibrate tab (docs/calibration.md): a measured track loaded onto the body shown, the
//! parameters to fit and the calibration running on its own thread.
struct CalibrationState {
    std::string body_field;   //!< a body file to show (Show body)
    std::string track_field;  //!< the path typed in the tab
    std::string track_path;   //!< the track loaded (absolute)
    std::shared_ptr<const evo::MeasuredTrack> track;
    //! evo::track_span_warning of the track loaded ("" when its span is near the experiment's):
    //! shown in the Calibrate tab and the status line, since every simulation runs to its end.
    std::string track_warning;
    //! The body the track was loaded onto (the one shown then) and its experiment: what the
    //! calibration simulates, whatever is shown later.
    std::shared_ptr<const evo::Body> framed_body;
    evo::Experiment experiment;
    std::int64_t body_id = -1;
    std::string body_label;
    //! The --fit names offered, and which are ticked; only those that apply to the experiment's
    //! actuation model are shown and sent (fit_name_applies).
    std::vector<std::string> fit_names = {"E",
                                          "density",
                                          "cte",
                                          "amplitude",
                                          "frequency",
                                          "phase_lag",
                                          "rise_s",
                                          "decay_s",
                                          "contraction_strain",
                                          "bond_damping",
                                          "global_damping",
                                          "friction"};
    std::vector<bool> fit_on = {true,  false, false, true,  false, false,
                                false, false, false, false, false, false};
    int max_simulations = 200;
    int threads = 0;  //!< 0: all cores
    CalibrationSession session;
    std::shared_ptr<const CalibrationSnapshot> snapshot;   //!< taken at the start of a frame
    CalibrationPhase seen_phase = CalibrationPhase::Idle;  //!< of the last snapshot's job
    std::uint64_t seen_job = 0;
    std::uint64_t applied_job = 0;      //!< the job whose values Apply last wrote (0: none)
    std::uint64_t applied_run_job = 0;  //!< the job last sent to the live run (0: none)
};

//! The bodies the 3D view replays: the simulators that make them, the one shown, the one beside
//! it, which champion is followed, and the voxel inspected (request_simulation and update_studio
//! in studio_actions.cpp, the replay and population panels).
struct ShownBodies {
    BodySimulator simulator;
    std::shared_ptr<const SimulatedBody> shown;  //!< body playing in the 3D view
    std::uint64_t shown_version = 0;
    //! A second body replayed beside the shown one (Analysis > Champions > beside).
    BodySimulator compare_simulator;
    std::shared_ptr<const SimulatedBody> compared;
    std::uint64_t compared_version = 0;
    bool follow_champion = true;  //!< replace the shown body when a new champion appears
    std::int64_t requested_champion = -1;
    //! Simulation mode: the voxel clicked (index into the replay of inspected_body), read at the
    //! replay time while that body is the one shown.
    int inspected_voxel = -1;
    std::shared_ptr<const SimulatedBody> inspected_body;
    //! The last body the studio drove with another controller (controller_actions.hpp): its
    //! label, and the controller file's object it was painted with ("" for a built-in).
    std::string driven_label;
    std::string driven_controller;
};

//! "Verify in FEM" (Analysis > FEM; verify_actions.cpp and panel_verify.cpp): the worker, its
//! newest state, and the verification of the body shown (just computed, or kept in the run
//! directory from an earlier session).
struct VerifyState {
    FemVerifier worker;
    std::shared_ptr<const FemVerifyState> state;
    std::uint64_t state_version = 0;
    std::uint64_t job_reported = 0;  //!< the last ended job the status line has told of
    std::shared_ptr<const FemVerification> result;
    std::string kept_error;  //!< a kept report that could not be read
    std::string result_key;  //!< "<run dir>#<id>" the kept report was looked up for
    int load = 1;            //!< row of the verification drawn in the 3D view (+A)
    //! The ids of the reports kept in the shown run's RUN_DIR/verify/ (Kept FEM reports), read
    //! when another run is shown and after each verification ends.
    std::vector<std::int64_t> kept_reports;
    std::string kept_reports_key;  //!< "<run dir>#<job>" they were listed for
    bool ghost = true;             //!< draw the FEM's shape over our static one
};

//! Analysis > Robustness (issue 44; robustness_actions.hpp, panel_robustness.cpp): the bodies
//! and controllers picked, the table being evaluated or shown, its export paths and the cell
//! shown in the 3D view. The table's experiment is the shown run's, else the editor's.
struct RobustnessView {
    std::set<int> champions;  //!< the shown run's champions picked, by generation found
    //! Body files, comma-separated (as `bhm robustness`'s BODY.json arguments).
    std::string body_files;
    //! The columns, comma-separated, as `bhm robustness --controllers`: uniform, wave, random,
    //! random:SEED, a controller file or a run directory (its champion's controller.json).
    std::string controllers = "uniform,wave,random";
    std::string csv_path = default_export_path("robustness.csv");
    std::string png_path = default_export_path("robustness.png");
    RobustnessRunner runner;
    std::shared_ptr<const RobustnessState> state;  //!< taken at the start of a frame
    std::uint64_t state_version = 0;
    std::uint64_t job_reported = 0;              //!< the last ended job the status line has told of
    int shown_body = -1, shown_controller = -1;  //!< the cell last sent to the 3D view
};

//! The run the Run panel, the population table and the fitness plots show (studio_actions.cpp's
//! run actions, take_run_snapshot in update_studio; panel_run, panel_population, panel_analysis):
//! the live evolution session or a run directory opened for viewing, the fields that name the
//! next run and the one to open, the row selected, and other runs compared with it.
struct RunView {
    EvolutionSession evolution;
    RunDirectoryWatch directory;                        //!< a run directory opened for viewing
    std::shared_ptr<const EvolutionSnapshot> snapshot;  //!< the one shown: session or directory
    //! The live session's generation in progress, read just before `snapshot` was taken: in
    //! that order a generation completed in between is in the snapshot, never missing from both.
    LiveProgress progress;
    bool showing_directory = false;
    std::chrono::steady_clock::time_point last_directory_check{};
    std::string dir_field;   //!< where the next run is written
    std::string open_field;  //!< run directory to open
    //! identity() of the document the live run belongs to (0: the editor shows none of its
    //! experiments): only that document's rule edits may reach the run, and only explicitly.
    std::uint64_t document_id = 0;
    //! A resumed run's experiment goes into the editor once its checkpoint is loaded.
    bool adopt_experiment = false;
    std::vector<ComparedRun> compared;  //!< other runs' curves on the fitness plots
    std::string compare_field;          //!< run directory to add to the comparison
    ChampionHistory champion_history;   //!< the shown run's champions/ folder
    std::int64_t selected_id = -1;      //!< population row selected
    FitnessPlot fitness_plot;           //!< hover state of the plot
    int fitness_plot_overlays = 0;      //!< other runs' curves drawn in the last frame
};

//! What the studio offers from disk to pick from: the material library (the Experiment panel's
//! picker, studio_material_library), the shipped presets and the Files tab's browser.
struct LibraryState {
    //! The material library (docs/materials-format.md): read once, on first use; the one-line
    //! reason when it did not load.
    std::optional<evo::MaterialLibrary> materials;
    std::string materials_error;
    std::string materials_dir = evo::default_material_library_dir();
    std::string material_filter;  //!< the picker's search text
    //! Shipped presets (the Files tab's gallery, the welcome): Save never overwrites them.
    std::string presets_dir = default_presets_dir();
    std::string browser_dir;  //!< folder the file browser shows (absolute; empty: the current)
    std::map<std::string, FileListing> file_listings;  //!< the Files tab's folders, re-read 2/s
};

//! The window around the panels (the shell, panel_frame, the welcome and the dialogs): the
//! status line, keys and frame timing, the widgets drawn and the tiles they were drawn in, and
//! the questions and dialogs open.
struct UiState {
    std::string status;  //!< one-line message in the status bar (set_status)
    bool status_is_error = false;
    std::vector<evo::Problem> edit_problems;  //!< why the last edit was refused
    //! The live run's phase when the status line last heard of it: an end of the run (finished,
    //! stopped, failed) replaces a status such as "evolution resumed" with the run's own message.
    RunPhase status_run_phase = RunPhase::Idle;
    //! Key presses since the last frame, each with the modifiers held when it went down (GLFW's
    //! key callback, or the headless input): dispatch_key_bindings takes them.
    std::vector<KeyChord> key_presses;
    bool show_help = false;
    bool screenshot_requested = false;  //!< F12: written by the app at the end of the frame
    bool show_demo_metrics = false;
    bool quit_requested = false;  //!< confirmed: the runner closes the window after this frame
    PendingAction pending;        //!< a question asked before an action that loses something

    int frame = 0;
    double frame_dt_s = 1.0 / 60.0;
    double fps = 0.0;
    //! Longest time a frame spent taking the workers' snapshots (ms): the UI never waits for
    //! evolution, so this stays far below a frame (bench_studio reports it).
    double max_update_ms = 0.0;
    std::map<std::string, WidgetRect> widgets;
    //! The last tooltip an experiment field showed (field_editor.hpp); tests read it.
    std::string shown_tooltip;
    //! The multiline text field open for typing (its path; empty: none) and the frame it was
    //! opened: the others show their text wrapped (field_editor.cpp).
    std::string text_field_open;
    int text_field_opened_frame = 0;
    TileLayout tiles;  //!< this frame's tile sizes (fit_layout of the settings' preferences)
    //! A narrow window folds the left column into a strip: its panels open over the 3D view.
    bool design_open = false;
    //! The welcome of a first start (welcome.hpp): the presets' gallery and the legend; Start
    //! waits until it is closed.
    bool welcome_open = false;
    std::vector<PresetCard> welcome_cards;
    //! Open... / Save As... / Open run... / Compare... (file_dialog.hpp).
    FileDialog file_dialog;
};

//! The sections are declared in this order so that their workers' threads stop as before: the
//! bodies' and Verify in FEM's first, the calibration's, then the run's (members are destroyed
//! in reverse order).
struct Studio {
    ExperimentDocument document;
    //! The copy the Experiment panel's fields edit while a field is active; committed through
    //! apply_edit when the field is left, re-read from the document whenever it changes.
    evo::Experiment draft;
    std::size_t draft_revision = static_cast<std::size_t>(-1);
    std::string path_field;  //!< File > Open / Save As text field
    StudioSettings settings;
    std::string settings_path;  //!< empty: settings are not persisted (headless tests)

    PainterState painter;
    ViewState view;
    ReplayClock clock;
    ExportState exports;

    RunView run;
    LibraryState library;
    CalibrationState calibration;
    ShownBodies bodies;
    VerifyState verify;
    RobustnessView robustness;
    UiState ui;
};

}  // namespace bhm::app::gui
