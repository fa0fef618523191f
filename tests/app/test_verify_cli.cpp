// bhm verify on the command line: its one-line errors (usage, bad input, body too large, ccx
// missing), a free body reported as outside the continuum's reach, the verdict on the
// experiment's measure with the FEM's automatic geometry, and the top-K report of a tiny run
// directory made by bhm evolve.
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment_io.hpp"
#include "evo/verify/ccx_run.hpp"
#include "shell_run.hpp"
#include "support/scratch.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bhm;

const std::string kBhm = std::string(BHM_BINARY_DIR) + "/bin/bhm";

struct Fixture {
    fs::path dir = bhm::test::scratch_dir("verify-cli");
    std::string experiment, free_experiment, body;

    Fixture() {
        // paper-exp1-attached (x- held) on a 5x3x3 workspace, 4 individuals, short evaluations.
        evo::Experiment e = evo::load_experiment(std::string(BHM_SOURCE_DIR) +
                                                 "/assets/experiments/paper-exp1-attached.json");
        e.workspace_size = {5, 3, 3};
        e.evolution.population = 4;
        e.simulation.settle_s = 0.2;
        e.simulation.evaluate_s = 0.5;
        experiment = (dir / "experiment.json").string();
        evo::save_experiment(experiment, e);
        e.boundary.faces[static_cast<int>(evo::Face::XMin)] = evo::BoundaryKind::Free;
        e.fitness.constraints.attached_to_fixed_face = false;
        free_experiment = (dir / "free.json").string();
        evo::save_experiment(free_experiment, e);
        evo::Body b;
        b.size = {5, 3, 3};
        b.cells.assign(static_cast<std::size_t>(b.cell_count()), 1);
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 5; ++x)
                b.cells[static_cast<std::size_t>(b.index(x, y, 0))] = 2;
        body = (dir / "body.json").string();
        evo::save_body(body, b);
    }
    ~Fixture() { fs::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
};

test::ShellResult bhm_run(const std::string& args) {
    return test::run_shell(kBhm + " " + args);
}

int lines(const std::string& s) {
    int n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

}  // namespace

TEST_CASE("bhm verify: usage and input errors are one line and a non-zero exit") {
    Fixture f;
    const auto help = bhm_run("verify --help");
    CHECK(help.status == 0);
    CHECK(help.output.find("RUN_DIR [--top K]") != std::string::npos);

    const auto no_body = bhm_run("verify " + f.experiment);
    CHECK(no_body.status == 2);
    CHECK(no_body.output.find("needs --body BODY") != std::string::npos);

    const auto both = bhm_run("verify " + f.experiment + " --body " + f.body +
                              " --nlgeom --linear");
    CHECK(both.status == 2);
    CHECK(both.output.find("--nlgeom and --linear exclude each other") != std::string::npos);

    // The loop's check chooses its steps itself (the free-strain rule), as the loop does.
    const auto loop_linear = bhm_run("verify " + f.experiment + " --body " + f.body +
                                     " --loop-check --linear");
    CHECK(loop_linear.status == 2);
    CHECK(loop_linear.output.find("--loop-check chooses linear or nonlinear steps itself") !=
          std::string::npos);

    const auto missing = bhm_run("verify " + f.path("nope.json") + " --body " + f.body);
    CHECK(missing.status == 1);
    CHECK(missing.output.find("nope.json") != std::string::npos);

    const auto large = bhm_run("verify " + f.experiment + " --body " + f.body +
                               " --max-voxels 10 --out " + f.path("large"));
    CHECK(large.status == 1);
    CHECK(large.output.find("body too large to verify: 45 voxels, at most 10") != std::string::npos);
    CHECK(lines(large.output) == 1);

    const auto no_ccx = test::run_shell("env PATH=/nonexistent " + kBhm + " verify " +
                                        f.experiment + " --body " + f.body + " --out " +
                                        f.path("no-ccx"));
    CHECK(no_ccx.status == 1);
    CHECK(no_ccx.output.find("ccx (CalculiX) is not on the PATH") != std::string::npos);
    CHECK(lines(no_ccx.output) == 1);
}

TEST_CASE("bhm verify: a free body is outside the continuum's reach, reported and not solved") {
    Fixture f;
    const auto r = bhm_run("verify " + f.free_experiment + " --body " + f.body + " --out " +
                           f.path("free"));
    CHECK(r.status == 0);
    CHECK(r.output.find("outside the continuum's reach: no voxel is held") != std::string::npos);
    std::ifstream in(f.path("free/report.json"));
    const auto j = nlohmann::json::parse(in);
    CHECK(j["status"] == "out_of_reach");
}

