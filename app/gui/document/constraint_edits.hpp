#pragma once
// The edits of the constraints painter, as pure functions experiment -> experiment, so the mouse,
// the keyboard, scripts and tests all produce exactly the same change (applied through
// ExperimentDocument::edit, which validates and records undo).
#include <array>
#include <string>

#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

//! free -> fixed -> free (the two kinds of the experiment format).
evo::BoundaryKind next_face_kind(evo::BoundaryKind kind);

evo::Experiment with_face_kind(const evo::Experiment& e, evo::Face face, evo::BoundaryKind kind);
evo::Experiment with_face_cycled(const evo::Experiment& e, evo::Face face);

//! Sets a face's enclosure thickness (voxels). When a frame appears and no frame material is set,
//! the first passive material becomes the frame material (the format requires one).
evo::Experiment with_enclosure_thickness(const evo::Experiment& e, evo::Face face, int voxels);

//! What a click with the voxel brush does to the cell under the cursor.
enum class PaintKind {
    Fixed,     //!< the voxel there, if any, is held in all six degrees of freedom
    Empty,     //!< forbidden: evolution can never put material there
    Material,  //!< always this material
    Clear,     //!< removes any override of the cell
};
inline constexpr std::array<const char*, 4> kPaintKindNames = {"fixed", "forbidden", "material",
                                                               "clear"};

//! The cell's override replaced by the brush's (material is 1-based, for PaintKind::Material).
evo::Experiment with_override(const evo::Experiment& e, const std::array<int, 3>& cell,
                              PaintKind kind, int material = 0);

//! Index of the override of a cell in boundary.voxel_overrides, or -1.
int find_override(const evo::Experiment& e, const std::array<int, 3>& cell);

//! "x- fixed", "voxel (1, 2, 0) forbidden": the undo label of an edit.
std::string face_edit_label(evo::Face face, evo::BoundaryKind kind);
std::string paint_edit_label(const std::array<int, 3>& cell, PaintKind kind, int material);

}  // namespace bhm::app::gui
