#pragma once
// Simulates one body for the 3D view (the live champion or an individual the user selected) on a
// worker thread: engine::run from t = 0 to settle + evaluate, poses recorded into an
// engine::Replay at the experiment's record_fps, the fitness measures tracked exactly as
// evo::evaluate_body does. The finished result is published into a LatestSlot; the UI never
// waits. A newer request cancels the one in progress (the newest champion is what matters).
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <glm/vec3.hpp>

#include "app/gui/session/body_analysis.hpp"
#include "app/gui/session/latest_slot.hpp"
#include "engine/replay.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

struct SimulationRequest {
    std::int64_t id = -1;  //!< individual id (-1: not from a run)
    std::string label;     //!< "champion #412, generation 37"
    evo::Experiment experiment;
    std::shared_ptr<const evo::Body> framed_body;  //!< apply_frame_and_overrides output
};

struct SimulatedBody {
    std::int64_t id = -1;
    std::string label;
    evo::Experiment experiment;
    std::shared_ptr<const evo::Body> framed_body;
    engine::Replay replay;
    std::vector<glm::vec3> com_m;  //!< centre of mass per replay frame
    //! Voxels with at least one empty face neighbour on the lattice: the only ones that can be
    //! seen (the view draws these; a solid 20x8x7 body has 580 of 1120).
    std::vector<int> surface_voxels;
    std::array<double, evo::kMeasureCount> measures{};  //!< by evo::FitnessMeasure
    double fitness = 0.0;  //!< under the experiment's measure (kDivergedFitness if diverged)
    bool diverged = false;
    std::string divergence_reason;
    double wall_s = 0.0;
    BodyTimeSeries series;               //!< per frame: COM, tip, bend angle (Analysis plots)
    VoxelDrive drive;  //!< actuation phase and fibre axis per replay voxel (colour modes)
    double bend_angle_deg() const {
        return measures[static_cast<int>(evo::FitnessMeasure::BendAngleDeg)];
    }
};

//! Indices of the voxels of a replay's lattice that have an empty face neighbour (or touch the
//! lattice's edge).
std::vector<int> surface_voxels(const engine::Replay& replay);

//! Runs one request on the calling thread; cancel (may be null) aborts with EvaluationCancelled.
//! Throws std::invalid_argument for a body the engine cannot build.
SimulatedBody simulate_body(const SimulationRequest& request,
                            const std::atomic<bool>* cancel = nullptr);

class BodySimulator {
  public:
    BodySimulator() = default;
    ~BodySimulator();
    BodySimulator(const BodySimulator&) = delete;
    BodySimulator& operator=(const BodySimulator&) = delete;

    //! Queues a simulation; a pending request is replaced and a running one cancelled.
    void request(SimulationRequest request);
    //! Drops the queued request and aborts the running one; nothing asked for before is
    //! published any more (another run is shown: its bodies must not appear under it).
    void cancel();
    //! The newest finished simulation (null before the first).
    std::shared_ptr<const SimulatedBody> latest() const { return results_.take(); }
    std::uint64_t version() const { return results_.version(); }
    //! A request is queued or running.
    bool busy() const { return busy_.load(); }
    //! Id of the request queued or running (-1 when idle).
    std::int64_t pending_id() const { return pending_id_.load(); }
    //! Label of the request queued or running ("" when idle or cancelled): the view says what
    //! is being simulated instead of letting the last body pass for it.
    std::string pending_label() const;
    //! The last failure ("" after a success).
    std::string last_error() const;

  private:
    void worker_loop();
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<SimulationRequest> queued_;
    bool quit_ = false;
    std::atomic<bool> cancel_{false};
    std::atomic<bool> busy_{false};
    std::atomic<std::int64_t> pending_id_{-1};
    std::uint64_t epoch_ = 0;  //!< under mutex_: raised by cancel()
    std::string last_error_;
    std::string pending_label_;  //!< under mutex_
    LatestSlot<SimulatedBody> results_;
    std::thread worker_;  //!< started by the first request
};

}  // namespace bhm::app::gui
