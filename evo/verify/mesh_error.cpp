#include "evo/verify/mesh_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bhm::evo {

int second_subdivision(int s) {
    // Twice: the same clamp plane where s is even (an odd subdivision clamps elsewhere, and a
    // clamp shifted by half a voxel, not the mesh, would be most of the estimate).
    return 2 * s <= 4 ? 2 * s : s / 2;
}

std::optional<MeshErrorEstimate> estimate_mesh_error(const engine::BodySpec& spec,
                                                     const BodyVerification& v,
                                                     const VerifyOptions& options) {
    if (v.status != VerifyStatus::Compared || !v.decision.decided_by) return std::nullopt;
    MeshErrorEstimate e;
    e.first_subdivision = v.mesh.mesh.subdivision;
    FemMeshOptions second = v.mesh.mesh;
    second.subdivision = second_subdivision(e.first_subdivision);
    e.subdivision = second.subdivision;
    const double cost = fem_mesh_cost(v.voxels, second);
    if (cost > kMeshErrorCapNodes) {
        char why[160];
        std::snprintf(why, sizeof why, "%d per edge would be about %.0f nodes, over the %.0f cap",
                      second.subdivision, cost, kMeshErrorCapNodes);
        e.skipped = why;
        return e;
    }
    VerifyOptions other = options;
    other.keep_dir.clear();
    // The second solve's progress as its own phase: a progress bar must not run back to the
    // first solve's.
    other.control.on_progress = [&options](const VerifyProgress& p) {
        if (p.phase == VerifyPhase::Solving)
            options.control.report({VerifyPhase::SecondMesh, p.load, p.loads});
    };
    const FemAnswer w = solve_fem(spec, second, v.nlgeom, other);
    const VerifyMeasure m = *v.decision.decided_by;
    e.fem_cpu_s = w.cpu_s;
    for (std::size_t k = 0; k < v.loads.size() && k < w.loads.size(); ++k) {
        if (!above_floor(v.loads[k], m, v.floors)) continue;
        const double first = fem_magnitude(v.loads[k], m);
        const double other_mesh = fem_magnitude(w.loads[k], m);
        e.relative = std::max(e.relative, std::fabs(other_mesh - first) / first);
    }
    return e;
}

std::string describe_mesh_error(const MeshErrorEstimate& e) {
    if (!e.skipped.empty()) return "FEM mesh error not estimated: " + e.skipped;
    char text[96];
    std::snprintf(text, sizeof text, "FEM mesh error ~%.1f %% (%d vs %d per edge)",
                  100.0 * e.relative, e.first_subdivision, e.subdivision);
    return text;
}

nlohmann::json mesh_error_json(const MeshErrorEstimate& e, const BodyVerification& v) {
    nlohmann::json j = {{"elements_per_voxel_edge", e.subdivision},
                        {"first_elements_per_voxel_edge", e.first_subdivision},
                        {"element", fem_element_name(v.mesh.mesh.element)}};
    if (!e.skipped.empty()) {
        j["skipped"] = e.skipped;
        return j;
    }
    if (v.decision.decided_by) j["measure"] = verify_measure_key(*v.decision.decided_by);
    j["relative_difference"] = e.relative;
    j["cpu_s"] = e.fem_cpu_s;
    return j;
}

}  // namespace bhm::evo
