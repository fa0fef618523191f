#include "evo/evaluate/settle_rest.hpp"

#include <algorithm>
#include <cmath>

namespace bhm::evo {

namespace {

//! A creep that shrinks by less than this a window is not trusted to keep decaying.
constexpr double kTrustedDecay = 0.9;
// 0.1 s (issue 42; 0.2 s before): every held body of the corpus was at rest at the first test
// two 0.2 s windows allowed (0.4 s), and the settling was a fifth of what a held body steps.
constexpr double kWindowS = 0.1;

std::int64_t whole(double x) {
    const double n = std::round(x);
    return n >= 1.0 && std::abs(x - n) <= 1e-6 * n ? static_cast<std::int64_t>(n) : 0;
}

double distance(const Vec3& a, const Vec3& b) {
    const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return std::sqrt(x * x + y * y + z * z);
}

}  // namespace

SettleRest::SettleRest(const Experiment& experiment, const ExploitGroups& groups, bool held)
    : voxel_size_m_(experiment.voxel_size_m),
      total_mass_kg_(groups.total_mass_kg),
      tolerance_(0.1 * experiment.simulation.periodic_tolerance) {
    const double fps =
        experiment.simulation.record_fps > 0.0 ? experiment.simulation.record_fps : 30.0;
    if (!held || !experiment.simulation.end_when_periodic || !(total_mass_kg_ > 0.0)) return;
    window_ = std::max(1, static_cast<int>(std::lround(kWindowS * fps)));
    settled_sample_ = whole(experiment.simulation.settle_s * fps);
}

bool SettleRest::observe(const TrackSample& sample) {
    const std::int64_t k = observed_++;
    if (!enabled() || fired_) return false;
    recent_.push_back(sample);
    const auto W = static_cast<std::size_t>(window_);
    if (recent_.size() > 2 * W + 1) recent_.pop_front();
    // At rest with at least one sample to skip before settle_s.
    if (recent_.size() < 2 * W + 1 || k + 1 >= settled_sample_) return false;
    auto spread = [&](int t, std::size_t end) {
        const Vec3& last = recent_[end].track(t);
        double s = 0.0;
        for (std::size_t i = end - W; i < end; ++i)
            s = std::max(s, distance(recent_[i].track(t), last));
        return s;
    };
    for (int t = 0; t < TrackSample::kTracks; ++t) {
        const double to_voxels =
            t >= 6 ? 1.0 / (total_mass_kg_ * voxel_size_m_) : 1.0 / voxel_size_m_;
        const double now = spread(t, 2 * W) * to_voxels;
        const double before = spread(t, W) * to_voxels;
        if (now == 0.0) continue;
        const double r = before > 0.0 ? now / before : 1.0;
        if (r >= kTrustedDecay) return false;
        if (now * std::max(1.0, r / (1.0 - r)) > tolerance_) return false;
    }
    fired_ = true;
    return true;
}

}  // namespace bhm::evo
