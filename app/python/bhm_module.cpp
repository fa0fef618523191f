// The `bhm` Python module (pybind11): wiring only. Files are read by evo/, bodies simulated by
// engine/, measured by app/simulation_report; this file converts between them and Python objects.
// The GIL is released while a body is simulated, so Python threads simulate in parallel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/file_kind.hpp"
#include "app/cli/simulation_limits.hpp"
#include "app/cli/simulation_report.hpp"
#include "bhm_version.hpp"
#include "engine/io/text_file.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/simulate.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/phenotype.hpp"

namespace py = pybind11;
using nlohmann::json;
using namespace bhm;

namespace {

// ---- JSON <-> Python ------------------------------------------------------------------------

py::object to_python(const json& j) {
    switch (j.type()) {
        case json::value_t::null:
            return py::none();
        case json::value_t::boolean:
            return py::bool_(j.get<bool>());
        case json::value_t::number_integer:
            return py::int_(j.get<std::int64_t>());
        case json::value_t::number_unsigned:
            return py::int_(j.get<std::uint64_t>());
        case json::value_t::number_float:
            return py::float_(j.get<double>());
        case json::value_t::string:
            return py::str(j.get<std::string>());
        case json::value_t::array: {
            py::list list;
            for (const auto& v : j)
                list.append(to_python(v));
            return list;
        }
        default: {
            py::dict dict;
            for (const auto& [key, v] : j.items())
                dict[py::str(key)] = to_python(v);
            return dict;
        }
    }
}

template <class Json>
py::object to_python_ordered(const Json& j) {
    return to_python(json::parse(j.dump()));
}

// A dict given for a file: through Python's json so that any mapping works, but strict JSON
// (allow_nan=False), so NaN or inf fail here with the argument's name instead of as a raw
// parser error further on (issue 26 N7).
json from_python(const py::handle& object, const std::string& label) {
    std::string text;
    try {
        text = py::module_::import("json")
                   .attr("dumps")(object, py::arg("allow_nan") = false)
                   .cast<std::string>();
    } catch (py::error_already_set& e) {
        const std::string why = e.value() ? py::str(e.value()).cast<std::string>() : e.what();
        if (e.matches(PyExc_TypeError)) throw py::type_error(label + ": " + why);
        throw py::value_error(label + ": not valid JSON: " + why);
    }
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw py::value_error(label + ": not valid JSON: " + evo::without_json_tags(e.what()));
    }
}

// A file argument: str or os.PathLike; anything else is a TypeError naming the argument, not a
// file named after the object's repr (issue 26 N7).
std::string path_arg(const py::handle& arg, const char* name, bool dict_allowed) {
    if (py::isinstance<py::str>(arg)) return arg.cast<std::string>();
    if (py::hasattr(arg, "__fspath__")) {
        const py::object path = py::module_::import("os").attr("fsdecode")(arg);
        return path.cast<std::string>();
    }
    throw py::type_error(std::string(name) + " must be a path (str or os.PathLike)" +
                         (dict_allowed ? " or a dict" : "") + ", got " +
                         py::str(py::type::handle_of(arg).attr("__name__")).cast<std::string>());
}

[[noreturn]] void raise_problems(const std::vector<evo::Problem>& problems) {
    std::string text;
    for (const auto& p : problems)
        text += (text.empty() ? "" : "\n") + p.to_string();
    throw py::value_error(text);
}

// What the material library skipped or found damaged (issue 41 R10), as Python warnings
// (UserWarning), where the command line prints "bhm: warning: ..." on stderr; a warnings filter
// set to "error" makes them exceptions.
void warn_about_library(const evo::Experiment& experiment) {
    for (const auto& line : evo::library_warnings_for(experiment))
        if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 1) != 0) throw py::error_already_set();
}

// An experiment given as a path (str or os.PathLike) or as a dict in the file format.
evo::Experiment experiment_arg(const py::handle& arg) {
    evo::Experiment experiment;
    try {
        if (py::isinstance<py::dict>(arg))
            experiment =
                evo::parse_experiment(from_python(arg, "<experiment dict>"), "<experiment dict>");
        else
            experiment = evo::load_experiment(path_arg(arg, "experiment", true));
    } catch (const evo::ValidationError& e) {
        raise_problems(e.problems);
    }
    warn_about_library(experiment);
    return experiment;
}

