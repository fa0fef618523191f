// Library files are written by people from papers and datasheets, so the reader is strict: unknown
// keys, a value without a source, a range that does not hold its value without a note, a value the
// engine refuses (nu 0.5) are each one line naming the file and the field.
#include "evo/experiment/material_library.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "engine/io/text_file.hpp"
#include "engine/limits.hpp"
#include "engine/muscle.hpp"
#include "evo/experiment/json_reader.hpp"

#ifndef BHM_MATERIALS_DIR_DEFAULT
#define BHM_MATERIALS_DIR_DEFAULT "assets/materials"
#endif

namespace bhm::evo {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string number_text(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

// What one property may hold: its lowest and highest admissible value (the engine's envelope for
// the value the engine is given).
struct PropertyRule {
    const char* key;
    double min, max;
    bool min_exclusive;
    const char* range_text;
};

std::optional<SourcedValue> read_value(JsonReader& r, const json& obj, const PropertyRule& rule,
                                       const std::string& path, bool required) {
    const std::string field = JsonReader::join(path, rule.key);
    const auto it = obj.find(rule.key);
    if (it == obj.end()) {
        if (required) r.problem(field, "is required");
        return std::nullopt;
    }
    if (!it->is_object()) {
        r.problem(field, "expected {\"value\": ..., \"source\": \"...\"}, got " +
                             JsonReader::type_name(*it));
        return std::nullopt;
    }
    r.check_keys(*it, field, {"value", "range", "source", "note"});
    SourcedValue v;
    bool ok = true;
    if (!it->contains("value")) {
        r.problem(JsonReader::join(field, "value"), "is required");
        ok = false;
    } else if (!(*it)["value"].is_number() || !std::isfinite((*it)["value"].get<double>())) {
        r.problem(JsonReader::join(field, "value"), "expected a finite number");
        ok = false;
    } else {
        v.value = (*it)["value"].get<double>();
        if (v.value < rule.min || v.value > rule.max || (rule.min_exclusive && v.value == rule.min)) {
            r.problem(JsonReader::join(field, "value"),
                      number_text(v.value) + " is outside " + rule.range_text);
            ok = false;
        }
    }
    v.source = r.string(*it, "source", field, "");
    if (v.source.empty())
        r.problem(JsonReader::join(field, "source"),
                  "is required: the paper or datasheet the value comes from");
    v.note = r.string(*it, "note", field, "");
    if (auto range = it->find("range"); range != it->end()) {
        const std::string rfield = JsonReader::join(field, "range");
        if (!range->is_array() || range->size() != 2 || !(*range)[0].is_number() ||
            !(*range)[1].is_number() || !std::isfinite((*range)[0].get<double>()) ||
            !std::isfinite((*range)[1].get<double>()) ||
            (*range)[0].get<double>() > (*range)[1].get<double>()) {
            r.problem(rfield, "expected [low, high], two finite numbers with low <= high");
            ok = false;
        } else {
            v.range = std::array<double, 2>{(*range)[0].get<double>(), (*range)[1].get<double>()};
            if (ok && (v.value < (*v.range)[0] || v.value > (*v.range)[1]) && v.note.empty())
                r.problem(JsonReader::join(field, "note"),
                          "is required when the value " + number_text(v.value) +
                              " lies outside the reported range: say why (e.g. clamped to the "
                              "engine's envelope)");
        }
    }
    if (!ok) return std::nullopt;
    return v;
}

const PropertyRule kModulus{"youngs_modulus_pa", 0.0, engine::limits::kMaxYoungsModulusPa, true,
                            "(0, 1e12] Pa"};
const PropertyRule kDensity{"density_kg_m3", 0.0, engine::limits::kMaxDensityKgM3, true,
                            "(0, 1e6] kg/m^3"};
const PropertyRule kPoisson{"poisson_ratio", engine::limits::kMinPoissonRatio,
                            engine::limits::kMaxPoissonRatio, false,
                            "the engine's [-0.9, 0.49] (docs/physics.md): give the reported value "
                            "in range and the value to simulate (e.g. 0.49) with a note"};
const PropertyRule kFriction{"static_friction", 0.0, 100.0, false, "[0, 100]"};
const PropertyRule kDynamicFriction{"dynamic_friction", 0.0, 100.0, false, "[0, 100]"};
const PropertyRule kStrain{"contraction_strain", 0.0, engine::limits::kMaxActuationStrain, true,
                           "(0, 0.6], the engine's largest actuation strain"};
const PropertyRule kFrequency{"frequency_hz", 0.0, 1000.0, true, "(0, 1000] Hz"};
const PropertyRule kRise{"rise_s", engine::muscle::kMinTimeConstantS,
                         engine::muscle::kMaxTimeConstantS, false, "[1e-4, 100] s"};
const PropertyRule kDecay{"decay_s", engine::muscle::kMinTimeConstantS,
                          engine::muscle::kMaxTimeConstantS, false, "[1e-4, 100] s"};
const PropertyRule kActiveStress{"active_stress_pa", 0.0, 1e9, true, "(0, 1e9] Pa"};
const PropertyRule kTwitchRatio{"twitch_tetanus_ratio", 0.0, 1.0, true, "(0, 1]"};

}  // namespace

const LibraryMaterial* MaterialLibrary::find(const std::string& id) const {
    for (const auto& m : materials)
        if (m.id == id) return &m;
    return nullptr;
}

const DamagedLibraryFile* MaterialLibrary::find_damaged(const std::string& id) const {
    for (const auto& d : damaged)
        if (d.id == id) return &d;
    return nullptr;
}

std::vector<std::string> MaterialLibrary::warnings() const {
    std::vector<std::string> out;
    for (const auto& p : skipped)
        out.push_back(p.to_string());
    for (const auto& d : damaged)
        out.push_back(d.problems.front().to_string() + " (material '" + d.id +
                      "' cannot be used; the rest of the library can)");
    return out;
}

std::vector<std::string> MaterialLibrary::ids() const {
    std::vector<std::string> out;
    for (const auto& m : materials)
        out.push_back(m.id);
    return out;
}

std::string default_material_library_dir() {
    if (const char* env = std::getenv("BHM_MATERIALS_DIR"); env && *env) return env;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed = exe.parent_path().parent_path() / "share" / "bhm" / "materials";
        if (fs::is_directory(installed, ec)) return installed.lexically_normal().string();
    }
    return fs::path(BHM_MATERIALS_DIR_DEFAULT).lexically_normal().string();
}

