#pragma once
// "Verify in FEM" (issue 27, docs/verify.md) for the studio: one body checked against CalculiX
// by evo::verify_body, then the FEM's own mesh error from a second mesh (evo::estimate_mesh_error,
// as bhm verify does), on a worker thread that never touches GL or ImGui. The worker publishes an
// immutable FemVerifyState (phase, load i of n, the result or the error) into a LatestSlot at
// every step; the UI takes the newest one at the start of a frame. The report goes into the run
// directory as one folder (RUN_DIR/verify/individual-<id>/: report.json, shapes.json and the
// FEM's VTK meshes), written into a hidden temporary folder and renamed into place only when
// complete, so a Cancel (which kills the ccx child) or a failure leaves nothing half-written.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/gui/session/latest_slot.hpp"
#include "engine/poses.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/verify/verify_body.hpp"

namespace bhm::app::gui {

//! One load's row of the result table: both answers' measures and their relative differences.
struct FemLoadRow {
    std::string load;  //!< "rest", "+A", "-A"; a muscle body's "rest", "peak"
    double temperature_c = 0.0;
    double fem_tip_m = 0.0, engine_tip_m = 0.0;        //!< |tip displacement|
    double fem_bend_deg = 0.0, engine_bend_deg = 0.0;  //!< bend angle
    double fem_com_yz_m = 0.0, engine_com_yz_m = 0.0;  //!< |YZ displacement of the COM|
    std::optional<double> tip, bend, com_yz, rms;      //!< relative differences
};

//! A verification as the studio shows it, read from its folder (report.json and shapes.json):
//! the same reader for a result just computed and for one kept from an earlier session.
struct FemVerification {
    std::int64_t id = -1;  //!< the individual verified
    std::string dir;       //!< its folder in the run directory
    std::string verdict;   //!< "agrees within X %", "differs by Y %" or "outside ..."
    bool compared = false;
    bool agrees = false;
    double worst = 0.0, tolerance = 0.10;
    double fem_cpu_s = 0.0, engine_cpu_s = 0.0;
    int fem_nodes = 0;
    std::string element;
    std::string mesh_reason;  //!< the mesh and why (automatic, or the caller's); "" in old reports
    //! The FEM's own mesh error (report.json's fem_mesh_error): "FEM mesh error ~5.2 % (2 vs 4
    //! per edge)", "FEM mesh error not estimated: ...", or "" where the report has none.
    std::string mesh_error;
    //! Nonlinear steps: the continuum law judged against and the other's difference (report.json's
    //! "law", BodyVerification::laws); "" for linear steps and older reports.
    std::string law;
    std::vector<FemLoadRow> rows;
    std::vector<int> voxel_cells;                  //!< lattice cell per voxel of the shapes
    std::vector<engine::VoxelPoses> fem_shape;     //!< per row: the FEM's deformed voxels
    std::vector<engine::VoxelPoses> engine_shape;  //!< per row: ours at rest under that load
};

//! The folder of individual `id`'s verification in a run directory.
std::string verification_dir(const std::string& run_dir, std::int64_t id);
//! Reads a verification folder; nullopt when it holds no report.json. Throws std::runtime_error
//! naming the file when one is unreadable, damaged or not a regular file (a FIFO, device or folder
//! named report.json or shapes.json is refused at once, never waited on).
std::optional<FemVerification> read_verification(const std::string& dir, std::int64_t id);
//! The ids of the reports kept in RUN_DIR/verify/ (folders individual-<id> holding a
//! report.json), ascending: a population member's is listed too, although a reopened run
//! directory shows only its champions. Hidden partial folders and other names are skipped;
//! empty when there is no such folder.
std::vector<std::int64_t> kept_verifications(const std::string& run_dir);

//! A partial folder this old is stale whoever wrote it: one lives only while a finished
//! verification's report is written (about a second), never during the solve.
inline constexpr double kStalePartialAge_s = 600.0;

//! Removes what a crash left in RUN_DIR/verify/: the hidden folders a report is written into
//! (`.individual-<id>.partial-<pid>-XXXXXX`) whose writer process is gone, and any (also of the
//! older name without a pid) last modified more than kStalePartialAge_s ago. This process's own
//! young ones are kept (its worker removes them itself), as are those of a live process; the
//! finished reports are never touched. Errors are ignored (a read-only run directory stays as it
//! is). Returns how many it removed. Called when a run directory is opened and when a
//! verification starts.
int remove_stale_partials(const std::string& run_dir);

struct FemVerifyRequest {
    std::int64_t id = -1;
    std::string label;  //!< "champion #412 of generation 37"
    evo::Experiment experiment;
    std::shared_ptr<const evo::Body> framed_body;  //!< apply_frame_and_overrides output
    std::string run_dir;                           //!< the report goes to verification_dir()
    evo::VerifyOptions options;                    //!< mesh, tolerance (control is the worker's)
};

enum class FemVerifyPhase { Running, Finished, Failed, Cancelled };

//! What the worker publishes: immutable once published.
struct FemVerifyState {
    std::uint64_t job = 0;  //!< 1 for the first start, then one more per start
    std::int64_t id = -1;
    std::string label;
    FemVerifyPhase phase = FemVerifyPhase::Running;
    evo::VerifyProgress progress;
    std::string step;  //!< "meshing", "CalculiX solving load 2 of 3", ..., "writing the report"
    std::chrono::steady_clock::time_point started{};
    double elapsed_s = 0.0;  //!< at the end (running: the UI measures from `started`)
    std::string error;       //!< Failed: one line (ccx missing, a failed solve, ...)
    std::shared_ptr<const FemVerification> result;  //!< Finished
};

class FemVerifier {
  public:
    FemVerifier() = default;
    ~FemVerifier();  //!< cancels a verification in progress and joins the worker
    FemVerifier(const FemVerifier&) = delete;
    FemVerifier& operator=(const FemVerifier&) = delete;

    //! Starts a verification; false (nothing started) while one is running. A missing ccx is
    //! reported at once as a Failed state, before any thread starts.
    bool start(FemVerifyRequest request);
    //! Kills the ccx child (or stops our engine's run) within a poll; the state becomes
    //! Cancelled and no folder appears. No-op when idle.
    void cancel();
    bool running() const { return running_.load(); }
    //! The newest state (null before the first start).
    std::shared_ptr<const FemVerifyState> state() const { return states_.take(); }
    std::uint64_t version() const { return states_.version(); }

  private:
    void work(FemVerifyRequest request, FemVerifyState state);
    std::atomic<bool> cancel_{false};
    std::atomic<bool> running_{false};
    std::uint64_t jobs_ = 0;  //!< the UI thread's (start)
    LatestSlot<FemVerifyState> states_;
    std::thread worker_;
};

}  // namespace bhm::app::gui
