#pragma once
// One function per panel; each draws into the current ImGui window (the layout places windows).
#include "app/gui/studio.hpp"

namespace bhm::app::gui {

class ViewRenderer;
class WelcomeThumbnails;

void draw_menu_bar(Studio& studio);
void draw_experiment_panel(Studio& studio);
void draw_constraints_panel(Studio& studio);
void draw_files_panel(Studio& studio);
void draw_export_panel(Studio& studio, ViewRenderer& renderer);
void draw_run_panel(Studio& studio);
void draw_fitness_panel(Studio& studio);
void draw_population_panel(Studio& studio);
void draw_analysis_panel(Studio& studio);
//! The Analysis panel's Calibrate tab (panel_calibrate.cpp).
void draw_calibrate_panel(Studio& studio);
//! Analysis > FEM: Verify in FEM for the body shown, its progress and result (panel_verify.cpp).
void draw_verify_panel(Studio& studio);
//! Analysis > Robustness: bodies against controllers, as bhm robustness (panel_robustness.cpp).
void draw_robustness_panel(Studio& studio);
void draw_replay_panel(Studio& studio);
void draw_viewport_panel(Studio& studio, ViewRenderer& renderer);
void draw_help_window(Studio& studio);
//! The first start's welcome (welcome.hpp): the presets with thumbnails, the quick demo first,
//! and the 3D view's legend. Renders missing thumbnails (UI thread).
void draw_welcome_window(Studio& studio, ViewRenderer& renderer, WelcomeThumbnails& thumbnails);
void draw_status_bar(Studio& studio);
//! The modal dialogs of the questions of actions/unsaved_guard.hpp (buttons recorded for scripts:
//! "Save changes", "Discard changes", "Cancel", "Finish generation, then quit", "Quit now").
void draw_confirm_dialogs(Studio& studio);

//! A table cell with the exploit flags' letters in red (E escaped, D detached motion, T
//! tentacle), their measures on hover; recorded under `widget` for scripts.
void exploit_cell(Studio& studio, const evo::ExploitReport& report, const std::string& widget);

}  // namespace bhm::app::gui
