#pragma once
// The Experiment panel's editor of one field of the experiment table
// (evo/experiment/experiment_fields.hpp): the label, unit, format and tooltip all come from the
// table, so the editor says what the validator checks. Bound to studio.draft; an edit that
// completes (Enter, focus left, a box ticked, a choice picked) is committed through commit_draft
// as "set <path>", the label a script's {"set": path} edit gets.
#include <cstddef>
#include <string_view>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! The field at `path` ("simulation.settle_s"), recorded under its path (and a choice's
//! selectables as "<key> <name>", e.g. "algorithm neat"). True when an edit was committed.
//! Throws std::logic_error for a path the table does not have.
bool experiment_field(Studio& studio, std::string_view path, bool multiline = false);
//! The table's tooltip of the field at `path`, shown while the last item drawn is hovered: for
//! the widgets drawn by hand over table fields (the Constraints panel's faces and frame).
//! Throws std::logic_error for a path the table does not have.
void field_tooltip_on_hover(Studio& studio, std::string_view path);
//! The physical field `key` of draft.materials[k] ("poisson_ratio"), recorded as
//! "materials[k].key".
bool material_field(Studio& studio, std::size_t k, std::string_view key);

}  // namespace bhm::app::gui
