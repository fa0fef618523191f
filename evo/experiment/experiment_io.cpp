// Experiment files: parsing (types, unknown keys, defaults) is separate from validation (ranges and
// cross-field rules) so the studio can validate an experiment it edited in memory.
#include "evo/experiment/experiment_io.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"
#include "engine/limits.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/material_library.hpp"

namespace bhm::evo {

namespace {

using nlohmann::json;

// Limits: a lattice of 4 million cells needs ~1 GB of engine state and links; more is refused.
constexpr int kMaxDimension = 255;
constexpr long long kMaxCells = 4'000'000;
constexpr int kMaxMaterials = 9;  // body layers use one character '1'..'9' per voxel

std::string problems_summary(const std::vector<Problem>& problems) {
    std::string s;
    for (size_t i = 0; i < problems.size(); ++i) {
        if (i) s += "\n";
        s += problems[i].to_string();
    }
    return s;
}

std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

std::vector<std::string> face_names() {
    return {kFaceNames.begin(), kFaceNames.end()};
}

std::string read_text(const std::string& path) {
    try {
        return engine::read_text(path, engine::kTextFileCap);
    } catch (const engine::FileReadError& e) {
        throw ValidationError({{path, "(file)", e.reason()}});
    }
}

json parse_json_text(const std::string& text, const std::string& path) {
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        // nlohmann's message starts with "[json.exception.parse_error.101] parse error at ...";
        // numbers beyond double's range (1e999) arrive as out_of_range.406.
        throw ValidationError({{path, "(json)", without_json_tags(e.what())}});
    }
}

void read_array3(JsonReader& r, const json& obj, const std::string& key, const std::string& path,
                 std::array<int, 3>& out) {
    auto it = obj.find(key);
    if (it == obj.end()) return;
    const std::string field = JsonReader::join(path, key);
    if (!it->is_array() || it->size() != 3) {
        r.problem(field, "expected an array of 3 integers [x, y, z]");
        return;
    }
    std::array<int, 3> v{};
    for (int i = 0; i < 3; ++i) {
        const json& e = (*it)[i];
        if (!e.is_number_integer() && !e.is_number_unsigned()) {
            r.problem(field + "[" + std::to_string(i) + "]",
                      "expected an integer, got " + JsonReader::type_name(e));
            return;
        }
        long long x = e.get<long long>();
        if (x < -1'000'000'000LL || x > 1'000'000'000LL) {
            r.problem(field + "[" + std::to_string(i) + "]", "is out of range");
            return;
        }
        v[i] = static_cast<int>(x);
    }
    out = v;
}

// base: the defaults of the fields the object does not give (a library material's values, or
// MaterialEntry's own).
MaterialEntry parse_material(JsonReader& r, const json& m, const std::string& path,
                             const MaterialEntry& base) {
    MaterialEntry entry = base;
    r.check_keys(m, path,
                 {"name", "library", "youngs_modulus_pa", "density_kg_m3", "poisson_ratio",
                  "cte_per_c", "static_friction", "dynamic_friction", "color"});
    entry.name = r.string(m, "name", path, base.name);
    auto& p = entry.physics;
    p.youngs_modulus_pa = r.number(m, "youngs_modulus_pa", path, p.youngs_modulus_pa);
    p.density_kg_m3 = r.number(m, "density_kg_m3", path, p.density_kg_m3);
    p.poisson_ratio = r.number(m, "poisson_ratio", path, p.poisson_ratio);
    p.cte_per_c = r.number(m, "cte_per_c", path, p.cte_per_c);
    p.static_friction = r.number(m, "static_friction", path, p.static_friction);
    p.dynamic_friction = r.number(m, "dynamic_friction", path, p.dynamic_friction);
    if (auto it = m.find("color"); it != m.end()) {
        const std::string field = JsonReader::join(path, "color");
        if (!it->is_array() || it->size() != 3) {
            r.problem(field, "expected [r, g, b] with each component in [0, 1]");
        } else {
            for (int i = 0; i < 3; ++i) {
                const json& c = (*it)[i];
                if (!c.is_number() || !std::isfinite(c.get<double>()) || c.get<double>() < 0 ||
                    c.get<double>() > 1) {
                    r.problem(field + "[" + std::to_string(i) + "]", "must be a number in [0, 1]");
                    continue;
                }
                entry.color[i] = c.get<float>();
            }
            entry.has_color = true;
        }
    }
    return entry;
}

// A slot naming a library material ("library": "<id>") takes the library's values for the fields
// it leaves out. The library is read only when a field is left out: a file bhm wrote holds every
// value and loads without it. A value the library has no source for must be given by the slot.
class LibraryFill {
  public:
    MaterialEntry base_for(JsonReader& r, const json& m, const std::string& path,
                           double temperature_amplitude_c) {
        MaterialEntry base;
        const auto it = m.find("library");
        if (it == m.end()) return base;
        const std::string field = JsonReader::join(path, "library");
        if (!it->is_string() || it->get<std::string>().empty()) {
            r.problem(field, "expected the id of a library material (a file name of "
                             "assets/materials/ without .json), e.g. \"ecoflex-00-30\"");
            return base;
        }
        base.library = it->get<std::string>();
        static const char* kFilled[] = {"name", "youngs_modulus_pa", "density_kg_m3",
                                        "poisson_ratio", "cte_per_c", "static_friction",
                                        "dynamic_friction", "color"};
        bool missing = false;
        for (const char* key : kFilled)
            missing = missing || !m.contains(key);
        if (!missing) return base;
        const MaterialLibrary* library = load(r, field);
        if (!library) return base;
        const LibraryMaterial* lm = library->find(base.library);
        if (!lm) {
            std::string message = "'" + base.library + "' is not in the material library " +
                                  library->dir;
            if (auto guess = closest_match(base.library, library->ids()); !guess.empty())
                message += " (did you mean '" + guess + "'?)";
            r.problem(field, message + "; `bhm materials` lists it");
            return base;
        }
        apply_library_material(*lm, temperature_amplitude_c, base);
        auto require = [&](const char* key, bool sourced) {
            if (!sourced && !m.contains(key))
                r.problem(JsonReader::join(path, key),
                          "is required: library material '" + lm->id +
                              "' has no sourced value for it (docs/materials-format.md)");
        };
        require("poisson_ratio", lm->poisson_ratio.has_value());
        require("density_kg_m3", lm->density_kg_m3.has_value());
        if (lm->active)
            require("cte_per_c",
                    lm->contraction_strain.has_value() && temperature_amplitude_c > 0);
        return base;
    }

