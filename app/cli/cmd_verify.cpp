// bhm verify: checks an evolved design in a continuum FEM (CalculiX) against our engine at the
// actuation's extremes (evo/verify/, docs/verify.md): one body of an experiment, or a run's top K
// distinct champions with the rank agreement of our fitness and the FEM's.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/problem_report.hpp"
#include "engine/io/staged_folder.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/mesh_error.hpp"
#include "evo/verify/verify_body.hpp"
#include "evo/verify/verify_report.hpp"

namespace bhm::app {

namespace {

namespace fs = std::filesystem;

// Under this many compared bodies a rank correlation is flagged: with 4 bodies a perfect order
// arises by chance once in 24 (docs/verify.md, "A run's top K").
constexpr long long kFewestRanked = 5;

// What bhm verify writes into its --out folder (evo/verify/verify_report.cpp, and rank-NN/ of a
// run's top K): the folder is replaced whole (engine/io/staged_folder.hpp), so only these.
bool verify_output(const std::string& name) {
    return evo::is_verification_file(name) || name.rfind("rank-", 0) == 0;
}

// Runs write, naming the --out folder's file instead of its staging copy in an error.
template <class Write>
auto staged_write(const engine::StagedFolder& staged, Write&& write) {
    try {
        return write();
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(staged.as_final(e.what()));
    }
}

evo::VerifyOptions options_of(const ArgParser& parser) {
    evo::VerifyOptions o;
    // Either option fixes the mesh (the other at its old default, C3D8I or 2 per edge); without
    // both the mesh is chosen from the body's narrowest section (fem_mesh_choice.hpp).
    if (parser.has("--element") || parser.has("--subdivision")) {
        evo::FemMeshOptions mesh;
        mesh.element = evo::parse_fem_element(parser.get("--element", "C3D8I"));
        mesh.subdivision = static_cast<int>(parser.get_int("--subdivision", 2));
        if (mesh.subdivision < 1 || mesh.subdivision > 4)
            throw UsageError("--subdivision: " + std::to_string(mesh.subdivision) +
                             " is not in [1, 4]");
        o.mesh = mesh;
    }
    if (parser.has("--nlgeom") && parser.has("--linear"))
        throw UsageError("--nlgeom and --linear exclude each other");
    o.geometry = parser.has("--nlgeom")   ? evo::FemGeometry::Nonlinear
                 : parser.has("--linear") ? evo::FemGeometry::Linear
                                          : evo::FemGeometry::Automatic;
    if (parser.has("--coarse-nonlinearity") && parser.has("--linear"))
        throw UsageError("--coarse-nonlinearity and --linear exclude each other");
    o.nonlinear_from_coarse_mesh = parser.has("--coarse-nonlinearity");
    // The evolution loop's own check (evo/verify/continuum_checker): what one of its checks costs
    // and decides, repeated by hand (docs/verify.md, "CalculiX in the evolution loop").
    if (parser.has("--loop-check")) {
        if (parser.has("--linear") || parser.has("--nlgeom"))
            throw UsageError("--loop-check chooses linear or nonlinear steps itself");
        o.nonlinear_from_coarse_mesh = true;
        o.second_law_only_where_first_differs = true;
        o.first_law = evo::FemMaterialLaw::NeoHookean;
    }
    // The coarse mesh of a body with a section 1 voxel across: C3D20 from the start (the default),
    // or C3D20R first and C3D20 only where its nonlinear solve fails (the loop before 2026-12-08;
    // docs/verify.md, "loop40d"), to compare the two.
    o.coarse_full_integration_where_narrow = !parser.has("--coarse-reduced-first");
    o.tolerance = parser.get_double("--tolerance", 10.0) / 100.0;
    if (!(o.tolerance > 0.0)) throw UsageError("--tolerance: must be a percentage above 0");
    o.max_voxels = static_cast<int>(parser.get_int("--max-voxels", 4000));
    return o;
}

int verify_one(ArgParser& parser, const std::string& experiment_path) {
    const std::string body_path = parser.get("--body");
    if (body_path.empty()) throw UsageError("an experiment needs --body BODY (or give a RUN_DIR)");
    const auto loaded = evo::load_experiment_and_body(experiment_path, body_path);
    const evo::Experiment& e = loaded.experiment;
    say_library_warnings(e);
    const auto framed = evo::apply_frame_and_overrides(e, *loaded.body);
    const auto spec = evo::make_body_spec(e, framed);
    const auto options = options_of(parser);
    const fs::path out =
        parser.get("--out", fs::path(body_path).stem().string() + "-verify");
    // Staged before the solve: a folder that cannot be written costs no solve, and a kill or a
    // failed write leaves the old report whole (issue 41 R5).
    engine::StagedFolder staged(out.string(), verify_output);
    const auto v = evo::verify_body(spec, e.fitness.measure, options);
    nlohmann::json report = staged_write(
        staged, [&] { return evo::write_verification(v, options, staged.staging()); });
    std::cout << body_path << ": " << v.verdict() << "\n";
    if (v.status == evo::VerifyStatus::Compared)
        std::cout << "  FEM mesh " << v.mesh.reason << "\n";
    if (v.status == evo::VerifyStatus::Compared && !parser.has("--no-mesh-error")) {
        const auto error = evo::estimate_mesh_error(spec, v, options);
        if (error && !error->skipped.empty()) {
            std::cout << "  " << evo::describe_mesh_error(*error) << "\n";
        } else if (error) {
            std::cout << "  " << evo::describe_mesh_error(*error) << " on "
                      << evo::verify_measure_label(*v.decision.decided_by) << "\n";
        }
        if (error) {
            report["fem_mesh_error"] = evo::mesh_error_json(*error, v);
            staged_write(staged, [&] {
                evo::write_file_atomically(staged.file("report.json"), report.dump(2) + "\n");
            });
        }
    }
    staged.commit();
    if (v.status == evo::VerifyStatus::Compared) {
        std::cout << "  beside it: " << v.beside() << "\n";
        std::cout << "  FEM steps " << v.geometry_reason << "\n";
        if (!v.laws().empty()) std::cout << "  FEM law " << v.laws() << "\n";
        std::printf("  FEM %d nodes, %.1f s CPU; engine %.1f s CPU; report %s\n", v.fem_nodes,
                    v.fem_cpu_s, v.engine_cpu_s, (out / "report.json").string().c_str());
    }
    return 0;
}

int verify_run(ArgParser& parser, const std::string& run_dir) {
    if (parser.has("--body")) throw UsageError("--body goes with an EXPERIMENT, not a RUN_DIR");
    const long long top = parser.get_int("--top", 10);
    if (top < 1) throw UsageError("--top: must be at least 1");
    if (top < kFewestRanked)
        std::cerr << "warning: --top " << top << ": fewer than " << kFewestRanked
                  << " bodies; their rank correlations will be flagged as too few to mean much\n";
    const evo::RunInfo info = evo::read_run_info(run_dir);
    for (const auto& w : info.warnings)
        std::cerr << "bhm verify: warning: " << w << "\n";
    const evo::Experiment e = info.current();
    const auto history = evo::read_champion_history(run_dir, e);
    // K distinct bodies, best recorded fitness first (later champions first among equals).
    std::vector<const evo::ChampionFile*> picked;
    for (auto it = history.rbegin(); it != history.rend(); ++it) {
        bool seen = false;
        for (const auto* p : picked)
            seen = seen || p->body == it->body;
        if (!seen) picked.push_back(&*it);
    }
    std::stable_sort(picked.begin(), picked.end(),
                     [](const auto* a, const auto* b) { return a->fitness > b->fitness; });
    if (static_cast<long long>(picked.size()) > top) picked.resize(static_cast<std::size_t>(top));

    const auto options = options_of(parser);
    // RUN_DIR/verify/ itself holds the evolve loop's and the studio's individual-N/ checks: the
    // top K is a folder of its own there, replaced whole. Staged before any solve, so a run
    // directory that cannot be written is refused at once, naming the folder (issue 41 R7).
    const fs::path out = parser.get("--out", (fs::path(run_dir) / "verify" / "top").string());
    engine::StagedFolder staged(out.string(), verify_output);
    nlohmann::json report;
    report["run_dir"] = run_dir;
    report["fitness_measure"] = evo::kFitnessNames[static_cast<std::size_t>(e.fitness.measure)];
    nlohmann::json bodies = nlohmann::json::array();
    std::vector<double> recorded, fem, ours;
    int rank = 0, failed = 0;
    if (!evo::ccx_available())
        throw std::runtime_error("ccx (CalculiX) is not on the PATH; install the Debian package "
                                 "calculix-ccx");
    for (const auto* c : picked) {
        ++rank;
        char folder[32];
        std::snprintf(folder, sizeof folder, "rank-%02d", rank);
        const auto spec = evo::make_body_spec(e, c->body);
        evo::BodyVerification v;
        try {
            v = evo::verify_body(spec, e.fitness.measure, options);
        } catch (const std::runtime_error& error) {
            // One body's failed solve costs that body only: the others are still verified.
            ++failed;
            bodies.push_back({{"folder", folder},
                              {"champion_id", c->id},
                              {"generation_found", c->generation_found},
                              {"recorded_fitness", c->fitness},
                              {"error", error.what()}});
            std::cout << "#" << rank << " (generation " << c->generation_found
                      << "): error: " << error.what() << "\n";
            continue;
        }
        nlohmann::json j = staged_write(staged, [&] {
            return evo::write_verification(v, options, staged.file(folder));
        });
        j["folder"] = folder;
        j["champion_id"] = c->id;
        j["generation_found"] = c->generation_found;
        j["recorded_fitness"] = c->fitness;
        bodies.push_back(j);
        std::cout << "#" << rank << " (generation " << c->generation_found << ", fitness "
                  << c->fitness << "): " << v.verdict() << "\n";
        if (v.status == evo::VerifyStatus::Compared)
            std::cout << "  beside it: " << v.beside() << "\n  FEM steps " << v.geometry_reason
                      << (v.laws().empty() ? "" : "\n  FEM law " + v.laws()) << "\n  FEM mesh "
                      << v.mesh.reason << "\n";
        if (v.status != evo::VerifyStatus::Compared) continue;
        recorded.push_back(c->fitness);
        fem.push_back(v.fem_score);
        ours.push_back(v.engine_score);
    }
    auto correlation = [](double r) { return std::isnan(r) ? nlohmann::json(nullptr) : nlohmann::json(r); };
    const double by_fitness = evo::spearman(recorded, fem);
    const double by_engine = evo::spearman(ours, fem);
    report["bodies"] = bodies;
    report["compared"] = fem.size();
    report["failed"] = failed;
    // Like for like first: our static score against the FEM's static score (the same measure,
    // the same loads). The run's recorded fitness is dynamic (the evaluation's motion): its rank
    // agreement with the FEM's static score is a different question, labelled as such.
    const bool too_few = static_cast<long long>(fem.size()) < kFewestRanked;
    report["spearman_engine_static_vs_fem"] = correlation(by_engine);
    report["spearman_recorded_fitness_vs_fem"] = correlation(by_fitness);
    report["spearman_recorded_fitness_is_dynamic"] = true;
    report["spearman_too_few_bodies"] = too_few;
    staged_write(staged, [&] {
        evo::write_file_atomically(staged.file("report.json"), report.dump(2) + "\n");
    });
    staged.commit();
    auto text = [](double r) { return std::isnan(r) ? std::string("n/a") : std::to_string(r); };
    std::printf("Spearman rank correlation over %zu compared bodies%s:\n"
                "  our engine's static score vs the FEM's static score: %s\n"
                "  (a different thing) the run's recorded dynamic fitness vs the FEM's static "
                "score: %s\n",
                fem.size(), too_few ? " (fewer than 5: too few to mean much)" : "",
                text(by_engine).c_str(), text(by_fitness).c_str());
    std::printf("report %s\n", (out / "report.json").string().c_str());
    return failed == 0 ? 0 : 1;
}

int verify_body(ArgParser& parser) {
    const std::string target = parser.positionals().front();
    if (fs::is_directory(target)) return verify_run(parser, target);
    return verify_one(parser, target);
}

}  // namespace

int cmd_verify(const Args& args) {
    ArgParser parser(
        "verify", "EXPERIMENT --body BODY [--out DIR] | RUN_DIR [--top K] [--out DIR]",
        "Checks designs in a continuum FEM (CalculiX, Debian calculix-ccx): the body meshed\n"
        "as hexahedra with shared nodes, its materials, held voxels clamped, gravity, and the\n"
        "active voxels' thermal strain, solved at rest and at the actuation's extremes +A and\n"
        "-A; our engine answers the same loads held constant until at rest. A muscle body is\n"
        "solved at rest and peak activation (a = 1: its fibres' free strain as an orthotropic\n"
        "expansion); a muscle only contracts, so it has no -A. Prints one verdict\n"
        "per body on the experiment's fitness measure (agrees within X % / differs by Y %,\n"
        "the other measures beside it), and writes report.json and the FEM's\n"
        "deformed mesh (legacy VTK) to DIR. With a RUN_DIR, the K best distinct champions of\n"
        "the run's history and the Spearman rank correlation of our fitness and the FEM's.\n"
        "The FEM's steps are geometrically nonlinear when our engine's answer turns a voxel\n"
        "or bends more than 10 degrees, or the actuation's free strain exceeds 5 %, each\n"
        "under two laws, Saint Venant-Kirchhoff and Neo-Hookean, judged on the nearer\n"
        "(--nlgeom, --linear force either). Its mesh is refined\n"
        "where the body is narrow: C3D20R, 2 per voxel edge, where a section is 1 voxel\n"
        "across (a single held voxel, a 1x1 neck), else C3D8I, 2 per edge (--element and\n"
        "--subdivision choose another).\n"
        "Free bodies (walkers) and detached parts are reported as outside the continuum's\n"
        "reach. docs/verify.md explains the model and its measured accuracy.\n"
        "Exit status: 0 when every body was verified or reported, 1 on an error (ccx missing,\n"
        "a failed solve, a body too large, bad input), 2 on a usage error.");
    parser.positional("TARGET", "experiment file (with --body) or run directory");
    parser.option("--body", "BODY", "body file to verify (with an EXPERIMENT)");
    parser.option("--top", "K", "distinct champions of a RUN_DIR to verify (default 10)");
    parser.option("--out", "DIR",
                  "folder for report.json and the VTK meshes, replaced whole (default "
                  "BODY-verify, or RUN_DIR/verify/top)",
                  PathRole::OutputDir);
    parser.option("--element", "TYPE",
                  "C3D8I or C3D20R (default: automatic, C3D20R where a section is 1 voxel "
                  "across, else C3D8I)");
    parser.option("--subdivision", "N",
                  "elements per voxel edge, 1 to 4 (default: automatic, 2; with --element "
                  "alone, 2)");
    parser.flag("--nlgeom",
                "geometrically nonlinear steps, always (default: when our engine turns a voxel "
                "or bends more than 10 deg)");
    parser.flag("--linear", "linear steps, always (however far the body turns)");
    parser.flag("--coarse-nonlinearity",
                "nonlinear steps solved on 1 element per voxel edge, their nonlinear part added "
                "to the mesh's linear answer: quicker, what the evolution loop's checks do");
    parser.flag("--loop-check",
                "the evolution loop's check exactly: --coarse-nonlinearity, Neo-Hookean first "
                "and the second law only where the first differs");
    parser.flag("--coarse-reduced-first",
                "the coarse mesh of a body with a 1-voxel section as C3D20R first, C3D20 only "
                "where its nonlinear solve fails (default: C3D20 from the start)");
    parser.flag("--no-mesh-error",
                "skip the second mesh (twice the subdivision, up to 4) that estimates the FEM's "
                "own error beside the verdict");
    parser.option("--tolerance", "PERCENT", "largest difference that agrees (default 10)");
    parser.option("--max-voxels", "N", "refuse larger bodies (default 4000)");
    return run_command(parser, args, verify_body);
}

}  // namespace bhm::app
