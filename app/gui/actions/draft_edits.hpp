#pragma once
// The Experiment panel's fields edit a draft (studio.draft) of the document: an edit, once complete,
// is committed through the document's validation and undo; the draft follows the document when
// it changes elsewhere (undo, open, a script).
#include <string>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! Applies studio.draft through apply_edit (validation, undo); reverts the draft when refused.
void commit_draft(Studio& studio, const std::string& label);
//! Re-reads the draft from the document when it changed and no field is being edited.
void sync_draft(Studio& studio);

}  // namespace bhm::app::gui