  private:
    const MaterialLibrary* load(JsonReader& r, const std::string& field) {
        if (!tried_) {
            tried_ = true;
            try {
                library_ = load_material_library(default_material_library_dir());
            } catch (const ValidationError& e) {
                error_ = e.problems.empty() ? std::string(e.what()) : e.problems[0].to_string();
            }
        }
        if (!library_)
            r.problem(field, "the values it leaves out cannot be filled: the material library "
                             "did not load (" + error_ + ")");
        return library_ ? &*library_ : nullptr;
    }
    bool tried_ = false;
    std::optional<MaterialLibrary> library_;
    std::string error_;
};

void parse_boundary(JsonReader& r, const json& b, const std::string& path, Boundary& out) {
    r.check_keys(b, path, {"faces", "enclosure", "voxel_overrides"});
    if (const json* faces = r.object(b, "faces", path)) {
        const std::string fpath = JsonReader::join(path, "faces");
        r.check_keys(*faces, fpath, face_names());
        for (int f = 0; f < 6; ++f)
            out.faces[f] = static_cast<BoundaryKind>(r.choice(
                *faces, kFaceNames[f], fpath, {"free", "fixed"}, static_cast<int>(out.faces[f])));
    }
    if (const json* enc = r.object(b, "enclosure", path)) {
        const std::string epath = JsonReader::join(path, "enclosure");
        r.check_keys(*enc, epath, {"thickness_voxels", "material"});
        if (const json* t = r.object(*enc, "thickness_voxels", epath)) {
            const std::string tpath = JsonReader::join(epath, "thickness_voxels");
            r.check_keys(*t, tpath, face_names());
            for (int f = 0; f < 6; ++f)
                out.enclosure_thickness[f] = static_cast<int>(r.integer(
                    *t, kFaceNames[f], tpath, out.enclosure_thickness[f], 0, kMaxDimension));
        }
        out.enclosure_material =
            static_cast<int>(r.integer(*enc, "material", epath, out.enclosure_material, 0, 255));
    }
    if (auto it = b.find("voxel_overrides"); it != b.end()) {
        const std::string opath = JsonReader::join(path, "voxel_overrides");
        if (!it->is_array()) {
            r.problem(opath, "expected an array of {\"voxel\": [x, y, z], \"kind\": ...}");
            return;
        }
        for (size_t i = 0; i < it->size(); ++i) {
            const json& o = (*it)[i];
            const std::string ipath = opath + "[" + std::to_string(i) + "]";
            if (!o.is_object()) {
                r.problem(ipath, "expected an object, got " + JsonReader::type_name(o));
                continue;
            }
            r.check_keys(o, ipath, {"voxel", "kind", "material"});
            VoxelOverride v;
            if (!o.contains("voxel")) r.problem(JsonReader::join(ipath, "voxel"), "is required");
            read_array3(r, o, "voxel", ipath, v.voxel);
            if (!o.contains("kind")) r.problem(JsonReader::join(ipath, "kind"), "is required");
            v.kind = static_cast<OverrideKind>(
                r.choice(o, "kind", ipath, {"fixed", "empty", "material"}, 0));
            v.material = static_cast<int>(r.integer(o, "material", ipath, 0, 0, 255));
            if (v.kind == OverrideKind::Material && !o.contains("material"))
                r.problem(JsonReader::join(ipath, "material"),
                          "is required when kind is \"material\"");
            out.voxel_overrides.push_back(v);
        }
    }
}

}  // namespace

ValidationError::ValidationError(std::vector<Problem> list)
    : std::runtime_error(problems_summary(list)), problems(std::move(list)) {}

