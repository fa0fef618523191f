#include "app/gui/panels/field_editor.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <imgui.h>
#include <imgui_internal.h>  // the frame a text box was opened

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

// The text box opens with its caret at the end of the text: a click on the wrapped text
// cannot say where in the unwrapped one it fell.
int caret_at_end_when_opened(ImGuiInputTextCallbackData* data) {
    if (ImGui::GetCurrentContext()->ActiveIdIsJustActivated)
        data->CursorPos = data->SelectionStart = data->SelectionEnd = data->BufTextLen;
    return 0;
}

// A multiline text shown wrapped to the panel in a box, opened for typing by a click: ImGui
// 1.86's text box cannot wrap, so a paragraph ran off the panel on one line (issue 39, the
// clipped-text low). True when an edit completed.
bool wrapped_text_field(Studio& s, const char* label, std::string& value, const std::string& name) {
    const ImVec2 pad = ImGui::GetStyle().FramePadding;
    const float width = ImGui::GetContentRegionAvail().x;
    const float text_height =
        ImGui::CalcTextSize(value.c_str(), nullptr, false, width - 2.0f * pad.x).y;
    const float lines = ImGui::GetTextLineHeight();
    // At least the four lines the text box had: the panel does not jump as the box opens.
    const ImVec2 size(width, std::max(text_height, 4.0f * lines) + 2.0f * pad.y);
    if (s.ui.text_field_open != name) {
        const ImVec2 at = ImGui::GetCursorScreenPos();
        const std::string id = std::string(label) + " wrapped";
        if (ImGui::InvisibleButton(id.c_str(), size)) {
            s.ui.text_field_open = name;
            s.ui.text_field_opened_frame = s.ui.frame;
        }
        if (ImGui::IsItemHovered()) ImGui::SetMouseCursor(ImGuiMouseCursor_TextInput);
        ImDrawList* draw = ImGui::GetWindowDrawList();
        const ImVec2 end(at.x + size.x, at.y + size.y);
        draw->AddRectFilled(at, end, ImGui::GetColorU32(ImGuiCol_FrameBg),
                            ImGui::GetStyle().FrameRounding);
        draw->AddRect(at, end, ImGui::GetColorU32(ImGuiCol_Border),
                      ImGui::GetStyle().FrameRounding);
        draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(at.x + pad.x, at.y + pad.y),
                      ImGui::GetColorU32(ImGuiCol_Text), value.c_str(), nullptr,
                      width - 2.0f * pad.x);
        return false;
    }
    // The frame after the click asks for the keyboard; ImGui hands it over the frame after.
    if (s.ui.frame == s.ui.text_field_opened_frame + 1) ImGui::SetKeyboardFocusHere();
    char buffer[2048];
    std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
    ImGui::InputTextMultiline(label, buffer, sizeof buffer, size,
                              ImGuiInputTextFlags_CallbackAlways, caret_at_end_when_opened);
    if (ImGui::IsItemEdited()) value = buffer;
    const bool done = ImGui::IsItemDeactivatedAfterEdit();
    // Left (a click elsewhere, Escape), or never taken: shown wrapped again.
    if (ImGui::IsItemDeactivated() ||
        (!ImGui::IsItemActive() && s.ui.frame > s.ui.text_field_opened_frame + 3))
        s.ui.text_field_open.clear();
    return done;
}

// Draws f bound to host; true when an edit completed.
template <class Host>
bool draw(Studio& s, const evo::FieldOf<Host>& f, Host& host, const std::string& name,
          bool multiline) {
    bool done = false;
    switch (f.kind()) {
        case evo::FieldKind::Text: {
            std::string& value = f.text(host);
            if (multiline) {
                done = wrapped_text_field(s, f.label, value, name);
                break;
            }
            char buffer[2048];
            std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
            ImGui::SetNextItemWidth(-1.0f);
            ImGui::InputText(f.label, buffer, sizeof buffer);
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