LibraryMaterial parse_library_material(const json& root, const std::string& file,
                                       const std::string& id) {
    std::vector<Problem> problems;
    JsonReader r(file, problems);
    if (!root.is_object()) throw ValidationError({{file, "(root)", "expected a JSON object"}});
    r.check_keys(root, "",
                 {"format_version", "name", "category", "description", "engine",
                  "youngs_modulus_pa", "poisson_ratio", "density_kg_m3", "static_friction",
                  "dynamic_friction", "active", "color"});
    LibraryMaterial m;
    m.id = id;
    m.file = file;
    if (!root.contains("format_version")) r.problem("format_version", "is required (1)");
    r.integer(root, "format_version", "", 1, 1, 1);
    m.name = r.string(root, "name", "", "");
    if (m.name.empty()) r.problem("name", "is required");
    const std::vector<std::string> categories(kLibraryCategories.begin(), kLibraryCategories.end());
    if (!root.contains("category")) r.problem("category", "is required");
    m.category = categories[static_cast<size_t>(r.choice(root, "category", "", categories, 0))];
    m.description = r.string(root, "description", "", "");
    m.engine_note = r.string(root, "engine", "", "");
    if (m.engine_note.empty())
        r.problem("engine", "is required: what the engine does with this material");
    if (auto v = read_value(r, root, kModulus, "", true)) m.youngs_modulus_pa = *v;
    m.poisson_ratio = read_value(r, root, kPoisson, "", false);
    m.density_kg_m3 = read_value(r, root, kDensity, "", false);
    m.static_friction = read_value(r, root, kFriction, "", false);
    m.dynamic_friction = read_value(r, root, kDynamicFriction, "", false);
    if (m.static_friction && m.dynamic_friction &&
        m.dynamic_friction->value > m.static_friction->value)
        r.problem("dynamic_friction.value", "must not exceed static_friction.value");
    if (const json* a = r.object(root, "active", "")) {
        m.active = true;
        r.check_keys(*a, "active",
                     {"contraction_strain", "frequency_hz", "rise_s", "decay_s", "active_stress_pa",
                      "twitch_tetanus_ratio"});
        m.contraction_strain = read_value(r, *a, kStrain, "active", false);
        m.frequency_hz = read_value(r, *a, kFrequency, "active", false);
        m.rise_s = read_value(r, *a, kRise, "active", false);
        m.decay_s = read_value(r, *a, kDecay, "active", false);
        m.active_stress_pa = read_value(r, *a, kActiveStress, "active", false);
        m.twitch_tetanus_ratio = read_value(r, *a, kTwitchRatio, "active", false);
    }
    if (auto it = root.find("color"); it != root.end()) {
        std::array<float, 3> c{};
        bool ok = it->is_array() && it->size() == 3;
        for (size_t i = 0; ok && i < 3; ++i) {
            ok = (*it)[i].is_number() && (*it)[i].get<double>() >= 0 && (*it)[i].get<double>() <= 1;
            if (ok) c[i] = (*it)[i].get<float>();
        }
        if (ok)
            m.color = c;
        else
            r.problem("color", "expected [r, g, b] with each component in [0, 1]");
    }
    if (!problems.empty()) throw ValidationError(std::move(problems));
    return m;
}