Experiment parse_experiment(const json& root, const std::string& file) {
    std::vector<Problem> problems;
    JsonReader r(file, problems);
    Experiment e;
    if (!root.is_object()) throw ValidationError({{file, "(root)", "expected a JSON object"}});
    r.check_keys(root, "",
                 {"format_version", "name", "description", "workspace", "materials", "actuation",
                  "environment", "boundary", "simulation", "fitness", "evolution"});
    r.integer(root, "format_version", "", 1, 1, 1);
    e.name = r.string(root, "name", "", "");
    e.description = r.string(root, "description", "", "");

    if (const json* w = r.object(root, "workspace", "")) {
        r.check_keys(*w, "workspace", {"size", "voxel_size_m"});
        read_array3(r, *w, "size", "workspace", e.workspace_size);
        e.voxel_size_m = r.number(*w, "voxel_size_m", "workspace", e.voxel_size_m);
    }

    // Actuation first: a library's active tissue sets cte_per_c from its amplitude.
    if (const json* a = r.object(root, "actuation", "")) {
        r.check_keys(*a, "actuation",
                     {"frequency_hz", "temperature_amplitude_c", "phase", "phase_offset_rad"});
        e.actuation.frequency_hz =
            r.number(*a, "frequency_hz", "actuation", e.actuation.frequency_hz);
        e.actuation.temperature_amplitude_c = r.number(*a, "temperature_amplitude_c", "actuation",
                                                       e.actuation.temperature_amplitude_c);
        e.actuation.phase =
            static_cast<PhaseMode>(r.choice(*a, "phase", "actuation", {"uniform", "random"}, 0));
        e.actuation.phase_offset_rad =
            r.number(*a, "phase_offset_rad", "actuation", e.actuation.phase_offset_rad);
    }

    if (auto it = root.find("materials"); it != root.end()) {
        if (!it->is_array()) {
            r.problem("materials", "expected an array of materials");
        } else {
            LibraryFill fill;
            for (size_t i = 0; i < it->size(); ++i) {
                const std::string path = "materials[" + std::to_string(i) + "]";
                if (!(*it)[i].is_object()) {
                    r.problem(path, "expected an object, got " + JsonReader::type_name((*it)[i]));
                    continue;
                }
                const MaterialEntry base = fill.base_for(r, (*it)[i], path,
                                                         e.actuation.temperature_amplitude_c);
                e.materials.push_back(parse_material(r, (*it)[i], path, base));
            }
        }
    } else {
        r.problem("materials", "is required (at least one material)");
    }

    if (const json* env = r.object(root, "environment", "")) {
        r.check_keys(*env, "environment", {"gravity_m_s2", "floor"});
        e.environment.gravity_m_s2 =
            r.number(*env, "gravity_m_s2", "environment", e.environment.gravity_m_s2);
        e.environment.floor = r.boolean(*env, "floor", "environment", e.environment.floor);
    }

    if (const json* b = r.object(root, "boundary", ""))
        parse_boundary(r, *b, "boundary", e.boundary);

    if (const json* s = r.object(root, "simulation", "")) {
        auto& sim = e.simulation;
        r.check_keys(
            *s, "simulation",
            {"settle_s", "evaluate_s", "dt_fraction", "bond_damping_ratio", "global_damping_ratio",
             "collision_damping_ratio", "record_fps", "end_when_periodic", "periodic_tolerance"});
        sim.settle_s = r.number(*s, "settle_s", "simulation", sim.settle_s);
        sim.evaluate_s = r.number(*s, "evaluate_s", "simulation", sim.evaluate_s);
        sim.dt_fraction = r.number(*s, "dt_fraction", "simulation", sim.dt_fraction);
        sim.bond_damping_ratio =
            r.number(*s, "bond_damping_ratio", "simulation", sim.bond_damping_ratio);
        sim.global_damping_ratio =
            r.number(*s, "global_damping_ratio", "simulation", sim.global_damping_ratio);
        sim.collision_damping_ratio =
            r.number(*s, "collision_damping_ratio", "simulation", sim.collision_damping_ratio);
        sim.record_fps = r.number(*s, "record_fps", "simulation", sim.record_fps);
        sim.end_when_periodic =
            r.boolean(*s, "end_when_periodic", "simulation", sim.end_when_periodic);
        sim.periodic_tolerance =
            r.number(*s, "periodic_tolerance", "simulation", sim.periodic_tolerance);
    }

    if (const json* f = r.object(root, "fitness", "")) {
        r.check_keys(*f, "fitness", {"measure", "constraints", "minimize_active_voxels"});
        e.fitness.measure = static_cast<FitnessMeasure>(
            r.choice(*f, "measure", "fitness", {kFitnessNames.begin(), kFitnessNames.end()},
                     static_cast<int>(e.fitness.measure)));
        e.fitness.minimize_active_voxels =
            r.boolean(*f, "minimize_active_voxels", "fitness", e.fitness.minimize_active_voxels);
        if (const json* c = r.object(*f, "constraints", "fitness")) {
            auto& con = e.fitness.constraints;
            const std::string cpath = "fitness.constraints";
            r.check_keys(*c, cpath,
                         {"attached_to_fixed_face", "min_fill_fraction", "min_active_voxels",
                          "reject_escaped", "reject_detached_motion", "reject_tentacle"});
            con.attached_to_fixed_face =
                r.boolean(*c, "attached_to_fixed_face", cpath, con.attached_to_fixed_face);
            con.min_fill_fraction = r.number(*c, "min_fill_fraction", cpath, con.min_fill_fraction);
            con.min_active_voxels =
                static_cast<int>(r.integer(*c, "min_active_voxels", cpath, con.min_active_voxels,
                                           -1'000'000'000LL, 1'000'000'000LL));
            con.reject_escaped = r.boolean(*c, "reject_escaped", cpath, con.reject_escaped);
            con.reject_detached_motion =
                r.boolean(*c, "reject_detached_motion", cpath, con.reject_detached_motion);
            con.reject_tentacle = r.boolean(*c, "reject_tentacle", cpath, con.reject_tentacle);
        }
    }

    if (const json* ev = r.object(root, "evolution", "")) {
        auto& evo = e.evolution;
        const std::string path = "evolution";
        r.check_keys(*ev, path,
                     {"algorithm", "population", "generations", "wall_budget_h",
                      "max_neutral_retries", "seed", "threads", "crossover_rate", "cppn", "neat",
                      "novelty"});
        constexpr long long kBig = 1'000'000'000LL;
        evo.algorithm = static_cast<Algorithm>(
            r.choice(*ev, "algorithm", path, {kAlgorithmNames.begin(), kAlgorithmNames.end()},
                     static_cast<int>(evo.algorithm)));
        evo.population =
            static_cast<int>(r.integer(*ev, "population", path, evo.population, -kBig, kBig));
        evo.generations =
            static_cast<int>(r.integer(*ev, "generations", path, evo.generations, -kBig, kBig));
        evo.wall_budget_h = r.number(*ev, "wall_budget_h", path, evo.wall_budget_h);
        evo.max_neutral_retries = static_cast<int>(
            r.integer(*ev, "max_neutral_retries", path, evo.max_neutral_retries, -kBig, kBig));
        if (auto it = ev->find("seed"); it != ev->end()) {
            if (it->is_number_unsigned())
                evo.seed = it->get<std::uint64_t>();
            else if (it->is_number_integer())
                r.problem("evolution.seed", "must be a non-negative integer");
            else
                r.problem("evolution.seed",
                          "expected an integer, got " + JsonReader::type_name(*it));
        }
        evo.threads = static_cast<int>(r.integer(*ev, "threads", path, evo.threads, -kBig, kBig));
        evo.crossover_rate = r.number(*ev, "crossover_rate", path, evo.crossover_rate);
        if (const json* c = r.object(*ev, "cppn", path)) {
            auto& cp = evo.cppn;
            const std::string cpath = "evolution.cppn";
            r.check_keys(
                *c, cpath,
                {"min_hidden_nodes", "max_hidden_nodes", "weight_range", "mutation_weight_sigma",
                 "material_outputs"});
            cp.min_hidden_nodes = static_cast<int>(
                r.integer(*c, "min_hidden_nodes", cpath, cp.min_hidden_nodes, -kBig, kBig));
            cp.max_hidden_nodes = static_cast<int>(
                r.integer(*c, "max_hidden_nodes", cpath, cp.max_hidden_nodes, -kBig, kBig));
            cp.weight_range = r.number(*c, "weight_range", cpath, cp.weight_range);
            cp.mutation_weight_sigma =
                r.number(*c, "mutation_weight_sigma", cpath, cp.mutation_weight_sigma);
            cp.material_outputs = static_cast<MaterialOutputs>(
                r.choice(*c, "material_outputs", cpath,
                         {kMaterialOutputsNames.begin(), kMaterialOutputsNames.end()},
                         static_cast<int>(cp.material_outputs)));
        }
        if (const json* n = r.object(*ev, "neat", path)) {
            auto& ne = evo.neat;
            const std::string npath = "evolution.neat";
            r.check_keys(*n, npath,
                         {"c1", "c2", "c3", "normalize_by_size", "compatibility_threshold",
                          "target_species",
                          "threshold_step", "survival_fraction", "elitism",
                          "stagnation_generations", "crossover_rate"});
            ne.c1 = r.number(*n, "c1", npath, ne.c1);
            ne.c2 = r.number(*n, "c2", npath, ne.c2);
            ne.c3 = r.number(*n, "c3", npath, ne.c3);
            ne.normalize_by_size =
                r.boolean(*n, "normalize_by_size", npath, ne.normalize_by_size);
            ne.compatibility_threshold =
                r.number(*n, "compatibility_threshold", npath, ne.compatibility_threshold);
            ne.target_species = static_cast<int>(
                r.integer(*n, "target_species", npath, ne.target_species, -kBig, kBig));
            ne.threshold_step = r.number(*n, "threshold_step", npath, ne.threshold_step);
            ne.survival_fraction = r.number(*n, "survival_fraction", npath, ne.survival_fraction);
            ne.elitism = static_cast<int>(r.integer(*n, "elitism", npath, ne.elitism, -kBig, kBig));
            ne.stagnation_generations = static_cast<int>(r.integer(
                *n, "stagnation_generations", npath, ne.stagnation_generations, -kBig, kBig));
            ne.crossover_rate = r.number(*n, "crossover_rate", npath, ne.crossover_rate);
        }
        if (const json* n = r.object(*ev, "novelty", path)) {
            auto& nv = evo.novelty;
            const std::string npath = "evolution.novelty";
            r.check_keys(*n, npath, {"k", "archive_threshold", "archive_capacity", "with_fitness"});
            nv.k = static_cast<int>(r.integer(*n, "k", npath, nv.k, -kBig, kBig));
            nv.archive_threshold = r.number(*n, "archive_threshold", npath, nv.archive_threshold);
            nv.archive_capacity = static_cast<int>(
                r.integer(*n, "archive_capacity", npath, nv.archive_capacity, -kBig, kBig));
            nv.with_fitness = r.boolean(*n, "with_fitness", npath, nv.with_fitness);
        }
    }

    auto more = validate_experiment(e, file);
    problems.insert(problems.end(), more.begin(), more.end());
    if (!problems.empty()) throw ValidationError(std::move(problems));
    return e;
}

