// The rules between fields (field_rules.hpp). Bounds come from the constants they use
// (engine/limits.hpp, experiment_fields.hpp), so a tooltip says what the check enforces.
#include "evo/experiment/field_rules.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/limits.hpp"
#include "engine/muscle.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_fields.hpp"

namespace bhm::evo {

namespace {

namespace lim = engine::limits;

std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

// The workspace's voxel count, or nothing while a dimension is outside its range (reported by the
// table's range check).
std::optional<long long> workspace_cells(const Experiment& e) {
    long long cells = 1;
    for (int n : e.workspace_size) {
        if (n < 1 || n > kMaxWorkspaceDimension) return std::nullopt;
        cells *= n;
    }
    return cells;
}

std::string materials_range(const Experiment& e) {
    return "1.." + std::to_string(e.materials.size());
}

bool has_active(const Experiment& e) {
    return std::any_of(e.materials.begin(), e.materials.end(),
                       [](const MaterialEntry& m) { return m.active(); });
}

void workspace_cells_rule(const RuleCheck& c) {
    const auto cells = workspace_cells(c.experiment);
    if (cells && *cells > kMaxWorkspaceCells)
        c.bad("workspace.size", "workspace of " + std::to_string(*cells) +
                                    " voxels is too large to simulate in memory (at most " +
                                    std::to_string(kMaxWorkspaceCells) + ")");
}

// The engine refuses a material whose actuation strain |cte x amplitude| is beyond its stable
// bound; with cte in its own range, the amplitude makes it too much.
void actuation_strain_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    for (std::size_t i = 0; i < e.materials.size(); ++i) {
        const std::string p = "materials[" + std::to_string(i) + "]";
        if (c.reported(p + ".cte_per_c")) continue;
        // A muscle's cte must be 0, whatever the amplitude (experiment_io.cpp reports it).
        if (e.materials[i].physics.actuation_model == engine::ActuationModel::Muscle) continue;
        for (const auto& problem :
             lim::material_problems(e.materials[i].physics, e.actuation.temperature_amplitude_c))
            if (problem.field == "cte_per_c")
                c.bad("actuation.temperature_amplitude_c",
                      "with " + p + ".cte_per_c " + problem.message);
    }
}

void friction_order_rule(const RuleCheck& c) {
    const auto& materials = c.experiment.materials;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const auto& m = materials[i].physics;
        if (std::isfinite(m.static_friction) && std::isfinite(m.dynamic_friction) &&
            m.dynamic_friction >= 0 && m.dynamic_friction > m.static_friction)
            c.bad("materials[" + std::to_string(i) + "].dynamic_friction",
                  "must not exceed static_friction");
    }
}

void active_and_passive_rule(const RuleCheck& c) {
    const auto& materials = c.experiment.materials;
    const bool passive = std::any_of(materials.begin(), materials.end(),
                                     [](const MaterialEntry& m) { return !m.active(); });
    if (!materials.empty() && !(has_active(c.experiment) && passive))
        c.bad("materials",
              "evolution needs a passive material (cte_per_c = 0) and an active one "
              "(cte_per_c > 0, or a muscle with muscle.contraction_strain > 0)");
}

// One actuation model per body and at most two muscle signals (engine/muscle.hpp): the palette
// as a whole, since evolution may paint any of its materials.
void actuation_model_rule(const RuleCheck& c) {
    std::vector<engine::Material> palette;
    for (const auto& m : c.experiment.materials)
        palette.push_back(m.physics);
    for (const auto& p : engine::muscle::palette_problems(palette))
        if (!c.reported(p.field)) c.bad(p.field, p.message);
}

void frame_thickness_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    if (!workspace_cells(e)) return;
    for (int axis = 0; axis < 3; ++axis) {
        const int lo = e.boundary.enclosure_thickness[2 * axis];
        const int hi = e.boundary.enclosure_thickness[2 * axis + 1];
        if (lo >= 0 && hi >= 0 && lo + hi >= e.workspace_size[axis])
            c.bad("boundary.enclosure.thickness_voxels",
                  std::string("frame thickness ") + kFaceNames[2 * axis] + " + " +
                      kFaceNames[2 * axis + 1] + " leaves no design space along " + "xyz"[axis]);
    }
}

