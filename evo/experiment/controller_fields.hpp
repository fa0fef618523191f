#pragma once
// evolution.controller in an experiment file (issue 44; docs/experiment-format.md, "Controllers"):
// the mode is a row of the field table (experiment_fields.cpp); its body and its list of
// controllers, structured values, are read, checked and written here.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"

namespace bhm::evo {

//! Reads evolution.controller.body (a body file's object, inline) and .controllers (each a
//! built-in name "uniform" | "wave" | "random", {"builtin": "random", "seed": n}, a controller
//! file's path relative to the experiment file, or {"name": ..., "controller": {...}} inline).
//! `evolution` is the experiment's "evolution" object; experiment_path resolves file paths.
void parse_controller_settings(JsonReader& r, const nlohmann::json& evolution,
                               const std::string& experiment_path, ControllerSettings& out);

//! The problems of the mode against its fields: fixed_body needs a body that fits the workspace,
//! fixed_controllers at least one controller; neither is read in another mode.
std::vector<Problem> controller_problems(const Experiment& experiment, const std::string& file);

//! Writes body and controllers into evolution.controller (inline, so that run.json carries them);
//! removes evolution.controller altogether in mode none with nothing set.
void write_controller_settings(const ControllerSettings& settings, nlohmann::json& evolution);

}  // namespace bhm::evo
