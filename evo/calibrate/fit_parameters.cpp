#include "evo/calibrate/fit_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "engine/muscle.hpp"

namespace bhm::evo {

namespace {

// A factor of 5 either way: the brief's "calibrate what the dish shows", not a global search.
const double kLogBound = std::log(5.0);

struct Name {
    const char* name;
    FitKind kind;
    bool per_material;
};
constexpr Name kNames[] = {
    {"E", FitKind::YoungsModulus, true},
    {"youngs_modulus", FitKind::YoungsModulus, true},
    {"density", FitKind::Density, true},
    {"cte", FitKind::Cte, false},
    {"amplitude", FitKind::Amplitude, false},
    {"frequency", FitKind::Frequency, false},
    {"phase_lag", FitKind::PhaseLag, false},
    {"bond_damping", FitKind::BondDamping, false},
    {"global_damping", FitKind::GlobalDamping, false},
    {"friction", FitKind::Friction, false},
    {"rise_s", FitKind::MuscleRise, true},
    {"decay_s", FitKind::MuscleDecay, true},
    {"contraction_strain", FitKind::MuscleStrain, true},
};

bool muscle_kind(FitKind k) {
    return k == FitKind::MuscleRise || k == FitKind::MuscleDecay || k == FitKind::MuscleStrain;
}
// The sine model's drive: nothing of it reaches a muscle voxel (engine/muscle.hpp).
bool sine_kind(FitKind k) {
    return k == FitKind::Cte || k == FitKind::Amplitude || k == FitKind::Frequency ||
           k == FitKind::PhaseLag;
}
bool uses_muscle(const engine::Material& m) {
    return m.actuation_model == engine::ActuationModel::Muscle;
}

// The muscle field a muscle parameter scales, and its name in the experiment file.
template <class M>
auto& muscle_field(M& m, FitKind k) {
    return k == FitKind::MuscleRise    ? m.muscle.rise_s
           : k == FitKind::MuscleDecay ? m.muscle.decay_s
                                       : m.muscle.contraction_strain;
}
const char* muscle_field_name(FitKind k) {
    return k == FitKind::MuscleRise    ? "muscle.rise_s"
           : k == FitKind::MuscleDecay ? "muscle.decay_s"
                                       : "muscle.contraction_strain";
}
const char* sine_field_name(FitKind k) {
    switch (k) {
        case FitKind::Cte:
            return "cte_per_c";
        case FitKind::Amplitude:
            return "actuation.temperature_amplitude_c";
        case FitKind::Frequency:
            return "actuation.frequency_hz (a muscle's is muscle.frequency_hz)";
        default:
            return "actuation.phase_offset_rad";
    }
}

// Whether parameter p changes material k: its own material, or every one (a muscle parameter:
// every muscle material).
bool changes(const FitParameter& p, std::size_t k, const engine::Material& m) {
    if (p.material >= 0 && static_cast<int>(k) != p.material) return false;
    return !muscle_kind(p.kind) || uses_muscle(m);
}

// Why p (given as `item`) cannot act on the experiment's materials: a muscle parameter where no
// material (or not the one named) uses the muscle model, a sine parameter where the active
// materials all do. Empty when it applies.
std::string not_applicable(const FitParameter& p, const std::string& item, const Experiment& e) {
    const auto& ms = e.materials;
    if (muscle_kind(p.kind)) {
        if (p.material >= 0 && !uses_muscle(ms[static_cast<std::size_t>(p.material)].physics))
            return "--fit: '" + item + "' does not apply: material '" +
                   ms[static_cast<std::size_t>(p.material)].name +
                   "' uses the sine model (materials[" + std::to_string(p.material) +
                   "].actuation_model), which has no " + muscle_field_name(p.kind);
        if (std::none_of(ms.begin(), ms.end(),
                         [](const MaterialEntry& m) { return uses_muscle(m.physics); }))
            return "--fit: '" + item +
                   "' does not apply: no material of the experiment uses the "
                   "muscle model (materials[k].actuation_model), so none has a " +
                   muscle_field_name(p.kind);
        return {};
    }
    if (!sine_kind(p.kind)) return {};
    for (std::size_t k = 0; k < ms.size(); ++k)
        if (ms[k].active() && !uses_muscle(ms[k].physics)) return {};
    for (std::size_t k = 0; k < ms.size(); ++k)
        if (uses_muscle(ms[k].physics))
            return "--fit: '" + item +
                   "' does not apply: the experiment's actuation is the muscle "
                   "model (materials[" +
                   std::to_string(k) + "].actuation_model), which ignores " +
                   sine_field_name(p.kind) + "; fit rise_s, decay_s or contraction_strain";
    return {};
}

// Narrows a muscle parameter's bounds to its field's range (engine/muscle.hpp) at every material
// it scales: a trial outside it would not be a valid experiment.
void narrow_to_field_range(FitParameter& p, const Experiment& e) {
    if (!muscle_kind(p.kind)) return;
    const bool strain = p.kind == FitKind::MuscleStrain;
    const double lo = strain ? 0.0 : engine::muscle::kMinTimeConstantS;
    const double hi =
        strain ? engine::muscle::kMaxContractionStrain : engine::muscle::kMaxTimeConstantS;
    for (std::size_t k = 0; k < e.materials.size(); ++k) {
        const engine::Material& m = e.materials[k].physics;
        const double v = muscle_field(m, p.kind);
        if (!changes(p, k, m) || !(v > 0.0)) continue;
        p.upper = std::min(p.upper, std::log(hi / v));
        if (lo > 0.0) p.lower = std::max(p.lower, std::log(lo / v));
    }
}

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return {};
    return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

}  // namespace

std::string fit_names_help() {
    return "E[:MATERIAL] (alias youngs_modulus), density[:MATERIAL], bond_damping, "
           "global_damping, friction; the sine model's cte, amplitude, frequency, phase_lag; "
           "the muscle model's rise_s[:MATERIAL], decay_s[:MATERIAL], "
           "contraction_strain[:MATERIAL]";
}

std::vector<FitParameter> parse_fit_list(const std::string& list, const Experiment& e) {
    std::vector<FitParameter> out;
    std::stringstream in(list);
    std::string item;
    while (std::getline(in, item, ',')) {
        item = trim(item);
        if (item.empty()) throw std::runtime_error("--fit: empty name in '" + list + "'");
        const auto colon = item.find(':');
        const std::string base = item.substr(0, colon);
        const Name* found = nullptr;
        for (const auto& n : kNames)
            if (base == n.name) found = &n;
        if (!found)
            throw std::runtime_error("--fit: unknown parameter '" + item +
                                     "' (known: " + fit_names_help() + ")");
        FitParameter p;
        p.name = item;
        p.kind = found->kind;
        if (colon != std::string::npos) {
            if (!found->per_material)
                throw std::runtime_error("--fit: '" + base + "' takes no material");
            const std::string material = item.substr(colon + 1);
            for (std::size_t k = 0; k < e.materials.size(); ++k)
                if (e.materials[k].name == material) p.material = static_cast<int>(k);
            if (p.material < 0)
                throw std::runtime_error("--fit: '" + item + "': the experiment has no material '" +
                                         material + "'");
        }
        for (const auto& q : out)
            if (q.kind == p.kind && (q.material < 0 || p.material < 0 || q.material == p.material))
                throw std::runtime_error("--fit: '" + item + "' overlaps '" + q.name + "'");
        if (const std::string why = not_applicable(p, item, e); !why.empty())
            throw std::runtime_error(why);
        p.log_scale = p.kind != FitKind::PhaseLag;
        p.lower = p.log_scale ? -kLogBound : -std::numbers::pi;
        p.upper = p.log_scale ? kLogBound : std::numbers::pi;
        if (p.log_scale && !(fit_value(e, p, 0.0) > 0.0))
            throw std::runtime_error("--fit: '" + item +
                                     "' is 0 in the experiment, and a factor cannot move it");
        narrow_to_field_range(p, e);
        out.push_back(p);
    }
    if (out.empty()) throw std::runtime_error("--fit: no parameter given");
    // A muscle material's time constants fitted apart from another's that shares its signal
    // split the signal in two: refused where the engine would then drive too many
    // (engine::muscle::kMaxSignals), before a trial finds it.
    std::vector<double> moved(out.size());
    for (std::size_t i = 0; i < out.size(); ++i)
        moved[i] = 0.5 * out[i].upper;
    auto palette_of = [](const Experiment& x) {
        std::vector<engine::Material> palette;
        for (const auto& m : x.materials)
            palette.push_back(m.physics);
        return palette;
    };
    if (engine::muscle::palette_problems(palette_of(e)).empty())
        if (const auto problems =
                engine::muscle::palette_problems(palette_of(apply_fit(e, out, moved).experiment));
            !problems.empty())
            throw std::runtime_error("--fit: '" + list +
                                     "' would split a muscle signal the materials share: " +
                                     problems.front().field + " " + problems.front().message);
    return out;
}

FitPoint apply_fit(const Experiment& base, const std::vector<FitParameter>& parameters,
                   const std::vector<double>& x) {
    FitPoint point{base, 0.0};
    Experiment& e = point.experiment;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
        const FitParameter& p = parameters[i];
        const double f = p.log_scale ? std::exp(x[i]) : 1.0;
        auto each_material = [&](auto&& change) {
            for (std::size_t k = 0; k < e.materials.size(); ++k)
                if (changes(p, k, e.materials[k].physics)) change(e.materials[k].physics);
        };
        switch (p.kind) {
            case FitKind::YoungsModulus:
                each_material([&](engine::Material& m) { m.youngs_modulus_pa *= f; });
                break;
            case FitKind::Density:
                each_material([&](engine::Material& m) { m.density_kg_m3 *= f; });
                break;
            case FitKind::Cte:
                each_material([&](engine::Material& m) { m.cte_per_c *= f; });
                break;
            case FitKind::Friction:
                each_material([&](engine::Material& m) {
                    m.static_friction *= f;
                    m.dynamic_friction *= f;
                });
                break;
            case FitKind::MuscleRise:
            case FitKind::MuscleDecay:
            case FitKind::MuscleStrain:
                each_material([&](engine::Material& m) { muscle_field(m, p.kind) *= f; });
                break;
            case FitKind::Amplitude:
                e.actuation.temperature_amplitude_c *= f;
                break;
            case FitKind::Frequency:
                e.actuation.frequency_hz *= f;
                break;
            case FitKind::BondDamping:
                e.simulation.bond_damping_ratio *= f;
                break;
            case FitKind::GlobalDamping:
                e.simulation.global_damping_ratio *= f;
                break;
            case FitKind::PhaseLag:
                // Into the experiment's uniform offset, wrapped into [-pi, pi] as it validates.
                point.phase_lag_rad += x[i];
                e.actuation.phase_offset_rad =
                    std::remainder(e.actuation.phase_offset_rad + x[i], 2.0 * std::numbers::pi);
                break;
        }
    }
    return point;
}