TEST_CASE("bhm verify: the verdict on the experiment's measure, the FEM's geometry and why") {
    if (!evo::ccx_available()) {
        MESSAGE("SKIPPED: CalculiX (ccx) is not installed");
        WARN(false);
        return;
    }
    // The 5x3x3 bilayer at the paper's +-14.5 % strain (fitness com_final_3d): our engine curls
    // it past 10 degrees, so the FEM is solved nonlinear; --linear forces the linear solve.
    Fixture f;
    const auto r = bhm_run("verify " + f.experiment + " --body " + f.body + " --out " +
                           f.path("auto"));
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find("(tolerance 10 %) on the centre of mass") != std::string::npos);
    CHECK(r.output.find("  beside it: ") != std::string::npos);
    CHECK(r.output.find("FEM steps nonlinear: our engine ") != std::string::npos);
    // The 5x3x3 body held by its whole x = 0 face is wide: the automatic mesh keeps C3D8I.
    CHECK(r.output.find("  FEM mesh C3D8I, 2 per voxel edge: every section at least 3 voxels "
                        "across\n") != std::string::npos);
    CHECK(r.output.find("  FEM mesh error ~") != std::string::npos);
    CHECK(r.output.find(" (2 vs 4 per edge) on the centre of mass\n") != std::string::npos);
    std::ifstream in(f.path("auto/report.json"));
    const auto j = nlohmann::json::parse(in);
    CHECK(j["experiment_measure"] == "com_displacement");
    CHECK(j["fem"]["nlgeom"] == true);
    CHECK(j["fem"]["geometry_choice"] == "automatic");
    CHECK(j["engine"]["largest_voxel_rotation_deg"].get<double>() > 10.0);
    CHECK(j["fem_mesh_error"]["elements_per_voxel_edge"] == 4);
    CHECK(j["fem_mesh_error"]["first_elements_per_voxel_edge"] == 2);
    CHECK(j["fem"]["mesh_choice"] == "automatic");
    CHECK(j["fem"]["element"] == "C3D8I");
    CHECK(j["fem"]["narrowest_section"]["voxels"] == 3);

    const auto l = bhm_run("verify " + f.experiment + " --body " + f.body + " --linear --no-mesh-error --out " +
                           f.path("linear"));
    INFO(l.output);
    REQUIRE(l.status == 0);
    CHECK(l.output.find("FEM steps linear (--linear)") != std::string::npos);
    CHECK(l.output.find("FEM mesh error") == std::string::npos);
}

TEST_CASE("bhm verify: the shipped muscle catheter at rest and peak activation, no -A") {
    if (!evo::ccx_available()) {
        MESSAGE("SKIPPED: CalculiX (ccx) is not installed");
        WARN(false);
        return;
    }
    // Issue 43: a muscle body is verified (CalculiX's orthotropic expansion at a = 1), not
    // refused. Measured: agrees within 8.7 % on the centre of mass (the bend angle, 1.1 deg, is
    // under its floor), the largest difference at rest (gravity), 7.4 % at peak activation.
    Fixture f;
    const std::string assets = std::string(BHM_SOURCE_DIR) + "/assets/";
    const auto r =
        bhm_run("verify " + assets + "experiments/muscle-catheter.json --body " + assets +
                "bodies/muscle-catheter.body.json --no-mesh-error --out " + f.path("muscle"));
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find(": agrees within ") != std::string::npos);
    CHECK(r.output.find(" at rest and peak activation (a muscle only contracts: no -A)\n") !=
          std::string::npos);
    std::ifstream in(f.path("muscle/report.json"));
    const auto j = nlohmann::json::parse(in);
    CHECK(j["status"] == "compared");
    REQUIRE(j["loads"].size() == 2);
    CHECK(j["loads"][0]["load"] == "rest");
    CHECK(j["loads"][1]["load"] == "peak");
    CHECK(j["loads"][1]["activation"] == 1.0);
    CHECK(j["loads_note"].get<std::string>().find("no -A load") != std::string::npos);
    CHECK(j["fem_meshes"] == nlohmann::json::array({"fem-rest.vtk", "fem-peak.vtk"}));
    CHECK(fs::exists(f.path("muscle/fem-peak.vtk")));
    // At peak the muscle layer (below the body's middle) shortens it and pulls the tip down
    // beyond its sag at rest, in both answers.
    for (const char* side : {"fem", "engine"}) {
        CAPTURE(side);
        const auto& rest = j["loads"][0][side]["tip_displacement_m"];
        const auto& peak = j["loads"][1][side]["tip_displacement_m"];
        CHECK(peak[0].get<double>() < rest[0].get<double>());
        CHECK(peak[2].get<double>() < rest[2].get<double>());
    }
}

