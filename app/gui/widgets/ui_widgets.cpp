#include "app/gui/widgets/ui_widgets.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>

#include <imgui_internal.h>

namespace bhm::app::gui {

namespace {

std::string visible_label(const char* label) {
    const std::string s(label);
    const auto hash = s.find("##");
    return hash == std::string::npos ? s : s.substr(0, hash);
}

void unit_and_hint(const char* unit, const char* hint) {
    if (hint && *hint && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", hint);
    if (unit && *unit) {
        ImGui::SameLine();
        ImGui::TextDisabled("%s", unit);
    }
}

bool finished_edit() {
    return ImGui::IsItemDeactivatedAfterEdit();
}

}  // namespace

void record_widget(Studio& studio, const std::string& name) {
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    studio.ui.widgets[name] = WidgetRect{{lo.x, lo.y}, {hi.x, hi.y}, studio.ui.frame};
}

void hinted_text_field(Studio& studio, const char* id, const char* hint, std::string& value) {
    char buffer[2048];
    std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::InputTextWithHint(id, hint, buffer, sizeof buffer)) value = buffer;
    record_widget(studio, id + 2);
}

bool tracked_button(Studio& studio, const char* label, ImVec2 size) {
    const bool pressed = ImGui::Button(label, size);
    record_widget(studio, visible_label(label));
    return pressed;
}

void centre_next_window(float width_em, float height_em, ImGuiCond condition) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float font = ImGui::GetFontSize();
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), condition,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(std::min(display.x - 40.0f, font * width_em),
                                    std::min(display.y - 60.0f, font * height_em)),
                             condition);
}

float field_width() {
    return ImGui::GetFontSize() * 8.5f;
}

bool field_double(const char* label, double& value, const char* unit, const char* hint,
                  const char* format) {
    ImGui::SetNextItemWidth(field_width());
    ImGui::InputDouble(label, &value, 0.0, 0.0, format);
    const bool done = finished_edit();
    unit_and_hint(unit, hint);
    return done;
}

bool field_int(const char* label, int& value, const char* unit, const char* hint) {
    ImGui::SetNextItemWidth(field_width());
    ImGui::InputInt(label, &value, 1, 10);
    const bool done = finished_edit();
    unit_and_hint(unit, hint);
    return done;
}

bool field_u64(const char* label, std::uint64_t& value, const char* hint) {
    ImGui::SetNextItemWidth(field_width());
    ImGui::InputScalar(label, ImGuiDataType_U64, &value);
    const bool done = finished_edit();
    unit_and_hint("", hint);
    return done;
}

bool field_bool(const char* label, bool& value, const char* hint) {
    const bool changed = ImGui::Checkbox(label, &value);
    unit_and_hint("", hint);
    return changed;
}

bool field_text(const char* label, std::string& value, const char* hint, bool multiline) {
    char buffer[2048];
    std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
    if (multiline) {
        ImGui::InputTextMultiline(label, buffer, sizeof buffer,
                                  ImVec2(-1.0f, ImGui::GetTextLineHeight() * 4.0f));
    } else {
        ImGui::SetNextItemWidth(-1.0f);
        ImGui::InputText(label, buffer, sizeof buffer);
    }
    if (ImGui::IsItemEdited()) value = buffer;
    const bool done = finished_edit();
    unit_and_hint("", hint);
    return done;
}

void wrapped_tooltip(const std::string& text) {
    const float display_w = ImGui::GetIO().DisplaySize.x;
    const float width = std::max(100.0f, std::min(display_w - 40.0f, ImGui::GetFontSize() * 35.0f));
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void section_title(const char* title) {
    ImGui::Spacing();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_HeaderActive));
    ImGui::TextUnformatted(title);
    ImGui::PopStyleColor();
    ImGui::Separator();
}

void hint_wrapped(const char* format, ...) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    va_list args;
    va_start(args, format);
    ImGui::TextWrappedV(format, args);
    va_end(args);
    ImGui::PopStyleColor();
}

void help_marker(const char* text) {
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

const char* fitness_unit(evo::FitnessMeasure measure) {
    return measure == evo::FitnessMeasure::BendAngleDeg ? "deg" : "voxels";
}

std::string format_fitness(double fitness, evo::FitnessMeasure measure) {
    char text[64];
    if (fitness <= -1.5) return "invalid";
    if (fitness < 0.0) return "diverged";
    std::snprintf(text, sizeof text, "%.3f %s", fitness, fitness_unit(measure));
    return text;
}

std::string format_duration(double seconds) {
    char text[64];
    if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "-";
    if (seconds < 60.0) {
        std::snprintf(text, sizeof text, "%.1f s", seconds);
    } else if (seconds < 3600.0) {
        const int s = static_cast<int>(seconds);
        std::snprintf(text, sizeof text, "%d min %02d s", s / 60, s % 60);
    } else {
        const int m = static_cast<int>(seconds / 60.0);
        std::snprintf(text, sizeof text, "%d h %02d min", m / 60, m % 60);
    }
    return text;
}

bool area_button(const char* id, ImVec2 size, ImGuiButtonFlags flags) {
    size.x = size.x >= 1.0f ? size.x : 1.0f;  // also maps NaN to 1
    size.y = size.y >= 1.0f ? size.y : 1.0f;
    return ImGui::InvisibleButton(id, size, flags);
}

}  // namespace bhm::app::gui
