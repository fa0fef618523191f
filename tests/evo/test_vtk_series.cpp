// ParaView series: written files read back by a small independent parser (the XML checker of the
// VXA tests plus number parsing): frame count, times, hexahedra, cell data and the COM path.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "evo/formats/vtk_series.hpp"
#include "evo_test_support.hpp"
#include "support/scratch.hpp"
#include "xml_check.hpp"

using namespace bhm;
using namespace bhm::evo;
using bhm::test::XmlReader;

namespace {

namespace fs = std::filesystem;

// The file's text; a file that is missing fails the test here, not as an empty text.
std::string read_text(const fs::path& path) {
    REQUIRE(fs::is_regular_file(path));
    return bhm::test::read_file(path);
}

std::vector<double> numbers(const std::string& text) {
    std::istringstream in(text);
    std::vector<double> out;
    double v;
    while (in >> v)
        out.push_back(v);
    return out;
}

const bhm::test::XmlElement* array_named(const bhm::test::XmlElement* parent,
                                         const std::string& name) {
    for (const auto* a : parent->all("DataArray"))
        if (a->attributes.count("Name") && a->attributes.at("Name") == name) return a;
    return nullptr;
}

// Two voxels along x, the second one fixed, over three frames: it slides +1 mm per frame and
// grows 1% per frame in x.
engine::Replay sliding_replay() {
    engine::Replay r;
    r.nx = 2;
    r.ny = 1;
    r.nz = 1;
    r.voxel_size_m = 0.01;
    r.voxel_cell = {0, 1};
    r.voxel_material = {1, 2};
    r.voxel_fixed = {0, 1};
    for (int f = 0; f < 3; ++f) {
        engine::VoxelPoses p;
        p.time_s = 0.5 * f;
        p.position_m = {0.005f, 0.005f, 0.005f, 0.015f + 0.001f * f, 0.005f, 0.005f};
        p.orientation = {1, 0, 0, 0, 1, 0, 0, 0};
        p.size_m = {0.01f, 0.01f, 0.01f, 0.01f * (1.0f + 0.01f * f), 0.01f, 0.01f};
        r.frames.push_back(p);
    }
    return r;
}

}  // namespace

