// bhm export --mesh / --vtk and bhm import, run as a user runs them: the files are parsed back
// independently (OBJ text, binary STL, VTK XML) and checked against the body they came from.
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "../evo/mesh_check.hpp"
#include "app/shell_run.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "support/scratch.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bhm;

const std::string kSource = BHM_SOURCE_DIR;
const std::string kBhm = std::string(BHM_BINARY_DIR) + "/bin/bhm";
const std::string kExperiment = kSource + "/assets/experiments/quick-demo.json";

using Result = test::ShellResult;

Result bhm_run(const std::string& args) {
    return test::run_shell(kBhm + " " + args);
}

// The file's text; a file that is missing fails the test here, not as an empty text.
std::string read_text(const fs::path& path) {
    REQUIRE(fs::is_regular_file(path));
    return bhm::test::read_file(path);
}

struct ObjMesh {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<int, 3>> triangles;
    std::vector<std::string> groups;
};

ObjMesh parse_obj(const std::string& text) {
    ObjMesh mesh;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream l(line);
        std::string tag;
        l >> tag;
        if (tag == "v") {
            std::array<double, 3> v{};
            l >> v[0] >> v[1] >> v[2];
            mesh.vertices.push_back(v);
        } else if (tag == "f") {
            std::array<int, 3> t{};
            l >> t[0] >> t[1] >> t[2];
            for (auto& i : t)
                --i;
            mesh.triangles.push_back(t);
        } else if (tag == "g") {
            std::string name;
            l >> name;
            mesh.groups.push_back(name);
        }
    }
    return mesh;
}

// Binary STL: triangles as vertex triples (no shared indices).
std::vector<std::array<std::array<double, 3>, 3>> parse_stl(const std::string& data) {
    REQUIRE(data.size() >= 84);
    const auto u32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i)
            v |= static_cast<std::uint32_t>(static_cast<unsigned char>(data[at + i])) << (8 * i);
        return v;
    };
    const std::uint32_t count = u32(80);
    REQUIRE(data.size() == 84 + 50ull * count);
    std::vector<std::array<std::array<double, 3>, 3>> out(count);
    for (std::uint32_t t = 0; t < count; ++t)
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
                out[t][k][a] = std::bit_cast<float>(u32(84 + 50ull * t + 12 + 12 * k + 4 * a));
    return out;
}

struct Fixture {
    fs::path dir = bhm::test::scratch_dir("export-cli");
    std::string body_path;
    evo::Experiment experiment = evo::load_experiment(kExperiment);
    evo::Body body;
    int voxels = 0;

