#include "evo/evaluate/replay_measures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace bhm::evo {

namespace {

using Vec3 = std::array<double, 3>;

double norm(const Vec3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

Vec3 centroid(const engine::VoxelPoses& frame, const std::vector<std::size_t>& voxels) {
    Vec3 sum{0.0, 0.0, 0.0};
    for (auto v : voxels)
        for (std::size_t k = 0; k < 3; ++k)
            sum[k] += frame.position_m[3 * v + k];
    for (auto& s : sum)
        s /= static_cast<double>(voxels.size());
    return sum;
}

}  // namespace

std::vector<std::array<double, kMeasureCount>> replay_measures(const Experiment& e,
                                                               const engine::Replay& replay) {
    const std::size_t n = replay.voxel_cell.size();
    std::vector<double> mass(n);
    for (std::size_t v = 0; v < n; ++v) {
        const std::size_t m = replay.voxel_material[v];
        if (m < 1 || m > e.materials.size())
            throw std::invalid_argument("replay voxel material " + std::to_string(m) +
                                        " is not in the experiment's palette");
        mass[v] = e.materials[m - 1].physics.density_kg_m3;
    }
    // The bend line's two layers, as MeasureTracker chooses them.
    int face = 0;
    for (int f = 0; f < 6; ++f)
        if (e.boundary.faces[static_cast<std::size_t>(f)] == BoundaryKind::Fixed) {
            face = f;
            break;
        }
    const int axis = face / 2;
    const auto coord = [&](std::size_t v) {
        const int c = replay.voxel_cell[v];
        const int xyz[3] = {c % replay.nx, (c / replay.nx) % replay.ny,
                            c / (replay.nx * replay.ny)};
        return xyz[axis];
    };
    std::vector<std::size_t> base, tip;
    if (n > 0) {
        int lo = coord(0), hi = lo;
        for (std::size_t v = 1; v < n; ++v) {
            lo = std::min(lo, coord(v));
            hi = std::max(hi, coord(v));
        }
        if (lo != hi) {
            const int base_layer = face % 2 == 1 ? hi : lo, tip_layer = face % 2 == 1 ? lo : hi;
            for (std::size_t v = 0; v < n; ++v) {
                if (coord(v) == base_layer) base.push_back(v);
                if (coord(v) == tip_layer) tip.push_back(v);
            }
        }
    }
    const double L = e.voxel_size_m;
    const auto index = [](FitnessMeasure m) { return static_cast<std::size_t>(m); };
    std::vector<std::array<double, kMeasureCount>> out;
    std::array<double, kMeasureCount> so_far{};
    bool referenced = false;
    Vec3 com0{}, direction0{};
    for (const auto& frame : replay.frames) {
        if (frame.time_s >= e.simulation.settle_s - 1e-9 && n > 0) {
            Vec3 com{0.0, 0.0, 0.0};
            double total = 0.0;
            for (std::size_t v = 0; v < n; ++v) {
                for (std::size_t k = 0; k < 3; ++k)
                    com[k] += mass[v] * frame.position_m[3 * v + k];
                total += mass[v];
            }
            for (auto& c : com)
                c /= total;
            Vec3 direction{0.0, 0.0, 0.0};
            if (!base.empty() && !tip.empty()) {
                const Vec3 b = centroid(frame, base), t = centroid(frame, tip);
                for (std::size_t k = 0; k < 3; ++k)
                    direction[k] = t[k] - b[k];
            }
            if (!referenced) {
                referenced = true;
                com0 = com;
                direction0 = direction;
            } else {
                const Vec3 d{com[0] - com0[0], com[1] - com0[1], com[2] - com0[2]};
                const double d3 = norm(d) / L, dyz = std::sqrt(d[1] * d[1] + d[2] * d[2]) / L;
                so_far[index(FitnessMeasure::ComFinal3d)] = d3;
                so_far[index(FitnessMeasure::ComFinalYz)] = dyz;
                auto& max3 = so_far[index(FitnessMeasure::ComMax3d)];
                auto& maxyz = so_far[index(FitnessMeasure::ComMaxYz)];
                max3 = std::max(max3, d3);
                maxyz = std::max(maxyz, dyz);
                const double lengths = norm(direction0) * norm(direction);
                if (lengths > 0.0) {
                    const double cosine =
                        (direction0[0] * direction[0] + direction0[1] * direction[1] +
                         direction0[2] * direction[2]) /
                        lengths;
                    auto& bend = so_far[index(FitnessMeasure::BendAngleDeg)];
                    bend = std::max(
                        bend, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi);
                }
            }
        }
        out.push_back(so_far);
    }
    return out;
}

}  // namespace bhm::evo