TEST_CASE("a VTK series reads back: one .vtu per frame, hexahedra and cell data") {
    const fs::path dir = bhm::test::scratch_dir("vtk", false);
    const auto replay = sliding_replay();
    auto e = bhm::evo::test::tiny_experiment({2, 1, 1});
    e.materials[1].physics.density_kg_m3 = 3000.0;  // COM weighted 1:3
    const auto summary = write_vtk_series(dir.string(), replay, e.materials);
    CHECK(summary.frames == 3);

    const auto pvd = XmlReader::parse(read_text(dir / "series.pvd"));
    CHECK(pvd->attributes.at("type") == "Collection");
    const auto datasets = pvd->child("Collection")->all("DataSet");
    REQUIRE(datasets.size() == 3);
    for (std::size_t f = 0; f < 3; ++f) {
        CHECK(std::stod(datasets[f]->attributes.at("timestep")) == doctest::Approx(0.5 * f));
        const auto vtu = XmlReader::parse(read_text(dir / datasets[f]->attributes.at("file")));
        CHECK(vtu->attributes.at("type") == "UnstructuredGrid");
        const auto* piece = vtu->child("UnstructuredGrid")->child("Piece");
        REQUIRE(piece);
        CHECK(piece->attributes.at("NumberOfCells") == "2");
        CHECK(piece->attributes.at("NumberOfPoints") == "16");
        const auto points = numbers(piece->child("Points")->child("DataArray")->text);
        REQUIRE(points.size() == 48);
        // Corner 0 of voxel 1 (x-, y-, z-) and corner 6 (x+, y+, z+).
        const double half = 0.005 * (1.0 + 0.01 * static_cast<double>(f));
        CHECK(points[24] == doctest::Approx(0.015 + 0.001 * f - half).epsilon(1e-6));
        CHECK(points[24 + 18] == doctest::Approx(0.015 + 0.001 * f + half).epsilon(1e-6));
        CHECK(points[24 + 19] == doctest::Approx(0.01));
        const auto* cells = piece->child("Cells");
        CHECK(numbers(array_named(cells, "types")->text) == std::vector<double>{12, 12});
        CHECK(numbers(array_named(cells, "offsets")->text) == std::vector<double>{8, 16});
        const auto* data = piece->child("CellData");
        CHECK(numbers(array_named(data, "material")->text) == std::vector<double>{1, 2});
        CHECK(numbers(array_named(data, "fixed")->text) == std::vector<double>{0, 1});
        const auto d = numbers(array_named(data, "displacement")->text);
        REQUIRE(d.size() == 6);
        CHECK(d[0] == doctest::Approx(0.0));
        CHECK(d[3] == doctest::Approx(0.001 * f).epsilon(1e-5));
        const auto strain = numbers(array_named(data, "volumetric_strain")->text);
        REQUIRE(strain.size() == 2);
        CHECK(strain[0] == doctest::Approx(0.0));
        CHECK(strain[1] == doctest::Approx(0.01 * f).epsilon(1e-4));
    }
    const auto vtp = XmlReader::parse(read_text(dir / "com_path.vtp"));
    const auto* piece = vtp->child("PolyData")->child("Piece");
    CHECK(piece->attributes.at("NumberOfLines") == "1");
    const auto com = numbers(piece->child("Points")->child("DataArray")->text);
    REQUIRE(com.size() == 9);
    for (int f = 0; f < 3; ++f)
        CHECK(com[3 * f] == doctest::Approx((0.005 + 3.0 * (0.015 + 0.001 * f)) / 4.0));
    CHECK(numbers(array_named(piece->child("Lines"), "connectivity")->text) ==
          std::vector<double>{0, 1, 2});

    // Every second frame, plus always the last: frames 0 and 2.
    const fs::path sparse = dir / "sparse";
    CHECK(write_vtk_series(sparse.string(), replay, e.materials, 2).frames == 2);
    CHECK(XmlReader::parse(read_text(sparse / "series.pvd"))
              ->child("Collection")
              ->all("DataSet")
              .size() == 2);
    fs::remove_all(dir);
}

TEST_CASE("a body at rest is a one-frame series with no displacement") {
    engine::BodySpec spec;
    spec.nx = 2;
    spec.ny = 2;
    spec.nz = 1;
    spec.voxel_size_m = 0.02;
    spec.material = {1, 0, 2, 3};
    spec.fixed = {1, 0, 0, 0};
    const auto replay = rest_replay(spec);
    REQUIRE(replay.frames.size() == 1);
    CHECK(replay.voxel_cell == std::vector<std::int32_t>{0, 2, 3});
    CHECK(replay.voxel_fixed == std::vector<std::uint8_t>{1, 0, 0});
    const auto doc = XmlReader::parse(vtu_document(replay, replay.frames[0], replay.frames[0]));
    const auto* piece = doc->child("UnstructuredGrid")->child("Piece");
    const auto points = numbers(piece->child("Points")->child("DataArray")->text);
    // Voxel (1,1,0): corners span [0.02, 0.04] in x and y.
    CHECK(points[2 * 24 + 0] == doctest::Approx(0.02));
    CHECK(points[2 * 24 + 18] == doctest::Approx(0.04));
    for (double d : numbers(array_named(piece->child("CellData"), "displacement")->text))
        CHECK(d == 0.0);
}

TEST_CASE("a series into an impossible directory fails naming it") {
    const auto replay = sliding_replay();
    auto e = bhm::evo::test::tiny_experiment({2, 1, 1});
    CHECK_THROWS_WITH_AS(write_vtk_series("/proc/self/no-such/dir", replay, e.materials),
                         doctest::Contains("/proc/self/no-such/dir"), std::runtime_error);
}
