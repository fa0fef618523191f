#include "evo/evaluate/constraints.hpp"

#include <cstdio>

#include "evo/evaluate/exploit_flags.hpp"

namespace bhm::evo {

bool touches_design_layer(const Phenotype& phenotype, const DesignSpace& space, Face face) {
    const int axis = static_cast<int>(face) / 2;
    const bool high_side = static_cast<int>(face) % 2 == 1;
    const auto a = static_cast<std::size_t>(axis);
    const int layer = high_side ? space.origin[a] + space.size[a] - 1 : space.origin[a];
    const Body& body = phenotype.body;
    for (int z = space.origin[2]; z < space.origin[2] + space.size[2]; ++z)
        for (int y = space.origin[1]; y < space.origin[1] + space.size[1]; ++y)
            for (int x = space.origin[0]; x < space.origin[0] + space.size[0]; ++x) {
                const int c[3] = {x, y, z};
                if (c[axis] != layer) continue;
                if (body.cells[static_cast<std::size_t>(body.index(x, y, z))] != 0) return true;
            }
    return false;
}

std::string constraint_violation(const Constraints& constraints, const Boundary& boundary,
                                 const DesignSpace& space, const Phenotype& phenotype) {
    if (phenotype.designed_voxels == 0) return "empty design";
    if (constraints.attached_to_fixed_face) {
        for (int f = 0; f < 6; ++f) {
            if (boundary.faces[static_cast<std::size_t>(f)] != BoundaryKind::Fixed) continue;
            if (!touches_design_layer(phenotype, space, static_cast<Face>(f)))
                return std::string("not attached to the fixed ") +
                       kFaceNames[static_cast<std::size_t>(f)] + " face";
        }
    }
    const double fill = static_cast<double>(phenotype.designed_voxels) / space.cell_count();
    if (fill < constraints.min_fill_fraction) {
        char buffer[96];
        std::snprintf(buffer, sizeof buffer, "fill fraction %.3f below %.3f", fill,
                      constraints.min_fill_fraction);
        return buffer;
    }
    if (phenotype.active_voxels < constraints.min_active_voxels)
        return std::to_string(phenotype.active_voxels) + " active voxels, fewer than " +
               std::to_string(constraints.min_active_voxels);
    if (constraints.reject_escaped) {
        const BodyAnatomy anatomy = body_anatomy(boundary, phenotype.body);
        if (anatomy.holds_anything && anatomy.unanchored > 0)
            return "escaped: " + std::to_string(anatomy.unanchored) + " of " +
                   std::to_string(anatomy.voxels) + " voxels are not held by a fixed face";
    }
    return {};
}

}  // namespace bhm::evo
