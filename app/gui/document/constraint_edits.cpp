#include "app/gui/document/constraint_edits.hpp"

#include <algorithm>

namespace bhm::app::gui {

evo::BoundaryKind next_face_kind(evo::BoundaryKind kind) {
    return kind == evo::BoundaryKind::Free ? evo::BoundaryKind::Fixed : evo::BoundaryKind::Free;
}

evo::Experiment with_face_kind(const evo::Experiment& e, evo::Face face, evo::BoundaryKind kind) {
    evo::Experiment next = e;
    next.boundary.faces[static_cast<int>(face)] = kind;
    return next;
}

evo::Experiment with_face_cycled(const evo::Experiment& e, evo::Face face) {
    return with_face_kind(e, face, next_face_kind(e.boundary.faces[static_cast<int>(face)]));
}

evo::Experiment with_enclosure_thickness(const evo::Experiment& e, evo::Face face, int voxels) {
    evo::Experiment next = e;
    next.boundary.enclosure_thickness[static_cast<int>(face)] = voxels;
    if (voxels > 0 && next.boundary.enclosure_material == 0) {
        for (std::size_t k = 0; k < next.materials.size(); ++k) {
            if (!next.materials[k].active()) {
                next.boundary.enclosure_material = static_cast<int>(k) + 1;
                break;
            }
        }
    }
    return next;
}

int find_override(const evo::Experiment& e, const std::array<int, 3>& cell) {
    const auto& overrides = e.boundary.voxel_overrides;
    for (std::size_t i = 0; i < overrides.size(); ++i)
        if (overrides[i].voxel == cell) return static_cast<int>(i);
    return -1;
}

evo::Experiment with_override(const evo::Experiment& e, const std::array<int, 3>& cell,
                              PaintKind kind, int material) {
    evo::Experiment next = e;
    auto& overrides = next.boundary.voxel_overrides;
    std::erase_if(overrides, [&](const evo::VoxelOverride& o) { return o.voxel == cell; });
    if (kind == PaintKind::Clear) return next;
    evo::VoxelOverride o;
    o.voxel = cell;
    o.kind = kind == PaintKind::Fixed   ? evo::OverrideKind::Fixed
             : kind == PaintKind::Empty ? evo::OverrideKind::Empty
                                        : evo::OverrideKind::Material;
    o.material = kind == PaintKind::Material ? material : 0;
    overrides.push_back(o);
    return next;
}

std::string face_edit_label(evo::Face face, evo::BoundaryKind kind) {
    return std::string("face ") + evo::kFaceNames[static_cast<int>(face)] +
           (kind == evo::BoundaryKind::Fixed ? " fixed" : " free");
}

std::string paint_edit_label(const std::array<int, 3>& cell, PaintKind kind, int material) {
    std::string label = "voxel (" + std::to_string(cell[0]) + ", " + std::to_string(cell[1]) +
                        ", " + std::to_string(cell[2]) + ") ";
    switch (kind) {
        case PaintKind::Fixed:
            return label + "fixed";
        case PaintKind::Empty:
            return label + "forbidden";
        case PaintKind::Material:
            return label + "material " + std::to_string(material);
        case PaintKind::Clear:
            return label + "cleared";
    }
    return label;
}

}  // namespace bhm::app::gui
