#pragma once
// Evaluations that end when the motion repeats (issue 23; docs/experiment-format.md, "simulation").
//
// Once the body has settled (t >= settle_s) every track the measures use (evo/evaluate/tracks.hpp:
// centre of mass, bend line ends, descriptor tip, exploit centroids and mass moments, all linear
// in the voxel positions) is compared period by period, sample by sample (S = record_fps x the
// drive's period, drive_period_s: the sine's 1 / frequency_hz, or a muscle's stimulus period). A
// held body (every connected part holds a fixed voxel) cannot drift: its motion tends to one
// periodic orbit, and what separates it from that orbit is a transient that decays. A free body (a
// walker) repeats plus a constant drift D per period.
// - Held: a_p = max_j |x_p[j] - x_{p-1}[j]| over the last period, a_{p-1} the same one period
//   earlier, r = a_p / a_{p-1} their ratio. A transient decaying by r a period has
//   a_p r / (1 - r) left to go, so the evaluation stops when
//     a_p max(1, r / (1 - r)) <= periodic_tolerance,  r < 0.9
//   (the transient in the last period, which the rest of the run repeats with D = 0), or, with M
//   periods left and no decay assumed, a_p (M + 1) <= periodic_tolerance. The r trusted is the
//   largest of (a_p / a_{p-L})^(1/L), L = 1..3 as far as the kept samples reach, over the last S/2
//   comparisons: a_p jitters with the window's phase, and one lucky pair of periods made a slow
//   decay (r ~ 0.9) look like r = 0.6 (paper-exp3/random-05 ended with 1.6x the allowed error).
// - Free: the drift's change residual = max_j |d_j - D| (d_j = x_p[j] - x_{p-1}[j], D the last
//   whole period's drift), with M periods left. A change kept up over the periods left adds up to
//   residual (1 + 2 + ... + (M + 1)); one that decays by r a period to residual (1 + M r / (1 -
//   r)). The evaluation stops when either bound is within the tolerance (the second only for r <
//   0.9), and the rest of the run is the last period plus q D.
// Tracks in voxel lengths (mass moments as the centre-of-mass shift they make); the bend
// direction's terms as an angle against the tolerance x (1 degree + its largest angle so far).
// The samples the full run would still have taken are extrapolated,
//   x[k + q S - i] = x[k - i] + q D,  0 <= i < S,
// at the times the full run would have sampled (each due time, evo/evaluate/tracks.hpp), and
// fed to the same trackers, so every measure (final, max, YZ, bend angle, exploit measures,
// descriptor) is what the full run would have measured, within the tolerance.
// It applies only when a period and the whole run are each a whole number of samples; otherwise
// (and when switched off) the evaluation runs the full time.
#include <array>
#include <deque>
#include <functional>
#include <vector>

#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::engine {
class Model;
}

namespace bhm::evo {

//! The period of the experiment's drive (s): 1 / actuation.frequency_hz under the sine model; under
//! the muscle model its stimulus's (a burst and its rest, or one pulse period of an endless train
//! or of beating), the same for every active muscle material, else 0 (no common period is sought:
//! the run goes the full time). 0 when nothing drives the body periodically.
double drive_period_s(const Experiment& experiment);

class PeriodicEnd {
  public:
    //! dt_s: the model's step; groups: the sampler's (their total mass scales the moments);
    //! held: the body cannot drift (every_part_held), so its motion tends to a pure repeat.
    PeriodicEnd(const Experiment& experiment, double dt_s, const ExploitGroups& groups,
                bool held = false);
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
    double due_time(std::int64_t k) const;  //!< the time sample k of the full run is due
    double settle_s_, voxel_size_m_, total_mass_kg_, tolerance_;
    double dt_s_, sample_period_s_, total_s_;
    int samples_per_period_ = 0;
    std::int64_t last_sample_ = 0;  //!< index of the full run's last sample
    std::int64_t observed_ = 0;     //!< samples observed so far
    std::int64_t first_settled_ = -1;
    bool can_bend_ = false;
    bool held_ = false;
    TrackSample reference_;  //!< the first settled sample
    //! The last 5S + 1 settled samples (all a comparison and the extrapolation read): memory stays
    //! bounded however long the evaluation.
    std::deque<TrackSample> settled_;
    double residual_voxels_ = 0.0;
    //! Each track's (and the bend direction's, last) decay ratios of the last decay_window_
    //! comparisons, a held body's trusted ratio being their largest.
    std::array<std::deque<double>, TrackSample::kTracks + 1> recent_ratios_;
    int decay_window_ = 1;
};

//! True when every connected part of the body (voxels joined through shared faces) holds a fixed
//! voxel: such a body cannot drift.
bool every_part_held(const engine::Model& model);

//! The accuracy gate of an early end (issue 23): the largest, over the fitness measures, of
//! |early - full| / max(0.5 % of |full|, 1e-3) (voxel lengths; degrees for the bend angle). At
//! most 1 passes.
double periodic_end_error(const FitnessReport& early, const FitnessReport& full);

}  // namespace bhm::evo