void copy_fitted_values(const Experiment& from, const std::vector<FitParameter>& parameters,
                        Experiment& to) {
    if (from.materials.size() != to.materials.size())
        throw std::runtime_error("the experiment has " + std::to_string(to.materials.size()) +
                                 " materials, the calibrated one " +
                                 std::to_string(from.materials.size()));
    for (const FitParameter& p : parameters) {
        auto each_material = [&](auto&& copy) {
            for (std::size_t k = 0; k < to.materials.size(); ++k)
                if (changes(p, k, to.materials[k].physics))
                    copy(from.materials[k].physics, to.materials[k].physics);
        };
        using M = engine::Material;
        switch (p.kind) {
            case FitKind::YoungsModulus:
                each_material([](const M& a, M& b) { b.youngs_modulus_pa = a.youngs_modulus_pa; });
                break;
            case FitKind::Density:
                each_material([](const M& a, M& b) { b.density_kg_m3 = a.density_kg_m3; });
                break;
            case FitKind::Cte:
                each_material([](const M& a, M& b) { b.cte_per_c = a.cte_per_c; });
                break;
            case FitKind::Friction:
                each_material([](const M& a, M& b) {
                    b.static_friction = a.static_friction;
                    b.dynamic_friction = a.dynamic_friction;
                });
                break;
            case FitKind::MuscleRise:
            case FitKind::MuscleDecay:
            case FitKind::MuscleStrain:
                each_material(
                    [&](const M& a, M& b) { muscle_field(b, p.kind) = muscle_field(a, p.kind); });
                break;
            case FitKind::Amplitude:
                to.actuation.temperature_amplitude_c = from.actuation.temperature_amplitude_c;
                break;
            case FitKind::Frequency:
                to.actuation.frequency_hz = from.actuation.frequency_hz;
                break;
            case FitKind::BondDamping:
                to.simulation.bond_damping_ratio = from.simulation.bond_damping_ratio;
                break;
            case FitKind::GlobalDamping:
                to.simulation.global_damping_ratio = from.simulation.global_damping_ratio;
                break;
            case FitKind::PhaseLag:
                to.actuation.phase_offset_rad = from.actuation.phase_offset_rad;
                break;
        }
    }
}

