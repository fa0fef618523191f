// Experiment files: parsing (types, unknown keys, defaults) is separate from validation (ranges and
// cross-field rules) so the studio can validate an experiment it edited in memory.
#include "evo/experiment/experiment_io.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string_view>
#include <system_error>

#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"
#include "engine/limits.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/controller_fields.hpp"
#include "evo/experiment/experiment_fields.hpp"
#include "evo/experiment/field_io.hpp"
#include "evo/experiment/field_rules.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/experiment/material_library.hpp"

namespace bhm::evo {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string problems_summary(const std::vector<Problem>& problems) {
    std::string s;
    for (size_t i = 0; i < problems.size(); ++i) {
        if (i) s += "\n";
        s += problems[i].to_string();
    }
    return s;
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

// The muscle's optional fatigue fields (off at their defaults, engine/muscle.hpp).
constexpr const char* kFatigueKeys[] = {"fatigue_s", "recovery_s", "fatigue_floor"};
bool is_fatigue_key(std::string_view key) {
    for (const char* k : kFatigueKeys)
        if (key == k) return true;
    return false;
}

// base: the defaults of the fields the object does not give (a library material's values, or
// MaterialEntry's own). The physical fields come from the table (material_fields()).
MaterialEntry parse_material(JsonReader& r, const json& m, const std::string& path,
                             const MaterialEntry& base) {
    MaterialEntry entry = base;
    read_fields(r, m, path, material_fields(), entry.physics, {{"", {"name", "library", "color"}}});
    // A library's contraction strain fills a sine slot's cte; a muscle slot's strain is its own.
    if (entry.physics.actuation_model == engine::ActuationModel::Muscle && !m.contains("cte_per_c"))
        entry.physics.cte_per_c = 0.0;
    entry.name = r.string(m, "name", path, base.name);
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
        bool missing = !m.contains("name") || !m.contains("color");
        const bool muscle = m.contains("actuation_model") && m["actuation_model"] == "muscle";
        for (const auto& f : material_fields()) {
            // A sine slot has no muscle keys; a muscle slot's sit in its "muscle" object.
            if (f.parent() == "muscle") {
                // Fatigue is optional and off unless given: no library value to miss.
                if (is_fatigue_key(f.key())) continue;
                const auto o = m.find("muscle");
                missing = missing || (muscle && (o == m.end() || !o->is_object() ||
                                                 !o->contains(std::string(f.key()))));
                continue;
            }
            if (std::string_view(f.path) == "actuation_model") continue;
            missing = missing || !m.contains(f.path);
        }
        if (!missing) return base;
        const MaterialLibrary* library = load(r, field);
        if (!library) return base;
        const LibraryMaterial* lm = library->find(base.library);
        if (const DamagedLibraryFile* d = library->find_damaged(base.library); !lm && d) {
            // Only the experiments naming a damaged file fail, and say which file (issue 41 R10).
            r.problem(field, "'" + base.library +
                                 "' cannot be used: its library file is damaged (" +
                                 d->problems.front().to_string() + ")");
            return base;
        }
        if (!lm) {
            std::string message = "'" + base.library + "' is not in the material library " +
                                  library->dir;
            for (const auto& skipped : library->skipped)
                if (fs::path(skipped.file).stem() == base.library)
                    message += " (" + skipped.file + " was " + skipped.message + ")";
            if (auto guess = closest_match(base.library, library->ids()); !guess.empty())
                message += " (did you mean '" + guess + "'?)";
            r.problem(field, message + "; `bhm materials` lists it");
            return base;
        }
        if (muscle) base.physics.actuation_model = engine::ActuationModel::Muscle;
        apply_library_material(*lm, temperature_amplitude_c, base);
        auto require = [&](const char* key, bool sourced) {
            if (!sourced && !m.contains(key))
                r.problem(JsonReader::join(path, key),
                          "is required: library material '" + lm->id +
                              "' has no sourced value for it (docs/materials-format.md)");
        };
        require("poisson_ratio", lm->poisson_ratio.has_value());
        require("density_kg_m3", lm->density_kg_m3.has_value());
        if (lm->active && !muscle)
            require("cte_per_c",
                    lm->contraction_strain.has_value() && temperature_amplitude_c > 0);
        if (lm->active && muscle && !lm->contraction_strain) {
            const auto o = m.find("muscle");
            if (o == m.end() || !o->is_object() || !o->contains("contraction_strain"))
                r.problem(JsonReader::join(path, "muscle.contraction_strain"),
                          "is required: library material '" + lm->id +
                              "' has no sourced value for it (docs/materials-format.md)");
        }
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

// The boundary's faces and frame are the table's rows; its voxel overrides, a list, are read here.
void parse_voxel_overrides(JsonReader& r, const json& b, const std::string& path, Boundary& out) {
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
            r.array3(o, "voxel", ipath, v.voxel);
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
    // Every scalar field from the table first: materials below need the actuation amplitude (a
    // library's active tissue sets cte_per_c from it).
    read_fields(r, root, "", experiment_fields(), e,
                {{"", {"format_version", "materials"}},
                 {"boundary", {"voxel_overrides"}},
                 {"evolution.controller", {"body", "controllers"}}});
    r.integer(root, "format_version", "", 1, 1, 1);

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

    // A boundary that is not an object was reported by read_fields.
    if (auto b = root.find("boundary"); b != root.end() && b->is_object())
        parse_voxel_overrides(r, *b, "boundary", e.boundary);
    if (auto ev = root.find("evolution"); ev != root.end() && ev->is_object())
        parse_controller_settings(r, *ev, file, e.evolution.controller);

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
    auto reported = [&](const std::string& field) {
        return std::any_of(problems.begin(), problems.end(),
                           [&](const Problem& p) { return p.field == field; });
    };

    // Every scalar field's range, from the table (experiment_fields.cpp).
    check_ranges(e, experiment_fields(), "", file, problems);
    // The physics envelope is the engine's (engine/limits.hpp): the same functions refuse a
    // BodySpec in Model::build, so what validates here always runs. The table's ranges are the
    // engine's constants; a field the table already refused is not reported twice.
    const engine::BodySpec settings = make_settings_spec(e);
    for (const auto& p : engine::limits::settings_problems(settings))
        if (const std::string field = experiment_field_of(p.field); !reported(field))
            bad(field, p.message);

    if (e.materials.empty()) bad("materials", "needs at least one material");
    if (e.materials.size() > static_cast<size_t>(kMaxMaterials))
        bad("materials", "at most " + std::to_string(kMaxMaterials) +
                             " materials (body layers use one character '1'..'9' per voxel)");
    for (size_t i = 0; i < e.materials.size(); ++i) {
        const auto& m = e.materials[i].physics;
        const std::string p = "materials[" + std::to_string(i) + "]";
        if (e.materials[i].name.empty()) bad(p + ".name", "is required");
        check_ranges(m, material_fields(), p, file, problems);
        // The engine's own refusals; cte_per_c's, which depends on the amplitude, is a rule.
        for (const auto& problem :
             engine::limits::material_problems(m, e.actuation.temperature_amplitude_c))
            if (const std::string field = p + "." + problem.field;
                (problem.field != "cte_per_c" ||
                 m.actuation_model == engine::ActuationModel::Muscle) &&
                !reported(field))
                bad(field, problem.message);
    }

    // The rules between fields (field_rules.cpp; the studio's tooltips quote them).
    check_rules(e, file, problems);
    for (Problem& p : controller_problems(e, file))
        problems.push_back(std::move(p));
    return problems;
}

Experiment load_experiment(const std::string& path) {
    return parse_experiment(parse_json_text(read_text(path), path), path);
}

json experiment_to_json(const Experiment& e) {
    json j;
    j["format_version"] = 1;
    write_fields(e, experiment_fields(), j);
    j["materials"] = json::array();
    for (const auto& m : e.materials) {
        json mj = {{"name", m.name}};
        write_fields(m.physics, material_fields(), mj);
        // The muscle model's keys only in a muscle slot: sine experiments stay byte for byte.
        if (m.physics.actuation_model == engine::ActuationModel::Sine) {
            mj.erase("actuation_model");
            mj.erase("muscle");
        } else if (const engine::Muscle& u = m.physics.muscle;
                   u.fatigue_s == 0.0 && u.recovery_s == 0.0 && u.fatigue_floor == 0.0) {
            // Fatigue's keys only when set: muscle experiments without it stay byte for byte.
            for (const char* key : kFatigueKeys)
                mj["muscle"].erase(key);
        }
        if (m.has_color) mj["color"] = m.color;
        if (!m.library.empty()) mj["library"] = m.library;
        j["materials"].push_back(mj);
    }
    json overrides = json::array();
    for (const auto& o : e.boundary.voxel_overrides) {
        static const char* kinds[] = {"fixed", "empty", "material"};
        json oj = {{"voxel", o.voxel}, {"kind", kinds[static_cast<int>(o.kind)]}};
        if (o.kind == OverrideKind::Material) oj["material"] = o.material;
        overrides.push_back(oj);
    }
    j["boundary"]["voxel_overrides"] = overrides;
    // A phase offset only when set: experiments without one stay byte for byte as they were.
    if (e.actuation.phase_offset_rad == 0.0) j["actuation"].erase("phase_offset_rad");
    // The rotary inertia scale only when set (issue 42): experiments, run directories and the
    // evaluation wire without it stay byte for byte as they were.
    if (e.simulation.rotary_inertia_scale == 1.0) j["simulation"].erase("rotary_inertia_scale");
    // NEAT's and novelty's blocks only where they say something: AFPO files stay as they were.
    const auto& ev = e.evolution;
    if (!uses_neat(ev.algorithm) && ev.neat == NeatSettings{}) j["evolution"].erase("neat");
    if (ev.algorithm != Algorithm::HyperNeat && ev.hyperneat == HyperNeatSettings{})
        j["evolution"].erase("hyperneat");
    if (ev.algorithm != Algorithm::Novelty && ev.novelty == NoveltySettings{})
        j["evolution"].erase("novelty");
    if (ev.verify == LoopVerifySettings{}) j["evolution"].erase("verify");
    // Fibre outputs only when on: experiments without them stay byte for byte as they were.
    if (!ev.cppn.fibre_outputs) j["evolution"]["cppn"].erase("fibre_outputs");
    // The controller block only where it says something (issue 44).
    write_controller_settings(ev.controller, j["evolution"]);
    return j;
}

void write_file_atomically(const std::string& path, const std::string& contents) {
    engine::write_file_atomically(path, contents);
}

void save_experiment(const std::string& path, const Experiment& e) {
    write_file_atomically(path, experiment_to_json(e).dump(2) + "\n");
}

namespace {

// The body file's "fibres": one string per z layer as "layers", a fibre axis character per cell.
void read_fibres(const json& fibres, Body& body, JsonReader& r) {
    const std::size_t per_layer = static_cast<std::size_t>(body.size[0]) * body.size[1];
    if (!fibres.is_array() || fibres.size() != static_cast<std::size_t>(body.size[2])) {
        r.problem("fibres", "expected an array of " + std::to_string(body.size[2]) +
                                " strings, one per z layer as \"layers\"");
        return;
    }
    body.fibre.assign(body.cells.size(), engine::kMaterialFibreAxis);
    for (std::size_t z = 0; z < fibres.size(); ++z) {
        const std::string field = "fibres[" + std::to_string(z) + "]";
        const json& layer = fibres[z];
        if (!layer.is_string() || layer.get_ref<const std::string&>().size() != per_layer) {
            r.problem(field, "expected a string of nx*ny = " + std::to_string(per_layer) +
                                 " characters 'x', 'y', 'z' or '.'");
            continue;
        }
        const auto& text = layer.get_ref<const std::string&>();
        for (std::size_t k = 0; k < text.size(); ++k) {
            const char ch = text[k];
            const auto axis = std::string_view("xyz").find(ch);
            if (ch == '.') continue;
            if (axis == std::string_view::npos) {
                r.problem(
                    field,
                    "character " + std::to_string(k) + " ('" +
                        std::string(1, std::isprint(static_cast<unsigned char>(ch)) ? ch : '?') +
                        "') is not a fibre axis 'x', 'y', 'z' or '.' (the material's)");
                break;
            }
            body.fibre[z * per_layer + k] = static_cast<std::uint8_t>(axis);
        }
    }
}

// The body file's "controller" (issue 44): {"phase_rad": [...], "amplitude": [...]}, one number
// per cell in the order of "layers" (x fastest), phase in [-pi, pi], amplitude in [0, 1].
void read_controller(const json& controller, Body& body, JsonReader& r) {
    if (!controller.is_object()) {
        r.problem("controller", "expected an object with \"phase_rad\" and \"amplitude\"");
        return;
    }
    r.check_keys(controller, "controller", {"phase_rad", "amplitude"});
    auto read = [&](const char* key, double lo, double hi, const char* range,
                    std::vector<float>& out) {
        const std::string field = std::string("controller.") + key;
        const auto it = controller.find(key);
        if (it == controller.end() || !it->is_array() || it->size() != body.cells.size()) {
            r.problem(field, "expected an array of " + std::to_string(body.cells.size()) +
                                 " numbers, one per cell (x fastest)");
            return;
        }
        out.resize(body.cells.size());
        for (std::size_t c = 0; c < it->size(); ++c) {
            const json& v = (*it)[c];
            if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi)) {
                r.problem(field + "[" + std::to_string(c) + "]",
                          std::string("expected a number in ") + range);
                return;
            }
            out[c] = v.get<float>();
        }
    };
    // A float's pi (3.14159274...) rounds above the double's: a controller painted at -pi or pi
    // (wave, a CPPN phase output of +-1) is written as it, and must read back.
    const double pi = static_cast<double>(std::numbers::pi_v<float>);
    read("phase_rad", -pi, pi, "[-pi, pi]", body.phase);
    read("amplitude", 0.0, 1.0, "[0, 1]", body.amplitude);
}

}  // namespace

Body parse_body(const json& root, const std::string& file) {
    std::vector<Problem> problems;
    JsonReader r(file, problems);
    if (!root.is_object()) throw ValidationError({{file, "(root)", "expected a JSON object"}});
    r.check_keys(root, "", {"size", "layers", "fibres", "controller", "format_version", "name"});
    Body body;
    if (!root.contains("size")) r.problem("size", "is required");
    std::array<int, 3> size{0, 0, 0};
    r.array3(root, "size", "", size);
    bool size_ok = root.contains("size") && problems.empty();
    long long cells = 1;
    for (int i = 0; i < 3 && size_ok; ++i) {
        if (size[i] < 1 || size[i] > kMaxWorkspaceDimension) {
            r.problem("size[" + std::to_string(i) + "]",
                      "must be in [1, " + std::to_string(kMaxWorkspaceDimension) + "]");
            size_ok = false;
        }
        cells *= size[i];
    }
    if (size_ok && cells > kMaxWorkspaceCells) {
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
    if (problems.empty() && root.contains("fibres")) read_fibres(root["fibres"], body, r);
    if (problems.empty() && root.contains("controller"))
        read_controller(root["controller"], body, r);
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
    json out = {{"size", body.size}, {"layers", layers}};
    const bool own_axis =
        std::any_of(body.fibre.begin(), body.fibre.end(), [](std::uint8_t a) { return a <= 2; });
    if (own_axis && body.fibre.size() == body.cells.size()) {
        json fibres = json::array();
        for (int z = 0; z < body.size[2]; ++z) {
            std::string layer(per_layer, '.');
            for (size_t k = 0; k < per_layer; ++k)
                if (const auto a = body.fibre[z * per_layer + k]; a <= 2) layer[k] = "xyz"[a];
            fibres.push_back(layer);
        }
        out["fibres"] = fibres;
    }
    if (body.has_controller() && body.phase.size() == body.cells.size() &&
        body.amplitude.size() == body.cells.size())
        out["controller"] = {{"phase_rad", body.phase}, {"amplitude", body.amplitude}};
    return out;
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

std::vector<std::string> library_warnings_for(const Experiment& experiment) {
    const bool uses_library =
        std::any_of(experiment.materials.begin(), experiment.materials.end(),
                    [](const MaterialEntry& m) { return !m.library.empty(); });
    if (!uses_library) return {};
    try {
        return load_material_library(default_material_library_dir()).warnings();
    } catch (const ValidationError&) {
        return {};  // the experiment's own load said why, had it needed a value from it
    }
}

}  // namespace bhm::evo
