#pragma once
// Evaluations that end when the motion repeats (issue 23; docs/experiment-format.md, "simulation").
//
// Once the body has settled (t >= settle_s) every track the measures use (evo/evaluate/tracks.hpp:
// centre of mass, bend line ends, descriptor tip, exploit centroids and mass moments, all linear
// in the voxel positions) is compared over the last two actuation periods, sample by sample
// (S = record_fps / frequency_hz samples a period):
//   d_j = x[k - S + j] - x[k - 2S + j],  D = x[k] - x[k - S],  residual = max_j |d_j - D|
// A held body repeats (D = 0), a walker repeats plus a constant drift D. With M periods still to
// run, the evaluation stops when, for every track,
//   residual * (M + 1) <= periodic_tolerance * (1 + |x[k] + M D - x_settled|)      (voxel lengths)
// and the bend direction's residual, as an angle, likewise against 1 degree + its largest angle
// so far. The samples the full run would still have taken are then extrapolated,
//   x[k + q S - i] = x[k - i] + q D,  0 <= i < S,
// at the times the full run would have sampled (the first step at or after each due time), and
// fed to the same trackers, so every measure (final, max, YZ, bend angle, exploit measures,
// descriptor) is what the full run would have measured, within the tolerance.
// It applies only when a period and the whole run are each a whole number of samples; otherwise
// (and when switched off) the evaluation runs the full time.
#include <deque>
#include <functional>
#include <vector>

#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

class PeriodicEnd {
  public:
    //! dt_s: the model's step; groups: the sampler's (their total mass scales the moments).
    PeriodicEnd(const Experiment& experiment, double dt_s, const ExploitGroups& groups);
    //! On for this experiment (switched on and a whole number of samples per period and run).
    bool enabled() const { return samples_per_period_ > 0; }
    int samples_per_period() const { return samples_per_period_; }
    //! Adds the next simulated sample (every scheduled one, in order). True when the tracks
    //! repeat closely enough that the rest of the run can be extrapolated.
    bool observe(const TrackSample& sample);
    //! Hands each sample the full run would take after the last observed one, extrapolated, to
    //! observe (one at a time: a long run's remainder is never held in memory).
    void extrapolate(const std::function<void(const TrackSample&)>& observe) const;
    //! The residual of the last comparison (voxel lengths), 0 before any.
    double residual_voxels() const { return residual_voxels_; }

  private:
    double due_time(std::int64_t k) const;  //!< the time the full run observes sample k
    double settle_s_, voxel_size_m_, total_mass_kg_, tolerance_;
    double dt_s_, sample_period_s_, total_s_;
    int samples_per_period_ = 0;
    std::int64_t last_sample_ = 0;  //!< index of the full run's last sample
    std::int64_t observed_ = 0;     //!< samples observed so far
    std::int64_t first_settled_ = -1;
    bool can_bend_ = false;
    TrackSample reference_;  //!< the first settled sample
    //! The last 2S + 1 settled samples (all a comparison and the extrapolation read): memory stays
    //! bounded however long the evaluation.
    std::deque<TrackSample> settled_;
    double residual_voxels_ = 0.0;
};

//! The accuracy gate of an early end (issue 23): the largest, over the fitness measures, of
//! |early - full| / max(0.5 % of |full|, 1e-3) (voxel lengths; degrees for the bend angle). At
//! most 1 passes.
double periodic_end_error(const FitnessReport& early, const FitnessReport& full);

}  // namespace bhm::evo
