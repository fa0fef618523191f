// The experiment field table (evo/experiment/experiment_fields.hpp): every field it lists is
// written at its path and read back, every range it states is what validation refuses (and says),
// the physics ranges are exactly the engine's (engine/limits.hpp, Model::build's check), and
// docs/experiment-format.md documents every field.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/limits.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_fields.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/field_rules.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
using nlohmann::json;

namespace {

Experiment preset() {
    return load_experiment(std::string(BHM_SOURCE_DIR) + "/assets/experiments/quick-demo.json");
}

// The JSON value at a dotted path, walked here rather than by the table's writer.
const json* at_path(const json& root, const std::string& path) {
    const json* j = &root;
    std::size_t start = 0;
    while (j) {
        const auto dot = path.find('.', start);
        const std::string key = path.substr(start, dot - start);
        j = j->is_object() && j->contains(key) ? &(*j)[key] : nullptr;
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    return j;
}

// A valid value different from the current one.
double other_number(double v, const Range& r) {
    const double candidate =
        v != 0.0 ? v * 1.1 : (std::isfinite(r.hi) ? r.lo + 0.1 * (r.hi - r.lo) : r.lo + 0.5);
    return r.contains(candidate) ? candidate : 0.5 * (v + (std::isfinite(r.hi) ? r.hi : v + 1));
}

// Sets a value of `field` other than the current one; returns it as JSON (what the file holds).
template <class Host>
json change(const FieldOf<Host>& f, Host& h) {
    switch (f.kind()) {
        case FieldKind::Text:
            return f.text(h) += " changed";
        case FieldKind::Number:
            return f.number(h) = other_number(f.number(h), f.range);
        case FieldKind::Integer: {
            int& v = f.integer(h);
            v = f.range.contains(v + 1) ? v + 1 : v - 1;
            return v;
        }
        case FieldKind::Boolean:
            return f.boolean(h) = !f.boolean(h);
        case FieldKind::Choice: {
            const int next = (f.get_choice(h) + 1) % static_cast<int>(f.choices.size());
            f.set_choice(h, next);
            return f.choices[static_cast<std::size_t>(next)];
        }
        case FieldKind::Seed:
            return f.seed(h) += 1;
        case FieldKind::Size3:
            for (int& n : f.size3(h))
                n += 1;
            return f.size3(h);
    }
    return nullptr;
}

// Values just outside the range (as doubles; integers step by one).
std::vector<double> outside(const Range& r, bool integer) {
    std::vector<double> out;
    const double step_lo = integer ? 1.0 : (r.lo != 0.0 ? 0.5 * std::fabs(r.lo) : 1.0);
    const double step_hi = integer ? 1.0 : (r.hi != 0.0 ? std::fabs(r.hi) : 1.0);
    if (std::isfinite(r.lo)) out.push_back(r.lo_open && !integer ? r.lo : r.lo - step_lo);
    if (std::isfinite(r.hi)) out.push_back(r.hi_open && !integer ? r.hi : r.hi + step_hi);
    return out;
}

// Values at or just inside each finite end.
std::vector<double> inside(const Range& r) {
    std::vector<double> out;
    if (std::isfinite(r.lo)) out.push_back(r.lo_open ? std::nextafter(r.lo, r.hi) : r.lo);
    if (std::isfinite(r.hi)) out.push_back(r.hi_open ? std::nextafter(r.hi, r.lo) : r.hi);
    return out;
}

bool refused_with(const std::vector<Problem>& problems, const std::string& field,
                  const std::string& text) {
    for (const auto& p : problems)
        if (p.field == field && p.message.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("every field of the table is written at its path and read back unchanged") {
    // A passive frame material and no attachment, so that a frame thickness or a face set free
    // keeps the experiment valid.
    Experiment base = preset();
    REQUIRE(base.materials.size() == 2);
    REQUIRE_FALSE(base.materials[0].active());
    base.boundary.enclosure_material = 1;
    base.fitness.constraints.attached_to_fixed_face = false;
    // The boundary's faces and frame are rows too (issue 22): the loop below covers them.
    for (const char* path :
         {"boundary.faces.x-", "boundary.faces.z+", "boundary.enclosure.thickness_voxels.y+",
          "boundary.enclosure.material"})
        CHECK(find_experiment_field(path) != nullptr);
    const auto dir = bhm::test::scratch_dir("experiment-fields");
    int checked = 0;
    for (const auto& f : experiment_fields()) {
        CAPTURE(f.path);
        Experiment e = base;
        if (std::string_view(f.path) == "evolution.cppn.fibre_outputs") {
            // Fibre outputs need a muscle material to turn (issue 43): the active one becomes one.
            auto& m = e.materials[1].physics;
            m.actuation_model = bhm::engine::ActuationModel::Muscle;
            m.cte_per_c = 0.0;
            m.muscle.contraction_strain = 0.05;
        }
        const Experiment before = e;
        const json value = change(f, e);
        REQUIRE_FALSE(e == before);
        const json written = experiment_to_json(e);
        const json* at = at_path(written, f.path);
        REQUIRE(at != nullptr);
        CHECK(*at == value);
        const std::string file = (dir / "e.json").string();
        save_experiment(file, e);
        CHECK(load_experiment(file) == e);
        CHECK(experiment_to_json(load_experiment(file)) == written);
        ++checked;
    }
    for (const auto& f : material_fields()) {
        CAPTURE(f.path);
        // The muscle model's fields are written only in a muscle slot (issue 43): change them
        // on a muscle material; actuation_model itself turns the sine one into a muscle.
        Experiment from = base;
        if (f.parent() == "muscle" || std::string_view(f.path) == "actuation_model") {
            auto& m = from.materials[1].physics;
            if (f.parent() == "muscle") m.actuation_model = bhm::engine::ActuationModel::Muscle;
            m.cte_per_c = 0.0;
            m.muscle.contraction_strain = 0.05;
            // Bursts, so that a rest between them is valid; but the stimulus field turns the
            // train into spontaneous beating, which has no on/off schedule.
            const bool beating_next = std::string_view(f.path) == "muscle.stimulus";
            m.muscle.train_on_s = beating_next ? 0.0 : 0.3;
            m.muscle.train_off_s = beating_next ? 0.0 : 0.2;
            // Fatigue on, so that its fields are written (and a recovery is due).
            m.muscle.fatigue_s = 10.0;
            m.muscle.recovery_s = 30.0;
            m.muscle.fatigue_floor = 0.5;
        }
        Experiment e = from;
        const json value = change(f, e.materials[1].physics);  // the active one
        REQUIRE_FALSE(e == from);
        const json written = experiment_to_json(e);
        const json* at = at_path(written["materials"][1], f.path);
        REQUIRE(at != nullptr);
        CHECK(*at == value);
        CHECK(parse_experiment(written, "e.json") == e);
        ++checked;
    }
    // A sine slot is written without the muscle model's keys: files stay as they were.
    CHECK_FALSE(experiment_to_json(base)["materials"][1].contains("muscle"));
    CHECK_FALSE(experiment_to_json(base)["materials"][1].contains("actuation_model"));
    CHECK(checked == static_cast<int>(experiment_fields().size() + material_fields().size()));
    std::filesystem::remove_all(dir);
}

TEST_CASE("a value outside a field's range is refused, naming the field and the table's range") {
    const Experiment base = preset();
    REQUIRE(validate_experiment(base, "e.json").empty());
    int refusals = 0;
    for (const auto& f : experiment_fields()) {
        const FieldKind kind = f.kind();
        if (kind != FieldKind::Number && kind != FieldKind::Integer && kind != FieldKind::Size3)
            continue;
        CAPTURE(f.path);
        REQUIRE(f.range.bounded());
        const std::string field = kind == FieldKind::Size3 ? std::string(f.path) + "[0]" : f.path;
        for (double v : outside(f.range, kind != FieldKind::Number)) {
            CAPTURE(v);
            Experiment e = base;
            if (kind == FieldKind::Number) f.number(e) = v;
            if (kind == FieldKind::Integer) f.integer(e) = static_cast<int>(v);
            if (kind == FieldKind::Size3) f.size3(e)[0] = static_cast<int>(v);
            const auto problems = validate_experiment(e, "e.json");
            CHECK(refused_with(problems, field, "must be in " + range_text(f.range)));
            ++refusals;
        }
        for (double v : inside(f.range)) {
            CAPTURE(v);
            Experiment e = base;
            if (kind == FieldKind::Number) f.number(e) = v;
            if (kind == FieldKind::Integer) f.integer(e) = static_cast<int>(v);
            if (kind == FieldKind::Size3) f.size3(e)[0] = static_cast<int>(v);
            CHECK_FALSE(refused_with(validate_experiment(e, "e.json"), field, "must be in"));
        }
    }
    for (const auto& f : material_fields()) {
        CAPTURE(f.path);
        for (double v : outside(f.range, false)) {
            CAPTURE(v);
            Experiment e = base;
            f.number(e.materials[0].physics) = v;
            CHECK(refused_with(validate_experiment(e, "e.json"),
                               std::string("materials[0].") + f.path,
                               "must be in " + range_text(f.range)));
            ++refusals;
        }
    }
    CHECK(refusals > 60);
    // A few as a person reads them (the range text itself is not derived here).
    auto message = [&](const char* path, double v) {
        Experiment e = base;
        find_experiment_field(path)->number(e) = v;
        for (const auto& p : validate_experiment(e, "e.json"))
            if (p.field == path) return p.message;
        return std::string();
    };
    CHECK(message("simulation.settle_s", -1) == "must be in [0, 10000] s");
    CHECK(message("workspace.voxel_size_m", 0) == "must be in [1e-6, 10] m");
    CHECK(message("evolution.novelty.archive_threshold", 0) == "must be in (0, 1e6] voxel lengths");
    Experiment e = base;
    e.materials[0].physics.poisson_ratio = 0.5;
    CHECK(refused_with(validate_experiment(e, "e.json"), "materials[0].poisson_ratio",
                       "must be in [-0.9, 0.49] (the engine's validated range)"));
    e = base;
    e.evolution.threads = -1;
    CHECK(refused_with(validate_experiment(e, "e.json"), "evolution.threads",
                       "must be in [0, 1024] (0 = all cores)"));
}

TEST_CASE("the table's physics ranges are the engine's: what it accepts, Model::build accepts") {
    const Experiment base = preset();
    // Fields the engine checks itself (engine::limits, called by Model::build).
    const char* engine_checked[] = {"workspace.voxel_size_m",
                                    "actuation.frequency_hz",
                                    "actuation.temperature_amplitude_c",
                                    "environment.gravity_m_s2",
                                    "simulation.dt_fraction",
                                    "simulation.rotary_inertia_scale",
                                    "simulation.bond_damping_ratio",
                                    "simulation.global_damping_ratio",
                                    "simulation.collision_damping_ratio"};
    auto engine_refuses = [](const Experiment& e, const std::string& path) {
        for (const auto& p : bhm::engine::limits::settings_problems(make_settings_spec(e)))
            if (experiment_field_of(p.field) == path) return true;
        return false;
    };
    for (const char* path : engine_checked) {
        CAPTURE(path);
        const ExperimentField* f = find_experiment_field(path);
        REQUIRE(f != nullptr);
        for (double v : outside(f->range, false)) {
            Experiment e = base;
            f->number(e) = v;
            CHECK(engine_refuses(e, path));
        }
        for (double v : inside(f->range)) {
            Experiment e = base;
            f->number(e) = v;
            CHECK_FALSE(engine_refuses(e, path));
        }
    }
    for (const char* key : {"youngs_modulus_pa", "density_kg_m3", "poisson_ratio",
                            "static_friction", "dynamic_friction"}) {
        CAPTURE(key);
        const MaterialField* f = find_material_field(key);
        REQUIRE(f != nullptr);
        auto refuses = [&](double v) {
            bhm::engine::Material m;
            f->number(m) = v;
            for (const auto& p : bhm::engine::limits::material_problems(m, 0.0))
                if (p.field == key) return true;
            return false;
        };
        for (double v : outside(f->range, false))
            CHECK(refuses(v));
        for (double v : inside(f->range))
            CHECK_FALSE(refuses(v));
    }
    // The muscle model's numbers (issue 43): the table's range is the engine's, on a muscle.
    for (const auto& f : material_fields()) {
        if (f.parent() != "muscle" || f.kind() != FieldKind::Number) continue;
        CAPTURE(f.path);
        auto refuses = [&](double v) {
            bhm::engine::Material m;
            m.actuation_model = bhm::engine::ActuationModel::Muscle;
            f.number(m) = v;
            for (const auto& p : bhm::engine::limits::material_problems(m, 0.0))
                if (p.field == f.path) return true;
            return false;
        };
        for (double v : outside(f.range, false))
            CHECK(refuses(v));
        for (double v : inside(f.range))
            CHECK_FALSE(refuses(v));
    }
    // The amplitude's tooltip states the engine's actuation strain bound.
    CHECK(field_tooltip(*find_experiment_field("actuation.temperature_amplitude_c"))
              .find("<= " + range_number(bhm::engine::limits::kMaxActuationStrain)) !=
          std::string::npos);
}

TEST_CASE("each rule between fields is declared once: validated, and in its fields' tooltips") {
    const Experiment base = preset();
    REQUIRE(validate_experiment(base, "e.json").empty());
    // One break per rule, in the rules' order, and the field the validator must name; written
    // here from the experiment-format's rules, not from field_rules.cpp.
    struct Break {
        const char* field;
        void (*apply)(Experiment&);
    };
    const Break breaks[] = {
        {"workspace.size",
         [](Experiment& e) {
             e.workspace_size = {200, 200, 200};
         }},
        {"actuation.temperature_amplitude_c",
         [](Experiment& e) { e.materials[1].physics.cte_per_c = 0.5; }},
        {"materials[0].dynamic_friction",
         [](Experiment& e) {
             e.materials[0].physics.static_friction = 0.5;
             e.materials[0].physics.dynamic_friction = 0.6;
         }},
        {"materials", [](Experiment& e) { e.materials[1].physics.cte_per_c = 0; }},
        // A muscle beside the sine-active material (issue 43): one model per experiment.
        {"materials[2].actuation_model",
         [](Experiment& e) {
             MaterialEntry m = e.materials[1];
             m.physics.cte_per_c = 0.0;
             m.physics.actuation_model = bhm::engine::ActuationModel::Muscle;
             m.physics.muscle.contraction_strain = 0.05;
             e.materials.push_back(m);
         }},
        {"boundary.enclosure.thickness_voxels",
         [](Experiment& e) {
             e.boundary.enclosure_material = 1;
             e.boundary.enclosure_thickness[0] = e.workspace_size[0] - 1;
             e.boundary.enclosure_thickness[1] = 1;
         }},
        {"boundary.enclosure.material",
         [](Experiment& e) {
             e.boundary.enclosure_thickness[4] = 1;
             e.boundary.enclosure_material = 2;  // the active one
         }},
        {"boundary.voxel_overrides[0].voxel",
         [](Experiment& e) {
             e.boundary.voxel_overrides.push_back({{0, e.workspace_size[1], 0}});
         }},
        {"fitness.constraints.attached_to_fixed_face",
         [](Experiment& e) {
             e.fitness.constraints.attached_to_fixed_face = true;
             e.boundary.faces.fill(BoundaryKind::Free);
         }},
        {"fitness.constraints.min_active_voxels",
         [](Experiment& e) {
             e.fitness.constraints.min_active_voxels =
                 e.workspace_size[0] * e.workspace_size[1] * e.workspace_size[2] + 1;
         }},
        {"evolution.cppn.max_hidden_nodes",
         [](Experiment& e) {
             e.evolution.cppn.min_hidden_nodes = 6;
             e.evolution.cppn.max_hidden_nodes = 5;
         }},
        {"evolution.cppn.material_outputs",
         [](Experiment& e) {
             e.evolution.cppn.material_outputs = MaterialOutputs::PerMaterial;
             e.materials.pop_back();
         }},
        // Fibre outputs without a muscle material to turn (issue 43).
        {"evolution.cppn.fibre_outputs",
         [](Experiment& e) { e.evolution.cppn.fibre_outputs = true; }},
        {"evolution.neat.elitism",
         [](Experiment& e) { e.evolution.neat.elitism = e.evolution.population + 1; }},
        // HyperNEAT's substrate: 15^3 cells x 9^3 = 2.46e6 connections, over its 2e6 (issue 44).
        {"evolution.hyperneat.radius",
         [](Experiment& e) {
             e.evolution.algorithm = Algorithm::HyperNeat;
             e.workspace_size = {15, 15, 15};
             e.evolution.hyperneat.radius = 4;
         }},
        {"simulation", [](Experiment& e) { e.simulation.evaluate_s = 9e4; }},
    };
    REQUIRE(std::size(breaks) == field_rules().size());
    for (const auto& b : breaks) {
        CAPTURE(b.field);
        Experiment e = base;
        b.apply(e);
        const auto problems = validate_experiment(e, "e.json");
        CHECK(std::any_of(problems.begin(), problems.end(),
                          [&](const Problem& p) { return p.field == b.field; }));
        // Nothing else of the table is out of range: the rule, not a range, refused it.
        for (const auto& p : problems)
            CHECK(p.message.find("must be in") == std::string::npos);
    }
    // Every field a rule names is a field of the table, and its tooltip says the rule.
    int quoted = 0;
    for (const auto& rule : field_rules()) {
        const std::string text = rule.text();
        for (const char* name : rule.fields) {
            if (!name) continue;
            CAPTURE(name);
            const std::string_view n(name);
            if (n.starts_with("materials[].")) {
                const MaterialField* f = find_material_field(n.substr(12));
                REQUIRE(f != nullptr);
                CHECK(field_tooltip(*f).find(text) != std::string::npos);
                ++quoted;
            } else if (n.ends_with('.')) {
                int under = 0;
                for (const auto& f : experiment_fields())
                    if (std::string_view(f.path).starts_with(n)) {
                        CHECK(field_tooltip(f).find(text) != std::string::npos);
                        ++under;
                    }
                CHECK(under == 6);  // the six faces
                quoted += under;
            } else {
                const ExperimentField* f = find_experiment_field(n);
                REQUIRE(f != nullptr);
                CHECK(field_tooltip(*f).find(text) != std::string::npos);
                ++quoted;
            }
        }
    }
    CHECK(quoted >= 25);
    // A field no rule names has no rule in its tooltip.
    CHECK(rules_text("simulation.record_fps").empty());
    CHECK(field_tooltip(*find_experiment_field("evolution.cppn.min_hidden_nodes"))
              .find("max_hidden_nodes >= min_hidden_nodes") != std::string::npos);
}

TEST_CASE("the boundary's rows read as the file gives them: objects, keys and kinds checked") {
    json j = experiment_to_json(preset());
    j["boundary"]["enclosure"]["thikness_voxels"] = json::object();
    j["boundary"]["faces"]["x+"] = "held";
    j["boundary"]["enclosure"]["thickness_voxels"]["z-"] = 1.5;
    try {
        (void)parse_experiment(j, "e.json");
        FAIL("a broken boundary was accepted");
    } catch (const ValidationError& e) {
        auto names = [&](const std::string& field, const std::string& text) {
            return refused_with(e.problems, field, text);
        };
        CHECK(names("boundary.enclosure.thikness_voxels", "thickness_voxels"));
        CHECK(names("boundary.faces.x+", "free"));
        CHECK(names("boundary.enclosure.thickness_voxels.z-", "integer"));
    }
    j = experiment_to_json(preset());
    j["boundary"] = 3;
    try {
        (void)parse_experiment(j, "e.json");
        FAIL("a boundary that is not an object was accepted");
    } catch (const ValidationError& e) {
        // Reported once, by the table's reader (the overrides' reader does not repeat it).
        CHECK(std::count_if(e.problems.begin(), e.problems.end(),
                            [](const Problem& p) { return p.field == "boundary"; }) == 1);
    }
}

TEST_CASE("docs/experiment-format.md documents every field of the table") {
    const std::string doc =
        bhm::test::read_file(std::string(BHM_SOURCE_DIR) + "/docs/experiment-format.md");
    REQUIRE_FALSE(doc.empty());
    // Each section's table names a field by its path within the section ("constraints.min_fill_
    // fraction" under fitness), so any dotted suffix of the path in backticks counts.
    auto documented = [&](const std::string& path) {
        for (std::size_t from = 0;; ++from) {
            if (doc.find("`" + path.substr(from) + "`") != std::string::npos) return true;
            from = path.find('.', from);
            if (from == std::string::npos) return false;
        }
    };
    for (const auto& f : experiment_fields()) {
        CAPTURE(f.path);
        CHECK(documented(f.path));
    }
    for (const auto& f : material_fields()) {
        CAPTURE(f.path);
        CHECK(documented(f.path));
    }
}

TEST_CASE("range numbers read as written") {
    CHECK(range_number(100000) == "100000");
    CHECK(range_number(1e6) == "1e6");
    CHECK(range_number(1e-6) == "1e-6");
    CHECK(range_number(1e12) == "1e12");
    CHECK(range_number(-0.9) == "-0.9");
    CHECK(range_text({0, 1, true}) == "(0, 1]");
    CHECK(range_text({0}) == "[0, inf)");
}
