#pragma once
// Analysis > Robustness (issue 44): the table of `bhm robustness` in the studio. The picks
// (champions of the shown run, body files, the --controllers list) become a RobustnessRequest
// evaluated on the runner's worker threads; a finished table is exported as the CLI writes it
// (robustness.csv, the heatmap PNG) and a click on a cell shows that body driven by that
// controller in the 3D view. Failures become the status line (one line naming file and field).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! The experiment a table is evaluated under: the shown run's, else the editor's document.
const evo::Experiment& robustness_experiment(const Studio& studio);
//! The --controllers items of a comma-separated list (empty items kept: they are refused).
std::vector<std::string> split_robustness_items(const std::string& text);
//! The request of the current picks: the champions picked (rows first, by generation), then the
//! body files in their order, against every controller of studio.robustness.controllers.
//! Throws std::runtime_error with one line (the file and field, or what is missing).
RobustnessRequest robustness_request(const Studio& studio);
//! Starts the table of the current picks on the worker; false (the status says why) on bad
//! input, with nothing picked, or while a table is running.
bool start_robustness(Studio& studio);
void cancel_robustness(Studio& studio);
//! Per frame (update_studio): the worker's newest state; a job's end told once on the status line.
void update_robustness(Studio& studio);
//! The finished table shown (null while none).
const evo::RobustnessTable* robustness_table(const Studio& studio);
//! Simulates cell (body, controller) of the finished table for the 3D view: the body framed and
//! painted by that controller (evo::robustness_cell_body), under the table's experiment.
bool show_robustness_cell(Studio& studio, std::size_t body, std::size_t controller);
//! robustness.csv and the heatmap PNG of the finished table, the bytes `bhm robustness` writes
//! (evo::robustness_csv, write_robustness_heatmap), written atomically.
bool export_robustness_csv(Studio& studio, const std::string& path);
bool export_robustness_png(Studio& studio, const std::string& path);

}  // namespace bhm::app::gui