void frame_material_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    const auto& b = e.boundary;
    if (c.reported("boundary.enclosure.material")) return;
    const int nmat = static_cast<int>(e.materials.size());
    const bool any_frame = std::any_of(b.enclosure_thickness.begin(), b.enclosure_thickness.end(),
                                       [](int t) { return t > 0; });
    if (any_frame) {
        if (b.enclosure_material < 1 || b.enclosure_material > nmat)
            c.bad("boundary.enclosure.material",
                  "must name a material " + materials_range(e) + " when the frame has a thickness");
        else if (e.materials[static_cast<std::size_t>(b.enclosure_material - 1)].active())
            c.bad("boundary.enclosure.material", "the enclosure frame must be a passive material");
    } else if (b.enclosure_material < 0 || b.enclosure_material > nmat) {
        c.bad("boundary.enclosure.material",
              "must be 0 (none) or a material " + materials_range(e));
    }
}

void voxel_overrides_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    const int nmat = static_cast<int>(e.materials.size());
    const auto& overrides = e.boundary.voxel_overrides;
    for (std::size_t i = 0; i < overrides.size(); ++i) {
        const auto& o = overrides[i];
        const std::string p = "boundary.voxel_overrides[" + std::to_string(i) + "]";
        for (int a = 0; a < 3; ++a)
            if (o.voxel[a] < 0 || o.voxel[a] >= e.workspace_size[a]) {
                c.bad(p + ".voxel", "lies outside the workspace");
                break;
            }
        if (o.kind == OverrideKind::Material && (o.material < 1 || o.material > nmat))
            c.bad(p + ".material", "must name a material " + materials_range(e));
    }
}

void attached_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    if (e.fitness.constraints.attached_to_fixed_face && !e.boundary.any_fixed_face())
        c.bad("fitness.constraints.attached_to_fixed_face",
              "is on but no face of boundary.faces is \"fixed\"");
}

void min_active_rule(const RuleCheck& c) {
    const auto cells = workspace_cells(c.experiment);
    if (cells && c.experiment.fitness.constraints.min_active_voxels > *cells)
        c.bad("fitness.constraints.min_active_voxels",
              "must not exceed the workspace's " + std::to_string(*cells) + " voxels");
}

void hidden_nodes_rule(const RuleCheck& c) {
    const auto& cppn = c.experiment.evolution.cppn;
    if (cppn.max_hidden_nodes < cppn.min_hidden_nodes)
        c.bad("evolution.cppn.max_hidden_nodes", "must be at least min_hidden_nodes");
}

void per_material_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    if (e.evolution.cppn.material_outputs == MaterialOutputs::PerMaterial && e.materials.size() < 2)
        c.bad("evolution.cppn.material_outputs",
              "\"per_material\" needs at least two materials to choose between");
}

void fibre_outputs_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    if (!e.evolution.cppn.fibre_outputs) return;
    for (const auto& m : e.materials)
        if (m.physics.actuation_model == engine::ActuationModel::Muscle && m.active()) return;
    c.bad("evolution.cppn.fibre_outputs",
          "needs a muscle material (actuation_model \"muscle\") whose fibres it can turn");
}

void elitism_rule(const RuleCheck& c) {
    const auto& ev = c.experiment.evolution;
    if (ev.neat.elitism > ev.population)
        c.bad("evolution.neat.elitism", "must not exceed evolution.population");
}

// HyperNEAT queries its CPPN once per substrate connection per development: cells x (2 radius +
// 1)^3 over the workspace (the controller's lattice, the larger of the two) must stay within
// kMaxHyperNeatConnections.
void hyperneat_size_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    if (e.evolution.algorithm != Algorithm::HyperNeat) return;
    const double cells =
        static_cast<double>(e.workspace_size[0]) * e.workspace_size[1] * e.workspace_size[2];
    const double field = 2.0 * e.evolution.hyperneat.radius + 1.0;
    const double connections = cells * field * field * field;
    if (connections > kMaxHyperNeatConnections)
        c.bad("evolution.hyperneat.radius",
              "the substrate would have " + short_number(connections) +
                  " connections per sheet (workspace cells x (2 radius + 1)^3), more than " +
                  short_number(kMaxHyperNeatConnections) + ": use a smaller radius");
}

// Only once every input it depends on is valid (else it would mislead): fitness and evolution
// settings do not enter it.
void step_budget_rule(const RuleCheck& c) {
    const auto& e = c.experiment;
    const auto cells = workspace_cells(e);
    const bool inputs_valid =
        std::all_of(c.problems.begin(), c.problems.end(), [](const Problem& p) {
            return p.field.starts_with("fitness.") || p.field.starts_with("evolution.");
        });
    if (!inputs_valid || !cells) return;
    const auto& s = e.simulation;
    std::vector<engine::Material> physics;
    for (const auto& m : e.materials)
        physics.push_back(m.physics);
    const auto range =
        lim::step_range(physics, e.voxel_size_m, s.dt_fraction, e.actuation.temperature_amplitude_c,
                        s.implicit_damping_sweeps, s.rotary_inertia_scale);
    const std::string why =
        lim::step_budget_problem(range, evaluation_seconds(e), e.actuation.frequency_hz,
                                 has_active(e) && e.actuation.temperature_amplitude_c > 0, *cells);
    if (!why.empty())
        c.bad("simulation",
              "settle_s + evaluate_s = " + short_number(evaluation_seconds(e)) + " s " + why);
}

