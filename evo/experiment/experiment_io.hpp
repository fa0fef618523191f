#pragma once
// Reading, validating and writing experiment and body files (docs/experiment-format.md).
// Validation reports every problem, one per line, as "file:field: message".
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct Problem {
    std::string file;
    std::string field;  //!< JSON path such as "materials[1].poisson_ratio"
    std::string message;
    std::string to_string() const { return file + ":" + field + ": " + message; }
};

//! Thrown by the loaders when a file is missing, unreadable or invalid; holds every problem found.
struct ValidationError : std::runtime_error {
    explicit ValidationError(std::vector<Problem> problems);
    std::vector<Problem> problems;
};

//! Parses and validates an experiment; throws ValidationError listing every problem.
Experiment load_experiment(const std::string& path);
Experiment parse_experiment(const nlohmann::json& json, const std::string& file_label);
//! The material library's warnings (entries skipped, files damaged: MaterialLibrary::warnings())
//! when `experiment` takes a material from it, else none: what a front end says beside an
//! experiment it loaded, which still loads unless it names a damaged file (issue 41 R10).
std::vector<std::string> library_warnings_for(const Experiment& experiment);
//! Validates without throwing; the list is empty when the experiment is valid.
std::vector<Problem> validate_experiment(const Experiment& experiment,
                                         const std::string& file_label);

nlohmann::json experiment_to_json(const Experiment& experiment);
//! Writes atomically (temp file + rename); throws std::runtime_error naming the path.
void save_experiment(const std::string& path, const Experiment& experiment);

//! Body file: {"size": [nx, ny, nz], "layers": ["...", ...]} (z layers bottom first, x fastest),
//! optionally "fibres": ["...", ...] in the same layout, 'x', 'y' or 'z' a muscle voxel's own
//! fibre axis and '.' its material's (Body::fibre; written only when a cell has its own axis).
Body load_body(const std::string& path);
Body parse_body(const nlohmann::json& json, const std::string& file_label);
nlohmann::json body_to_json(const Body& body);
void save_body(const std::string& path, const Body& body);
//! Problems of a body against an experiment (size larger than the workspace, unknown material...).
std::vector<Problem> validate_body_against(const Body& body, const Experiment& experiment,
                                           const std::string& file_label);

struct ExperimentAndBody {
    Experiment experiment;
    std::optional<Body> body;
};
//! Loads an experiment and, when body_path is not empty, a body checked against it; reads both
//! before giving up and throws one ValidationError listing every problem of both files.
ExperimentAndBody load_experiment_and_body(const std::string& experiment_path,
                                           const std::string& body_path);

//! engine::write_file_atomically (engine/io/atomic_file.hpp): every write, the fsync and the close
//! checked, then a rename; on failure the old file is untouched. Throws std::runtime_error.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace bhm::evo