double fit_value(const Experiment& e, const FitParameter& p, double x) {
    const double f = p.log_scale ? std::exp(x) : 1.0;
    auto first = [&](auto&& get) {
        for (std::size_t k = 0; k < e.materials.size(); ++k)
            if (changes(p, k, e.materials[k].physics)) {
                const double v = get(e.materials[k].physics);
                if (v > 0.0 || p.material >= 0) return v * f;
            }
        return 0.0;
    };
    switch (p.kind) {
        case FitKind::YoungsModulus:
            return first([](const engine::Material& m) { return m.youngs_modulus_pa; });
        case FitKind::Density:
            return first([](const engine::Material& m) { return m.density_kg_m3; });
        case FitKind::Cte:
            return first([](const engine::Material& m) { return m.cte_per_c; });
        case FitKind::Friction:
            return first([](const engine::Material& m) { return m.static_friction; });
        case FitKind::MuscleRise:
        case FitKind::MuscleDecay:
        case FitKind::MuscleStrain:
            return first([&](const engine::Material& m) { return muscle_field(m, p.kind); });
        case FitKind::Amplitude:
            return e.actuation.temperature_amplitude_c * f;
        case FitKind::Frequency:
            return e.actuation.frequency_hz * f;
        case FitKind::BondDamping:
            return e.simulation.bond_damping_ratio * f;
        case FitKind::GlobalDamping:
            return e.simulation.global_damping_ratio * f;
        case FitKind::PhaseLag:
            return x;
    }
    return 0.0;
}

const char* fit_unit(const FitParameter& p) {
    switch (p.kind) {
        case FitKind::YoungsModulus:
            return "Pa";
        case FitKind::Density:
            return "kg/m^3";
        case FitKind::Cte:
            return "1/C";
        case FitKind::Amplitude:
            return "C";
        case FitKind::Frequency:
            return "Hz";
        case FitKind::PhaseLag:
            return "rad";
        case FitKind::Friction:
            return "static friction coefficient";
        case FitKind::MuscleRise:
        case FitKind::MuscleDecay:
            return "s";
        case FitKind::MuscleStrain:
            return "m/m";
        default:
            return "ratio of critical";
    }
}

}  // namespace bhm::evo
