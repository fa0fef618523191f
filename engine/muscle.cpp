// The muscle model's stimulus and activation (muscle.hpp; docs/physics.md, "Muscle actuation").
#include "engine/muscle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace bhm::engine::muscle {
namespace {

// a -> exp(log_slope) a + offset: what a stretch of stimulus or rest does to the activation.
struct Affine {
    double log_slope = 0.0;  //!< <= 0
    double offset = 0.0;
    double apply(double a) const { return std::exp(log_slope) * a + offset; }
};

// A state that relaxes at first order toward `on_target` with time constant `on_s` while
// stimulated and toward `off_target` with `off_s` at rest: the activation (1 with rise_s, 0 with
// decay_s) or the fatigue factor (fatigue_floor with fatigue_s, 1 with recovery_s).
struct Relaxation {
    double on_target = 1.0, on_s = 1.0, off_target = 0.0, off_s = 1.0;
};
Relaxation activation_of(const Muscle& m) {
    return {1.0, m.rise_s, 0.0, m.decay_s};
}
Relaxation fatigue_of(const Muscle& m) {
    return {std::clamp(m.fatigue_floor, 0.0, 1.0), m.fatigue_s, 1.0, m.recovery_s};
}

// Toward `target` for x seconds at time constant s: y -> target + (y - target) e^(-x / s).
// (For the activation: stimulated a -> 1 - (1 - a) e^(-x / rise), resting a -> a e^(-x / decay).)
Affine relax(double target, double s, double x) {
    return {-x / s, target * -std::expm1(-x / s)};
}
// Stimulated for x seconds.
Affine stimulated_for(const Relaxation& m, double x) {
    return relax(m.on_target, m.on_s, x);
}
// Resting for x seconds.
Affine resting_for(const Relaxation& m, double x) {
    return relax(m.off_target, m.off_s, x);
}
// first, then second.
Affine then(const Affine& first, const Affine& second) {
    return {first.log_slope + second.log_slope,
            std::exp(second.log_slope) * first.offset + second.offset};
}
// f applied n times: slope^n, offset (1 + s + ... + s^(n-1)) = offset (1 - s^n) / (1 - s).
Affine power(const Affine& f, double n) {
    if (n <= 0.0) return {};
    if (f.log_slope == 0.0) return {0.0, f.offset * n};
    return {f.log_slope * n, f.offset * (std::expm1(n * f.log_slope) / std::expm1(f.log_slope))};
}

struct Train {
    double period = 0.0;  //!< between pulse starts
    double width = 0.0;   //!< of a pulse, at most the period
    double on = 0.0;      //!< of a burst; infinity for one endless train
    double off = 0.0;     //!< rest between bursts
};

Train train_of(const Muscle& m) {
    Train t;
    t.period = 1.0 / m.frequency_hz;
    t.width = std::min(m.pulse_width_s, t.period);
    const bool bursts = m.stimulus == MuscleStimulus::PulseTrain && m.train_on_s > 0.0 &&
                        m.train_off_s > 0.0;
    t.on = bursts ? m.train_on_s : std::numeric_limits<double>::infinity();
    t.off = bursts ? m.train_off_s : 0.0;
    return t;
}

// r seconds into a pulse period: stimulated for min(r, width), then resting.
Affine into_period(const Relaxation& m, const Train& t, double r) {
    if (r <= t.width) return stimulated_for(m, r);
    return then(stimulated_for(m, t.width), resting_for(m, r - t.width));
}

// s seconds into a burst (s <= t.on): whole pulse periods, then the part of one.
Affine into_burst(const Relaxation& m, const Train& t, double s, bool* stimulated_now) {
    double n = std::floor(s / t.period);
    double r = s - n * t.period;
    if (r < 0.0) r = 0.0;
    if (r >= t.period) {  // rounding at a period's end
        n += 1.0;
        r = 0.0;
    }
    if (stimulated_now) *stimulated_now = r < t.width;
    const Affine period = into_period(m, t, t.period);
    return then(power(period, n), into_period(m, t, r));
}

}  // namespace

bool stimulated(const Muscle& m, double tau) {
    return activation(m, tau).stimulated;
}