TEST_CASE("bhm verify: the automatic mesh is printed and reported; --element, --subdivision win") {
    if (!evo::ccx_available()) {
        MESSAGE("SKIPPED: CalculiX (ccx) is not installed");
        WARN(false);
        return;
    }
    // A passive 5x3x3 body whose x = 0 layer keeps only its middle voxel (held): narrow.
    Fixture f;
    evo::Body b;
    b.size = {5, 3, 3};
    b.cells.assign(static_cast<std::size_t>(b.cell_count()), 1);
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            if (y != 1 || z != 1) b.cells[static_cast<std::size_t>(b.index(0, y, z))] = 0;
    const std::string narrow = f.path("narrow.json");
    evo::save_body(narrow, b);
    auto report = [&](const std::string& dir) {
        std::ifstream in(f.path(dir + "/report.json"));
        return nlohmann::json::parse(in);
    };

    const auto a = bhm_run("verify " + f.experiment + " --body " + narrow +
                           " --no-mesh-error --out " + f.path("auto"));
    INFO(a.output);
    REQUIRE(a.status == 0);
    CHECK(a.output.find("  FEM mesh C3D20R, 2 per voxel edge: narrowest section 1 voxel across "
                        "(the held patch at voxel (0, 1, 1))\n") != std::string::npos);
    const auto ja = report("auto");
    CHECK(ja["fem"]["element"] == "C3D20R");
    CHECK(ja["fem"]["elements_per_voxel_edge"] == 2);
    CHECK(ja["fem"]["mesh_choice"] == "automatic");
    CHECK(ja["fem"]["mesh_reason"].get<std::string>().rfind("C3D20R, 2 per voxel edge: ", 0) == 0);
    CHECK(ja["fem"]["narrowest_section"]["voxels"] == 1);
    CHECK(ja["fem"]["narrowest_section"]["held"] == true);

    // --subdivision alone: the old default element at that subdivision, said to be the caller's.
    const auto s = bhm_run("verify " + f.experiment + " --body " + narrow +
                           " --subdivision 1 --no-mesh-error --out " + f.path("explicit"));
    INFO(s.output);
    REQUIRE(s.status == 0);
    CHECK(s.output.find("  FEM mesh C3D8I, 1 per voxel edge: chosen by the caller") !=
          std::string::npos);
    const auto js = report("explicit");
    CHECK(js["fem"]["element"] == "C3D8I");
    CHECK(js["fem"]["elements_per_voxel_edge"] == 1);
    CHECK(js["fem"]["mesh_choice"] == "explicit");
    CHECK_FALSE(js["fem"].contains("narrowest_section"));

    // --element alone on the wide body: that element at 2 per edge.
    const auto e = bhm_run("verify " + f.experiment + " --body " + f.body +
                           " --element C3D20R --linear --no-mesh-error --out " + f.path("element"));
    INFO(e.output);
    REQUIRE(e.status == 0);
    const auto je = report("element");
    CHECK(je["fem"]["element"] == "C3D20R");
    CHECK(je["fem"]["elements_per_voxel_edge"] == 2);
    CHECK(je["fem"]["mesh_choice"] == "explicit");
}

TEST_CASE("bhm verify RUN_DIR --top 2: each champion's verdict and the rank correlation") {
    if (!evo::ccx_available()) {
        MESSAGE("SKIPPED: CalculiX (ccx) is not installed");
        WARN(false);
        return;
    }
    Fixture f;
    const std::string run = f.path("run");
    const auto evolve = bhm_run("evolve " + f.experiment + " --out " + run +
                                " --generations 4 --threads 1");
    REQUIRE(evolve.status == 0);
    const auto r = bhm_run("verify " + run + " --top 2");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find("#1 (generation ") != std::string::npos);
    CHECK(r.output.find("Spearman rank correlation over ") != std::string::npos);
    // Like for like first; the dynamic fitness labelled as a different thing; 2 < 5 flagged.
    CHECK(r.output.find("our engine's static score vs the FEM's static score: ") !=
          std::string::npos);
    CHECK(r.output.find("(a different thing) the run's recorded dynamic fitness vs the FEM's "
                        "static score: ") != std::string::npos);
    CHECK(r.output.find("warning: --top 2: fewer than 5 bodies") != std::string::npos);
    CHECK(r.output.find("(fewer than 5: too few to mean much)") != std::string::npos);
    std::ifstream in(run + "/verify/top/report.json");
    REQUIRE(in.good());
    const auto j = nlohmann::json::parse(in);
    REQUIRE(j["bodies"].size() >= 1);
    CHECK(j["bodies"].size() <= 2);
    CHECK(j.contains("spearman_recorded_fitness_vs_fem"));
    CHECK(j.contains("spearman_engine_static_vs_fem"));
    CHECK(j["spearman_recorded_fitness_is_dynamic"] == true);
    CHECK(j["spearman_too_few_bodies"] == true);
    CHECK(j["failed"] == 0);
    // best recorded fitness first, and each body's deformed FEM mesh beside its report
    if (j["bodies"].size() == 2)
        CHECK(j["bodies"][0]["recorded_fitness"].get<double>() >=
              j["bodies"][1]["recorded_fitness"].get<double>());
    CHECK(fs::exists(run + "/verify/top/rank-01/report.json"));
    CHECK(fs::exists(run + "/verify/top/rank-01/fem-rest.vtk"));
}

