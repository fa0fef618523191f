#include "app/gui/panels/material_picker.hpp"

#include <cctype>
#include <cstdio>
#include <sstream>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

std::string lower(std::string s) {
    for (auto& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

}  // namespace

bool library_material_matches(const evo::LibraryMaterial& m, const std::string& filter) {
    const std::string haystack = lower(m.id + " " + m.name + " " + m.category +
                                       (m.active ? " active" : " passive"));
    std::istringstream words(lower(filter));
    for (std::string word; words >> word;)
        if (haystack.find(word) == std::string::npos) return false;
    return true;
}

std::vector<std::string> fields_changed_from_library(const evo::LibraryMaterial& m,
                                                     const evo::MaterialEntry& entry,
                                                     double temperature_amplitude_c) {
    evo::MaterialEntry filled = entry;
    evo::apply_library_material(m, temperature_amplitude_c, filled);
    std::vector<std::string> out;
    const auto& a = entry.physics;
    const auto& b = filled.physics;
    if (a.youngs_modulus_pa != b.youngs_modulus_pa) out.push_back("E");
    if (a.poisson_ratio != b.poisson_ratio) out.push_back("nu");
    if (a.density_kg_m3 != b.density_kg_m3) out.push_back("density");
    if (a.cte_per_c != b.cte_per_c) out.push_back("CTE");
    if (a.static_friction != b.static_friction) out.push_back("static friction");
    if (a.dynamic_friction != b.dynamic_friction) out.push_back("dynamic friction");
    return out;
}

void material_library_picker(Studio& s, std::size_t slot) {
    const evo::MaterialEntry& entry = s.draft.materials[slot];
    const evo::MaterialLibrary* library = studio_material_library(s);
    const evo::LibraryMaterial* current =
        library && !entry.library.empty() ? library->find(entry.library) : nullptr;
    const std::string preview = entry.library.empty() ? std::string("typed by hand")
                                : current             ? current->name
                                                      : entry.library + " (not in the library)";
    const std::string popup = "library_popup";
    if (ImGui::Button((preview + "##library").c_str())) {
        s.library.material_filter.clear();
        ImGui::OpenPopup(popup.c_str());
    }
    record_widget(s, "library " + std::to_string(slot + 1));
    ImGui::SameLine();
    ImGui::TextDisabled("library");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("pick a documented material (assets/materials/, `bhm materials`) or type\n"
                          "your own values below; a value typed over a library one is kept");
    if (current) {
        const auto changed =
            fields_changed_from_library(*current, entry, s.draft.actuation.temperature_amplitude_c);
        std::string text = "E " + short_number(current->youngs_modulus_pa.value) + " Pa";
        if (!changed.empty()) {
            text += "; changed here:";
            for (const auto& f : changed)
                text += " " + f;
        }
        ImGui::TextDisabled("%s", text.c_str());
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s", evo::describe_library_material(*current).c_str());
        // The tissue's frequency is the whole body's actuation frequency: offered, not imposed.
        if (current->frequency_hz && current->frequency_hz->value != s.draft.actuation.frequency_hz) {
            ImGui::TextDisabled("tissue: %s Hz, actuation: %s Hz",
                                short_number(current->frequency_hz->value).c_str(),
                                short_number(s.draft.actuation.frequency_hz).c_str());
            ImGui::SameLine();
            if (ImGui::SmallButton("use")) {
                auto next = s.document.experiment();
                next.actuation.frequency_hz = current->frequency_hz->value;
                apply_edit(s, next, "actuation frequency from " + current->name);
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s", current->frequency_hz->source.c_str());
        }
    }
    std::string chosen;
    if (ImGui::BeginPopup(popup.c_str())) {
        if (!library) {
            ImGui::TextDisabled("the library did not load: %s", s.library.materials_error.c_str());
        } else {
            // What the library did not read, above its list (issue 41 R10).
            for (const auto& w : library->warnings())
                ImGui::TextColored(ImColor(IM_COL32(190, 60, 30, 255)), "%s", w.c_str());
            char buffer[128];
            std::snprintf(buffer, sizeof buffer, "%s", s.library.material_filter.c_str());
            ImGui::SetNextItemWidth(ImGui::GetFontSize() * 24.0f);
            if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
            if (ImGui::InputTextWithHint("##filter", "search: name, id, category, active",
                                         buffer, sizeof buffer))
                s.library.material_filter = buffer;
            int shown = 0;
            for (const auto& m : library->materials) {
                if (!library_material_matches(m, s.library.material_filter)) continue;
                ++shown;
                const std::string label = m.name + "   E " +
                                          short_number(m.youngs_modulus_pa.value) + " Pa" +
                                          (m.active ? "   active" : "") + "##" + m.id;
                if (ImGui::Selectable(label.c_str(), m.id == entry.library)) chosen = m.id;
                record_widget(s, "library item " + m.id);
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("%s\n%s", m.id.c_str(),
                                      evo::describe_library_material(m).c_str());
            }
            if (shown == 0) ImGui::TextDisabled("no material matches");
        }
        ImGui::EndPopup();
    }
    if (!chosen.empty()) choose_library_material(s, slot, chosen);
}

}  // namespace bhm::app::gui