namespace {

// A relaxing state (starting at y0 when the actuation starts) tau > 0 seconds in, and whether the
// stimulus is on then.
struct State {
    double y = 0.0;
    bool on = false;
};
State evolve(const Relaxation& r, const Train& t, double tau, double y0) {
    State out;
    double y_start = y0;  // at the start of the current burst
    double s = tau;       // time into it
    if (std::isfinite(t.on)) {
        const double burst_period = t.on + t.off;
        double k = std::floor(tau / burst_period);
        s = tau - k * burst_period;
        if (s < 0.0) s = 0.0;
        if (s >= burst_period) {
            k += 1.0;
            s = 0.0;
        }
        const Affine burst = then(into_burst(r, t, t.on, nullptr), resting_for(r, t.off));
        y_start = power(burst, k).apply(y0);
        if (s >= t.on) {
            out.y = then(into_burst(r, t, t.on, nullptr), resting_for(r, s - t.on)).apply(y_start);
            return out;
        }
    }
    out.y = into_burst(r, t, s, &out.on).apply(y_start);
    return out;
}

}  // namespace

bool fatigues(const Muscle& m) {
    return m.fatigue_s > 0.0 && m.recovery_s > 0.0;
}

Activation activation(const Muscle& m, double tau) {
    Activation out;
    if (!(tau > 0.0) || !(m.frequency_hz > 0.0) || !(m.rise_s > 0.0) || !(m.decay_s > 0.0))
        return out;
    const Train t = train_of(m);
    const State a = evolve(activation_of(m), t, tau, 0.0);
    out.a = std::clamp(a.y, 0.0, 1.0);
    out.stimulated = a.on;
    out.rate = a.on ? (1.0 - out.a) / m.rise_s : -out.a / m.decay_s;
    if (!fatigues(m)) return out;
    // The force left, f(0) = 1, on the same stretches of stimulus and rest.
    const double floor = std::clamp(m.fatigue_floor, 0.0, 1.0);
    const double f = std::clamp(evolve(fatigue_of(m), t, tau, 1.0).y, floor, 1.0);
    const double f_rate = a.on ? -(f - floor) / m.fatigue_s : (1.0 - f) / m.recovery_s;
    out.rate = out.rate * f + out.a * f_rate;
    out.a *= f;
    out.fatigue = f;
    return out;
}

double axis_strain(const Material& m, int axis) {
    const double e = m.muscle.contraction_strain;
    return axis == m.muscle.fibre_axis ? -e : m.poisson_ratio * e;
}

double largest_scale(const Material& m) {
    return 1.0 + std::max(0.0, m.poisson_ratio) * std::fabs(m.muscle.contraction_strain);
}

namespace {
std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}
bool within(double x, double lo, double hi) {
    return std::isfinite(x) && x >= lo && x <= hi;
}
}  // namespace

std::vector<Problem> material_problems(const Material& m) {
    std::vector<Problem> out;
    if (m.actuation_model != ActuationModel::Muscle) return out;
    const Muscle& u = m.muscle;
    if (m.cte_per_c != 0.0)
        out.push_back({"cte_per_c", "must be 0 under the muscle model (its strain is "
                                    "muscle.contraction_strain)"});
    if (u.fibre_axis < 0 || u.fibre_axis > 2)
        out.push_back({"muscle.fibre_axis", "must be x, y or z"});
    if (!within(u.contraction_strain, 0.0, kMaxContractionStrain))
        out.push_back({"muscle.contraction_strain",
                       "must be in [0, " + number(kMaxContractionStrain) +
                           "] (the engine's stable actuation strain)"});
    const std::pair<const char*, double> times[] = {{"muscle.rise_s", u.rise_s},
                                                    {"muscle.decay_s", u.decay_s}};
    for (const auto& [field, x] : times)
        if (!within(x, kMinTimeConstantS, kMaxTimeConstantS))
            out.push_back({field, "must be in [" + number(kMinTimeConstantS) + ", " +
                                      number(kMaxTimeConstantS) + "] s"});
    if (!within(u.frequency_hz, 0.0, kMaxStimulusFrequencyHz) || u.frequency_hz == 0.0)
        out.push_back({"muscle.frequency_hz",
                       "must be in (0, " + number(kMaxStimulusFrequencyHz) + "] Hz"});
    if (!within(u.pulse_width_s, 0.0, kMaxTimeConstantS) || u.pulse_width_s == 0.0)
        out.push_back({"muscle.pulse_width_s",
                       "must be in (0, " + number(kMaxTimeConstantS) + "] s"});
    const std::pair<const char*, double> train[] = {{"muscle.train_on_s", u.train_on_s},
                                                    {"muscle.train_off_s", u.train_off_s}};
    for (const auto& [field, x] : train) {
        if (!within(x, 0.0, kMaxTrainS))
            out.push_back({field, "must be in [0, " + number(kMaxTrainS) + "] s"});
        else if (u.stimulus == MuscleStimulus::Beating && x != 0.0)
            out.push_back({field, "must be 0 for spontaneous beating (an on/off schedule is a "
                                  "pulse train's)"});
    }
    if (u.stimulus == MuscleStimulus::PulseTrain && u.train_off_s > 0.0 && u.train_on_s == 0.0)
        out.push_back({"muscle.train_on_s", "must be > 0 when muscle.train_off_s is (the bursts "
                                            "between the rests)"});
    // Fatigue: off at fatigue_s = 0; when on, it needs a recovery and a floor in [0, 1].
    if (!within(u.fatigue_s, 0.0, kMaxFatigueS) ||
        (u.fatigue_s > 0.0 && u.fatigue_s < kMinTimeConstantS))
        out.push_back({"muscle.fatigue_s", "must be 0 (no fatigue) or in [" +
                                               number(kMinTimeConstantS) + ", " +
                                               number(kMaxFatigueS) + "] s"});
    if (!within(u.recovery_s, 0.0, kMaxFatigueS) ||
        (u.recovery_s > 0.0 && u.recovery_s < kMinTimeConstantS))
        out.push_back({"muscle.recovery_s", "must be 0 (unset) or in [" +
                                                number(kMinTimeConstantS) + ", " +
                                                number(kMaxFatigueS) + "] s"});
    else if (u.fatigue_s > 0.0 && u.recovery_s == 0.0)
        out.push_back({"muscle.recovery_s", "must be > 0 when muscle.fatigue_s is (the time "
                                            "constant of the recovery at rest)"});
    if (!within(u.fatigue_floor, 0.0, 1.0))
        out.push_back({"muscle.fatigue_floor", "must be in [0, 1] (the fraction of the force a "
                                               "long stimulus leaves)"});
    return out;
}