LibraryMaterial load_library_material(const std::string& path) {
    std::string text;
    try {
        text = engine::read_text(path, engine::kTextFileCap);
    } catch (const engine::FileReadError& e) {
        throw ValidationError({{path, "(file)", e.reason()}});
    }
    json root;
    try {
        root = json::parse(text);
    } catch (const json::exception& e) {
        throw ValidationError({{path, "(json)", without_json_tags(e.what())}});
    }
    return parse_library_material(root, path, fs::path(path).stem().string());
}

namespace {

// Why an entry of the library folder is not read, from its status alone (nothing is opened: a FIFO
// would block the open until a writer came); "" for a regular file or a link to one.
std::string unread_entry_reason(const fs::directory_entry& entry) {
    std::error_code ec, link_ec;
    const fs::file_status target = entry.status(ec);  // through a symbolic link
    if (ec || target.type() == fs::file_type::not_found) {
        if (entry.is_symlink(link_ec)) return "a symbolic link to a missing file";
        return "cannot be examined (" + (ec ? ec.message() : std::string("gone")) + ")";
    }
    switch (target.type()) {
        case fs::file_type::regular:
            return "";
        case fs::file_type::directory:
            return "a folder (the library reads only the files directly in it)";
        case fs::file_type::fifo:
            return "a named pipe (FIFO), not a file";
        case fs::file_type::socket:
            return "a socket, not a file";
        case fs::file_type::block:
        case fs::file_type::character:
            return "a device, not a file";
        default:
            return "not a regular file";
    }
}

}  // namespace

MaterialLibrary load_material_library(const std::string& dir) {
    MaterialLibrary library;
    library.dir = dir;
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw ValidationError({{dir, "(folder)", "is not a folder of material files "
                                                 "(set BHM_MATERIALS_DIR to the library)"}});
    std::vector<std::string> paths;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;  // hidden: an editor's or a tool's own
        if (const std::string reason = unread_entry_reason(*it); !reason.empty())
            library.skipped.push_back({it->path().string(), "(file)", "skipped: " + reason});
        else if (it->path().extension() == ".json")
            paths.push_back(it->path().string());
    }
    if (ec) throw ValidationError({{dir, "(folder)", "cannot be listed: " + ec.message()}});
    std::sort(paths.begin(), paths.end());
    std::sort(library.skipped.begin(), library.skipped.end(),
              [](const Problem& a, const Problem& b) { return a.file < b.file; });
    for (const auto& path : paths) {
        try {
            library.materials.push_back(load_library_material(path));
        } catch (const ValidationError& e) {
            library.damaged.push_back({fs::path(path).stem().string(), path, e.problems});
        }
    }
    if (paths.empty()) {
        std::vector<Problem> problems = library.skipped;
        problems.push_back({dir, "(folder)", "holds no material files (*.json)"});
        throw ValidationError(std::move(problems));
    }
    return library;
}

