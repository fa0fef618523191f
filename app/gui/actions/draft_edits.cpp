#include "app/gui/actions/draft_edits.hpp"

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"

namespace bhm::app::gui {

void commit_draft(Studio& studio, const std::string& label) {
    if (!apply_edit(studio, studio.draft, label)) studio.draft = studio.document.experiment();
    studio.draft_revision = studio.document.revision();
}

void sync_draft(Studio& studio) {
    if (studio.draft_revision == studio.document.revision()) return;
    if (ImGui::GetCurrentContext() && ImGui::IsAnyItemActive()) return;
    studio.draft = studio.document.experiment();
    studio.draft_revision = studio.document.revision();
}

}  // namespace bhm::app::gui