    Fixture() {
        // An L-shaped 8 x 6 x 5 body with a second material and a voxel touching the rest only
        // along an edge (the mesh must still be a closed 2-manifold).
        body.size = experiment.workspace_size;
        body.cells.assign(static_cast<std::size_t>(body.cell_count()), 0);
        for (int z = 0; z < 2; ++z)
            for (int y = 0; y < 3; ++y)
                for (int x = 0; x < 6; ++x)
                    body.cells[body.index(x, y, z)] = x < 3 ? 1 : 2;
        body.cells[body.index(0, 4, 0)] = 1;  // apart
        body.cells[body.index(6, 3, 1)] = 2;  // touches (5, 2, 1) along an edge only
        body_path = (dir / "body.json").string();
        evo::save_body(body_path, body);
        for (auto c : evo::apply_frame_and_overrides(experiment, body).cells)
            voxels += c ? 1 : 0;
    }
    ~Fixture() { fs::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace

TEST_CASE("bhm export --mesh: a watertight OBJ and STL of the body at rest, volume N L^3") {
    Fixture f;
    const double L = f.experiment.voxel_size_m;
    const auto r = bhm_run("export " + kExperiment + " --body " + f.body_path + " --mesh " +
                           f.path("body.obj"));
    REQUIRE_MESSAGE(r.status == 0, r.output);
    CHECK(r.output.find("at rest") != std::string::npos);
    const ObjMesh obj = parse_obj(read_text(f.path("body.obj")));
    const auto topology = test::check_topology(obj.triangles);
    CHECK(topology.edges_not_in_two == 0);
    CHECK(topology.directed_edges_repeated == 0);
    CHECK(test::signed_volume(obj.vertices, obj.triangles) ==
          doctest::Approx(f.voxels * L * L * L).epsilon(1e-9));
    CHECK(obj.groups.size() == 2);  // one group per material used
    CHECK(fs::exists(f.path("body.mtl")));

    const auto s = bhm_run("export " + kExperiment + " --body " + f.body_path + " --mesh " +
                           f.path("body.stl"));
    REQUIRE_MESSAGE(s.status == 0, s.output);
    const auto stl = parse_stl(read_text(f.path("body.stl")));
    CHECK(stl.size() == obj.triangles.size());
    double volume = 0.0;
    for (const auto& t : stl)
        volume += test::signed_volume({t[0], t[1], t[2]}, {{0, 1, 2}});
    CHECK(volume == doctest::Approx(f.voxels * L * L * L).epsilon(1e-5));

    CHECK(bhm_run("export " + kExperiment + " --body " + f.body_path + " --mesh " +
                  f.path("body.ply"))
              .status == 2);
    const auto unwritable = bhm_run("export " + kExperiment + " --body " + f.body_path +
                                    " --mesh /proc/no-such-dir/x.stl");
    CHECK(unwritable.status == 1);
    CHECK(unwritable.output.find("/proc/no-such-dir/x.stl") != std::string::npos);
}

TEST_CASE("bhm export with a replay: deformed mesh at --time, VTK series with every frame") {
    Fixture f;
    const auto sim = bhm_run("simulate " + kExperiment + " --body " + f.body_path +
                             " --seconds 0.2 --out " + f.path("sim"));
    REQUIRE_MESSAGE(sim.status == 0, sim.output);
    const std::string replay = f.path("sim/replay.bin");
    const auto m = bhm_run("export " + kExperiment + " --body " + f.body_path + " --replay " +
                           replay + " --time 0.1 --mesh " + f.path("deformed.obj"));
    REQUIRE_MESSAGE(m.status == 0, m.output);
    CHECK(m.output.find("at t = 0.1 s") != std::string::npos);
    const ObjMesh obj = parse_obj(read_text(f.path("deformed.obj")));
    const auto topology = test::check_topology(obj.triangles);
    CHECK(topology.edges_not_in_two == 0);
    CHECK(topology.directed_edges_repeated == 0);
    // Gravity sags the soft body a little; the volume stays within a few percent of N L^3.
    const double L = f.experiment.voxel_size_m;
    CHECK(test::signed_volume(obj.vertices, obj.triangles) ==
          doctest::Approx(f.voxels * L * L * L).epsilon(0.05));

    const auto v = bhm_run("export " + kExperiment + " --body " + f.body_path + " --replay " +
                           replay + " --vtk " + f.path("vtk"));
    REQUIRE_MESSAGE(v.status == 0, v.output);
    // Frames in the replay: the summary says how many samples were recorded.
    const auto summary = nlohmann::json::parse(read_text(f.path("sim/summary.json")));
    const int samples = summary.at("samples").get<int>();
    const std::string pvd = read_text(f.path("vtk/series.pvd"));
    int datasets = 0;
    for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos;
         at = pvd.find("<DataSet", at + 1))
        ++datasets;
    CHECK(datasets == samples);
    for (int i = 0; i < datasets; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "vtk/frame-%05d.vtu", i);
        CHECK(fs::exists(f.path(name)));
    }
    const std::string last = read_text(f.path("vtk/frame-00000.vtu"));
    CHECK(last.find("NumberOfCells=\"" + std::to_string(f.voxels) + "\"") != std::string::npos);
    CHECK(fs::exists(f.path("vtk/com_path.vtp")));

    CHECK(bhm_run("export " + kExperiment + " --body " + f.body_path + " --replay " + replay +
                  " --time 99 --mesh " + f.path("late.stl"))
              .status == 1);
    CHECK_FALSE(fs::exists(f.path("late.stl")));
}