std::vector<Problem> validate_experiment(const Experiment& e, const std::string& file) {
    std::vector<Problem> problems;
    auto bad = [&](const std::string& field, const std::string& message) {
        problems.push_back({file, field, message});
    };
    auto finite = [](double v) { return std::isfinite(v); };

    long long cells = 1;
    bool size_ok = true;
    for (int i = 0; i < 3; ++i) {
        int n = e.workspace_size[i];
        if (n < 1 || n > kMaxDimension) {
            bad("workspace.size[" + std::to_string(i) + "]",
                "must be in [1, " + std::to_string(kMaxDimension) + "], got " + std::to_string(n));
            size_ok = false;
        } else {
            cells *= n;
        }
    }
    if (size_ok && cells > kMaxCells)
        bad("workspace.size", "workspace of " + std::to_string(cells) +
                                  " voxels is too large to simulate in memory (at most " +
                                  std::to_string(kMaxCells) + ")");
    // The physics envelope is the engine's (engine/limits.hpp): the same functions refuse a
    // BodySpec in Model::build, so what validates here always runs.
    const engine::BodySpec settings = make_settings_spec(e);
    for (const auto& p : engine::limits::settings_problems(settings))
        bad(experiment_field_of(p.field), p.message);

    if (!finite(e.actuation.phase_offset_rad) ||
        std::abs(e.actuation.phase_offset_rad) > std::numbers::pi)
        bad("actuation.phase_offset_rad",
            "must lie in [-pi, pi] radians, got " + std::to_string(e.actuation.phase_offset_rad));
    if (e.materials.empty()) bad("materials", "needs at least one material");
    if (e.materials.size() > static_cast<size_t>(kMaxMaterials))
        bad("materials", "at most " + std::to_string(kMaxMaterials) +
                             " materials (body layers use one character '1'..'9' per voxel)");
    bool has_active = false, has_passive = false;
    for (size_t i = 0; i < e.materials.size(); ++i) {
        const auto& m = e.materials[i].physics;
        const std::string p = "materials[" + std::to_string(i) + "]";
        if (e.materials[i].name.empty()) bad(p + ".name", "is required");
        for (const auto& problem :
             engine::limits::material_problems(m, e.actuation.temperature_amplitude_c)) {
            if (problem.field == "cte_per_c" && finite(m.cte_per_c) && m.cte_per_c >= 0 &&
                m.cte_per_c <= 1)
                bad("actuation.temperature_amplitude_c",
                    "with " + p + ".cte_per_c " + problem.message);
            else if (problem.field != "cte_per_c")
                bad(p + "." + problem.field, problem.message);
        }
        if (!finite(m.cte_per_c) || m.cte_per_c < 0 || m.cte_per_c > 1)
            bad(p + ".cte_per_c", "must be in [0, 1] (> 0 makes the material active)");
        if (finite(m.static_friction) && finite(m.dynamic_friction) && m.dynamic_friction >= 0 &&
            m.dynamic_friction > m.static_friction)
            bad(p + ".dynamic_friction", "must not exceed static_friction");
        (m.cte_per_c > 0 ? has_active : has_passive) = true;
    }
    if (!e.materials.empty() && !(has_active && has_passive))
        bad("materials",
            "evolution needs a passive material (cte_per_c = 0) and an active one "
            "(cte_per_c > 0)");

    const int nmat = static_cast<int>(e.materials.size());
    const auto& b = e.boundary;
    bool any_enclosure = false;
    for (int axis = 0; axis < 3 && size_ok; ++axis) {
        int lo = b.enclosure_thickness[2 * axis], hi = b.enclosure_thickness[2 * axis + 1];
        any_enclosure = any_enclosure || lo > 0 || hi > 0;
        if (lo < 0 || hi < 0 || lo + hi >= e.workspace_size[axis])
            bad("boundary.enclosure.thickness_voxels",
                std::string("frame thickness ") + kFaceNames[2 * axis] + " + " +
                    kFaceNames[2 * axis + 1] + " leaves no design space along " + "xyz"[axis]);
    }
    if (any_enclosure) {
        if (b.enclosure_material < 1 || b.enclosure_material > nmat)
            bad("boundary.enclosure.material", "must name a material 1.." + std::to_string(nmat) +
                                                   " when the frame has a thickness");
        else if (e.materials[b.enclosure_material - 1].active())
            bad("boundary.enclosure.material", "the enclosure frame must be a passive material");
    } else if (b.enclosure_material < 0 || b.enclosure_material > nmat) {
        bad("boundary.enclosure.material",
            "must be 0 (none) or a material 1.." + std::to_string(nmat));
    }
    for (size_t i = 0; i < b.voxel_overrides.size(); ++i) {
        const auto& o = b.voxel_overrides[i];
        const std::string p = "boundary.voxel_overrides[" + std::to_string(i) + "]";
        for (int a = 0; a < 3; ++a)
            if (o.voxel[a] < 0 || o.voxel[a] >= e.workspace_size[a]) {
                bad(p + ".voxel", "lies outside the workspace");
                break;
            }
        if (o.kind == OverrideKind::Material && (o.material < 1 || o.material > nmat))
            bad(p + ".material", "must name a material 1.." + std::to_string(nmat));
    }

    const auto& s = e.simulation;
    if (!finite(s.settle_s) || s.settle_s < 0 || s.settle_s > 1e4)
        bad("simulation.settle_s", "must be in [0, 10000] seconds");
    if (!finite(s.evaluate_s) || s.evaluate_s <= 0 || s.evaluate_s > 1e5)
        bad("simulation.evaluate_s", "must be in (0, 100000] seconds");
    if (!finite(s.record_fps) || s.record_fps <= 0 || s.record_fps > 1000)
        bad("simulation.record_fps", "must be in (0, 1000]");
    if (!finite(s.periodic_tolerance) || s.periodic_tolerance <= 0 || s.periodic_tolerance > 1)
        bad("simulation.periodic_tolerance", "must be in (0, 1]");
    // The step budget, only once every input it depends on is valid (else it would mislead).
    if (problems.empty() && size_ok) {
        std::vector<engine::Material> physics;
        for (const auto& m : e.materials)
            physics.push_back(m.physics);
        const auto range = engine::limits::step_range(physics, e.voxel_size_m, s.dt_fraction,
                                                      e.actuation.temperature_amplitude_c);
        const std::string why = engine::limits::step_budget_problem(
            range, evaluation_seconds(e), e.actuation.frequency_hz,
            has_active && e.actuation.temperature_amplitude_c > 0, cells);
        if (!why.empty())
            bad("simulation",
                "settle_s + evaluate_s = " + short_number(evaluation_seconds(e)) + " s " + why);
    }

    const auto& c = e.fitness.constraints;
    if (c.attached_to_fixed_face && !b.any_fixed_face())
        bad("fitness.constraints.attached_to_fixed_face",
            "is on but no face of boundary.faces is \"fixed\"");
    if (!finite(c.min_fill_fraction) || c.min_fill_fraction < 0 || c.min_fill_fraction > 1)
        bad("fitness.constraints.min_fill_fraction", "must be in [0, 1]");
    if (c.min_active_voxels < 0 || (size_ok && c.min_active_voxels > cells))
        bad("fitness.constraints.min_active_voxels", "must be in [0, workspace voxels]");

    const auto& ev = e.evolution;
    if (ev.population < 2 || ev.population > 100000)
        bad("evolution.population", "must be in [2, 100000]");
    if (ev.generations < 0 || ev.generations > 100000000)
        bad("evolution.generations", "must be >= 0");
    if (!finite(ev.wall_budget_h) || ev.wall_budget_h <= 0 || ev.wall_budget_h > 1e5)
        bad("evolution.wall_budget_h", "must be in (0, 100000] hours");
    if (ev.max_neutral_retries < 0 || ev.max_neutral_retries > 10000000)
        bad("evolution.max_neutral_retries", "must be in [0, 10000000]");
    if (ev.threads < 0 || ev.threads > 1024)
        bad("evolution.threads", "must be in [0, 1024] (0 = all cores)");
    const auto& cp = ev.cppn;
    if (cp.min_hidden_nodes < 0 || cp.min_hidden_nodes > 1000)
        bad("evolution.cppn.min_hidden_nodes", "must be in [0, 1000]");
    if (cp.max_hidden_nodes < cp.min_hidden_nodes || cp.max_hidden_nodes > 1000)
        bad("evolution.cppn.max_hidden_nodes", "must be in [min_hidden_nodes, 1000]");
    if (!finite(cp.weight_range) || cp.weight_range <= 0 || cp.weight_range > 100)
        bad("evolution.cppn.weight_range", "must be in (0, 100]");
    if (!finite(cp.mutation_weight_sigma) || cp.mutation_weight_sigma <= 0 ||
        cp.mutation_weight_sigma > 100)
        bad("evolution.cppn.mutation_weight_sigma", "must be in (0, 100]");
    if (!finite(ev.crossover_rate) || ev.crossover_rate < 0 || ev.crossover_rate > 1)
        bad("evolution.crossover_rate", "must be in [0, 1] (0 = mutation only, the paper's)");
    const auto& nv = ev.novelty;
    if (nv.k < 1 || nv.k > 1000) bad("evolution.novelty.k", "must be in [1, 1000]; 15 by default");
    if (!finite(nv.archive_threshold) || nv.archive_threshold <= 0 || nv.archive_threshold > 1e6)
        bad("evolution.novelty.archive_threshold", "must be in (0, 1e6] voxel lengths; 1 by default");
    if (nv.archive_capacity < 0 || nv.archive_capacity > 100000)
        bad("evolution.novelty.archive_capacity", "must be in [0, 100000]; 1000 by default");
    if (cp.material_outputs == MaterialOutputs::PerMaterial && e.materials.size() < 2)
        bad("evolution.cppn.material_outputs",
            "\"per_material\" needs at least two materials to choose between");
    const auto& ne = ev.neat;
    auto neat_number = [&](const char* key, double v, double lo, double hi, bool lo_open,
                           const char* range) {
        if (!finite(v) || v < lo || v > hi || (lo_open && v == lo))
            bad(std::string("evolution.neat.") + key, std::string("must be in ") + range);
    };
    neat_number("c1", ne.c1, 0, 100, false, "[0, 100]");
    neat_number("c2", ne.c2, 0, 100, false, "[0, 100]");
    neat_number("c3", ne.c3, 0, 100, false, "[0, 100]");
    neat_number("compatibility_threshold", ne.compatibility_threshold, 0, 1000, true,
                "(0, 1000]");
    neat_number("threshold_step", ne.threshold_step, 0, 100, true, "(0, 100]");
    neat_number("survival_fraction", ne.survival_fraction, 0, 1, true, "(0, 1]");
    neat_number("crossover_rate", ne.crossover_rate, 0, 1, false, "[0, 1]");
    if (ne.target_species < 0 || ne.target_species > 100000)
        bad("evolution.neat.target_species", "must be in [0, 100000] (0 = keep the threshold fixed)");
    if (ne.elitism < 0 || ne.elitism > ev.population)
        bad("evolution.neat.elitism", "must be in [0, evolution.population]");
    if (ne.stagnation_generations < 1 || ne.stagnation_generations > 100000000)
        bad("evolution.neat.stagnation_generations", "must be in [1, 1e8]");
    return problems;
}

