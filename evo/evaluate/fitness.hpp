#pragma once
// Evaluation of one individual: simulate the framed body for settle_s + evaluate_s and measure,
// from the end of settling (t = settle_s), every fitness measure of the experiment format:
//  - com_final_3d / com_final_yz: displacement of the centre of mass at the end (3D, or its
//    projection on the YZ plane, paper section 4.3), in voxel lengths;
//  - com_max_3d / com_max_yz: the largest such displacement over the window;
//  - bend_angle_deg: the largest angle over the window between the settled and the current
//    direction of the line from the centroid of the base voxels to the centroid of the far-end
//    voxels. Base = voxels in the workspace layer of the first fixed face (x- when no face is
//    fixed; the nearest filled layer when that one is empty); far end = the filled layer farthest
//    from it. A body with a single layer along that axis scores 0.
// All five are computed every time (they are cheap), so a change of measure between generations
// needs no new simulation. Samples are taken at simulation.record_fps.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::engine {
class World;
}

namespace bhm::evo {

//! Fitness given to a diverged simulation: every measure is >= 0, so -1 ranks below any real
//! result while staying a finite number for CSV and JSON.
inline constexpr double kDivergedFitness = -1.0;
//! Fitness of a member that breaks a constraint (after a change of rules between generations, or a
//! reject_* exploit constraint): below kDivergedFitness, so AFPO drops it before any real result.
inline constexpr double kInvalidFitness = -2.0;
inline constexpr int kMeasureCount = static_cast<int>(kFitnessNames.size());

struct FitnessReport {
    double fitness = 0.0;  //!< the experiment's measure (kDivergedFitness if diverged)
    std::array<double, kMeasureCount> measures{};  //!< indexed by FitnessMeasure
    bool diverged = false;
    std::string divergence_reason;
    double simulated_s = 0.0;  //!< simulated time reached (where the simulation stopped)
    //! The simulation stopped before the requested end because the motion repeated, and the rest
    //! was extrapolated (evo/evaluate/periodic_end.hpp).
    bool ended_early = false;
    //! The period-to-period residual of the last comparison (voxel lengths; 0 when none was made).
    double periodic_residual = 0.0;
    std::int64_t steps = 0;
    double sim_wall_s = 0.0;  //!< wall-clock time of the simulation (not deterministic)
    ExploitReport exploits;   //!< escaped / detached_motion / tentacle with their measures
    //! Where the body went (evo/evaluate/behaviour.hpp): kBehaviourLength values in voxel lengths, empty
    //! when diverged or read from a result written before descriptors existed.
    std::vector<double> behaviour;
};

//! The fitness of a report under a measure (kDivergedFitness when it diverged).
double fitness_under(const FitnessReport& report, FitnessMeasure measure);
//! The fitness under the whole rules: kInvalidFitness when a reject_* constraint catches one of
//! the report's exploit flags, else fitness_under(report, rules.measure).
double fitness_under(const FitnessReport& report, const Fitness& rules);

//! Thrown out of evaluate_body when the cancel flag is raised mid-simulation.
struct EvaluationCancelled : std::runtime_error {
    EvaluationCancelled() : std::runtime_error("evaluation cancelled") {}
};

//! Steps between two looks at an EvaluationControl: a few milliseconds even for large bodies, and
//! independent of record_fps (a sample can span the whole simulation).
inline constexpr int kControlCheckSteps = 64;

//! Controls of a running evaluation from other threads (or a signal handler); both optional.
//! Neither changes the result: the world is stepped exactly as without them.
struct EvaluationControl {
    const std::atomic<bool>* cancel = nullptr;  //!< raised: throw EvaluationCancelled
    const std::atomic<bool>* pause = nullptr;   //!< raised: sleep until lowered (or cancelled)
};

//! Simulates the framed body (apply_frame_and_overrides output) under the experiment. Random
//! actuation phases are seeded from experiment.evolution.seed, so the result is a pure function
//! of (experiment, body). Looks at the controls every kControlCheckSteps steps and at every
//! sample: a raised cancel flag throws EvaluationCancelled within milliseconds.
FitnessReport evaluate_body(const Experiment& experiment, const Body& framed_body,
                            const EvaluationControl& control);
FitnessReport evaluate_body(const Experiment& experiment, const Body& framed_body,
                            const std::atomic<bool>* cancel = nullptr);

//! The observer that computes the measures from the samples; public for tests and the studio.
class MeasureTracker {
  public:
    MeasureTracker(const Experiment& experiment, const engine::World& world);
    //! Samples the world itself (a TrackSampler of its own).
    void observe(const engine::World& world);
    //! A sample of a TrackSampler of the same world (simulated or extrapolated).
    void observe(const TrackSample& sample);
    //! The measures so far (all zero until t reaches settle_s).
    std::array<double, kMeasureCount> measures() const { return measures_; }
    bool reference_taken() const { return has_reference_; }

  private:
    double settle_s_;
    double voxel_size_m_;
    bool can_bend_ = false;
    std::unique_ptr<TrackSampler> own_sampler_;
    bool has_reference_ = false;
    std::array<double, 3> com0_{}, direction0_{};
    std::array<double, kMeasureCount> measures_{};
};

}  // namespace bhm::evo