double stimulus_period_s(const Muscle& m) {
    const Train t = train_of(m);
    return std::isfinite(t.on) ? t.on + t.off : t.period;
}

int delay_bin(double phase_rad) {
    const double turns = phase_rad / (2.0 * std::numbers::pi);
    const double bins = std::round((turns - std::floor(turns)) * kDelayBins);
    const int bin = static_cast<int>(bins) % kDelayBins;  // a phase just under 2 pi rounds to 0
    return bin < 0 ? 0 : bin;
}

double bin_delay_s(const Muscle& m, int bin) {
    return stimulus_period_s(m) * bin / kDelayBins;
}

bool same_signal(const Muscle& a, const Muscle& b) {
    Muscle x = a, y = b;
    x.fibre_axis = y.fibre_axis = 0;
    x.contraction_strain = y.contraction_strain = 0.0;
    if (x.stimulus == MuscleStimulus::Beating) x.train_on_s = x.train_off_s = 0.0;
    if (y.stimulus == MuscleStimulus::Beating) y.train_on_s = y.train_off_s = 0.0;
    // Without fatigue its other two fields do nothing.
    for (Muscle* u : {&x, &y})
        if (!fatigues(*u)) u->fatigue_s = u->recovery_s = u->fatigue_floor = 0.0;
    return x == y;
}

std::vector<Problem> palette_problems(const std::vector<Material>& materials,
                                      const std::vector<bool>* used) {
    std::vector<Problem> out;
    int sine = -1;
    std::vector<int> signals;  // the first material of each distinct muscle signal
    auto name = [](std::size_t k) { return "materials[" + std::to_string(k) + "]"; };
    for (std::size_t k = 0; k < materials.size(); ++k) {
        if (used && (k >= used->size() || !(*used)[k])) continue;
        const Material& m = materials[k];
        if (!is_active(m)) continue;
        if (m.actuation_model == ActuationModel::Sine) {
            if (sine < 0) sine = static_cast<int>(k);
            continue;
        }
        bool known = false;
        for (int s : signals)
            known = known || same_signal(materials[static_cast<std::size_t>(s)].muscle, m.muscle);
        if (known) continue;
        signals.push_back(static_cast<int>(k));
        if (static_cast<int>(signals.size()) > kMaxSignals)
            out.push_back({name(k) + ".muscle",
                           "is a third distinct muscle signal (stimulus and time constants) in "
                           "one body; the engine drives at most " +
                               std::to_string(kMaxSignals) +
                               ": give it the stimulus and time constants of " +
                               name(static_cast<std::size_t>(signals[0])) + " or " +
                               name(static_cast<std::size_t>(signals[1]))});
    }
    if (sine >= 0 && !signals.empty())
        out.push_back({name(static_cast<std::size_t>(signals[0])) + ".actuation_model",
                       "is muscle but " + name(static_cast<std::size_t>(sine)) +
                           " is active under the sine model: one body is driven by one model "
                           "(make the other passive or give it the same model)"});
    return out;
}

}  // namespace bhm::engine::muscle