Experiment load_experiment(const std::string& path) {
    return parse_experiment(parse_json_text(read_text(path), path), path);
}

json experiment_to_json(const Experiment& e) {
    json j;
    j["format_version"] = 1;
    j["name"] = e.name;
    j["description"] = e.description;
    j["workspace"] = {{"size", e.workspace_size}, {"voxel_size_m", e.voxel_size_m}};
    j["materials"] = json::array();
    for (const auto& m : e.materials) {
        json mj = {{"name", m.name},
                   {"youngs_modulus_pa", m.physics.youngs_modulus_pa},
                   {"density_kg_m3", m.physics.density_kg_m3},
                   {"poisson_ratio", m.physics.poisson_ratio},
                   {"cte_per_c", m.physics.cte_per_c},
                   {"static_friction", m.physics.static_friction},
                   {"dynamic_friction", m.physics.dynamic_friction}};
        if (m.has_color) mj["color"] = m.color;
        if (!m.library.empty()) mj["library"] = m.library;
        j["materials"].push_back(mj);
    }
    j["actuation"] = {{"frequency_hz", e.actuation.frequency_hz},
                      {"temperature_amplitude_c", e.actuation.temperature_amplitude_c},
                      {"phase", e.actuation.phase == PhaseMode::Uniform ? "uniform" : "random"}};
    // Only when set: experiments without one stay byte for byte as they were.
    if (e.actuation.phase_offset_rad != 0.0)
        j["actuation"]["phase_offset_rad"] = e.actuation.phase_offset_rad;
    j["environment"] = {{"gravity_m_s2", e.environment.gravity_m_s2},
                        {"floor", e.environment.floor}};
    json faces, thickness;
    for (int f = 0; f < 6; ++f) {
        faces[kFaceNames[f]] = e.boundary.faces[f] == BoundaryKind::Fixed ? "fixed" : "free";
        thickness[kFaceNames[f]] = e.boundary.enclosure_thickness[f];
    }
    json overrides = json::array();
    for (const auto& o : e.boundary.voxel_overrides) {
        static const char* kinds[] = {"fixed", "empty", "material"};
        json oj = {{"voxel", o.voxel}, {"kind", kinds[static_cast<int>(o.kind)]}};
        if (o.kind == OverrideKind::Material) oj["material"] = o.material;
        overrides.push_back(oj);
    }
    j["boundary"] = {
        {"faces", faces},
        {"enclosure",
         {{"thickness_voxels", thickness}, {"material", e.boundary.enclosure_material}}},
        {"voxel_overrides", overrides}};
    const auto& s = e.simulation;
    j["simulation"] = {{"settle_s", s.settle_s},
                       {"evaluate_s", s.evaluate_s},
                       {"dt_fraction", s.dt_fraction},
                       {"bond_damping_ratio", s.bond_damping_ratio},
                       {"global_damping_ratio", s.global_damping_ratio},
                       {"collision_damping_ratio", s.collision_damping_ratio},
                       {"record_fps", s.record_fps},
                       {"end_when_periodic", s.end_when_periodic},
                       {"periodic_tolerance", s.periodic_tolerance}};
    const auto& c = e.fitness.constraints;
    j["fitness"] = {{"measure", kFitnessNames[static_cast<int>(e.fitness.measure)]},
                    {"minimize_active_voxels", e.fitness.minimize_active_voxels},
                    {"constraints",
                     {{"attached_to_fixed_face", c.attached_to_fixed_face},
                      {"min_fill_fraction", c.min_fill_fraction},
                      {"min_active_voxels", c.min_active_voxels},
                      {"reject_escaped", c.reject_escaped},
                      {"reject_detached_motion", c.reject_detached_motion},
                      {"reject_tentacle", c.reject_tentacle}}}};
    const auto& ev = e.evolution;
    j["evolution"] = {{"algorithm", kAlgorithmNames[static_cast<int>(ev.algorithm)]},
                      {"population", ev.population},
                      {"generations", ev.generations},
                      {"wall_budget_h", ev.wall_budget_h},
                      {"max_neutral_retries", ev.max_neutral_retries},
                      {"seed", ev.seed},
                      {"threads", ev.threads},
                      {"crossover_rate", ev.crossover_rate},
                      {"cppn",
                       {{"min_hidden_nodes", ev.cppn.min_hidden_nodes},
                        {"max_hidden_nodes", ev.cppn.max_hidden_nodes},
                        {"weight_range", ev.cppn.weight_range},
                        {"mutation_weight_sigma", ev.cppn.mutation_weight_sigma},
                        {"material_outputs",
                         kMaterialOutputsNames[static_cast<int>(ev.cppn.material_outputs)]}}}};
    // NEAT's block only where it says something: AFPO files stay as they were.
    if (ev.algorithm == Algorithm::Neat || !(ev.neat == NeatSettings{})) {
        const auto& n = ev.neat;
        j["evolution"]["neat"] = {{"c1", n.c1},
                                  {"c2", n.c2},
                                  {"c3", n.c3},
                                  {"normalize_by_size", n.normalize_by_size},
                                  {"compatibility_threshold", n.compatibility_threshold},
                                  {"target_species", n.target_species},
                                  {"threshold_step", n.threshold_step},
                                  {"survival_fraction", n.survival_fraction},
                                  {"elitism", n.elitism},
                                  {"stagnation_generations", n.stagnation_generations},
                                  {"crossover_rate", n.crossover_rate}};
    }
    if (ev.algorithm == Algorithm::Novelty || !(ev.novelty == NoveltySettings{})) {
        const auto& n = ev.novelty;
        j["evolution"]["novelty"] = {{"k", n.k},
                                     {"archive_threshold", n.archive_threshold},
                                     {"archive_capacity", n.archive_capacity},
                                     {"with_fitness", n.with_fitness}};
    }
    return j;
}

