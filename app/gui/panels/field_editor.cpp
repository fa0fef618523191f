#include "app/gui/panels/field_editor.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#include <imgui.h>

#include "app/gui/actions/draft_edits.hpp"
#include "app/gui/widgets/ui_widgets.hpp"
#include "evo/experiment/experiment_fields.hpp"

namespace bhm::app::gui {

namespace {

std::string visible(const char* label) {
    const std::string s(label);
    return s.substr(0, s.find("##"));
}

template <class Host>
void tooltip_on_hover(Studio& s, const evo::FieldOf<Host>& f) {
    if (ImGui::IsItemHovered()) {
        s.ui.shown_tooltip = evo::field_tooltip(f);
        ImGui::SetTooltip("%s", s.ui.shown_tooltip.c_str());
    }
}

// After the input item: recorded for scripts, the table's tooltip on hover, then the unit.
template <class Host>
void after_item(Studio& s, const evo::FieldOf<Host>& f, const std::string& name) {
    record_widget(s, name);
    tooltip_on_hover(s, f);
    if (*f.unit) {
        ImGui::SameLine();
        ImGui::TextDisabled("%s", f.unit);
    }
}

// Draws f bound to host; true when an edit completed.
template <class Host>
bool draw(Studio& s, const evo::FieldOf<Host>& f, Host& host, const std::string& name,
          bool multiline) {
    bool done = false;
    switch (f.kind()) {
        case evo::FieldKind::Text: {
            std::string& value = f.text(host);
            char buffer[2048];
            std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
            if (multiline) {
                ImGui::InputTextMultiline(f.label, buffer, sizeof buffer,
                                          ImVec2(-1.0f, ImGui::GetTextLineHeight() * 4.0f));
            } else {
                ImGui::SetNextItemWidth(-1.0f);
                ImGui::InputText(f.label, buffer, sizeof buffer);
            }
            if (ImGui::IsItemEdited()) value = buffer;
            done = ImGui::IsItemDeactivatedAfterEdit();
            break;
        }
        case evo::FieldKind::Number:
            ImGui::SetNextItemWidth(field_width());
            ImGui::InputDouble(f.label, &f.number(host), 0.0, 0.0, f.format);
            done = ImGui::IsItemDeactivatedAfterEdit();
            break;
        case evo::FieldKind::Integer:
            ImGui::SetNextItemWidth(field_width());
            ImGui::InputInt(f.label, &f.integer(host), 1, 10);
            done = ImGui::IsItemDeactivatedAfterEdit();
            break;
        case evo::FieldKind::Seed:
            ImGui::SetNextItemWidth(field_width());
            ImGui::InputScalar(f.label, ImGuiDataType_U64, &f.seed(host));
            done = ImGui::IsItemDeactivatedAfterEdit();
            break;
        case evo::FieldKind::Size3:
            ImGui::SetNextItemWidth(field_width());
            ImGui::InputInt3(f.label, f.size3(host).data());
            done = ImGui::IsItemDeactivatedAfterEdit();
            break;
        case evo::FieldKind::Boolean:
            done = ImGui::Checkbox(f.label, &f.boolean(host));
            break;
        case evo::FieldKind::Choice: {
            const int current = f.get_choice(host);
            ImGui::SetNextItemWidth(field_width() * 1.4f);  // "bend_angle_deg" fits
            const bool open =
                ImGui::BeginCombo(f.label, f.choices[static_cast<std::size_t>(current)]);
            after_item(s, f, name);
            record_widget(s, visible(f.label));
            if (open) {
                for (std::size_t k = 0; k < f.choices.size(); ++k) {
                    if (ImGui::Selectable(f.choices[k], static_cast<int>(k) == current) &&
                        static_cast<int>(k) != current) {
                        f.set_choice(host, static_cast<int>(k));
                        done = true;
                    }
                    record_widget(s, std::string(f.key()) + " " + f.choices[k]);
                }
                ImGui::EndCombo();
            }
            return done;
        }
    }
    after_item(s, f, name);
    return done;
}

}  // namespace

bool experiment_field(Studio& s, std::string_view path, bool multiline) {
    const evo::ExperimentField* f = evo::find_experiment_field(path);
    if (!f) throw std::logic_error("no experiment field " + std::string(path));
    if (!draw(s, *f, s.draft, f->path, multiline)) return false;
    commit_draft(s, std::string("set ") + f->path);
    return true;
}

void field_tooltip_on_hover(Studio& s, std::string_view path) {
    const evo::ExperimentField* f = evo::find_experiment_field(path);
    if (!f) throw std::logic_error("no experiment field " + std::string(path));
    tooltip_on_hover(s, *f);
}

bool material_field(Studio& s, std::size_t k, std::string_view key) {
    const evo::MaterialField* f = evo::find_material_field(key);
    if (!f) throw std::logic_error("no material field " + std::string(key));
    const std::string name = "materials[" + std::to_string(k) + "]." + f->path;
    if (!draw(s, *f, s.draft.materials[k].physics, name, false)) return false;
    commit_draft(s, "set " + name);
    return true;
}

}  // namespace bhm::app::gui
