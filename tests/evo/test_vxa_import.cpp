// VXA import: a hand-written VoxCAD-style file, an evosoro-style file, our own export read back
// exactly, the VoxCAD fields of our export alone, and clear errors for broken files.
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/formats/vxa.hpp"
#include "evo/formats/vxa_import.hpp"
#include "evo_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;

namespace {

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

// As VoxCAD 1.x saves it (indented, TempAmplitude, Boundary_Conditions), ASCII_READABLE, a 4x2x2
// lattice, IDs 1..3, a fixed x- layer narrower than a voxel, one forced region, a PhaseOffset
// layer set that BHM cannot map.
const char* const kVoxcadFile = R"(<?xml version="1.0" encoding="ISO-8859-1"?>
<VXA Version="1.1">
  <Simulator>
    <Integration><Integrator>0</Integrator><DtFrac>0.8</DtFrac></Integration>
    <Damping><BondDampingZ>0.9</BondDampingZ><ColDampingZ>0.7</ColDampingZ>
      <SlowDampingZ>0.02</SlowDampingZ></Damping>
    <Collisions><SelfColEnabled>0</SelfColEnabled><ColSystem>3</ColSystem></Collisions>
    <StopCondition><StopConditionType>2</StopConditionType>
      <StopConditionValue>3.5</StopConditionValue><InitCmTime>0.5</InitCmTime></StopCondition>
  </Simulator>
  <Environment>
    <Boundary_Conditions>
      <NumBCs>2</NumBCs>
      <FRegion><PrimType>0</PrimType><X>0</X><Y>0</Y><Z>0</Z><dX>0.1</dX><dY>1</dY><dZ>1</dZ>
        <DofFixed>63</DofFixed></FRegion>
      <FRegion><PrimType>0</PrimType><X>0.9</X><Y>0</Y><Z>0</Z><dX>0.1</dX><dY>1</dY><dZ>1</dZ>
        <DofFixed>0</DofFixed><ForceZ>-1</ForceZ></FRegion>
    </Boundary_Conditions>
    <Gravity><GravEnabled>1</GravEnabled><GravAcc>-9.81</GravAcc><FloorEnabled>0</FloorEnabled></Gravity>
    <Thermal><TempEnabled>1</TempEnabled><TempAmplitude>12</TempAmplitude><TempBase>25</TempBase>
      <VaryTempEnabled>1</VaryTempEnabled><TempPeriod>0.25</TempPeriod></Thermal>
  </Environment>
  <VXC Version="0.94">
    <Lattice><Lattice_Dim>0.005</Lattice_Dim><X_Dim_Adj>1</X_Dim_Adj></Lattice>
    <Voxel><Vox_Name>BOX</Vox_Name></Voxel>
    <Palette>
      <Material ID="1"><MatType>0</MatType><Name>Active_+</Name>
        <Display><Red>1</Red><Green>0</Green><Blue>0</Blue><Alpha>1</Alpha></Display>
        <Mechanical><MatModel>0</MatModel><Elastic_Mod>1e+007</Elastic_Mod><Density>1e+003</Density>
          <Poissons_Ratio>0.35</Poissons_Ratio><CTE>0.01</CTE><uStatic>1</uStatic><uDynamic>0.5</uDynamic>
        </Mechanical></Material>
      <Material ID="2"><MatType>0</MatType><Name>Passive_Soft</Name>
        <Display><Red>0</Red><Green>1</Green><Blue>1</Blue></Display>
        <Mechanical><Elastic_Mod>5e+006</Elastic_Mod><Density>1100</Density><Poissons_Ratio>0.3</Poissons_Ratio>
          <CTE>0</CTE></Mechanical></Material>
      <Material ID="3"><Name>Passive_Hard</Name>
        <Mechanical><Elastic_Mod>5e+007</Elastic_Mod><Density>1200</Density><CTE>0</CTE>
          <Fail_Stress>1e6</Fail_Stress></Mechanical></Material>
    </Palette>
    <Structure Compression="ASCII_READABLE">
      <X_Voxels>4</X_Voxels><Y_Voxels>2</Y_Voxels><Z_Voxels>2</Z_Voxels>
      <Data>
        <Layer><![CDATA[12301230]]></Layer>
        <Layer><![CDATA[11002200]]></Layer>
      </Data>
      <PhaseOffset>
        <Layer><![CDATA[0, 0, 0, 0, 0, 0, 0, 0, ]]></Layer>
        <Layer><![CDATA[0, 0, 0, 0, 0, 0, 0, 0, ]]></Layer>
      </PhaseOffset>
    </Structure>
  </VXC>
</VXA>
)";

}  // namespace

