#pragma once
// An evolved controller out of the studio and onto another body (issue 44): the shown
// champion's controller CPPN saved as a controller file (controller.json, the format `bhm
// evolve` writes beside champion.json and `bhm robustness --controllers` reads), and any
// controller (a controller file, a run directory's champion controller, or uniform, wave,
// random[:SEED]) painted onto the body shown and replayed. Failures become the status line.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! The controller of the body shown: the controller file's object of the champion it is (a
//! champion of the shown run's history whose file holds one), or of the controller the studio
//! last painted onto it (drive_shown_body with a controller file). nullopt when it has none (a
//! run without evolution.controller coevolve / fixed_body, or a built-in controller).
std::optional<nlohmann::json> shown_controller(Studio& studio);
//! Writes shown_controller as a controller file at path (atomically, its folder created).
bool export_shown_controller(Studio& studio, const std::string& path);
//! Paints the controller `item` (as one item of bhm robustness --controllers) onto the body
//! shown, replacing its own phases and amplitudes, and replays it under the same experiment.
bool drive_shown_body(Studio& studio, const std::string& item);

}  // namespace bhm::app::gui
