// The physics envelope (limits.hpp): ranges, stable-step estimates and the step budget.
#include "engine/limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "engine/internal/poisson.hpp"
#include "engine/internal/moduli.hpp"
#include "engine/muscle.hpp"

namespace bhm::engine::limits {
namespace {

bool finite(double x) {
    return std::isfinite(x);
}

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

// A bound of a range as written: 1000, not number()'s 1e+03.
std::string bound(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

// Torsion constant of a square section of side a: J = 0.1406 a^4 (Saint-Venant, b/a = 1).
constexpr double kSquareTorsionFactor = 0.1406;

}  // namespace

std::vector<Problem> material_problems(const Material& m, double temperature_amplitude_c) {
    std::vector<Problem> out;
    if (!finite(m.youngs_modulus_pa) || m.youngs_modulus_pa <= 0.0 ||
        m.youngs_modulus_pa > kMaxYoungsModulusPa)
        out.push_back({"youngs_modulus_pa", "must be in (0, " + number(kMaxYoungsModulusPa) +
                                                "] Pa (beyond any real material)"});
    if (!finite(m.density_kg_m3) || m.density_kg_m3 <= 0.0 || m.density_kg_m3 > kMaxDensityKgM3)
        out.push_back({"density_kg_m3", "must be in (0, " + number(kMaxDensityKgM3) + "] kg/m^3"});
    if (!finite(m.poisson_ratio) || m.poisson_ratio < kMinPoissonRatio ||
        m.poisson_ratio > kMaxPoissonRatio)
        out.push_back({"poisson_ratio", "must be in [" + number(kMinPoissonRatio) + ", " +
                                            number(kMaxPoissonRatio) +
                                            "] (the engine's validated range)"});
    const double strain = m.cte_per_c * temperature_amplitude_c;
    if (!finite(m.cte_per_c) || !finite(strain) || std::fabs(strain) > kMaxActuationStrain)
        out.push_back({"cte_per_c",
                       "times the temperature amplitude gives a linear actuation "
                       "strain of " +
                           number(strain) + ", beyond the engine's stable " +
                           number(kMaxActuationStrain)});
    if (!finite(m.static_friction) || m.static_friction < 0.0)
        out.push_back({"static_friction", "must be >= 0"});
    if (!finite(m.dynamic_friction) || m.dynamic_friction < 0.0)
        out.push_back({"dynamic_friction", "must be >= 0"});
    for (const muscle::Problem& p : muscle::material_problems(m))
        out.push_back({p.field, p.message});
    return out;
}

std::vector<Problem> settings_problems(const BodySpec& spec) {
    std::vector<Problem> out;
    if (!finite(spec.voxel_size_m) || spec.voxel_size_m < kMinVoxelSizeM ||
        spec.voxel_size_m > kMaxVoxelSizeM)
        out.push_back({"voxel_size_m", "must be in [" + number(kMinVoxelSizeM) + ", " +
                                           number(kMaxVoxelSizeM) + "] m"});
    const Damping& d = spec.damping;
    const std::pair<const char*, double> ratios[] = {
        {"damping.bond_ratio", d.bond_ratio},
        {"damping.global_ratio", d.global_ratio},
        {"damping.collision_ratio", d.collision_ratio}};
    for (const auto& [field, ratio] : ratios)
        if (!finite(ratio) || ratio < 0.0 || ratio > kMaxDampingRatio)
            out.push_back({field, "must be in [0, " + number(kMaxDampingRatio) + "]"});
    if (d.implicit_sweeps < 0 || d.implicit_sweeps > kMaxImplicitSweeps)
        out.push_back({"damping.implicit_sweeps",
                       "must be in [0, " + std::to_string(kMaxImplicitSweeps) + "]"});
    const Actuation& a = spec.actuation;
    if (!finite(a.frequency_hz) || a.frequency_hz < 0.0 || a.frequency_hz > kMaxFrequencyHz)
        out.push_back(
            {"actuation.frequency_hz", "must be in [0, " + bound(kMaxFrequencyHz) + "] Hz"});
    if (!finite(a.temperature_amplitude_c) || a.temperature_amplitude_c < 0.0 ||
        a.temperature_amplitude_c > kMaxTemperatureAmplitudeC)
        out.push_back({"actuation.temperature_amplitude_c",
                       "must be in [0, " + bound(kMaxTemperatureAmplitudeC) + "] degC"});
    if (!finite(a.start_s)) out.push_back({"actuation.start_s", "must be finite"});
    if (!finite(spec.environment.gravity_m_s2) ||
        std::fabs(spec.environment.gravity_m_s2) > kMaxGravityMS2)
        out.push_back({"environment.gravity_m_s2", "must be in [" + bound(-kMaxGravityMS2) + ", " +
                                                       bound(kMaxGravityMS2) + "] m/s^2"});
    const double max_dt_fraction =
        spec.damping.implicit_sweeps > 0 ? kMaxDtFraction : kMaxExplicitDtFraction;
    if (!finite(spec.dt_fraction) || spec.dt_fraction <= 0.0 || spec.dt_fraction > max_dt_fraction)
        out.push_back({"dt_fraction",
                       "must be in (0, " + number(max_dt_fraction) +
                           (spec.damping.implicit_sweeps > 0
                                ? "] (a fraction of the implicit damping's stable step)"
                                : "] with the explicit damping (a fraction of the stable step)")});
    // At least the cube's own inertia: scaling it down would only shorten the step.
    if (!finite(spec.rotary_inertia_scale) || spec.rotary_inertia_scale < kMinRotaryInertiaScale ||
        spec.rotary_inertia_scale > kMaxRotaryInertiaScale)
        out.push_back({"rotary_inertia_scale", "must be in [" + bound(kMinRotaryInertiaScale) +
                                                   ", " + bound(kMaxRotaryInertiaScale) +
                                                   "] (times a cube's m L^2 / 6)"});
    return out;
}

std::vector<Problem> body_spec_problems(const BodySpec& spec) {
    std::vector<Problem> out;
    if (spec.nx <= 0 || spec.ny <= 0 || spec.nz <= 0) {
        out.push_back({"nx, ny, nz", "must be positive (got " + std::to_string(spec.nx) + " x " +
                                         std::to_string(spec.ny) + " x " + std::to_string(spec.nz) +
                                         ")"});
        return out;
    }
    const long long cells = 1LL * spec.nx * spec.ny * spec.nz;
    if (cells > (1LL << 26)) {
        out.push_back(
            {"nx, ny, nz", "lattice of " + std::to_string(cells) + " cells is too large"});
        return out;
    }
    auto count = [](std::size_t n) { return std::to_string(n); };
    if (static_cast<long long>(spec.material.size()) != cells)
        out.push_back({"material", "has " + count(spec.material.size()) + " entries, expected " +
                                       std::to_string(cells)});
    if (!spec.fixed.empty() && static_cast<long long>(spec.fixed.size()) != cells)
        out.push_back({"fixed", "has " + count(spec.fixed.size()) + " entries, expected 0 or " +
                                    std::to_string(cells)});
    if (!spec.phase_rad.empty() && static_cast<long long>(spec.phase_rad.size()) != cells)
        out.push_back({"phase_rad", "has " + count(spec.phase_rad.size()) +
                                        " entries, expected 0 or " + std::to_string(cells)});
    if (!spec.amplitude_scale.empty() &&
        static_cast<long long>(spec.amplitude_scale.size()) != cells)
        out.push_back({"amplitude_scale", "has " + count(spec.amplitude_scale.size()) +
                                              " entries, expected 0 or " + std::to_string(cells)});
    if (!spec.fibre_axis.empty() && static_cast<long long>(spec.fibre_axis.size()) != cells)
        out.push_back({"fibre_axis", "has " + count(spec.fibre_axis.size()) +
                                         " entries, expected 0 or " + std::to_string(cells)});
    for (std::size_t c = 0; c < spec.fibre_axis.size(); ++c)
        if (spec.fibre_axis[c] > 2 && spec.fibre_axis[c] != kMaterialFibreAxis) {
            out.push_back({"fibre_axis[" + std::to_string(c) + "]",
                           "= " + std::to_string(spec.fibre_axis[c]) +
                               ", expected 0 (x), 1 (y), 2 (z) or 255 (the material's axis)"});
            break;
        }
    for (std::size_t k = 0; k < spec.materials.size(); ++k)
        for (const Problem& p :
             material_problems(spec.materials[k], spec.actuation.temperature_amplitude_c))
            out.push_back({"materials[" + std::to_string(k) + "]." + p.field, p.message});
    for (const Problem& p : settings_problems(spec))
        out.push_back(p);
    if (static_cast<long long>(spec.material.size()) == cells) {
        bool any_voxel = false;
        for (long long c = 0; c < cells; ++c) {
            const int k = spec.material[c];
            if (k == 0) continue;
            any_voxel = true;
            if (k > static_cast<int>(spec.materials.size())) {
                out.push_back({"material[" + std::to_string(c) + "]",
                               "= " + std::to_string(k) + " but only " +
                                   count(spec.materials.size()) + " materials are defined"});
                break;
            }
        }
        if (!any_voxel) out.push_back({"material", "the body has no voxels: nothing to simulate"});
        // One actuation model per body, at most two muscle signals (engine/muscle.hpp).
        std::vector<bool> used(spec.materials.size(), false);
        for (long long c = 0; c < cells; ++c)
            if (const int k = spec.material[c]; k > 0 && k <= static_cast<int>(used.size()))
                used[k - 1] = true;
        for (const muscle::Problem& p : muscle::palette_problems(spec.materials, &used))
            out.push_back({p.field, p.message});
    }
    for (float p : spec.phase_rad)
        if (!std::isfinite(p)) {
            out.push_back({"phase_rad", "has a non-finite entry"});
            break;
        }
    for (float a : spec.amplitude_scale)
        if (!(a >= 0.0f && a <= 1.0f)) {  // NaN fails too
            out.push_back({"amplitude_scale", "has an entry outside [0, 1]"});
            break;
        }
    return out;
}

namespace {
// Largest size scale 1 + |cte A| of a material's voxels over an actuation period.
double largest_scale(const Material& m, double temperature_amplitude_c) {
    if (m.actuation_model == ActuationModel::Muscle) return muscle::largest_scale(m);
    return 1.0 + std::fabs(m.cte_per_c * temperature_amplitude_c);
}
}  // namespace

double voxel_omega2(const Material& m, double L, double temperature_amplitude_c,
                    double rotary_inertia_scale) {
    const double mass = m.density_kg_m3 * (L * L * L);
    const double inertia = rotary_inertia_scale * mass * L * L / 6.0;
    const double k_axial = m.youngs_modulus_pa * L;              // E A / L
    const double k_rot = m.youngs_modulus_pa * L * L * L / 3.0;  // 4 E I / L
    const double scale = largest_scale(m, temperature_amplitude_c);
    return std::max(scale * k_axial / mass, scale * scale * k_rot / inertia);
}

namespace {
// The stiffest mode of the link between materials a and b on its lighter end, at the largest
// actuated size of either end; its axial stiffness is E times axial_factor(nu) of each material,
// in series; its bending and torsion the materials' in series times bending_factor.
double link_mode_omega2(const Material& a, const Material& b, double L,
                        double temperature_amplitude_c, double (*axial_factor)(double),
                        double bending_factor, double rotary_inertia_scale) {
    const double e = bending_factor * series(a.youngs_modulus_pa, b.youngs_modulus_pa);
    const double g = bending_factor * series(shear_modulus(a), shear_modulus(b));
    const double m_min = std::min(a.density_kg_m3, b.density_kg_m3) * (L * L * L);
    const double inertia = rotary_inertia_scale * m_min * L * L / 6.0;
    const double k_axial = series(a.youngs_modulus_pa * axial_factor(a.poisson_ratio),
                                  b.youngs_modulus_pa * axial_factor(b.poisson_ratio)) *
                           L;
    const double k_bend4 = 4.0 * e * (std::pow(L, 4) / 12.0 / L);  // 4 E I / L
    // Twisting both ends against each other: 2 G J / L on each.
    const double k_twist2 = 2.0 * g * kSquareTorsionFactor * std::pow(L, 4) / L;
    const double scale = std::max(largest_scale(a, temperature_amplitude_c),
                                  largest_scale(b, temperature_amplitude_c));
    return std::max({scale * k_axial / m_min, scale * scale * k_bend4 / inertia,
                     scale * scale * k_twist2 / inertia});
}
}  // namespace

double link_omega2(const Material& a, const Material& b, double L, double temperature_amplitude_c,
                   double bending_factor, double rotary_inertia_scale) {
    // The Poisson coupling stiffens the axial modes up to the P-wave modulus M = lambda + 2 G.
    return link_mode_omega2(a, b, L, temperature_amplitude_c, poisson_wave_factor, bending_factor,
                            rotary_inertia_scale);
}

double link_damping_omega2(const Material& a, const Material& b, double L,
                           double temperature_amplitude_c, double bending_factor,
                           double rotary_inertia_scale) {
    // With the volumetric 3 K where it is stiffer than M (nu > 0.25).
    return link_mode_omega2(a, b, L, temperature_amplitude_c, poisson_stiffness_factor,
                            bending_factor, rotary_inertia_scale);
}

double stable_step_for(double omega2) {
    return 1.0 / (2.0 * std::numbers::pi * std::sqrt(omega2));
}

double step_multiple(int implicit_sweeps) {
    return implicit_sweeps > 0 ? kImplicitStepMultiple : 1.0;
}

StepRange step_range(const std::vector<Material>& materials, double L, double dt_fraction,
                     double temperature_amplitude_c, int implicit_sweeps,
                     double rotary_inertia_scale) {
    const double A = temperature_amplitude_c;
    double stiffest = 0.0, softest = 0.0;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const double alone = voxel_omega2(materials[i], L, A, rotary_inertia_scale);
        softest = i == 0 ? alone : std::min(softest, alone);
        stiffest = std::max(stiffest, alone);
        for (std::size_t j = i; j < materials.size(); ++j)
            stiffest = std::max(
                stiffest, link_omega2(materials[i], materials[j], L, A, 1.0, rotary_inertia_scale));
    }
    if (materials.empty()) return {};
    const double fraction = dt_fraction * step_multiple(implicit_sweeps);
    return {fraction * stable_step_for(stiffest), fraction * stable_step_for(softest)};
}

std::int64_t steps_for(double total_s, double dt_s) {
    // run() stops at the first step count whose time reaches total_s - dt / 2.
    if (!(total_s > 0.0) || !(dt_s > 0.0)) return 0;
    return static_cast<std::int64_t>(std::max(0.0, std::ceil(total_s / dt_s - 0.5)));
}

std::string step_budget_problem(const StepRange& range, double total_s, double frequency_hz,
                                bool actuated, long long voxels) {
    if (!(range.shortest_s > 0.0) || !(range.longest_s > 0.0) || !(total_s > 0.0)) return {};
    const double most = total_s / range.shortest_s;
    if (most > kMaxStepsPerSimulation) {
        const double hours =
            most * static_cast<double>(std::max(1LL, voxels)) / kNominalVoxelStepsPerS / 3600.0;
        return "needs " + number(most) + " steps of " + number(range.shortest_s) + " s, about " +
               number(hours) + " h per simulation of " + std::to_string(voxels) +
               " voxels (the budget is " + number(kMaxStepsPerSimulation) +
               " steps: use larger voxels, softer or denser materials, or a shorter simulation)";
    }
    const double fewest = total_s / range.longest_s;
    if (fewest < kMinStepsPerSimulation)
        return "would take only " + number(std::floor(fewest)) + " steps of " +
               number(range.longest_s) + " s (at least " + number(kMinStepsPerSimulation) +
               " are needed: use smaller voxels, stiffer or lighter materials, or a longer "
               "simulation)";
    if (actuated && frequency_hz > 0.0) {
        const double per_period = 1.0 / (frequency_hz * range.longest_s);
        if (per_period < kMinStepsPerActuationPeriod)
            return "samples each actuation period with only " + number(per_period) + " steps of " +
                   number(range.longest_s) + " s (at least " + number(kMinStepsPerActuationPeriod) +
                   " are needed: lower the frequency)";
    }
    return {};
}

}  // namespace bhm::engine::limits