TEST_CASE("a hand-written VoxCAD file: palette, layers, physics, fixed face, what is lost") {
    const VxaImport in = parse_vxa(kVoxcadFile, "hand.vxa");
    const Experiment& e = in.experiment;
    CHECK_FALSE(in.had_bhm_experiment);
    CHECK(e.name == "hand");
    CHECK(e.workspace_size == std::array<int, 3>{4, 2, 2});
    CHECK(e.voxel_size_m == 0.005);
    REQUIRE(e.materials.size() == 3);
    CHECK(e.materials[0].name == "Active_+");
    CHECK(e.materials[0].physics.youngs_modulus_pa == 1e7);
    CHECK(e.materials[0].physics.density_kg_m3 == 1000.0);
    CHECK(e.materials[0].physics.cte_per_c == 0.01);
    CHECK(e.materials[0].color == std::array<float, 3>{1.0f, 0.0f, 0.0f});
    CHECK(e.materials[1].physics.poisson_ratio == 0.3);
    CHECK(e.materials[1].physics.density_kg_m3 == 1100.0);
    CHECK(e.materials[2].physics.youngs_modulus_pa == 5e7);
    CHECK_FALSE(e.materials[2].has_color);
    CHECK(in.body.size == std::array<int, 3>{4, 2, 2});
    CHECK(in.body.cells ==
          std::vector<std::uint8_t>{1, 2, 3, 0, 1, 2, 3, 0, 1, 1, 0, 0, 2, 2, 0, 0});
    CHECK(e.simulation.dt_fraction == 0.8);
    CHECK(e.simulation.bond_damping_ratio == 0.9);
    CHECK(e.simulation.collision_damping_ratio == 0.7);
    CHECK(e.simulation.global_damping_ratio == 0.02);
    CHECK(e.simulation.settle_s == 0.5);
    CHECK(e.simulation.evaluate_s == 3.0);
    CHECK(e.environment.gravity_m_s2 == -9.81);
    CHECK_FALSE(e.environment.floor);
    CHECK(e.actuation.temperature_amplitude_c == 12.0);
    CHECK(e.actuation.frequency_hz == 4.0);
    // The 0.1-wide region at x = 0 overlaps only the first layer of 4: the x- face.
    CHECK(e.boundary.faces[0] == BoundaryKind::Fixed);
    for (int f = 1; f < 6; ++f)
        CHECK(e.boundary.faces[static_cast<std::size_t>(f)] == BoundaryKind::Free);
    CHECK(e.boundary.voxel_overrides.empty());
    CHECK(mentions(in.unmapped, "ForceZ"));
    CHECK(mentions(in.unmapped, "PhaseOffset"));
    CHECK(mentions(in.unmapped, "Fail_Stress"));
    CHECK(mentions(in.unmapped, "InitCmTime"));
    CHECK_FALSE(mentions(in.unmapped, "ColSystem"));  // no physical meaning for BHM
    // What it maps to is a valid experiment with a valid body.
    CHECK(validate_experiment(e, "hand.vxa").empty());
    CHECK(validate_body_against(in.body, e, "hand.vxa").empty());
}

TEST_CASE("VoxCAD's default ZLIB structure: base64 of the compressed ID bytes per layer") {
    std::string text = kVoxcadFile;
    const auto begin = text.find("<Structure");
    const auto end = text.find("</Structure>");
    // The same 4x2x2 layers as kVoxcadFile, compressed by Python's zlib and base64-encoded.
    text.replace(begin, end - begin,
                 "<Structure Compression=\"ZLIB\"><X_Voxels>4</X_Voxels><Y_Voxels>2</Y_Voxels>"
                 "<Z_Voxels>2</Z_Voxels><Data><Layer><![CDATA[eJxjZGJmYARiAABAAA0=]]></Layer>"
                 "<Layer><![CDATA[eJxjZGRgYGJiYAAAACUABw==]]></Layer></Data>");
#if BHM_WITH_ZLIB
    const VxaImport in = parse_vxa(text, "zlib.vxa");
    CHECK(in.body.cells == parse_vxa(kVoxcadFile, "hand.vxa").body.cells);
    const auto broken = text.replace(text.find("eJxjZGJm"), 8, "AAAAAAAA");
    CHECK_THROWS_WITH_AS(parse_vxa(broken, "zlib.vxa"), doctest::Contains("Layer[0]"),
                         std::runtime_error);
#else
    CHECK_THROWS_WITH_AS(parse_vxa(text, "zlib.vxa"), doctest::Contains("ASCII_READABLE"),
                         std::runtime_error);
#endif
}

