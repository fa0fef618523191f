#pragma once
// Independent checks of a triangle mesh: closed and consistently oriented (every undirected edge
// in exactly two triangles, every directed edge in exactly one), and its enclosed volume.
#include <array>
#include <map>
#include <utility>
#include <vector>

namespace bhm::test {

struct MeshTopology {
    int edges = 0;
    int edges_not_in_two = 0;         //!< undirected edges used by other than two triangles
    int directed_edges_repeated = 0;  //!< same direction twice: inconsistent winding
};

inline MeshTopology check_topology(const std::vector<std::array<int, 3>>& triangles) {
    std::map<std::pair<int, int>, int> undirected, directed;
    for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            ++undirected[{std::min(a, b), std::max(a, b)}];
            ++directed[{a, b}];
        }
    MeshTopology topology;
    topology.edges = static_cast<int>(undirected.size());
    for (const auto& [edge, count] : undirected)
        topology.edges_not_in_two += count != 2 ? 1 : 0;
    for (const auto& [edge, count] : directed)
        topology.directed_edges_repeated += count != 1 ? 1 : 0;
    return topology;
}

//! Sum of signed tetrahedra from the origin (divergence theorem).
inline double signed_volume(const std::vector<std::array<double, 3>>& v,
                            const std::vector<std::array<int, 3>>& triangles) {
    double six = 0.0;
    for (const auto& t : triangles) {
        const auto &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
        six += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return six / 6.0;
}

}  // namespace bhm::test
