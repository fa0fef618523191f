#include "evo/verify/verify_body.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <queue>
#include <stdexcept>

#include "engine/muscle.hpp"
#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/coarse_nonlinearity.hpp"
#include "evo/verify/fem_shape.hpp"

namespace bhm::evo {

namespace {

using Vec = std::array<double, 3>;

double norm(const Vec& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

bool held_cell(const engine::BodySpec& s, int cell) {
    return !s.fixed.empty() && s.fixed[static_cast<std::size_t>(cell)] != 0;
}

std::array<int, 3> coords(const engine::BodySpec& s, int cell) {
    return {cell % s.nx, (cell / s.nx) % s.ny, cell / (s.nx * s.ny)};
}

Vec centre_m(const engine::BodySpec& s, int cell) {
    const auto c = coords(s, cell);
    return {(c[0] + 0.5) * s.voxel_size_m, (c[1] + 0.5) * s.voxel_size_m,
            (c[2] + 0.5) * s.voxel_size_m};
}

// The geometry every measure refers to: the held voxels' centroid (the root), the voxel farthest
// from it (the tip) and each voxel's mass.
struct Geometry {
    std::vector<int> cells;
    std::vector<double> mass;
    Vec root{};
    int tip = 0;  // index into cells
};

Geometry geometry_of(const engine::BodySpec& s, const std::vector<int>& cells) {
    Geometry g;
    g.cells = cells;
    int held = 0;
    for (int cell : cells) {
        const auto& m = s.materials[static_cast<std::size_t>(
            s.material[static_cast<std::size_t>(cell)] - 1)];
        g.mass.push_back(m.density_kg_m3);
        if (!held_cell(s, cell)) continue;
        const Vec c = centre_m(s, cell);
        for (int a = 0; a < 3; ++a)
            g.root[a] += c[a];
        ++held;
    }
    for (int a = 0; a < 3; ++a)
        g.root[a] /= std::max(held, 1);
    double farthest = -1.0;
    for (std::size_t v = 0; v < cells.size(); ++v) {
        const Vec c = centre_m(s, cells[v]);
        const double d = norm({c[0] - g.root[0], c[1] - g.root[1], c[2] - g.root[2]});
        if (d > farthest + 1e-12) {
            farthest = d;
            g.tip = static_cast<int>(v);
        }
    }
    return g;
}

ResponseMeasures measure(const engine::BodySpec& s, const Geometry& g,
                         const std::vector<Vec>& u) {
    ResponseMeasures r;
    const std::size_t tip = static_cast<std::size_t>(g.tip);
    r.tip_m = u[tip];
    const Vec c = centre_m(s, g.cells[tip]);
    const Vec before{c[0] - g.root[0], c[1] - g.root[1], c[2] - g.root[2]};
    const Vec after{before[0] + u[tip][0], before[1] + u[tip][1], before[2] + u[tip][2]};
    const double cosine = (before[0] * after[0] + before[1] * after[1] + before[2] * after[2]) /
                          std::max(norm(before) * norm(after), 1e-300);
    r.bend_deg = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
    Vec com{};
    double mass = 0.0;
    for (std::size_t v = 0; v < u.size(); ++v) {
        for (int a = 0; a < 3; ++a)
            com[a] += g.mass[v] * u[v][a];
        mass += g.mass[v];
    }
    for (int a = 0; a < 3; ++a)
        com[a] /= mass;
    r.com_yz_m = {com[1], com[2]};
    r.com_m = com;
    return r;
}

// The largest angle any voxel has turned from its rest orientation (unit quaternions w x y z).
double largest_rotation_deg(const engine::VoxelPoses& shape) {
    double largest = 0.0;
    for (std::size_t k = 0; k + 3 < shape.orientation.size(); k += 4) {
        const double w = std::min(1.0, std::fabs(static_cast<double>(shape.orientation[k])));
        largest = std::max(largest, 2.0 * std::acos(w) * 180.0 / std::numbers::pi);
    }
    return largest;
}

std::optional<double> relative(double difference, double truth, double smallest) {
    if (std::fabs(truth) < smallest) return std::nullopt;
    return std::fabs(difference) / std::fabs(truth);
}

std::vector<Vec> fem_voxel_displacements(const FemModel& m, const NodalDisplacements& nodes) {
    std::vector<Vec> out;
    for (const auto& centre : m.voxel_centre) {
        Vec u{};
        for (const auto& [id, w] : centre) {
            const auto it = nodes.find(id);
            if (it == nodes.end())
                throw std::runtime_error("ccx printed no displacement for node " +
                                         std::to_string(id));
            for (int a = 0; a < 3; ++a)
                u[a] += w * it->second[a];
        }
        out.push_back(u);
    }
    return out;
}

// The load steps: rest, and +A and -A where some voxel is active and the amplitude is not 0; a
// muscle body's rest and peak activation (a = 1: a muscle only contracts, so there is no -A).
std::vector<FemLoad> loads_of(const engine::BodySpec& spec) {
    std::vector<FemLoad> loads{{"rest", 0.0}};
    if (muscle_driven(spec)) {
        loads.push_back({"peak", 1.0});
        return loads;
    }
    const double amplitude = spec.actuation.temperature_amplitude_c;
    bool active = false;
    for (int m : spec.material)
        active = active ||
                 (m != 0 && engine::is_active(spec.materials[static_cast<std::size_t>(m - 1)]));
    if (active && amplitude != 0.0) {
        loads.push_back({"+A", amplitude});
        loads.push_back({"-A", -amplitude});
    }
    return loads;
}

// Whether the loads are rest, +A and -A (not a muscle body's rest and peak).
bool symmetric_loads(const std::vector<FemLoad>& loads) {
    return loads.size() == 3 && loads[0].temperature_c == 0.0 &&
           loads[2].temperature_c == -loads[1].temperature_c;
}

// One ccx solve of every load, reporting its progress; throws on a missing block. `cost`, when
// given, hears what the solve cost (a failed solve leaves it alone).
//
// Two shortcuts where the loads are rest, +A and -A (docs/verify.md, "Overhead, measured"):
// - linear steps: only rest and +A are solved, and -A is 2 rest - (+A). Each linear step costs
//   ccx a factorisation of the same stiffness, and the answer is linear in the temperature, so
//   this is the same answer (measured within ccx's printed 7 digits) for two thirds of the cost;
// - nonlinear steps: -A is solved in a run of its own from the undeformed body, not as a step
//   from +A. ccx's steps follow one another, so -A was reached across a swing of 2 A, which took
//   it more Newton iterations than the whole way from rest (measured on a 238-voxel champion's
//   coarse mesh: 22 against 9 under Neo-Hookean, 10 against 5 under Saint Venant-Kirchhoff).
//   The equilibrium is the same (a hyperelastic body's answer does not depend on its path; the
//   two differ by 1e-5 of the largest displacement, ccx's Newton tolerance).
CcxResult run_fem(const FemModel& model, const engine::BodySpec& spec,
                  const std::vector<FemLoad>& loads, bool nlgeom, const VerifyOptions& options,
                  FemMaterialLaw law = FemMaterialLaw::Hooke, FemSolveCost* cost = nullptr,
                  FemNewtonControls newton = FemNewtonControls::CcxDefaults,
                  bool full_integration = false) {
    const VerifyControl& control = options.control;
    const int load_count = static_cast<int>(loads.size());
    const bool symmetric = symmetric_loads(loads);
    double deck_s = 0.0;
    CcxResult fem;
    // One ccx run of loads [first, last) (`first` > 0: steps from the undeformed body again).
    auto run = [&](std::size_t first, std::size_t last) {
        const std::vector<FemLoad> part(loads.begin() + static_cast<std::ptrdiff_t>(first),
                                        loads.begin() + static_cast<std::ptrdiff_t>(last));
        const auto deck_start = std::chrono::steady_clock::now();
        const std::string deck = ccx_deck(model, spec, part, nlgeom, law, newton, full_integration);
        deck_s +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - deck_start).count();
        control.report({VerifyPhase::Solving, static_cast<int>(first) + 1, load_count});
        CcxWatch watch;
        watch.cancel = control.cancel;
        watch.steps_done = [&](int done) {
            control.report({VerifyPhase::Solving,
                            std::min(static_cast<int>(first) + done + 1, load_count), load_count});
        };
        CcxResult part_result = run_ccx("body", deck, options.threads, options.keep_dir, watch);
        if (part_result.blocks.size() != part.size())
            throw std::runtime_error("ccx printed " + std::to_string(part_result.blocks.size()) +
                                     " displacement blocks for " + std::to_string(part.size()) +
                                     " load steps");
        fem.cpu_s += part_result.cpu_s;
        fem.wall_s += part_result.wall_s;
        for (auto& b : part_result.blocks)
            fem.blocks.push_back(std::move(b));
    };
    if (symmetric && !nlgeom) {
        run(0, 2);
        NodalDisplacements minus = fem.blocks[0];
        for (auto& [id, u] : minus) {
            const auto it = fem.blocks[1].find(id);
            if (it == fem.blocks[1].end())
                throw std::runtime_error("ccx printed no displacement for node " +
                                         std::to_string(id) + " at +A");
            for (int a = 0; a < 3; ++a)
                u[a] = 2.0 * u[a] - it->second[a];
        }
        fem.blocks.push_back(std::move(minus));
    } else if (symmetric) {
        run(0, 2);
        run(2, 3);
    } else {
        run(0, loads.size());
    }
    if (cost) {
        cost->nlgeom = nlgeom;
        cost->law = nlgeom ? fem_material_law_name(law) : "";
        cost->element = full_integration && model.options.element == FemElement::C3D20R
                            ? std::string("C3D20")
                            : std::string(fem_element_name(model.options.element));
        cost->elements = static_cast<int>(model.elements.size());
        cost->nodes = model.node_count();
        cost->deck_s = deck_s;
        cost->cpu_s = fem.cpu_s;
        cost->wall_s = fem.wall_s;
    }
    return fem;
}

// The FEM's side of one load's comparison (fem, fem_rms_m, fem_largest_m); returns its voxel
// displacements.
std::vector<Vec> fem_side(const engine::BodySpec& spec, const Geometry& g, const FemModel& model,
                          const NodalDisplacements& block, LoadComparison& c) {
    auto theirs = fem_voxel_displacements(model, block);
    c.fem = measure(spec, g, theirs);
    double f2 = 0.0;
    for (const auto& u : theirs) {
        c.fem_largest_m = std::max(c.fem_largest_m, norm(u));
        f2 += u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    }
    c.fem_rms_m = std::sqrt(f2 / static_cast<double>(theirs.size()));
    return theirs;
}

// One load compared: the FEM's side from `block`, ours from `displacement_m` (our engine's, or,
// for the spread of the two continuum laws, the other law's voxel displacements).
LoadComparison compare_load(const engine::BodySpec& spec, const Geometry& g, const FemModel& model,
                            const NodalDisplacements& block, const std::vector<Vec>& displacement_m,
                            const FemLoad& load) {
    const double smallest_m = 1e-4 * spec.voxel_size_m;
    LoadComparison c;
    c.load = load.name;
    c.temperature_c = load.temperature_c;
    const auto theirs = fem_side(spec, g, model, block, c);
    c.engine = measure(spec, g, displacement_m);
    Vec tip_difference{};
    for (int a = 0; a < 3; ++a)
        tip_difference[a] = c.engine.tip_m[a] - c.fem.tip_m[a];
    c.differences.tip = relative(norm(tip_difference), norm(c.fem.tip_m), smallest_m);
    c.differences.bend = relative(c.engine.bend_deg - c.fem.bend_deg, c.fem.bend_deg, 0.05);
    c.differences.com_yz = relative(std::hypot(c.engine.com_yz_m[0] - c.fem.com_yz_m[0],
                                               c.engine.com_yz_m[1] - c.fem.com_yz_m[1]),
                                    std::hypot(c.fem.com_yz_m[0], c.fem.com_yz_m[1]), smallest_m);
    c.differences.com =
        relative(std::hypot(c.engine.com_m[0] - c.fem.com_m[0], c.engine.com_m[1] - c.fem.com_m[1],
                            c.engine.com_m[2] - c.fem.com_m[2]),
                 std::hypot(c.fem.com_m[0], c.fem.com_m[1], c.fem.com_m[2]), smallest_m);
    double d2 = 0.0;
    for (std::size_t v = 0; v < theirs.size(); ++v)
        for (int a = 0; a < 3; ++a) {
            const double d = displacement_m[v][a] - theirs[v][a];
            d2 += d * d;
        }
    const double n = static_cast<double>(theirs.size());
    c.differences.rms = relative(std::sqrt(d2 / n), c.fem_rms_m, smallest_m);
    return c;
}

}  // namespace

std::string describe_progress(const VerifyProgress& p) {
    const std::string of = " " + std::to_string(p.load) + " of " + std::to_string(p.loads);
    switch (p.phase) {
        case VerifyPhase::Meshing:
            return "meshing";
        case VerifyPhase::Solving:
            return "CalculiX solving load" + of;
        case VerifyPhase::Engine:
            return "our engine at load" + of;
        case VerifyPhase::Comparing:
            return "comparing";
        case VerifyPhase::SecondMesh:
            return "mesh error: CalculiX solving the second mesh, load" + of;
    }
    return "";
}

double Differences::worst() const {
    double w = 0.0;
    for (const auto& d : {tip, bend, com_yz, com, rms})
        if (d) w = std::max(w, *d);
    return w;
}

std::optional<double> Differences::of(VerifyMeasure m) const {
    switch (m) {
        case VerifyMeasure::Com: return com;
        case VerifyMeasure::ComYz: return com_yz;
        case VerifyMeasure::Tip: return tip;
        case VerifyMeasure::Bend: return bend;
        case VerifyMeasure::Rms: return rms;
    }
    return std::nullopt;
}

std::string BodyVerification::verdict() const {
    if (status == VerifyStatus::OutOfReach) return "outside the continuum's reach: " + reason;
    return verdict_line(decision, measure, tolerance, floors) + (muscle ? kMuscleLoadsNote : "");
}

std::string BodyVerification::laws() const {
    if (status == VerifyStatus::OutOfReach || material_law.empty() || other_law.empty()) return "";
    if (other_law_skipped)
        return "judged against the " + material_law + " continuum, solved first, which agrees; " +
               other_law +
               " not solved (the nearer of two laws cannot turn an agreement into a "
               "difference)";
    std::string line = "judged against the " + material_law + " continuum, the nearer of two laws";
    if (other_law_worst) line += " (" + other_law + ": " + percent(*other_law_worst) + ")";
    if (law_spread && decision.decided_by)
        line += "; the two laws' answers differ by " + percent(*law_spread) + " on " +
                verify_measure_label(*decision.decided_by);
    return line;
}

double actuation_free_strain(const engine::BodySpec& spec) {
    double largest = 0.0;
    for (int m : spec.material) {
        if (m == 0) continue;
        const engine::Material& material = spec.materials.at(static_cast<std::size_t>(m - 1));
        if (!engine::is_active(material)) continue;
        largest = std::max(
            largest, material.actuation_model == engine::ActuationModel::Muscle
                         ? engine::muscle::largest_scale(material) - 1.0
                         : std::fabs(material.cte_per_c * spec.actuation.temperature_amplitude_c));
    }
    return largest;
}

std::string BodyVerification::beside() const {
    return status == VerifyStatus::OutOfReach ? "" : measures_beside(decision, floors);
}

std::string continuum_reach_problem(const engine::BodySpec& s) {
    std::vector<int> seen(static_cast<std::size_t>(s.cell_count()), 0);
    std::queue<int> todo;
    int voxels = 0;
    for (int c = 0; c < s.cell_count(); ++c) {
        if (s.material[static_cast<std::size_t>(c)] == 0) continue;
        ++voxels;
        if (held_cell(s, c)) {
            seen[static_cast<std::size_t>(c)] = 1;
            todo.push(c);
        }
    }
    if (voxels == 0) return "the body has no voxel";
    if (todo.empty())
        return "no voxel is held (a free body moves by its contact with the floor, which the "
               "continuum model does not have)";
    int reached = static_cast<int>(todo.size());
    while (!todo.empty()) {
        const auto c = coords(s, todo.front());
        todo.pop();
        const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (const auto& d : steps) {
            const int x = c[0] + d[0], y = c[1] + d[1], z = c[2] + d[2];
            if (x < 0 || y < 0 || z < 0 || x >= s.nx || y >= s.ny || z >= s.nz) continue;
            const int n = s.cell_index(x, y, z);
            if (seen[static_cast<std::size_t>(n)] || s.material[static_cast<std::size_t>(n)] == 0)
                continue;
            seen[static_cast<std::size_t>(n)] = 1;
            ++reached;
            todo.push(n);
        }
    }
    if (reached < voxels)
        return std::to_string(voxels - reached) + " of " + std::to_string(voxels) +
               " voxels are not attached to a held voxel (a detached or escaped part)";
    return "";
}

FemAnswer solve_fem(const engine::BodySpec& spec, const FemMeshOptions& mesh, bool nlgeom,
                    const VerifyOptions& options) {
    if (options.control.cancelled()) throw VerifyCancelled();
    options.control.report({VerifyPhase::Meshing, 0, 0});
    const FemModel model = build_fem_model(spec, mesh);
    const auto loads = loads_of(spec);
    const CcxResult fem = run_fem(model, spec, loads, nlgeom, options);
    const Geometry g = geometry_of(spec, model.voxel_cells);
    FemAnswer out;
    out.cpu_s = fem.cpu_s;
    out.wall_s = fem.wall_s;
    out.nodes = model.node_count();
    for (std::size_t k = 0; k < loads.size(); ++k) {
        LoadComparison c;
        c.load = loads[k].name;
        c.temperature_c = loads[k].temperature_c;
        fem_side(spec, g, model, fem.blocks[k], c);
        out.loads.push_back(std::move(c));
    }
    return out;
}

BodyVerification verify_body(const engine::BodySpec& spec, FitnessMeasure fitness,
                             const VerifyOptions& options) {
    BodyVerification out;
    out.tolerance = options.tolerance;
    out.floors = options.floors;
    out.measure = verify_measure_of(fitness);
    out.muscle = muscle_driven(spec);
    for (int c = 0; c < spec.cell_count(); ++c) {
        const int m = spec.material[static_cast<std::size_t>(c)];
        if (m == 0) continue;
        ++out.voxels;
        if (held_cell(spec, c)) ++out.held_voxels;
        if (engine::is_active(spec.materials[static_cast<std::size_t>(m - 1)])) ++out.active_voxels;
    }
    if (out.voxels > options.max_voxels)
        throw std::runtime_error("body too large to verify: " + std::to_string(out.voxels) +
                                 " voxels, at most " + std::to_string(options.max_voxels) +
                                 " (--max-voxels)");
    out.reason = continuum_reach_problem(spec);
    if (!out.reason.empty()) {
        out.status = VerifyStatus::OutOfReach;
        return out;
    }

    // The continuum.
    const VerifyControl& control = options.control;
    if (control.cancelled()) throw VerifyCancelled();
    control.report({VerifyPhase::Meshing, 0, 0});
    out.mesh = options.mesh ? explicit_fem_mesh(*options.mesh) : choose_fem_mesh(spec);
    out.fem_model = build_fem_model(spec, out.mesh.mesh);
    out.fem_nodes = out.fem_model.node_count();
    out.fem_elements = static_cast<int>(out.fem_model.elements.size());
    const std::vector<FemLoad> loads = loads_of(spec);
    const int load_count = static_cast<int>(loads.size());
    // The coarse mesh's elements with full integration (C3D20 for C3D20R): from the start where
    // the mesh is C3D20R for a section 1 voxel across (VerifyOptions), else from its first failed
    // nonlinear solve on (coarse_nonlinear below).
    const bool coarse_full_integration_up_front =
        options.coarse_full_integration_where_narrow &&
        out.mesh.mesh.element == FemElement::C3D20R &&
        narrowest_section(spec).width_voxels <= kNarrowSectionVoxels;
    bool coarse_full_integration = coarse_full_integration_up_front;
    // Every solve's cost is counted (fem_cpu_s: all of them) and recorded (fem_solves).
    auto counted = [&](const FemModel& model, bool nlgeom, FemMaterialLaw law) {
        FemSolveCost cost;
        cost.coarse = &model != &out.fem_model;
        // The coarse mesh's nonlinear part lets its increments grow faster (ccx_deck.hpp,
        // FemNewtonControls::Loose: 9-14 % fewer Newton iterations on the loop's picks, the
        // answers within 2e-3; docs/verify.md, "loop40c"); the mesh's own solves keep ccx's.
        const FemNewtonControls newton =
            cost.coarse ? FemNewtonControls::Loose : FemNewtonControls::CcxDefaults;
        CcxResult fem = run_fem(model, spec, loads, nlgeom, options, law, &cost, newton,
                                cost.coarse && coarse_full_integration);
        out.fem_cpu_s += fem.cpu_s;
        out.fem_wall_s += fem.wall_s;
        out.fem_solves.push_back(std::move(cost));
        return fem;
    };
    auto solve = [&](bool nlgeom, FemMaterialLaw law) {
        return counted(out.fem_model, nlgeom, law);
    };
    // The nonlinear part from a coarse mesh needs this mesh's linear answer first.
    const bool from_coarse = options.nonlinear_from_coarse_mesh && out.mesh.mesh.subdivision > 1;
    out.nlgeom = options.geometry == FemGeometry::Nonlinear;
    const bool solved_nonlinear = out.nlgeom && !from_coarse;
    CcxResult fem = solve(solved_nonlinear, FemMaterialLaw::Hooke);
    // Our engine's answers at the loads (filled below, before any nonlinear solve), and every
    // load's comparison of an FEM answer with them.
    const Geometry g = geometry_of(spec, out.fem_model.voxel_cells);
    out.tip_cell = g.cells[static_cast<std::size_t>(g.tip)];
    std::vector<QuasiStaticResult> answers;
    auto compare_all = [&](const std::vector<NodalDisplacements>& blocks) {
        std::vector<LoadComparison> all;
        for (std::size_t k = 0; k < loads.size(); ++k) {
            LoadComparison c = compare_load(spec, g, out.fem_model, blocks[k],
                                            answers[k].displacement_m, loads[k]);
            c.engine_shape = answers[k].shape;
            c.fem_shape = fem_voxel_shape(out.fem_model, blocks[k], answers[k].rest_position_m);
            all.push_back(std::move(c));
        }
        return all;
    };
    // Whether one law's answer alone agrees: then the other law need not be solved where
    // options.second_law_only_where_first_differs, since the verdict is the nearer law's and the
    // nearer of two cannot turn an agreement into a difference.
    const bool lazy_second_law = options.second_law_only_where_first_differs;
    auto agrees_alone = [&](const std::vector<NodalDisplacements>& blocks) {
        const VerdictDecision d =
            decide_verdict(compare_all(blocks), out.measure, options.tolerance, options.floors);
        return d.decided_by.has_value() && d.agrees;
    };
    // The nonlinear answers under each continuum law (ccx_deck.hpp): solved on this mesh, or its
    // linear one plus the coarse mesh's nonlinear part. The Neo-Hookean answer is empty where
    // its solve failed or was not needed (geometry_reason says why); the Saint Venant-Kirchhoff
    // one is `fem`, unless it was not needed (hooke_skipped: `fem` is then the linear answer).
    std::vector<NodalDisplacements> neo_hookean;
    bool neo_hookean_tried = false, hooke_skipped = false, neo_hookean_skipped = false;
    auto solve_nonlinear = [&]() {
        const double turned = std::max(out.engine_rotation_deg, out.engine_bend_deg);
        if (from_coarse && turned >= options.coarse_nonlinearity_below_deg) {
            char why[160];
            std::snprintf(why, sizeof why,
                          "; solved in full on this mesh, as our engine turns by %.1f deg, over "
                          "the %g deg up to which a coarse mesh's nonlinear part is used",
                          turned, options.coarse_nonlinearity_below_deg);
            out.geometry_reason += why;
        }
        // The second law's answer: its nonlinear part on the coarse mesh added to this mesh's
        // linear answer, also where the first law is solved in full, since a Neo-Hookean full
        // solve cuts its increments much more (measured: a 4976-element C3D20R champion still at
        // 0.19 of its first step after 5 min of CPU) and the second law is there for the spread.
        // Where it fails, the first law alone, and the reason says so.
        auto coarse_linear_of = [&](const FemModel& coarse) {
            return counted(coarse, false, FemMaterialLaw::Hooke);
        };
        // One element per voxel edge's nonlinear solve. C3D20R's can fail where the body's
        // 1-voxel sections turn ("too many cutbacks", even at rest under gravity on two of the
        // loop's three picks, 2026-12-07), which used to send the check to a full solve of
        // minutes; so it is solved again with C3D20, whose full integration has no spurious
        // modes, and the coarse linear answer with it, so that the part added is one element's
        // difference (docs/verify.md, "loop40c"). A second failure is the caller's.
        auto coarse_nonlinear = [&](const FemModel& coarse, FemMaterialLaw law,
                                    CcxResult& coarse_linear) {
            try {
                return counted(coarse, true, law);
            } catch (const std::runtime_error& e) {
                if (options.control.cancelled() || coarse_full_integration ||
                    coarse.options.element != FemElement::C3D20R)
                    throw;
                coarse_full_integration = true;
                out.geometry_reason +=
                    "; the coarse mesh's " + std::string(fem_material_law_name(law)) +
                    " solve failed with C3D20R (" + e.what() + "), so the coarse mesh is C3D20";
                coarse_linear = coarse_linear_of(coarse);
                return counted(coarse, true, law);
            }
        };
        // The coarse part's element, as the reason names it.
        auto coarse_element = [&]() {
            if (coarse_full_integration_up_front)
                return std::string("C3D20 (full integration, as a section is 1 voxel across)");
            return coarse_full_integration ? std::string("C3D20")
                                           : fem_element_name(out.mesh.mesh.element);
        };
        auto second_law = [&](const std::vector<NodalDisplacements>& fine_linear,
                              const FemModel& coarse, CcxResult& coarse_linear) {
            if (neo_hookean_tried) return;  // solved first (options.first_law)
            neo_hookean_tried = true;
            try {
                const CcxResult nh =
                    coarse_nonlinear(coarse, FemMaterialLaw::NeoHookean, coarse_linear);
                for (std::size_t k = 0; k < fine_linear.size(); ++k)
                    neo_hookean.push_back(with_coarse_nonlinearity(out.fem_model, fine_linear[k],
                                                                   coarse, coarse_linear.blocks[k],
                                                                   nh.blocks[k]));
            } catch (const std::runtime_error& e) {
                if (options.control.cancelled()) throw;
                neo_hookean.clear();
                out.geometry_reason += "; the Neo-Hookean solve failed (" + std::string(e.what()) +
                                       "), Saint Venant-Kirchhoff alone";
            }
        };
        // The Neo-Hookean law after Saint Venant-Kirchhoff's answer `fem`: not solved where that
        // agrees alone and the second law is solved only where the first differs.
        auto skip_neo_hookean = [&]() {
            neo_hookean_skipped = true;
            out.geometry_reason += "; Neo-Hookean not solved, as Saint Venant-Kirchhoff agrees";
        };
        auto then_second_law = [&](const std::vector<NodalDisplacements>& fine_linear,
                                   const FemModel& coarse, CcxResult& coarse_linear) {
            if (!neo_hookean_tried && lazy_second_law && agrees_alone(fem.blocks))
                skip_neo_hookean();
            else
                second_law(fine_linear, coarse, coarse_linear);
        };
        auto in_full = [&]() {
            const CcxResult fine_linear =
                solved_nonlinear ? solve(false, FemMaterialLaw::Hooke) : fem;
            if (!solved_nonlinear) fem = solve(true, FemMaterialLaw::Hooke);
            if (!neo_hookean_tried && lazy_second_law && agrees_alone(fem.blocks)) {
                skip_neo_hookean();
            } else if (!neo_hookean_tried) {
                const FemModel coarse = build_fem_model(spec, coarse_mesh_of(out.mesh.mesh));
                CcxResult coarse_linear = coarse_linear_of(coarse);
                second_law(fine_linear.blocks, coarse, coarse_linear);
            }
            if (!neo_hookean.empty())
                out.geometry_reason += "; the Neo-Hookean answer's nonlinear part from " +
                                       coarse_element() + ", 1 per voxel edge";
        };
        if (!from_coarse || turned >= options.coarse_nonlinearity_below_deg) {
            in_full();
            return;
        }
        const FemModel coarse = build_fem_model(spec, coarse_mesh_of(out.mesh.mesh));
        CcxResult linear = coarse_linear_of(coarse);
        // The Neo-Hookean law first (the evolution loop's choice): Saint Venant-Kirchhoff is then
        // solved only where the Neo-Hookean answer does not agree alone, or has none.
        if (lazy_second_law && options.first_law == FemMaterialLaw::NeoHookean) {
            second_law(fem.blocks, coarse, linear);
            if (!neo_hookean.empty() && agrees_alone(neo_hookean)) {
                hooke_skipped = true;
                out.nlgeom_from_coarse_mesh = true;
                out.geometry_reason += "; its nonlinear part from " + coarse_element() +
                                       ", 1 per voxel edge, added to this mesh's linear answer; "
                                       "Saint Venant-Kirchhoff not solved, as Neo-Hookean agrees";
                return;
            }
        }
        CcxResult nonlinear;
        try {
            nonlinear = coarse_nonlinear(coarse, FemMaterialLaw::Hooke, linear);
        } catch (const std::runtime_error& e) {
            // One element per voxel edge can fail where the mesh converges (a 1x1 neck under
            // large rotations, measured: "too many cutbacks"): solve in full instead.
            if (options.control.cancelled()) throw;
            out.geometry_reason +=
                "; solved in full on this mesh, as the coarse mesh's nonlinear "
                "solve failed (" +
                std::string(e.what()) + ")";
            in_full();
            return;
        }
        const std::vector<NodalDisplacements> fine_linear = fem.blocks;
        for (std::size_t k = 0; k < fem.blocks.size(); ++k)
            fem.blocks[k] = with_coarse_nonlinearity(out.fem_model, fem.blocks[k], coarse,
                                                     linear.blocks[k], nonlinear.blocks[k]);
        then_second_law(fine_linear, coarse, linear);
        out.nlgeom_from_coarse_mesh = true;
        out.geometry_reason += "; its nonlinear part from " + coarse_element() +
                               ", 1 per voxel edge, added to this mesh's linear answer";
    };

    QuasiStaticOptions engine_options = options.engine;
    if (!engine_options.cancel) engine_options.cancel = control.cancel;
    std::string turned_at, bent_at;
    for (std::size_t k = 0; k < loads.size(); ++k) {
        control.report({VerifyPhase::Engine, static_cast<int>(k) + 1, load_count});
        auto ours = engine_quasi_static(spec, loads[k].temperature_c, engine_options);
        out.engine_cpu_s += ours.cpu_s;
        if (!ours.problem.empty())
            throw std::runtime_error("our engine has no static answer at " + loads[k].name + ": " +
                                     ours.problem);
        const double turned = largest_rotation_deg(ours.shape);
        const double bent = measure(spec, g, ours.displacement_m).bend_deg;
        if (turned > out.engine_rotation_deg) {
            out.engine_rotation_deg = turned;
            turned_at = loads[k].name;
        }
        if (bent > out.engine_bend_deg) {
            out.engine_bend_deg = bent;
            bent_at = loads[k].name;
        }
        answers.push_back(std::move(ours));
    }

    // Linear or nonlinear: from how far our engine's answer turns, then from the actuation's free
    // strain (docs/verify.md).
    char reason[256];
    const double limit = options.nlgeom_above_deg;
    if (options.geometry == FemGeometry::Nonlinear) {
        out.geometry_reason = "nonlinear (--nlgeom)";
        solve_nonlinear();
    } else if (options.geometry == FemGeometry::Linear) {
        out.geometry_reason = "linear (--linear)";
    } else if (out.engine_rotation_deg > limit || out.engine_bend_deg > limit) {
        const bool by_voxel = out.engine_rotation_deg >= out.engine_bend_deg;
        std::snprintf(reason, sizeof reason,
                      "nonlinear: our engine %s by %.1f deg at %s, over the %g deg threshold",
                      by_voxel ? "turns a voxel" : "bends the root-to-tip line",
                      by_voxel ? out.engine_rotation_deg : out.engine_bend_deg,
                      (by_voxel ? turned_at : bent_at).c_str(), limit);
        out.geometry_reason = reason;
        out.nlgeom = true;
        solve_nonlinear();
    } else if (const double strain = actuation_free_strain(spec);
               strain > options.nlgeom_above_strain) {
        std::snprintf(reason, sizeof reason,
                      "nonlinear: the actuation's free strain is %.1f %%, over the %g %% up to "
                      "which linear steps hold",
                      100.0 * strain, 100.0 * options.nlgeom_above_strain);
        out.geometry_reason = reason;
        out.nlgeom = true;
        solve_nonlinear();
    } else {
        std::snprintf(reason, sizeof reason,
                      "linear: our engine turns no voxel more than %.1f deg and bends at most "
                      "%.1f deg, under the %g deg threshold, and the actuation's free strain is "
                      "at most %g %%",
                      out.engine_rotation_deg, out.engine_bend_deg, limit,
                      100.0 * options.nlgeom_above_strain);
        out.geometry_reason = reason;
    }
    // Each law's comparison; the verdict is the nearer law's (docs/verify.md, "Two continuum
    // laws"), the other's and the laws' own spread reported beside it.
    control.report({VerifyPhase::Comparing, 0, load_count});
    if (hooke_skipped) {  // the Neo-Hookean answer agrees alone
        out.fem_displacements = neo_hookean;
        out.loads = compare_all(neo_hookean);
        out.decision = decide_verdict(out.loads, out.measure, options.tolerance, options.floors);
        out.material_law = fem_material_law_name(FemMaterialLaw::NeoHookean);
        out.other_law = fem_material_law_name(FemMaterialLaw::Hooke);
        out.other_law_skipped = true;
    } else {
        out.fem_displacements = fem.blocks;
        out.loads = compare_all(fem.blocks);
        out.decision = decide_verdict(out.loads, out.measure, options.tolerance, options.floors);
        out.material_law = out.nlgeom ? fem_material_law_name(FemMaterialLaw::Hooke) : "";
    }
    if (neo_hookean_skipped) {  // the Saint Venant-Kirchhoff answer agrees alone
        out.other_law = fem_material_law_name(FemMaterialLaw::NeoHookean);
        out.other_law_skipped = true;
    }
    if (!neo_hookean.empty() && !hooke_skipped) {
        std::vector<LoadComparison> nh = compare_all(neo_hookean);
        VerdictDecision nh_decision =
            decide_verdict(nh, out.measure, options.tolerance, options.floors);
        // The laws' spread: the Neo-Hookean answer judged against the Saint Venant-Kirchhoff one.
        std::vector<LoadComparison> spread;
        for (std::size_t k = 0; k < loads.size(); ++k) {
            const auto other = fem_voxel_displacements(out.fem_model, neo_hookean[k]);
            spread.push_back(compare_load(spec, g, out.fem_model, fem.blocks[k], other, loads[k]));
        }
        const VerdictDecision laws =
            decide_verdict(spread, out.measure, options.tolerance, options.floors);
        if (laws.decided_by) out.law_spread = laws.worst;
        const bool nh_nearer = nh_decision.decided_by &&
                               (!out.decision.decided_by || nh_decision.worst < out.decision.worst);
        if (nh_nearer) {
            if (out.decision.decided_by) out.other_law_worst = out.decision.worst;
            out.other_law = fem_material_law_name(FemMaterialLaw::Hooke);
            out.material_law = fem_material_law_name(FemMaterialLaw::NeoHookean);
            out.decision = std::move(nh_decision);
            out.loads = std::move(nh);
            out.fem_displacements = neo_hookean;
        } else {
            if (nh_decision.decided_by) out.other_law_worst = nh_decision.worst;
            out.other_law = fem_material_law_name(FemMaterialLaw::NeoHookean);
        }
    }
    for (const LoadComparison& c : out.loads)
        out.worst_any = std::max(out.worst_any, c.differences.worst());
    out.worst = out.decision.worst;
    out.agrees = out.decision.agrees;

    // The experiment's measure at the actuation's extremes, from the rest shape.
    auto score = [&](auto pick) {
        double best = 0.0;
        for (std::size_t k = 1; k < out.loads.size(); ++k)
            best = std::max(best, pick(out.loads[k], out.loads[0]));
        return best;
    };
    auto pick_of = [&](bool from_fem) {
        return [from_fem, fitness](const LoadComparison& at, const LoadComparison& rest) {
            const ResponseMeasures& m = from_fem ? at.fem : at.engine;
            const ResponseMeasures& r = from_fem ? rest.fem : rest.engine;
            switch (fitness) {
                case FitnessMeasure::BendAngleDeg:
                    return m.bend_deg;
                case FitnessMeasure::ComFinalYz:
                case FitnessMeasure::ComMaxYz:
                    return std::hypot(m.com_yz_m[0] - r.com_yz_m[0], m.com_yz_m[1] - r.com_yz_m[1]);
                default:
                    return norm({m.com_m[0] - r.com_m[0], m.com_m[1] - r.com_m[1],
                                 m.com_m[2] - r.com_m[2]});
            }
        };
    };
    out.fem_score = score(pick_of(true));
    out.engine_score = score(pick_of(false));
    return out;
}

}  // namespace bhm::evo