TEST_CASE("an evosoro-style file: TempAmp, Fixed_Regions, GA settings reported") {
    const std::string text = R"(<?xml version="1.0" encoding="ISO-8859-1"?>
<VXA Version="1.0"><Simulator><Integration><Integrator>0</Integrator><DtFrac>0.9</DtFrac></Integration>
<StopCondition><StopConditionType>2</StopConditionType><StopConditionValue>2</StopConditionValue>
<InitCmTime>0</InitCmTime></StopCondition>
<GA><WriteFitnessFile>1</WriteFitnessFile><FitnessFileName>out.xml</FitnessFileName></GA></Simulator>
<Environment><Fixed_Regions><NumFixed>1</NumFixed>
<Region><PrimType>0</PrimType><X>0</X><Y>0</Y><Z>0</Z><dX>0.5</dX><dY>0.5</dY><dZ>1</dZ></Region>
</Fixed_Regions><Forced_Regions><NumForced>0</NumForced></Forced_Regions>
<Gravity><GravEnabled>0</GravEnabled><GravAcc>-9.81</GravAcc><FloorEnabled>1</FloorEnabled></Gravity>
<Thermal><TempEnabled>1</TempEnabled><TempAmp>39</TempAmp><TempBase>25</TempBase>
<VaryTempEnabled>1</VaryTempEnabled><TempPeriod>0.5</TempPeriod></Thermal>
<StickyFloor>1</StickyFloor></Environment>
<VXC Version="0.93"><Lattice><Lattice_Dim>0.01</Lattice_Dim></Lattice>
<Palette><Material ID="1"><Name>Passive_Soft</Name><Mechanical><Elastic_Mod>1e+007</Elastic_Mod>
<Density>1e+006</Density><Poissons_Ratio>0.35</Poissons_Ratio><CTE>0</CTE></Mechanical></Material>
<Material ID="2"><Name>Active</Name><Mechanical><Elastic_Mod>1e+007</Elastic_Mod>
<Density>1e+006</Density><Poissons_Ratio>0.35</Poissons_Ratio><CTE>0.01</CTE></Mechanical></Material>
</Palette><Structure Compression="ASCII_READABLE"><X_Voxels>2</X_Voxels><Y_Voxels>2</Y_Voxels>
<Z_Voxels>1</Z_Voxels><Data><Layer><![CDATA[1212]]></Layer></Data></Structure></VXC></VXA>)";
    const VxaImport in = parse_vxa(text, "run/softbot--id_00001.vxa");
    const Experiment& e = in.experiment;
    CHECK(e.actuation.temperature_amplitude_c == 39.0);
    CHECK(e.actuation.frequency_hz == 2.0);
    CHECK(e.environment.gravity_m_s2 == 0.0);
    CHECK(e.simulation.settle_s == 0.0);
    CHECK(e.simulation.evaluate_s == 2.0);
    // A quarter of the x-y plane, whole height: not a face, so the one voxel (0,0,0) is held.
    REQUIRE(e.boundary.voxel_overrides.size() == 1);
    CHECK(e.boundary.voxel_overrides[0].voxel == std::array<int, 3>{0, 0, 0});
    CHECK(e.boundary.voxel_overrides[0].kind == OverrideKind::Fixed);
    CHECK(mentions(in.unmapped, "Simulator/GA"));
    CHECK(mentions(in.unmapped, "StickyFloor"));
    CHECK(in.body.cells == std::vector<std::uint8_t>{1, 2, 1, 2});
}

