#include "evo/verify/fem_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bhm::evo {

namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec& a, const Vec& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec scaled(const Vec& a, double k) {
    return {a[0] * k, a[1] * k, a[2] * k};
}

// Unit quaternion (w, x, y, z) of the rotation whose columns are the orthonormal r0, r1, r2.
std::array<double, 4> quaternion(const Vec& r0, const Vec& r1, const Vec& r2) {
    const double m00 = r0[0], m10 = r0[1], m20 = r0[2];
    const double m01 = r1[0], m11 = r1[1], m21 = r1[2];
    const double m02 = r2[0], m12 = r2[1], m22 = r2[2];
    const double trace = m00 + m11 + m22;
    std::array<double, 4> q{};
    if (trace > 0.0) {
        const double s = 2.0 * std::sqrt(trace + 1.0);
        q = {0.25 * s, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s};
    } else if (m00 > m11 && m00 > m22) {
        const double s = 2.0 * std::sqrt(1.0 + m00 - m11 - m22);
        q = {(m21 - m12) / s, 0.25 * s, (m01 + m10) / s, (m02 + m20) / s};
    } else if (m11 > m22) {
        const double s = 2.0 * std::sqrt(1.0 + m11 - m00 - m22);
        q = {(m02 - m20) / s, (m01 + m10) / s, 0.25 * s, (m12 + m21) / s};
    } else {
        const double s = 2.0 * std::sqrt(1.0 + m22 - m00 - m11);
        q = {(m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, 0.25 * s};
    }
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (auto& c : q)
        c /= n;
    return q;
}

}  // namespace

engine::VoxelPoses fem_voxel_shape(const FemModel& m, const NodalDisplacements& u,
                                   const std::vector<std::array<double, 3>>& rest_position_m) {
    if (rest_position_m.size() != m.voxel_cells.size())
        throw std::runtime_error("fem_voxel_shape: " + std::to_string(rest_position_m.size()) +
                                 " rest positions for " + std::to_string(m.voxel_cells.size()) +
                                 " voxels");
    auto displaced = [&](int id) {
        const auto it = u.find(id);
        if (it == u.end())
            throw std::runtime_error("ccx printed no displacement for node " + std::to_string(id));
        const auto p = m.node_position_m(id);
        return Vec{p[0] + it->second[0], p[1] + it->second[1], p[2] + it->second[2]};
    };
    engine::VoxelPoses out;
    for (std::size_t v = 0; v < m.voxel_cells.size(); ++v) {
        Vec centre{};
        for (const auto& [id, w] : m.voxel_centre[v]) {
            const auto it = u.find(id);
            if (it == u.end())
                throw std::runtime_error("ccx printed no displacement for node " +
                                         std::to_string(id));
            for (int a = 0; a < 3; ++a)
                centre[a] += w * it->second[a];
        }
        std::array<Vec, 8> corner;
        for (int c = 0; c < 8; ++c)
            corner[static_cast<std::size_t>(c)] =
                displaced(m.voxel_corners[v][static_cast<std::size_t>(c)]);
        // Mean edge vector along each axis: the 4 edges from corners without that bit set.
        std::array<Vec, 3> edge{};
        for (int axis = 0; axis < 3; ++axis)
            for (int c = 0; c < 8; ++c) {
                if (c & (1 << axis)) continue;
                const Vec d = sub(corner[static_cast<std::size_t>(c | (1 << axis))],
                                  corner[static_cast<std::size_t>(c)]);
                for (int a = 0; a < 3; ++a)
                    edge[static_cast<std::size_t>(axis)][a] += 0.25 * d[a];
            }
        const Vec r0 = scaled(edge[0], 1.0 / std::sqrt(dot(edge[0], edge[0])));
        Vec r1 = sub(edge[1], scaled(r0, dot(edge[1], r0)));
        r1 = scaled(r1, 1.0 / std::sqrt(dot(r1, r1)));
        const Vec r2 = cross(r0, r1);
        const auto q = quaternion(r0, r1, r2);
        for (int a = 0; a < 3; ++a) {
            out.position_m.push_back(static_cast<float>(rest_position_m[v][a] + centre[a]));
            out.size_m.push_back(static_cast<float>(std::sqrt(
                dot(edge[static_cast<std::size_t>(a)], edge[static_cast<std::size_t>(a)]))));
        }
        for (double c : q)
            out.orientation.push_back(static_cast<float>(c));
    }
    return out;
}

}  // namespace bhm::evo
