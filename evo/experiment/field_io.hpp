#pragma once
// The field table (experiment_fields.hpp) applied to JSON: reading with type and unknown-key
// checks, writing, and range checks. experiment_io.cpp calls these for the experiment and for each
// material; what is not in the table (materials' name and colour, voxel overrides) it does by
// hand.
#include <map>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment_fields.hpp"
#include "evo/experiment/json_reader.hpp"

namespace bhm::evo {

//! Keys the table does not list, per object path relative to the root ("" = the root itself).
using ExtraKeys = std::map<std::string, std::vector<std::string>>;

//! Reads every field of `fields` that `root` gives into host (the rest keep host's values),
//! reports unknown keys (known: the table's and extra_keys'), wrong types and objects that are
//! not objects, each as root_path + the field's path.
template <class Host>
void read_fields(JsonReader& r, const nlohmann::json& root, const std::string& root_path,
                 std::span<const FieldOf<Host>> fields, Host& host, const ExtraKeys& extra_keys);

//! Writes every field of `fields` into out (objects created along each path).
template <class Host>
void write_fields(const Host& host, std::span<const FieldOf<Host>> fields, nlohmann::json& out);

//! One problem per field whose value is outside the table's range, named prefix + path
//! ("materials[0]" + "poisson_ratio" -> "materials[0].poisson_ratio").
template <class Host>
void check_ranges(const Host& host, std::span<const FieldOf<Host>> fields,
                  const std::string& prefix, const std::string& file,
                  std::vector<Problem>& problems);

}  // namespace bhm::evo