TEST_CASE("our own export reads back exactly, with any number of materials") {
    auto e = test::tiny_experiment({4, 3, 2});
    e.name = "round ]]> trip";  // the CDATA terminator inside the embedded JSON
    e.description = "a <description> & more";
    MaterialEntry stiff;
    stiff.name = "stiff";
    stiff.physics.youngs_modulus_pa = 2.5e7;
    stiff.color = {0.1f, 0.2f, 0.3f};
    stiff.has_color = true;
    e.materials.push_back(stiff);
    e.boundary.enclosure_thickness[static_cast<int>(Face::ZMax)] = 1;
    e.boundary.enclosure_material = 3;
    e.boundary.voxel_overrides.push_back({{1, 1, 0}, OverrideKind::Fixed, 0});
    e.actuation.frequency_hz = 3.0;  // 1 / (1 / 3) is not exactly 3 in doubles
    e.simulation.settle_s = 0.3;
    e.simulation.evaluate_s = 0.7;  // 0.3 + 0.7 - 0.3 is not exactly 0.7 either
    REQUIRE(validate_experiment(e, "e").empty());
    Body body;
    body.size = {4, 3, 2};
    body.cells = {1, 2, 0, 1, 2, 2, 1, 0, 0, 1, 1, 2, 3, 0, 0, 0, 1, 2, 2, 2, 0, 0, 1, 1};
    const Body framed = apply_frame_and_overrides(e, body);
    const VxaImport in = parse_vxa(vxa_document(e, framed), "ours.vxa");
    CHECK(in.had_bhm_experiment);
    CHECK(in.unmapped.empty());
    CHECK(in.experiment == e);
    CHECK(in.body == framed);

    SUBCASE("without the embedded experiment the VoxCAD fields alone still map") {
        std::string text = vxa_document(e, framed);
        const auto begin = text.find("<BHM_Experiment>");
        const auto end = text.find("</BHM_Experiment>") + 17;
        text.erase(begin, end - begin);
        const VxaImport plain = parse_vxa(text, "plain.vxa");
        CHECK_FALSE(plain.had_bhm_experiment);
        CHECK(plain.body == framed);
        CHECK(plain.experiment.materials.size() == 3);
        for (std::size_t m = 0; m < 3; ++m) {
            CHECK(plain.experiment.materials[m].physics == e.materials[m].physics);
            CHECK(plain.experiment.materials[m].name == e.materials[m].name);
            CHECK(plain.experiment.materials[m].color == e.materials[m].color);
        }
        CHECK(plain.experiment.workspace_size == e.workspace_size);
        CHECK(plain.experiment.voxel_size_m == e.voxel_size_m);
        CHECK(plain.experiment.boundary.faces == e.boundary.faces);
        CHECK(plain.experiment.simulation.dt_fraction == e.simulation.dt_fraction);
        CHECK(plain.experiment.simulation.global_damping_ratio ==
              e.simulation.global_damping_ratio);
        CHECK(plain.experiment.environment == e.environment);
        CHECK(plain.experiment.actuation.temperature_amplitude_c ==
              e.actuation.temperature_amplitude_c);
        CHECK(plain.experiment.actuation.frequency_hz == doctest::Approx(3.0).epsilon(1e-12));
        CHECK(plain.experiment.simulation.evaluate_s == doctest::Approx(1.0));  // no settle in VXA
    }
    SUBCASE("edited after export: the VoxCAD fields win over the embedded experiment") {
        std::string text = vxa_document(e, framed);
        const std::string from = "<DtFrac>0.9</DtFrac>", to = "<DtFrac>0.5</DtFrac>";
        REQUIRE(text.find(from) != std::string::npos);
        text.replace(text.find(from), from.size(), to);
        const VxaImport edited = parse_vxa(text, "edited.vxa");
        CHECK_FALSE(edited.had_bhm_experiment);
        CHECK(edited.experiment.simulation.dt_fraction == 0.5);
        CHECK(edited.experiment.fitness == e.fitness);  // only the embedded copy has it
        CHECK(mentions(edited.unmapped, "changed after BHM wrote it"));
    }
}

