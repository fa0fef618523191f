#include "evo/experiment/validated_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "evo/experiment/body_spec_of.hpp"

namespace bhm::evo {

namespace {

std::string number_text(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

}  // namespace

std::vector<Problem> envelope_warnings(const Experiment& e, const Body* body,
                                       const std::string& file) {
    std::vector<Problem> out;
    // The materials the body uses (1-based), or all of them.
    std::vector<bool> used(e.materials.size() + 1, body == nullptr);
    if (body) {
        const Body framed = apply_frame_and_overrides(e, *body);
        for (auto cell : framed.cells)
            if (cell > 0 && cell < used.size()) used[cell] = true;
    }
    double e_min = 0, e_max = 0;
    int k_min = 0, k_max = 0;
    for (size_t k = 1; k < used.size(); ++k) {
        if (!used[k]) continue;
        const auto& m = e.materials[k - 1].physics;
        if (k_min == 0 || m.youngs_modulus_pa < e_min) {
            e_min = m.youngs_modulus_pa;
            k_min = static_cast<int>(k);
        }
        if (k_max == 0 || m.youngs_modulus_pa > e_max) {
            e_max = m.youngs_modulus_pa;
            k_max = static_cast<int>(k);
        }
        if (m.poisson_ratio < validated::kMinPoissonRatio ||
            m.poisson_ratio > validated::kMaxPoissonRatio)
            out.push_back({file, "materials[" + std::to_string(k - 1) + "].poisson_ratio",
                           "warning: nu " + number_text(m.poisson_ratio) +
                               " lies outside the validated [" +
                               number_text(validated::kMinPoissonRatio) + ", " +
                               number_text(validated::kMaxPoissonRatio) +
                               "] (docs/physics.md, Known limits: auxetic voxels are not "
                               "tested in bending)"});
        if (m.actuation_model == engine::ActuationModel::Muscle &&
            m.muscle.contraction_strain > validated::kFastTwitchMaxStrain &&
            m.youngs_modulus_pa > 0.0 && m.density_kg_m3 > 0.0) {
            // The slowest transit: the workspace's longest side at this material's bar speed.
            const double longest = e.voxel_size_m * *std::max_element(e.workspace_size.begin(),
                                                                      e.workspace_size.end());
            const double transit_s = longest / std::sqrt(m.youngs_modulus_pa / m.density_kg_m3);
            if (m.muscle.rise_s < transit_s)
                out.push_back(
                    {file, "materials[" + std::to_string(k - 1) + "].muscle.rise_s",
                     "warning: a twitch rising in " + number_text(m.muscle.rise_s) +
                         " s, faster than a wave crosses the workspace (" + number_text(transit_s) +
                         " s), at contraction_strain " + number_text(m.muscle.contraction_strain) +
                         " (above " + number_text(validated::kFastTwitchMaxStrain) +
                         ") can squeeze a link past the engine's guard: such a body stops as "
                         "diverged (docs/physics.md, Known limits)"});
        }
    }
    if (k_min == 0 || e_min <= 0) return out;
    const double contrast = e_max / e_min;
    const std::string what = body ? "the body's materials" : "the experiment's materials";
    const std::string pair = "materials[" + std::to_string(k_max - 1) + "] E " +
                             number_text(e_max) + " Pa / materials[" + std::to_string(k_min - 1) +
                             "] E " + number_text(e_min) + " Pa";
    if (contrast > validated::kMaxStiffnessContrast)
        out.push_back({file, "materials",
                       "warning: stiffness contrast " + number_text(contrast) + " of " + what +
                           " (" + pair + ") exceeds " +
                           number_text(validated::kMaxStiffnessContrast) +
                           ", the largest validated against CalculiX (docs/physics.md): "
                           "bending may be off by tens of percent"});
    return out;
}

}  // namespace bhm::evo
