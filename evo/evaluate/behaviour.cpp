#include "evo/evaluate/behaviour.hpp"

#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"

namespace bhm::evo {

namespace {

// The same tolerance as MeasureTracker: a sample lands on or just after its nominal time.
constexpr double kTimeTolerance_s = 1e-9;

}  // namespace

BehaviourRecorder::BehaviourRecorder(double settle_s, double evaluate_s, double voxel_size_m)
    : settle_s_(settle_s), evaluate_s_(evaluate_s), voxel_size_m_(voxel_size_m) {
    values_.reserve(kBehaviourLength);
}

void BehaviourRecorder::observe(double t_s, const std::array<double, 3>& com_m,
                                const std::array<double, 3>& tip_m) {
    if (t_s < settle_s_ - kTimeTolerance_s) return;
    if (!has_reference_) {
        has_reference_ = true;
        com0_ = com_m;
        tip0_ = tip_m;
    }
    // One sample may stand for several sample times when samples are sparser than they are.
    while (filled_ < kBehaviourSamples) {
        const double due = settle_s_ + evaluate_s_ * (filled_ + 1) / kBehaviourSamples;
        if (t_s < due - kTimeTolerance_s) break;
        for (std::size_t k = 0; k < 3; ++k)
            values_.push_back((com_m[k] - com0_[k]) / voxel_size_m_);
        for (std::size_t k = 0; k < 3; ++k)
            values_.push_back((tip_m[k] - tip0_[k]) / voxel_size_m_);
        ++filled_;
    }
}

std::vector<double> BehaviourRecorder::descriptor() const {
    return filled_ == kBehaviourSamples ? values_ : std::vector<double>{};
}

BehaviourTracker::BehaviourTracker(const Experiment& experiment, const engine::World& world)
    : recorder_(experiment.simulation.settle_s, experiment.simulation.evaluate_s,
                experiment.voxel_size_m),
      own_sampler_(std::make_unique<TrackSampler>(experiment, world)) {}

void BehaviourTracker::observe(const engine::World& world) {
    observe(own_sampler_->sample(world));
}

void BehaviourTracker::observe(const TrackSample& sample) {
    recorder_.observe(sample.t_s, sample.com_m, sample.behaviour_tip_m);
}

}  // namespace bhm::evo
