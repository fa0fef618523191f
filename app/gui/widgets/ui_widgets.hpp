#pragma once
// Small widgets shared by the panels: buttons that scripts can find, numeric fields with units that
// commit through the document's validation, section titles and tooltips.
#include <string>

#include <imgui.h>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! Records the last item's rectangle under `name` (scripts click it by that name).
void record_widget(Studio& studio, const std::string& name);
//! A full-width one-line text box with a grey hint while empty, recorded under `id` without its
//! leading "##" (ids are "##name"); `value` changes as it is typed.
void hinted_text_field(Studio& studio, const char* id, const char* hint, std::string& value);
//! A button recorded under its label (without the "##id" part).
bool tracked_button(Studio& studio, const char* label, ImVec2 size = ImVec2(0, 0));
//! ImGui::InvisibleButton with each side at least one pixel: in a tiny window the space left for a
//! plot or the 3D view can be zero or negative, which ImGui asserts on (the studio aborted).
bool area_button(const char* id, ImVec2 size, ImGuiButtonFlags flags = 0);

//! Field editors bound to studio.draft. They return true when an edit is complete (Enter, focus
//! left, a drag released, a box ticked): the caller then calls commit_draft
//! (actions/draft_edits.hpp) with a label.
//! The unit is printed after the field; the hint (ranges, paper values) shows on hover.
bool field_double(const char* label, double& value, const char* unit, const char* hint,
                  const char* format = "%.6g");
bool field_int(const char* label, int& value, const char* unit, const char* hint);
bool field_u64(const char* label, std::uint64_t& value, const char* hint);
bool field_bool(const char* label, bool& value, const char* hint);
bool field_text(const char* label, std::string& value, const char* hint, bool multiline = false);

//! A bold-ish section title with a separator line.
void section_title(const char* title);
//! A tooltip of `text` wrapped at 35 font sizes (at most the display's width less 40 px): a
//! paragraph (a preset's description) stays on the screen instead of one line running off it.
void wrapped_tooltip(const std::string& text);
//! A hint in the disabled colour, wrapped at the window's right edge: a narrow tile (the Analysis
//! tile at 400 px) shows every word instead of cutting the line (ImGui::TextDisabled never wraps).
void hint_wrapped(const char* format, ...) IM_FMTARGS(1);
//! "(?)" marker with a tooltip.
void help_marker(const char* text);
//! Width for a field so the unit fits after it.
float field_width();
//! Centres the next window on the display at width_em x height_em font sizes, kept 40 x 60 px
//! inside the display (the welcome, the help and the file dialog).
void centre_next_window(float width_em, float height_em, ImGuiCond condition);

//! "12.34 deg" / "3.21 voxels": the fitness with the unit of its measure.
std::string format_fitness(double fitness, evo::FitnessMeasure measure);
const char* fitness_unit(evo::FitnessMeasure measure);
//! "1 h 02 min", "3 min 05 s", "12.3 s".
std::string format_duration(double seconds);

}  // namespace bhm::app::gui
