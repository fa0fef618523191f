#pragma once
// The behaviour descriptor of a simulation, for novelty search (Lehman & Stanley 2011;
// docs/evolution.md, "Novelty search"): where the body went, not how well it scored.
//
// At kBehaviourSamples fixed times of the evaluation window, t_k = settle_s + k / kBehaviourSamples
// * evaluate_s (k = 1..kBehaviourSamples; the last one is the end of the simulation), the
// displacement from the settled state (the first sample at or after settle_s, as for the fitness)
// of two points, in voxel lengths:
//   - the centre of mass (x, y, z), and
//   - the tip: the centroid of the far-end layer of the bend line (bend_layers(), the point the
//     bend angle follows); the centroid of every voxel when the body has a single layer.
// Sample k is the first recorded sample at or after t_k (samples come at simulation.record_fps).
// The descriptor is [com_1, tip_1, com_2, tip_2, ...]: kBehaviourLength numbers. It is empty for a
// simulation that diverged (or never reached the end), and in results written before it existed.
#include <array>
#include <memory>
#include <vector>

#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::engine {
class World;
}

namespace bhm::evo {

inline constexpr int kBehaviourSamples = 4;
inline constexpr int kBehaviourPointValues = 6;  //!< centre of mass xyz, then tip xyz
inline constexpr int kBehaviourLength = kBehaviourSamples * kBehaviourPointValues;

//! The descriptor from a trajectory of (t, centre of mass, tip) samples in metres, in time order:
//! the world-free core of BehaviourTracker, so a known trajectory can be checked by hand.
class BehaviourRecorder {
  public:
    BehaviourRecorder(double settle_s, double evaluate_s, double voxel_size_m);
    void observe(double t_s, const std::array<double, 3>& com_m,
                 const std::array<double, 3>& tip_m);
    //! kBehaviourLength values once every sample time was reached, else empty.
    std::vector<double> descriptor() const;

  private:
    double settle_s_, evaluate_s_, voxel_size_m_;
    bool has_reference_ = false;
    std::array<double, 3> com0_{}, tip0_{};
    int filled_ = 0;  //!< sample times reached so far
    std::vector<double> values_;
};

//! Follows a simulation (observe() at every recorded sample, like MeasureTracker).
class BehaviourTracker {
  public:
    BehaviourTracker(const Experiment& experiment, const engine::World& world);
    //! Samples the world itself (a TrackSampler of its own).
    void observe(const engine::World& world);
    //! A sample of a TrackSampler of the same world (simulated or extrapolated).
    void observe(const TrackSample& sample);
    std::vector<double> descriptor() const { return recorder_.descriptor(); }

  private:
    BehaviourRecorder recorder_;
    std::unique_ptr<TrackSampler> own_sampler_;
};

}  // namespace bhm::evo
