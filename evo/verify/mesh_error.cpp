#include "evo/verify/mesh_error.hpp"

#include <algorithm>
#include <cmath>

namespace bhm::evo {

std::optional<MeshErrorEstimate> estimate_mesh_error(const engine::BodySpec& spec,
                                                     FitnessMeasure fitness,
                                                     const BodyVerification& v,
                                                     const VerifyOptions& options) {
    if (v.status != VerifyStatus::Compared || !v.decision.decided_by) return std::nullopt;
    const int s = options.mesh.subdivision;
    VerifyOptions other = options;
    // Twice: the same clamp plane where s is even (an odd subdivision clamps elsewhere, and a
    // clamp shifted by half a voxel, not the mesh, would be most of the estimate).
    other.mesh.subdivision = 2 * s <= 4 ? 2 * s : s / 2;
    other.geometry = v.nlgeom ? FemGeometry::Nonlinear : FemGeometry::Linear;
    other.keep_dir.clear();
    const BodyVerification w = verify_body(spec, fitness, other);
    const VerifyMeasure m = *v.decision.decided_by;
    MeshErrorEstimate e;
    e.subdivision = other.mesh.subdivision;
    e.fem_cpu_s = w.fem_cpu_s;
    for (std::size_t k = 0; k < v.loads.size() && k < w.loads.size(); ++k) {
        if (!above_floor(v.loads[k], m, v.floors)) continue;
        const double first = fem_magnitude(v.loads[k], m);
        const double second = fem_magnitude(w.loads[k], m);
        e.relative = std::max(e.relative, std::fabs(second - first) / first);
    }
    return e;
}

}  // namespace bhm::evo