void write_file_atomically(const std::string& path, const std::string& contents) {
    engine::write_file_atomically(path, contents);
}

void save_experiment(const std::string& path, const Experiment& e) {
    write_file_atomically(path, experiment_to_json(e).dump(2) + "\n");
}

Body parse_body(const json& root, const std::string& file) {
    std::vector<Problem> problems;
    JsonReader r(file, problems);
    if (!root.is_object()) throw ValidationError({{file, "(root)", "expected a JSON object"}});
    r.check_keys(root, "", {"size", "layers", "format_version", "name"});
    Body body;
    if (!root.contains("size")) r.problem("size", "is required");
    std::array<int, 3> size{0, 0, 0};
    read_array3(r, root, "size", "", size);
    bool size_ok = root.contains("size") && problems.empty();
    long long cells = 1;
    for (int i = 0; i < 3 && size_ok; ++i) {
        if (size[i] < 1 || size[i] > kMaxDimension) {
            r.problem("size[" + std::to_string(i) + "]",
                      "must be in [1, " + std::to_string(kMaxDimension) + "]");
            size_ok = false;
        }
        cells *= size[i];
    }
    if (size_ok && cells > kMaxCells) {
        r.problem("size", "too large to simulate in memory");
        size_ok = false;
    }
    auto it = root.find("layers");
    if (it == root.end()) {
        r.problem("layers", "is required");
    } else if (!it->is_array()) {
        r.problem("layers", "expected an array of strings, one per z layer");
    } else if (size_ok) {
        body.size = size;
        body.cells.assign(static_cast<size_t>(cells), 0);
        if (it->size() != static_cast<size_t>(size[2]))
            r.problem("layers", "has " + std::to_string(it->size()) + " layers, size[2] says " +
                                    std::to_string(size[2]));
        const size_t per_layer = static_cast<size_t>(size[0]) * size[1];
        for (size_t z = 0; z < it->size() && z < static_cast<size_t>(size[2]); ++z) {
            const std::string field = "layers[" + std::to_string(z) + "]";
            const json& layer = (*it)[z];
            if (!layer.is_string()) {
                r.problem(field, "expected a string, got " + JsonReader::type_name(layer));
                continue;
            }
            const auto& text = layer.get_ref<const std::string&>();
            if (text.size() != per_layer) {
                r.problem(field, "has " + std::to_string(text.size()) +
                                     " characters, expected nx*ny = " + std::to_string(per_layer));
                continue;
            }
            for (size_t k = 0; k < text.size(); ++k) {
                char ch = text[k];
                if (ch < '0' || ch > '9') {
                    r.problem(field,
                              "character " + std::to_string(k) + " ('" +
                                  std::string(
                                      1, std::isprint(static_cast<unsigned char>(ch)) ? ch : '?') +
                                  "') is not a material digit 0-9");
                    break;
                }
                body.cells[z * per_layer + k] = static_cast<std::uint8_t>(ch - '0');
            }
        }
    }
    if (!problems.empty()) throw ValidationError(std::move(problems));
    return body;
}