evo::Body body_arg(const py::handle& arg, const evo::Experiment& experiment) {
    try {
        std::string label = "<body dict>";
        evo::Body body;
        if (py::isinstance<py::dict>(arg)) {
            body = evo::parse_body(from_python(arg, label), label);
        } else {
            label = path_arg(arg, "body", true);
            body = evo::load_body(label);
        }
        const auto problems = evo::validate_body_against(body, experiment, label);
        if (!problems.empty()) raise_problems(problems);
        return body;
    } catch (const evo::ValidationError& e) {
        raise_problems(e.problems);
    }
}

template <class T>
py::array_t<T> array(const std::vector<T>& values, std::vector<py::ssize_t> shape) {
    py::array_t<T> out(shape);
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

json read_json_file(const std::filesystem::path& path) {
    json j = json::parse(engine::read_text(path.string(), engine::kLargeFileCap), nullptr, false);
    if (j.is_discarded()) throw std::runtime_error(path.string() + ": not valid JSON");
    return j;
}

// ---- the API --------------------------------------------------------------------------------

constexpr auto kSignalCheckInterval = std::chrono::milliseconds(50);
struct SimulationInterrupted {};

std::vector<std::string> validate(const py::handle& path_arg, const py::handle& experiment_arg_) {
    const std::string path = ::path_arg(path_arg, "path", false);
    std::vector<evo::Problem> problems;
    try {
        if (app::detect_file_kind(path) == app::FileKind::Body) {
            const evo::Body body = evo::load_body(path);
            if (!experiment_arg_.is_none()) {
                const auto experiment = experiment_arg(experiment_arg_);
                problems = evo::validate_body_against(body, experiment, path);
            }
        } else {
            warn_about_library(evo::load_experiment(path));
        }
    } catch (const evo::ValidationError& e) {
        problems = e.problems;
    }
    std::vector<std::string> out;
    for (const auto& p : problems)
        out.push_back(p.to_string());
    return out;
}

py::dict simulate(const py::handle& experiment_in, const py::handle& body_in,
                  std::optional<double> seconds, std::uint64_t phase_seed) {
    const evo::Experiment experiment = experiment_arg(experiment_in);
    const evo::Body body = body_arg(body_in, experiment);
    const double total_s = seconds.value_or(evo::evaluation_seconds(experiment));
    if (!std::isfinite(total_s) || !(total_s > 0.0))
        throw py::value_error("seconds must be a positive finite number, got " +
                              engine::format_number(total_s));
    std::shared_ptr<const engine::Model> model;
    try {
        model =
            evo::model_of(experiment, evo::apply_frame_and_overrides(experiment, body), phase_seed);
    } catch (const std::invalid_argument& e) {
        throw py::value_error(std::string("cannot simulate the body: ") + e.what());
    }
    // The same limit as bhm simulate: a duration that would run for hours is refused up front.
    if (const auto problem = app::simulation_seconds_problem(*model, experiment, total_s);
        !problem.empty())
        throw py::value_error("seconds: " + problem);
    const double settle_s = experiment.simulation.settle_s;
    const double record_fps = experiment.simulation.record_fps;
    app::SimulationRecorder recorder(*model, settle_s);
    double wall_s = 0.0;
    bool interrupted = false;
    std::optional<evo::SimulationResult> sim;
    {
        // Physics touches no Python object: other Python threads run meanwhile. Every 50 ms the
        // GIL is taken back for a moment to run Python's signal handlers, so Ctrl-C (or any
        // handler that raises) stops the simulation within a fraction of a second.
        py::gil_scoped_release release;
        const auto start = std::chrono::steady_clock::now();
        auto next_check = start + kSignalCheckInterval;
        try {
            // The studio's and bhm simulate's recipe (evo/evaluate/simulate.hpp), the whole time.
            evo::SimulationOptions options;
            options.seconds = total_s;
            options.end_early = false;
            evo::SimulationHooks hooks;
            hooks.record = [&](const engine::World& w) { recorder.observe(w); };
            hooks.poll = [&](const engine::World&) {
                const auto now = std::chrono::steady_clock::now();
                if (now < next_check) return;
                next_check = now + kSignalCheckInterval;
                py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) throw SimulationInterrupted{};
            };
            sim.emplace(evo::simulate(experiment, model, options, hooks));
        } catch (const SimulationInterrupted&) {
            interrupted = true;  // the Python error (KeyboardInterrupt) is set on this thread
        }
        wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    if (interrupted) throw py::error_already_set();
    const app::RunStats stats = app::run_stats_of(*model, sim->world, wall_s);
    const auto& samples = recorder.samples();
    auto summary = app::summary_json(
        stats, app::summarize_displacements(samples, settle_s, model->voxel_size_m()));
    // The same extra fields as bhm simulate's summary.json.
    summary["settle_s"] = settle_s;
    summary["requested_s"] = total_s;
    summary["record_fps"] = record_fps;
    summary["samples"] = samples.size();
    summary["voxel_size_m"] = model->voxel_size_m();

    const auto n = static_cast<py::ssize_t>(samples.size());
    std::vector<double> t, com, tip;
    for (const auto& s : samples) {
        t.push_back(s.t_s);
        com.insert(com.end(), s.com_m.begin(), s.com_m.end());
        tip.insert(tip.end(), s.tip_m.begin(), s.tip_m.end());
    }
    const engine::Replay& replay = recorder.replay();
    const auto frames = static_cast<py::ssize_t>(replay.frames.size());
    const auto voxels = static_cast<py::ssize_t>(replay.voxel_cell.size());
    std::vector<float> positions, orientations, sizes;
    std::vector<double> frame_t;
    for (const auto& f : replay.frames) {
        frame_t.push_back(f.time_s);
        positions.insert(positions.end(), f.position_m.begin(), f.position_m.end());
        orientations.insert(orientations.end(), f.orientation.begin(), f.orientation.end());
        sizes.insert(sizes.end(), f.size_m.begin(), f.size_m.end());
    }
    py::dict out;
    out["summary"] = to_python_ordered(summary);
    out["t"] = array(t, {n});
    out["com"] = array(com, {n, 3});
    out["tip"] = array(tip, {n, 3});
    out["frame_t"] = array(frame_t, {frames});
    out["positions"] = array(positions, {frames, voxels, 3});
    out["orientations"] = array(orientations, {frames, voxels, 4});
    out["sizes"] = array(sizes, {frames, voxels, 3});
    out["voxel_cell"] = array(replay.voxel_cell, {voxels});
    out["voxel_material"] = array(replay.voxel_material, {voxels});
    out["voxel_fixed"] = array(replay.voxel_fixed, {voxels});
    out["lattice"] = py::make_tuple(replay.nx, replay.ny, replay.nz);
    return out;
}

py::object decode(const py::handle& experiment_in, const py::handle& genome_in) {
    const evo::Experiment experiment = experiment_arg(experiment_in);
    json genome_json;
    if (py::isinstance<py::str>(genome_in)) {
        genome_json = json::parse(genome_in.cast<std::string>(), nullptr, false);
        if (genome_json.is_discarded()) throw py::value_error("genome_json is not valid JSON");
    } else {
        genome_json = from_python(genome_in, "genome_json");
    }
    // A whole champion file holds the genome under "genome".
    if (genome_json.is_object() && genome_json.contains("genome"))
        genome_json = genome_json["genome"];
    try {
        const evo::Genome genome =
            evo::genome_from_json(genome_json, experiment.evolution.cppn.weight_range);
        const evo::Developer developer(experiment);
        return to_python(evo::body_to_json(developer.develop(genome).body));
    } catch (const std::invalid_argument& e) {
        throw py::value_error(std::string("cannot decode the genome: ") + e.what());
    } catch (const json::exception& e) {
        throw py::value_error(std::string("cannot decode the genome: ") +
                              evo::without_json_tags(e.what()));
    }
}

// fitness.csv as one numpy column per header field.
py::dict fitness_columns(const std::filesystem::path& path) {
    std::istringstream in(engine::read_text(path.string(), engine::kLargeFileCap));
    std::string line;
    if (!std::getline(in, line)) throw std::runtime_error(path.string() + ": empty file");
    std::vector<std::string> names;
    {
        std::stringstream header(line);
        std::string name;
        while (std::getline(header, name, ','))
            names.push_back(name);
    }
    std::vector<std::vector<double>> columns(names.size());
    int row = 1;
    while (std::getline(in, line)) {
        ++row;
        if (line.empty()) continue;
        std::stringstream cells(line);
        std::string cell;
        std::size_t c = 0;
        for (; std::getline(cells, cell, ','); ++c) {
            if (c >= names.size())
                throw std::runtime_error(path.string() + ": row " + std::to_string(row) +
                                         " has more cells than the header");
            std::size_t used = 0;
            double value = 0.0;
            try {
                value = std::stod(cell, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != cell.size())
                throw std::runtime_error(path.string() + ": row " + std::to_string(row) +
                                         ", column " + names[c] + ": not a number '" + cell + "'");
            columns[c].push_back(value);
        }
        if (c != names.size())
            throw std::runtime_error(path.string() + ": row " + std::to_string(row) + " has " +
                                     std::to_string(c) + " cells, the header " +
                                     std::to_string(names.size()));
    }
    py::dict out;
    for (std::size_t c = 0; c < names.size(); ++c)
        out[py::str(names[c])] = array(columns[c], {static_cast<py::ssize_t>(columns[c].size())});
    return out;
}

py::dict load_run(const py::handle& dir_arg) {
    namespace fs = std::filesystem;
    const fs::path dir(path_arg(dir_arg, "run_dir", false));
    if (!fs::is_directory(dir)) throw py::value_error(dir.string() + ": not a run directory");
    const json run = read_json_file(dir / "run.json");
    py::dict out;
    out["run_dir"] = dir.string();
    out["fitness"] = fitness_columns(dir / "fitness.csv");
    // population.csv (the last generation's members with their volume): runs before it lack it.
    if (fs::exists(dir / "population.csv"))
        out["population"] = fitness_columns(dir / "population.csv");
    out["experiment"] = to_python(run.value("experiment", json::object()));
    out["rule_changes"] = to_python(run.value("rule_changes", json::array()));
    out["seed"] = to_python(run.value("seed", json()));
    out["bhm_version"] = to_python(run.value("bhm_version", json()));
    py::list champions;
    std::vector<fs::path> files;
    if (fs::is_directory(dir / "champions"))
        for (const auto& entry : fs::directory_iterator(dir / "champions"))
            if (entry.path().extension() == ".json") files.push_back(entry.path());
    std::sort(files.begin(), files.end());  // gen-NNNNN.json: generation order
    for (const auto& f : files)
        champions.append(to_python(read_json_file(f)));
    out["champions"] = champions;
    out["champion"] = fs::exists(dir / "champion.json")
                          ? to_python(read_json_file(dir / "champion.json"))
                          : py::none();
    return out;
}

}  // namespace

PYBIND11_MODULE(bhm, m) {
    m.doc() =
        "BHM Studio: validate experiment and body files, simulate bodies, decode genomes "
        "and read evolution run directories (docs: README, 'Python module').";
    m.attr("__version__") = BHM_VERSION_STRING;
    // Anything else that escapes (a damaged run directory, say) reads without library tags.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const nlohmann::json::exception& e) {
            PyErr_SetString(PyExc_ValueError, evo::without_json_tags(e.what()).c_str());
        }
    });
    m.def("validate", &validate, py::arg("path"), py::arg("experiment") = py::none(),
          "Problems of an experiment or body file as 'file:field: message' strings (empty when "
          "valid). A body is also checked against `experiment` (path or dict) when given.");
    m.def("simulate", &simulate, py::arg("experiment"), py::arg("body"),
          py::arg("seconds") = py::none(), py::arg("phase_seed") = 0,
          "Simulates a body (path or dict) under an experiment (path or dict) for seconds "
          "(default settle_s + evaluate_s), without holding the GIL. Returns a dict: 'summary' "
          "(the fields of bhm simulate's summary.json), 't' (N,), 'com' and 'tip' (N, 3) in "
          "metres at record_fps, 'frame_t' (F,), 'positions' and 'sizes' (F, V, 3), "
          "'orientations' (F, V, 4, w x y z), 'voxel_cell', 'voxel_material', 'voxel_fixed' (V,) "
          "and 'lattice' (nx, ny, nz).");
    m.def("decode", &decode, py::arg("experiment"), py::arg("genome_json"),
          "The framed, workspace-sized body (a body-file dict) that a CPPN genome (dict, JSON "
          "text, or a champion dict holding 'genome') develops into under the experiment.");
    m.def("load_run", &load_run, py::arg("run_dir"),
          "A run directory of bhm evolve: 'fitness' (fitness.csv as numpy columns), "
          "'population' (population.csv as numpy columns, where the run wrote one), "
          "'champions' (champions/gen-*.json in generation order), 'champion', 'experiment', "
          "'rule_changes', 'seed', 'bhm_version'.");
}