// clang-format off
const FieldRule kRules[] = {
    {.fields = {"workspace.size"},
     .text = [] { return "at most " + std::to_string(kMaxWorkspaceCells) + " voxels in all"; },
     .check = workspace_cells_rule},
    {.fields = {"actuation.temperature_amplitude_c", "materials[].cte_per_c"},
     .text = [] {
         return "|cte_per_c x amplitude| <= " + range_number(lim::kMaxActuationStrain) +
                " (the engine's stable actuation strain)";
     },
     .check = actuation_strain_rule},
    {.fields = {"materials[].dynamic_friction"},
     .text = [] { return std::string("at most static_friction"); },
     .check = friction_order_rule},
    {.text = [] { return std::string("a passive material (cte_per_c = 0) and an active one"); },
     .check = active_and_passive_rule},
    {.fields = {"materials[].actuation_model"},
     .text = [] {
         return std::string("one model per experiment (sine or muscle), at most 2 distinct "
                            "muscle stimuli and time constants");
     },
     .check = actuation_model_rule},
    {.fields = {"boundary.enclosure.thickness_voxels."},
     .text = [] { return std::string("the two faces of an axis leave design space: x- + x+ < "
                                     "workspace x"); },
     .check = frame_thickness_rule},
    {.fields = {"boundary.enclosure.material"},
     .text = [] { return std::string("a passive material when a face has a frame"); },
     .check = frame_material_rule},
    {.text = [] { return std::string("each override inside the workspace, naming a material"); },
     .check = voxel_overrides_rule},
    {.fields = {"fitness.constraints.attached_to_fixed_face", "boundary.faces."},
     .text = [] { return std::string("attached_to_fixed_face needs a fixed face"); },
     .check = attached_rule},
    {.fields = {"fitness.constraints.min_active_voxels"},
     .text = [] { return std::string("at most the workspace's voxel count"); },
     .check = min_active_rule},
    {.fields = {"evolution.cppn.max_hidden_nodes", "evolution.cppn.min_hidden_nodes"},
     .text = [] { return std::string("max_hidden_nodes >= min_hidden_nodes"); },
     .check = hidden_nodes_rule},
    {.fields = {"evolution.cppn.material_outputs"},
     .text = [] { return std::string("per_material needs two materials or more"); },
     .check = per_material_rule},
    {.fields = {"evolution.cppn.fibre_outputs", "materials[].actuation_model"},
     .text = [] { return std::string("fibre_outputs needs a muscle material"); },
     .check = fibre_outputs_rule},
    {.fields = {"evolution.neat.elitism", "evolution.population"},
     .text = [] { return std::string("neat.elitism <= population"); },
     .check = elitism_rule},
    {.fields = {"evolution.hyperneat.radius", "workspace.size"},
     .text = [] {
         return "workspace cells x (2 radius + 1)^3 <= " + short_number(kMaxHyperNeatConnections);
     },
     .check = hyperneat_size_rule},
    {.fields = {"simulation.settle_s", "simulation.evaluate_s"},
     .text = [] {
         return std::string("settle_s + evaluate_s within the step budget (docs/physics.md)");
     },
     .check = step_budget_rule},
};
// clang-format on

bool names(const char* rule_field, std::string_view path) {
    if (!rule_field) return false;
    const std::string_view r(rule_field);
    return r.ends_with('.') ? path.starts_with(r) : path == r;
}

}  // namespace

bool RuleCheck::reported(std::string_view field) const {
    return std::any_of(problems.begin(), problems.end(),
                       [&](const Problem& p) { return p.field == field; });
}

std::span<const FieldRule> field_rules() {
    return kRules;
}

std::string rules_text(std::string_view path) {
    std::string s;
    for (const auto& rule : kRules)
        if (names(rule.fields[0], path) || names(rule.fields[1], path))
            s += (s.empty() ? "" : "; ") + rule.text();
    return s;
}

void check_rules(const Experiment& experiment, const std::string& file,
                 std::vector<Problem>& problems) {
    const RuleCheck check{experiment, file, problems};
    for (const auto& rule : kRules)
        rule.check(check);
}

}  // namespace bhm::evo