TEST_CASE("bhm export writes every output or none, and a VTK series is replaced whole") {
    const Fixture f;
    // The .mtl beside an .obj cannot be written (a folder holds its name): before the pre-check,
    // out.vxa and body-out were written first, then the command failed half done (issue 26 N5).
    fs::create_directories(f.path("m.mtl"));
    const auto r =
        bhm_run("export " + kExperiment + " --body " + f.body_path + " --vxa " + f.path("out.vxa") +
                " --body-out " + f.path("b.json") + " --mesh " + f.path("m.obj"));
    CHECK(r.status == 1);
    CHECK(r.output.find(f.path("m.mtl") + ": is a folder") != std::string::npos);
    CHECK(r.output.find("nothing was written") != std::string::npos);
    CHECK_FALSE(fs::exists(f.path("out.vxa")));
    CHECK_FALSE(fs::exists(f.path("b.json")));
    CHECK_FALSE(fs::exists(f.path("m.obj")));

    // A long series, then a one-frame series (the body at rest) into the same folder: none of
    // the old frames is left beside the new ones, and no staging folder either. A user's own
    // file in the folder stays.
    const auto sim = bhm_run("simulate " + kExperiment + " --body " + f.body_path + " --out " +
                             f.path("sim") + " --seconds 0.05");
    REQUIRE_MESSAGE(sim.status == 0, sim.output);
    REQUIRE(bhm_run("export " + kExperiment + " --body " + f.body_path + " --replay " +
                    f.path("sim/replay.bin") + " --vtk " + f.path("vtk"))
                .status == 0);
    REQUIRE(fs::exists(f.path("vtk/frame-00001.vtu")));
    std::ofstream(f.path("vtk/notes.txt")) << "mine";
    REQUIRE(bhm_run("export " + kExperiment + " --body " + f.body_path + " --vtk " + f.path("vtk"))
                .status == 0);
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(f.path("vtk")))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    CHECK(names ==
          std::vector<std::string>{"com_path.vtp", "frame-00000.vtu", "notes.txt", "series.pvd"});
}

TEST_CASE("bhm import: our export round-trips exactly through the command line") {
    Fixture f;
    const auto x = bhm_run("export " + kExperiment + " --body " + f.body_path + " --vxa " +
                           f.path("out.vxa") + " --body-out " + f.path("framed.json"));
    REQUIRE_MESSAGE(x.status == 0, x.output);
    const auto i = bhm_run("import " + f.path("out.vxa") + " --experiment-out " +
                           f.path("back.json") + " --body-out " + f.path("back-body.json"));
    REQUIRE_MESSAGE(i.status == 0, i.output);
    CHECK(i.output.find("read back exactly") != std::string::npos);
    CHECK(evo::load_experiment(f.path("back.json")) == f.experiment);
    CHECK(evo::load_body(f.path("back-body.json")) == evo::load_body(f.path("framed.json")));
    // The imported pair validates and simulates like the original.
    CHECK(bhm_run("validate " + f.path("back.json") + " " + f.path("back-body.json")).status == 0);

    const auto missing =
        bhm_run("import " + f.path("nope.vxa") + " --body-out " + f.path("b.json"));
    CHECK(missing.status == 1);
    CHECK(missing.output.find("nope.vxa") != std::string::npos);
    CHECK(bhm_run("import " + f.path("out.vxa")).status == 2);
}

TEST_CASE("bhm export: a write that fails after earlier outputs leaves every output as it was") {
    // Issue 41 R6: the pre-check passes, then the disk fills while the mesh is written (an
    // injected ENOSPC): the body file written before it was left replaced.
    const Fixture f;
    std::ofstream(f.path("b.json")) << "old body";
    const auto r = test::run_shell("BHM_FAULT_FILE=" + f.path("m.stl") + " LD_PRELOAD=" +
                                   BHM_FAULT_SHIM + " " + kBhm + " export " + kExperiment +
                                   " --body " + f.body_path + " --body-out " + f.path("b.json") +
                                   " --mesh " + f.path("m.stl"));
    CHECK(r.status == 1);
    CHECK(r.output.find(f.path("m.stl") + ": cannot write (No space left on device)") !=
          std::string::npos);
    CHECK(r.output.find("nothing was written") != std::string::npos);
    CHECK(r.output.find('\n') == r.output.size() - 1);  // one line
    CHECK(read_text(f.path("b.json")) == "old body");
    CHECK_FALSE(fs::exists(f.path("m.stl")));
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(f.dir)) names.push_back(e.path().filename().string());
    for (const auto& name : names) CHECK(name.find(".staged") == std::string::npos);
}