TEST_CASE("our own export keeps a body's own fibre axes (issue 43)") {
    auto e = test::tiny_experiment({3, 2, 2});
    auto& muscle = e.materials[1].physics;
    muscle.cte_per_c = 0.0;
    muscle.actuation_model = bhm::engine::ActuationModel::Muscle;
    muscle.muscle.contraction_strain = 0.1;
    REQUIRE(validate_experiment(e, "e").empty());
    Body body;
    body.size = {3, 2, 2};
    body.cells = {1, 2, 2, 2, 0, 1, 2, 2, 1, 0, 2, 2};
    constexpr std::uint8_t m = bhm::engine::kMaterialFibreAxis;
    body.fibre = {m, 0, 2, 1, m, m, m, m, m, m, 2, 0};
    const std::string text = vxa_document(e, body);
    CHECK(text.find("<BHM_Fibres>") != std::string::npos);
    const VxaImport in = parse_vxa(text, "fibres.vxa");
    CHECK(in.had_bhm_experiment);
    CHECK(in.body == body);
    CHECK(in.body.fibre == body.fibre);
    // Without the embedded experiment (a VoxCAD user kept our fibres element): still read.
    std::string plain = text;
    plain.erase(plain.find("<BHM_Experiment>"),
                plain.find("</BHM_Experiment>") + 17 - plain.find("<BHM_Experiment>"));
    CHECK(parse_vxa(plain, "plain.vxa").body.fibre == body.fibre);
    // A body without its own axes writes no element, as before.
    body.fibre.clear();
    CHECK(vxa_document(e, body).find("BHM_Fibres") == std::string::npos);
    // A broken element is refused with the file and the field.
    std::string broken = text;
    const auto at = broken.find("<BHM_Fibres><![CDATA[") + 21;
    broken.replace(at, 1, "{");
    CHECK_THROWS_WITH_AS(parse_vxa(broken, "broken.vxa"), doctest::Contains("BHM_Fibres"),
                         std::runtime_error);
}

TEST_CASE("broken VXA files fail with the file and the field") {
    const auto fails_with = [](const std::string& text, const std::string& needle) {
        try {
            parse_vxa(text, "bad.vxa");
        } catch (const std::runtime_error& e) {
            const std::string what = e.what();
            CHECK(what.find("bad.vxa") == 0);
            CHECK_MESSAGE(what.find(needle) != std::string::npos, what);
            return;
        }
        FAIL("no error for " << text);
    };
    fails_with("<VXA><VXC></VXA>", "line 1");
    fails_with("<Foo/>", "neither VXA nor VXC");
    fails_with("<VXA><VXC><Structure/></VXC></VXA>", "Palette");
    const std::string palette =
        "<Palette><Material ID=\"1\"><Mechanical><CTE>0</CTE></Mechanical></Material></Palette>";
    fails_with("<VXC>" + palette +
                   "<Structure Compression=\"LZMA\"><X_Voxels>1</X_Voxels></Structure></VXC>",
               "ASCII_READABLE");
    fails_with("<VXC>" + palette +
                   "<Structure><X_Voxels>2</X_Voxels><Y_Voxels>1</Y_Voxels><Z_Voxels>1</Z_Voxels>"
                   "<Data><Layer>1</Layer></Data></Structure></VXC>",
               "Layer[0]");
    fails_with("<VXC>" + palette +
                   "<Structure><X_Voxels>2</X_Voxels><Y_Voxels>1</Y_Voxels><Z_Voxels>1</Z_Voxels>"
                   "<Data><Layer>12</Layer></Data></Structure></VXC>",
               "names no palette material");
    fails_with("<VXC><Lattice><Lattice_Dim>abc</Lattice_Dim></Lattice>" + palette + "</VXC>",
               "Lattice_Dim");
}

TEST_CASE("a VXA over the 64 MiB cap, a folder or a device is refused by name before parsing") {
    // Before the cap, a 200 MB file was parsed with 887 MB of memory (issue 26 N3).
    const auto dir = bhm::test::scratch_dir("vxa-cap");
    const auto big = (dir / "huge.vxa").string();
    std::ofstream(big).close();
    std::filesystem::resize_file(big, 64 * 1024 * 1024 + 1);  // sparse: no disk used
    CHECK_THROWS_WITH(load_vxa(big),
                      doctest::Contains((big + ": is larger than the 64 MiB").c_str()));
    CHECK_THROWS_WITH(load_vxa(dir.string()),
                      (dir.string() + ": is a directory, not a file").c_str());
    CHECK_THROWS_WITH(load_vxa("/dev/zero"), doctest::Contains("/dev/zero: is not a regular file"));
    std::filesystem::remove_all(dir);
}
