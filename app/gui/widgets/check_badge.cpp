#include "app/gui/widgets/check_badge.hpp"

#include <cstdio>

#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

CheckBadge check_badge(const evo::LoopCheck& check) {
    CheckBadge badge;
    char text[64] = "";
    switch (check.outcome) {
        case evo::LoopCheckOutcome::Agrees:
        case evo::LoopCheckOutcome::Differs: {
            const bool agrees = check.outcome == evo::LoopCheckOutcome::Agrees;
            // Whole percent: the tolerance is 10 % by default, so a tenth would be noise here
            // (the verdict on hover has the exact figure).
            std::snprintf(text, sizeof text, "FEM %s %.0f %%", agrees ? "ok" : "differs",
                          100.0 * check.worst);
            badge.color = agrees ? ImVec4(0.12f, 0.50f, 0.20f, 1.0f)
                                 : ImVec4(0.80f, 0.16f, 0.12f, 1.0f);
            break;
        }
        case evo::LoopCheckOutcome::OutOfReach:
        case evo::LoopCheckOutcome::Failed:
            std::snprintf(text, sizeof text, "FEM n/a");
            badge.color = ImVec4(0.45f, 0.47f, 0.52f, 1.0f);
            break;
    }
    badge.text = text;
    const char* what = check.outcome == evo::LoopCheckOutcome::OutOfReach ? "out of reach: "
                       : check.outcome == evo::LoopCheckOutcome::Failed   ? "failed: "
                                                                          : "";
    // Picked from generation g's population, solved beside g + 1's simulations, applied there.
    char where[128];
    std::snprintf(where, sizeof where,
                  "\nchecked in CalculiX in generation %d (individual #%lld of generation %d)",
                  check.generation + 1, static_cast<long long>(check.id), check.generation);
    badge.tooltip = what + check.verdict + where;
    return badge;
}

void draw_check_badge(Studio& studio, const evo::LoopCheck* check, const std::string& name) {
    if (!check) return;
    const CheckBadge badge = check_badge(*check);
    ImGui::TextColored(badge.color, "%s", badge.text.c_str());
    record_widget(studio, name);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", badge.tooltip.c_str());
}

}  // namespace bhm::app::gui
