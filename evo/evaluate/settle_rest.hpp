#pragma once
// Settling that ends once the body is at rest (issue 23; docs/experiment-format.md, "simulation").
//
// Before actuation starts (t < settle_s) a body only sags under gravity and comes to rest; the
// rest of its settling changes nothing. Every track the measures use (evo/evaluate/tracks.hpp) is
// watched over windows of W = 0.1 s of samples: s_w = max_i |x[i] - x[e]| over the window ending at
// sample e (voxel lengths; mass moments as the centre-of-mass shift they make), s_{w-1} the same
// one window earlier, r = s_w / s_{w-1}. A creep that falls by r a window still has s_w r / (1 - r)
// to go, so the body is at rest when for every track
//   s_w max(1, r / (1 - r)) <= periodic_tolerance / 10,   r < 0.9
// (a tenth: what is left of the settling adds to the early end's own error). The evaluation then
// lets the rest of the settling pass without integrating (engine::World::rest_until) and feeds the
// samples the full run would have taken meanwhile as copies of the last one.
// The criterion is on positions, not kinetic energy: a kinetic energy vanishes at every turning
// point of a slow swing, a window's spread does not (a swing of period T <= 0.5 s moves by at
// least 0.69 of its amplitude inside 0.1 s; a slower one of amplitude A still spreads by at least
// A (1 - cos(pi W / T)), 0.05 A at T = 1 s, against a tenth of the tolerance).
// Only held bodies (every_part_held) end their settling early: a free body's later walk can be
// chaotic, and a state a tolerance away from the full run's may then end somewhere else.
// It applies with end_when_periodic, when settle_s is a whole number of samples, and never on the
// last sample before settle_s.
#include <cstdint>
#include <deque>

#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

class SettleRest {
  public:
    //! groups: the sampler's (their total mass scales the moments); held: every_part_held.
    SettleRest(const Experiment& experiment, const ExploitGroups& groups, bool held);
    bool enabled() const { return settled_sample_ > 0; }
    //! Adds the next sample (every scheduled one, in order, from t = 0). True once, at the sample
    //! where the body is at rest with samples still to go before settle_s.
    bool observe(const TrackSample& sample);
    //! The index of the first sample at or past settle_s (where simulation resumes).
    std::int64_t settled_sample() const { return settled_sample_; }
    //! The index of the next sample to observe.
    std::int64_t next_sample() const { return observed_; }

  private:
    double voxel_size_m_, total_mass_kg_, tolerance_;
    int window_ = 0;                   //!< samples in a window
    std::int64_t settled_sample_ = 0;  //!< 0: off
    std::int64_t observed_ = 0;
    bool fired_ = false;
    std::deque<TrackSample> recent_;  //!< the last 2W + 1 samples
};

}  // namespace bhm::evo