void apply_library_material(const LibraryMaterial& m, double temperature_amplitude_c,
                            MaterialEntry& entry) {
    entry.library = m.id;
    if (entry.name.empty()) entry.name = m.name;
    auto& p = entry.physics;
    p.youngs_modulus_pa = m.youngs_modulus_pa.value;
    if (m.poisson_ratio) p.poisson_ratio = m.poisson_ratio->value;
    if (m.density_kg_m3) p.density_kg_m3 = m.density_kg_m3->value;
    if (m.static_friction) p.static_friction = m.static_friction->value;
    if (m.dynamic_friction) p.dynamic_friction = m.dynamic_friction->value;
    // A sine slot takes the tissue's strain as a thermal expansion; a muscle slot takes it, the
    // twitch times and the rate as its muscle fields and keeps no cte. Only the slot's own model
    // is filled: a sine slot is written without muscle keys, so a filled muscle object would not
    // survive its round trip.
    const bool muscle = p.actuation_model == engine::ActuationModel::Muscle;
    if (!m.active || muscle)
        p.cte_per_c = 0.0;
    else if (m.contraction_strain && temperature_amplitude_c > 0)
        p.cte_per_c = m.contraction_strain->value / temperature_amplitude_c;
    if (muscle) {
        if (m.contraction_strain) p.muscle.contraction_strain = m.contraction_strain->value;
        if (m.rise_s) p.muscle.rise_s = m.rise_s->value;
        if (m.decay_s) p.muscle.decay_s = m.decay_s->value;
        if (m.frequency_hz) p.muscle.frequency_hz = m.frequency_hz->value;
    }
    if (m.color) {
        entry.color = *m.color;
        entry.has_color = true;
    }
}

std::string describe_library_material(const LibraryMaterial& m) {
    std::string out;
    auto line = [&](const char* label, const std::optional<SourcedValue>& v, const char* unit) {
        out += std::string("  ") + label + ": ";
        if (!v) {
            out += "not in the library (no source found): the experiment gives it\n";
            return;
        }
        out += number_text(v->value) + unit;
        if (v->range)
            out += " (reported " + number_text((*v->range)[0]) + " to " +
                   number_text((*v->range)[1]) + ")";
        out += " - " + v->source;
        if (!v->note.empty()) out += " [" + v->note + "]";
        out += "\n";
    };
    line("E", m.youngs_modulus_pa, " Pa");
    line("nu", m.poisson_ratio, "");
    line("density", m.density_kg_m3, " kg/m^3");
    if (m.static_friction || m.dynamic_friction) {
        line("static friction", m.static_friction, "");
        line("dynamic friction", m.dynamic_friction, "");
    }
    if (m.active) {
        line("contraction strain", m.contraction_strain, "");
        line("frequency", m.frequency_hz, " Hz");
        line("twitch rise time constant", m.rise_s, " s");
        line("twitch decay time constant", m.decay_s, " s");
        // Measured for judging a slot's values, not engine inputs: listed only where sourced.
        if (m.active_stress_pa)
            line("active stress (measured, not an engine input)", m.active_stress_pa, " Pa");
        if (m.twitch_tetanus_ratio)
            line("twitch-to-tetanus force ratio", m.twitch_tetanus_ratio, "");
    }
    out += "  engine: " + m.engine_note + "\n";
    return out;
}

}  // namespace bhm::evo