namespace {

std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

TEST_CASE("bhm verify --out: a write failing part way leaves the old report folder whole") {
    // Issue 41 R5: the meshes and shapes.json went into the folder one by one, so a kill or a
    // full disk at report.json left them beside the old report. The failure is injected
    // (tests/reliability/fault_inject.c) where a kill would stop the writer.
    if (!evo::ccx_available()) {
        MESSAGE("SKIPPED: CalculiX (ccx) is not installed");
        WARN(false);
        return;
    }
    Fixture f;
    const fs::path out = f.dir / "out";
    fs::create_directories(out);
    std::ofstream(out / "report.json") << "old report";
    const auto r = test::run_shell("BHM_FAULT_FILE=/report.json LD_PRELOAD=" +
                                   std::string(BHM_FAULT_SHIM) + " " + kBhm + " verify " +
                                   f.experiment + " --body " + f.body +
                                   " --no-mesh-error --out " + out.string());
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find((out / "report.json").string() + ": cannot write") != std::string::npos);
    CHECK(entries(out) == std::vector<std::string>{"report.json"});
    CHECK(bhm::test::read_file(out / "report.json") == "old report");
    CHECK(entries(f.dir) == std::vector<std::string>{"body.json", "experiment.json", "free.json",
                                                     "out"});
    // Then whole: the new folder in place of the old one, nothing left beside it.
    const auto good = bhm_run("verify " + f.experiment + " --body " + f.body +
                              " --no-mesh-error --out " + out.string());
    REQUIRE_MESSAGE(good.status == 0, good.output);
    CHECK(bhm::test::read_file(out / "report.json") != "old report");
    CHECK(fs::exists(out / "fem-rest.vtk"));
    CHECK(entries(f.dir).size() == 4);
    // A folder of the user's own files is never replaced whole: refused before any solve.
    std::ofstream(out / "notes.txt") << "mine";
    const auto foreign = bhm_run("verify " + f.experiment + " --body " + f.body +
                                 " --out " + out.string());
    CHECK(foreign.status == 1);
    CHECK(foreign.output.find(out.string() + ": holds notes.txt, which this command does not "
                                             "write") != std::string::npos);
}

TEST_CASE("bhm verify RUN_DIR on a run it cannot write refuses before any solve, naming it") {
    // Issue 41 R7: it solved one body, then failed with libstdc++'s filesystem text.
    if (!evo::ccx_available()) {
        MESSAGE("SKIPPED: CalculiX (ccx) is not installed");
        WARN(false);
        return;
    }
    // Root writes anywhere: the command runs as nobody then (as tests/reliability does).
    std::string prefix;
    if (::geteuid() == 0) {
        if (std::system("command -v setpriv > /dev/null 2>&1") != 0) {
            MESSAGE("SKIPPED: root without setpriv");
            return;
        }
        prefix = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
    }
    Fixture f;
    const std::string run = f.path("run");
    REQUIRE(bhm_run("evolve " + f.experiment + " --out " + run + " --generations 2 --threads 1")
                .status == 0);
    fs::permissions(f.dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                               fs::perms::others_read | fs::perms::others_exec);
    for (const auto& e : fs::recursive_directory_iterator(run))
        fs::permissions(e.path(), fs::perms::owner_write | fs::perms::group_write |
                                      fs::perms::others_write, fs::perm_options::remove);
    fs::permissions(run, fs::perms::owner_write | fs::perms::group_write |
                             fs::perms::others_write, fs::perm_options::remove);
    const auto r = test::run_shell(prefix + kBhm + " verify " + run + " --top 5");
    fs::permissions(run, fs::perms::owner_write, fs::perm_options::add);
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.find(run + "/verify") != std::string::npos);
    CHECK(r.output.find("Permission denied") != std::string::npos);
    CHECK(r.output.find("#1 (generation") == std::string::npos);  // nothing solved
    CHECK(r.output.find("filesystem error") == std::string::npos);
}
