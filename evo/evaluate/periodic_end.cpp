#include "evo/evaluate/periodic_end.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/muscle.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace bhm::evo {

namespace {

double norm(const Vec3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

Vec3 minus(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

//! n when x is within a millionth of the whole number n >= 1, else 0.
std::int64_t whole(double x) {
    const double n = std::round(x);
    return n >= 1.0 && std::abs(x - n) <= 1e-6 * n ? static_cast<std::int64_t>(n) : 0;
}

double angle_deg(const Vec3& a, const Vec3& b) {
    const double lengths = norm(a) * norm(b);
    if (!(lengths > 0.0)) return 0.0;
    const double cosine = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / lengths;
    return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

double drive_period_s(const Experiment& experiment) {
    double muscle_period = 0.0;
    bool muscles = false;
    for (const auto& entry : experiment.materials) {
        const engine::Material& m = entry.physics;
        if (m.actuation_model != engine::ActuationModel::Muscle || !engine::is_active(m)) continue;
        const engine::Muscle& u = m.muscle;
        if (!(u.frequency_hz > 0.0)) return 0.0;
        // A fatiguing muscle's force fades over the stimulus and never repeats (engine/muscle.hpp).
        if (engine::muscle::fatigues(u)) return 0.0;
        // The stimulus restarts its pulses at each burst (engine/muscle.hpp), so a scheduled
        // train repeats with its burst, an endless one with its pulses; a controller's delay
        // (less than a period, issue 44) shifts a voxel's train without changing its period.
        const double period = engine::muscle::stimulus_period_s(u);
        if (muscles && std::abs(period - muscle_period) > 1e-9 * period) return 0.0;
        muscles = true;
        muscle_period = period;
    }
    if (muscles) return muscle_period;
    return experiment.actuation.frequency_hz > 0.0 ? 1.0 / experiment.actuation.frequency_hz : 0.0;
}

PeriodicEnd::PeriodicEnd(const Experiment& experiment, double dt_s, const ExploitGroups& groups,
                         bool held)
    : settle_s_(experiment.simulation.settle_s),
      voxel_size_m_(experiment.voxel_size_m),
      total_mass_kg_(groups.total_mass_kg),
      tolerance_(experiment.simulation.periodic_tolerance),
      dt_s_(dt_s),
      total_s_(evaluation_seconds(experiment)),
      held_(held) {
    const double fps =
        experiment.simulation.record_fps > 0.0 ? experiment.simulation.record_fps : 30.0;
    sample_period_s_ = 1.0 / fps;
    const double period_s = drive_period_s(experiment);
    if (!experiment.simulation.end_when_periodic || !(period_s > 0.0)) return;
    if (!(total_mass_kg_ > 0.0) || !(sample_period_s_ > dt_s_)) return;
    const std::int64_t per_period = whole(fps * period_s);
    last_sample_ = whole(total_s_ * fps);
    if (per_period < 2 || last_sample_ == 0) return;
    samples_per_period_ = static_cast<int>(per_period);
    decay_window_ = std::max(1, samples_per_period_ / 2);
}

double PeriodicEnd::due_time(std::int64_t k) const {
    return sample_due_s(k, sample_period_s_, total_s_, dt_s_);
}

namespace {

//! A transient that shrinks by less than this a period is not trusted to keep decaying.
constexpr double kTrustedDecay = 0.9;
//! The longest baseline, in periods, over which a decay ratio is measured.
constexpr int kDecayBaselinePeriods = 3;

//! What a transient that decays by r a period still has to go, as a multiple of its last
//! period's change (r / (1 - r), at least 1); infinite when it is not trusted to decay.
double transient_left(double r) {
    if (!(r < kTrustedDecay)) return std::numeric_limits<double>::infinity();
    return std::max(1.0, r / (1.0 - r));
}

//! The decay ratio of one comparison: now / before (0 when nothing changes now, infinite when
//! something changes now after nothing did).
double decay_ratio(double now, double before) {
    if (now == 0.0) return 0.0;
    return before > 0.0 ? now / before : std::numeric_limits<double>::infinity();
}

//! Period-to-period comparisons of one track x(i) (any units) over the window ending at sample e:
//! the largest change a = max_j |x[e - S + j] - x[e - 2S + j]| (0 <= j <= S) and the drift's
//! change residual = max_j |x[e - S + j] - x[e - 2S + j] - (x[e] - x[e - S])| (0 <= j < S).
struct PeriodChange {
    double change = 0.0, residual = 0.0;
};

template <class Track>
PeriodChange period_change(const Track& x, std::int64_t e, int S) {
    PeriodChange c;
    const Vec3 drift = minus(x(e), x(e - S));
    for (int j = 0; j <= S; ++j) {
        const Vec3 d = minus(x(e - S + j), x(e - 2 * S + j));
        c.change = std::max(c.change, norm(d));
        if (j < S) c.residual = std::max(c.residual, norm(minus(d, drift)));
    }
    return c;
}

}  // namespace

bool PeriodicEnd::observe(const TrackSample& sample) {
    const std::int64_t k = observed_++;
    if (!enabled() || !settled(sample.t_s, settle_s_)) return false;
    if (first_settled_ < 0) {
        first_settled_ = k;
        reference_ = sample;
        can_bend_ = norm(minus(sample.bend_tip_m, sample.bend_base_m)) > 0.0;
    }
    settled_.push_back(sample);
    const int S = samples_per_period_;
    if (settled_.size() > static_cast<std::size_t>((kDecayBaselinePeriods + 2) * S + 1))
        settled_.pop_front();
    const auto n = static_cast<std::int64_t>(settled_.size());
    if (n < 2 * S + 1 || k >= last_sample_) return false;
    const bool have_before = n >= 3 * S + 1;  // the comparison one period earlier
    const std::int64_t periods_left = (last_sample_ - k + S - 1) / S;
    const double M = static_cast<double>(periods_left);
    // A drift change kept up over the periods left adds up to residual (1 + 2 + ... + (M + 1)).
    const double kept_up = 0.5 * (M + 1.0) * (M + 2.0);
    auto at = [&](std::int64_t i) -> const TrackSample& {
        return settled_[static_cast<std::size_t>(i)];
    };
    // One track's verdict, its comparisons scaled by `scale` into the units of `allowed`.
    auto within = [&](int index, const auto& x, double scale, double allowed, double* worst) {
        const PeriodChange now = period_change(x, n - 1, S);
        const PeriodChange before = have_before ? period_change(x, n - 1 - S, S) : PeriodChange{};
        if (worst) *worst = std::max(*worst, (held_ ? now.change : now.residual) * scale);
        if (held_) {
            // The decay ratio trusted is the largest of the last few comparisons, each the
            // geometric mean over the longest baseline the kept samples allow (up to 3 periods):
            // a period's largest change moves with the window's phase, and a slow decay under a
            // jittering one can look fast from one pair of periods (paper-exp3/random-05).
            auto& ratios = recent_ratios_[static_cast<std::size_t>(index)];
            if (have_before) {
                double r = decay_ratio(now.change, before.change);
                for (int L = 2; L <= kDecayBaselinePeriods && n >= (L + 2) * S + 1; ++L) {
                    const double earlier = period_change(x, n - 1 - L * S, S).change;
                    r = std::max(r, std::pow(decay_ratio(now.change, earlier), 1.0 / L));
                }
                ratios.push_back(r);
                if (ratios.size() > static_cast<std::size_t>(decay_window_)) ratios.pop_front();
            }
            // Kept up unchanged over the periods left (no decay assumed), or decaying.
            const double change = now.change * scale;
            if (change * (M + 1.0) <= allowed) return true;
            if (!have_before || change == 0.0) return change == 0.0;
            return change * transient_left(*std::max_element(ratios.begin(), ratios.end())) <=
                   allowed;
        }
        return now.residual * scale * kept_up <= allowed;
    };
    // Every track is compared at every sample (no early out), so each one's recent decay ratios
    // are consecutive.
    bool repeats = true;
    double worst = 0.0;
    for (int t = 0; t < TrackSample::kTracks; ++t) {
        // Mass moments (kg m) read as the centre-of-mass shift they make.
        const double to_voxels =
            t >= 6 ? 1.0 / (total_mass_kg_ * voxel_size_m_) : 1.0 / voxel_size_m_;
        auto track = [&](std::int64_t i) { return at(i).track(t); };
        // Absolute (voxel lengths): a measure may be a small projection of a long track.
        repeats = within(t, track, to_voxels, tolerance_, &worst) && repeats;
    }
    if (can_bend_) {
        // The bend angle follows the direction base -> tip: its changes as an angle (radians per
        // unit length of the line), against 1 degree + the largest angle of the last period.
        const Vec3 dir0 = minus(reference_.bend_tip_m, reference_.bend_base_m);
        const TrackSample& last = at(n - 1);
        const double length = norm(minus(last.bend_tip_m, last.bend_base_m));
        auto dir = [&](std::int64_t i) { return minus(at(i).bend_tip_m, at(i).bend_base_m); };
        double largest_deg = 0.0;
        for (int j = 0; j <= S; ++j)
            largest_deg = std::max(largest_deg, angle_deg(dir0, dir(n - 1 - S + j)));
        const double to_deg = length > 0.0 ? 180.0 / std::numbers::pi / length : 0.0;
        repeats = within(TrackSample::kTracks, dir, to_deg, tolerance_ * (1.0 + largest_deg),
                         nullptr) &&
                  repeats;
    }
    residual_voxels_ = worst;
    return repeats;
}

void PeriodicEnd::extrapolate(const std::function<void(const TrackSample&)>& observe) const {
    const int S = samples_per_period_;
    const auto n = static_cast<std::int64_t>(settled_.size());
    if (!enabled() || n < S + 1) return;
    const std::int64_t last = observed_ - 1;  // index of the last observed sample
    const TrackSample& now = settled_.back();
    const TrackSample& before = settled_[static_cast<std::size_t>(n - 1 - S)];
    for (std::int64_t k = last + 1; k <= last_sample_; ++k) {
        const std::int64_t q = (k - last + S - 1) / S;  // periods ahead
        const std::int64_t source = n - 1 - (last - (k - q * S));
        TrackSample s = settled_[static_cast<std::size_t>(source)];
        s.t_s = due_time(k);
        for (int t = 0; t < TrackSample::kTracks && !held_; ++t)
            for (std::size_t c = 0; c < 3; ++c)
                s.track(t)[c] += static_cast<double>(q) * (now.track(t)[c] - before.track(t)[c]);
        observe(s);
    }
}

bool every_part_held(const engine::Model& model) {
    // Union-find over face neighbours (the links of the lattice join exactly those).
    const int n = model.voxel_count();
    std::vector<int> parent(static_cast<std::size_t>(n));
    for (int v = 0; v < n; ++v)
        parent[static_cast<std::size_t>(v)] = v;
    auto root = [&](int v) {
        while (parent[static_cast<std::size_t>(v)] != v) {
            auto& p = parent[static_cast<std::size_t>(v)];
            p = parent[static_cast<std::size_t>(p)];
            v = p;
        }
        return v;
    };
    std::map<std::array<int, 3>, int> at;
    for (int v = 0; v < n; ++v)
        at.emplace(model.voxel_coords(v), v);
    for (int v = 0; v < n; ++v) {
        const auto c = model.voxel_coords(v);
        for (int axis = 0; axis < 3; ++axis) {
            auto next = c;
            ++next[static_cast<std::size_t>(axis)];
            const auto it = at.find(next);
            if (it != at.end()) parent[static_cast<std::size_t>(root(v))] = root(it->second);
        }
    }
    std::vector<char> held(static_cast<std::size_t>(n), 0);
    for (int v = 0; v < n; ++v)
        if (model.voxel_fixed(v)) held[static_cast<std::size_t>(root(v))] = 1;
    for (int v = 0; v < n; ++v)
        if (!held[static_cast<std::size_t>(root(v))]) return false;
    return n > 0;
}

double periodic_end_error(const FitnessReport& early, const FitnessReport& full) {
    double worst = 0.0;
    for (std::size_t m = 0; m < early.measures.size(); ++m) {
        const double allowed = std::max(0.005 * std::abs(full.measures[m]), 1e-3);
        worst = std::max(worst, std::abs(early.measures[m] - full.measures[m]) / allowed);
    }
    return worst;
}

}  // namespace bhm::evo
