#include "evo/verify/fem_mesh_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace bhm::evo {

namespace {

// Per cell and axis: the length of the contiguous run of cells for which `in` holds through it
// along that axis (0 where `in` does not hold).
template <class In>
std::vector<std::array<int, 3>> runs(const engine::BodySpec& s, In in) {
    std::vector<std::array<int, 3>> r(static_cast<std::size_t>(s.cell_count()), {0, 0, 0});
    const std::array<int, 3> n{s.nx, s.ny, s.nz};
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int b = 0; b < n[v]; ++b)
            for (int a = 0; a < n[u]; ++a) {
                std::array<int, 3> p{};
                p[u] = a;
                p[v] = b;
                int start = 0;
                for (int k = 0; k <= n[axis]; ++k) {
                    p[axis] = k;
                    const bool inside = k < n[axis] && in(s.cell_index(p[0], p[1], p[2]));
                    if (inside) continue;
                    for (int j = start; j < k; ++j) {  // close the run [start, k)
                        p[axis] = j;
                        r[static_cast<std::size_t>(s.cell_index(p[0], p[1], p[2]))][axis] =
                            k - start;
                    }
                    start = k + 1;
                }
            }
    }
    return r;
}

}  // namespace

NarrowestSection narrowest_section(const engine::BodySpec& s) {
    auto material = [&](int c) { return s.material[static_cast<std::size_t>(c)] != 0; };
    auto held = [&](int c) {
        return material(c) && !s.fixed.empty() && s.fixed[static_cast<std::size_t>(c)] != 0;
    };
    const auto material_runs = runs(s, material);
    const auto held_runs = runs(s, held);

    std::array<double, 3> root{};  // the held voxels' centroid, in voxels
    int held_count = 0;
    for (int c = 0; c < s.cell_count(); ++c) {
        if (!held(c)) continue;
        const std::array<int, 3> p{c % s.nx, (c / s.nx) % s.ny, c / (s.nx * s.ny)};
        for (int a = 0; a < 3; ++a)
            root[a] += p[a] + 0.5;
        ++held_count;
    }
    for (int a = 0; a < 3; ++a)
        root[a] /= std::max(held_count, 1);

    NarrowestSection out;
    for (int c = 0; c < s.cell_count(); ++c) {
        if (!material(c)) continue;
        const std::array<int, 3> p{c % s.nx, (c / s.nx) % s.ny, c / (s.nx * s.ny)};
        const auto& r = material_runs[static_cast<std::size_t>(c)];
        int width = 0;
        if (held(c)) {
            std::array<int, 3> h = held_runs[static_cast<std::size_t>(c)];
            std::sort(h.begin(), h.end());
            width = h[1];
        } else {
            // Across the load path: the axis (or axes, on a tie) of the largest offset.
            std::array<double, 3> offset{};
            double largest = 0.0;
            for (int a = 0; a < 3; ++a) {
                offset[a] = std::fabs(p[a] + 0.5 - root[a]);
                largest = std::max(largest, offset[a]);
            }
            width = 1 << 30;
            for (int a = 0; a < 3; ++a)
                if (offset[a] >= largest - 1e-9)
                    width = std::min(width, std::min(r[(a + 1) % 3], r[(a + 2) % 3]));
        }
        if (out.width_voxels == 0 || width < out.width_voxels) {
            out.width_voxels = width;
            out.at = p;
            out.held = held(c);
        }
    }
    return out;
}

double fem_mesh_cost(int voxels, const FemMeshOptions& mesh) {
    const double s = mesh.subdivision;
    return voxels * s * s * s * (mesh.element == FemElement::C3D20R ? 4.0 : 1.0);
}

std::string describe_fem_mesh(const FemMeshOptions& mesh) {
    return fem_element_name(mesh.element) + ", " + std::to_string(mesh.subdivision) +
           " per voxel edge";
}

FemMeshChoice choose_fem_mesh(const engine::BodySpec& spec) {
    FemMeshChoice c;
    c.narrowest = narrowest_section(spec);
    int voxels = 0;
    for (int m : spec.material)
        voxels += m != 0;
    const NarrowestSection& n = c.narrowest;
    char where[160];
    std::snprintf(where, sizeof where,
                  "narrowest section %d voxel%s across (%s at voxel (%d, %d, %d))", n.width_voxels,
                  n.width_voxels == 1 ? "" : "s", n.held ? "the held patch" : "a neck or thin part",
                  n.at[0], n.at[1], n.at[2]);
    if (n.width_voxels > kNarrowSectionVoxels) {
        c.mesh = {FemElement::C3D8I, 2};
        c.reason = describe_fem_mesh(c.mesh) + ": every section at least " +
                   std::to_string(n.width_voxels) + " voxels across";
        return c;
    }
    // A held voxel clamped at a point or along a line (one inside the body: its fixed nodes are
    // its centre, its rotation held by ties) is a singular support: its sag grows as the mesh is
    // refined, so the mesh its ties were measured on stays (docs/verify.md).
    const FemModel probe = build_fem_model(spec, {FemElement::C3D8I, 2});
    if (!probe.rotation_ties.empty()) {
        const FemTie& t = probe.rotation_ties.front();
        std::array<int, 3> voxel{};
        for (int a = 0; a < 3; ++a)
            voxel[static_cast<std::size_t>(a)] =
                (probe.node_grid[static_cast<std::size_t>(t.dependent - 1)][a] +
                 probe.node_grid[static_cast<std::size_t>(t.independent - 1)][a]) /
                (2 * probe.points_per_voxel);
        c.point_clamp = true;
        c.mesh = {FemElement::C3D8I, 2};
        char why[200];
        std::snprintf(why, sizeof why,
                      ": held voxel (%d, %d, %d) is clamped at a point or along a line, where "
                      "refining does not converge",
                      voxel[0], voxel[1], voxel[2]);
        c.reason = describe_fem_mesh(c.mesh) + why;
        return c;
    }
    // Narrow: quadratic bricks, 2 per voxel edge, within the cap; else the default, and why.
    const FemMeshOptions refined{FemElement::C3D20R, 2};
    if (fem_mesh_cost(voxels, refined) <= kMeshCostCapNodes) {
        c.mesh = refined;
        c.reason = describe_fem_mesh(refined) + ": " + where;
        return c;
    }
    c.capped = true;
    c.mesh = {FemElement::C3D8I, 2};
    char capped[200];
    std::snprintf(capped, sizeof capped,
                  "; C3D20R would pass the cost cap (%d voxels, about %.0f nodes, at most %.0f): "
                  "expect it up to 25 %% stiff there",
                  voxels, fem_mesh_cost(voxels, refined), kMeshCostCapNodes);
    c.reason = describe_fem_mesh(c.mesh) + ": " + where + capped;
    return c;
}

FemMeshChoice explicit_fem_mesh(const FemMeshOptions& mesh) {
    FemMeshChoice c;
    c.mesh = mesh;
    c.automatic = false;
    c.reason = describe_fem_mesh(mesh) + ": chosen by the caller (--element, --subdivision)";
    return c;
}

}  // namespace bhm::evo