Body load_body(const std::string& path) {
    return parse_body(parse_json_text(read_text(path), path), path);
}

json body_to_json(const Body& body) {
    json layers = json::array();
    const size_t per_layer = static_cast<size_t>(body.size[0]) * body.size[1];
    for (int z = 0; z < body.size[2]; ++z) {
        std::string layer(per_layer, '0');
        for (size_t k = 0; k < per_layer; ++k)
            layer[k] = static_cast<char>('0' + body.cells[z * per_layer + k]);
        layers.push_back(layer);
    }
    return {{"size", body.size}, {"layers", layers}};
}

void save_body(const std::string& path, const Body& body) {
    write_file_atomically(path, body_to_json(body).dump(2) + "\n");
}

namespace {

// Size and material indices of a body against the experiment.
std::vector<Problem> body_shape_problems(const Body& body, const Experiment& e,
                                         const std::string& file) {
    std::vector<Problem> problems;
    for (int i = 0; i < 3; ++i)
        if (body.size[i] > e.workspace_size[i]) {
            problems.push_back({file, "size[" + std::to_string(i) + "]",
                                "body is larger than the workspace (" +
                                    std::to_string(body.size[i]) + " > " +
                                    std::to_string(e.workspace_size[i]) + ")"});
        }
    const int nmat = static_cast<int>(e.materials.size());
    const size_t per_layer = static_cast<size_t>(body.size[0]) * body.size[1];
    for (size_t k = 0; k < body.cells.size(); ++k) {
        if (body.cells[k] > nmat) {
            size_t z = per_layer ? k / per_layer : 0;
            problems.push_back({file, "layers[" + std::to_string(z) + "]",
                                "material " + std::to_string(body.cells[k]) + " at character " +
                                    std::to_string(k - z * per_layer) +
                                    " has no entry in materials (" + std::to_string(nmat) +
                                    " defined)"});
            break;
        }
    }
    return problems;
}

}  // namespace

std::vector<Problem> validate_body_against(const Body& body, const Experiment& e,
                                           const std::string& file) {
    std::vector<Problem> problems = body_shape_problems(body, e, file);
    if (!problems.empty()) return problems;
    // What the engine would be given: an empty result cannot be simulated.
    const Body framed = apply_frame_and_overrides(e, body);
    bool any_voxel = false;
    for (auto cell : framed.cells)
        any_voxel = any_voxel || cell != 0;
    if (!any_voxel)
        problems.push_back({file, "layers",
                            "the body has no voxels (with the experiment's frame and overrides): "
                            "nothing to simulate"});
    return problems;
}

ExperimentAndBody load_experiment_and_body(const std::string& experiment_path,
                                           const std::string& body_path) {
    std::vector<Problem> problems;
    ExperimentAndBody out;
    bool experiment_ok = false;
    try {
        out.experiment = load_experiment(experiment_path);
        experiment_ok = true;
    } catch (const ValidationError& e) {
        problems.insert(problems.end(), e.problems.begin(), e.problems.end());
    }
    if (!body_path.empty()) {
        try {
            out.body = load_body(body_path);
            if (experiment_ok) {
                auto more = validate_body_against(*out.body, out.experiment, body_path);
                problems.insert(problems.end(), more.begin(), more.end());
            }
        } catch (const ValidationError& e) {
            problems.insert(problems.end(), e.problems.begin(), e.problems.end());
        }
    }
    if (!problems.empty()) throw ValidationError(std::move(problems));
    return out;
}

}  // namespace bhm::evo
