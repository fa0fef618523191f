// VXA export: well-formed XML with the right palette, settings and layers; the checker itself
// rejects malformed documents.
#include <doctest/doctest.h>

#include <clocale>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/io/text_file.hpp"
#include "evo/formats/vxa.hpp"
#include "evo_test_support.hpp"
#include "support/scratch.hpp"
#include "xml_check.hpp"

using namespace bhm::evo;
using bhm::test::XmlReader;

TEST_CASE("the XML checker rejects what is not well formed") {
    CHECK_NOTHROW(
        XmlReader::parse("<?xml version=\"1.0\"?><a x=\"1\"><b>t&amp;</b><![CDATA[<>]]><c/></a>"));
    CHECK_THROWS(XmlReader::parse("<a><b></a></b>"));
    CHECK_THROWS(XmlReader::parse("<a>1 < 2</a>"));
    CHECK_THROWS(XmlReader::parse("<a></a><b></b>"));
    CHECK_THROWS(XmlReader::parse("<a x=1></a>"));
    CHECK_THROWS(XmlReader::parse("<a>&nbsp;</a>"));
    CHECK_THROWS(XmlReader::parse("<a><![CDATA[open</a>"));
    CHECK_THROWS(XmlReader::parse("<a>"));
    CHECK_THROWS(XmlReader::parse("<!-- a -- b --><a/>"));
    CHECK_THROWS(XmlReader::parse("<a><!-- a ---></a>"));
}

TEST_CASE("VXA of a known body: layers, palette and settings") {
    auto e = test::tiny_experiment({3, 2, 2});
    e.materials[0].name = "passive <soft> & \"tissue\"";
    e.name = "dash--dash---end-";  // "--" is not allowed inside the XML comment that names it
    e.materials[1].color = {0.25f, 0.5f, 1.0f};
    e.actuation.frequency_hz = 4.0;
    Body body;
    body.size = {3, 2, 2};
    // z = 0: (0,0)=1 (1,0)=2 (2,0)=0 / (0,1)=1 (1,1)=1 (2,1)=0 ; z = 1: only (0,0,1) = 2
    body.cells = {1, 2, 0, 1, 1, 0, 2, 0, 0, 0, 0, 0};
    const std::string text = vxa_document(e, body);
    const auto root = XmlReader::parse(text);
    CHECK(root->name == "VXA");
    CHECK(root->attributes.at("Version") == "1.0");
    const auto* vxc = root->child("VXC");
    REQUIRE(vxc);
    const auto* structure = vxc->child("Structure");
    REQUIRE(structure);
    CHECK(structure->attributes.at("Compression") == "ASCII_READABLE");
    CHECK(structure->child("X_Voxels")->text == "3");
    CHECK(structure->child("Y_Voxels")->text == "2");
    CHECK(structure->child("Z_Voxels")->text == "2");
    const auto layers = structure->child("Data")->all("Layer");
    REQUIRE(layers.size() == 2);
    CHECK(layers[0]->text == "120110");
    CHECK(layers[1]->text == "200000");

    const auto materials = vxc->child("Palette")->all("Material");
    REQUIRE(materials.size() == 2);
    CHECK(materials[0]->attributes.at("ID") == "1");
    CHECK(materials[0]->child("Name")->text == "passive <soft> & \"tissue\"");
    CHECK(materials[0]->child("Mechanical")->child("CTE")->text == "0");
    CHECK(materials[1]->child("Mechanical")->child("CTE")->text == "0.01");
    CHECK(std::stod(materials[1]->child("Mechanical")->child("Elastic_Mod")->text) == 5e6);
    CHECK(materials[1]->child("Mechanical")->child("Poissons_Ratio")->text == "0.35");
    CHECK(materials[1]->child("Display")->child("Green")->text == "0.5");

    const auto* env = root->child("Environment");
    REQUIRE(env);
    CHECK(env->child("Thermal")->child("TempPeriod")->text == "0.25");
    CHECK(env->child("Gravity")->child("GravAcc")->text == "-9.81");
    const auto* bcs = env->child("Boundary_Conditions");
    CHECK(bcs->child("NumBCs")->text == "1");
    const auto* region = bcs->child("FRegion");
    CHECK(region->child("X")->text == "0");
    CHECK(std::stod(region->child("dX")->text) == doctest::Approx(1.0 / 3.0));
    CHECK(region->child("DofFixed")->text == "63");
    CHECK(
        std::stod(
            root->child("Simulator")->child("StopCondition")->child("StopConditionValue")->text) ==
        doctest::Approx(e.simulation.settle_s + e.simulation.evaluate_s));
}

TEST_CASE("VXA numbers ignore the process locale") {
    const char* previous = std::setlocale(LC_NUMERIC, nullptr);
    const std::string saved = previous ? previous : "C";
    // A comma-decimal locale, when the machine has one; the output must not change.
    const bool switched = std::setlocale(LC_NUMERIC, "de_DE.UTF-8") != nullptr;
    CHECK(bhm::engine::format_number(0.35) == "0.35");
    CHECK(bhm::engine::format_number(5e6) == "5e+06");
    CHECK(bhm::engine::format_number(1234.5) == "1234.5");
    CHECK(bhm::engine::format_number(-9.81) == "-9.81");
    std::setlocale(LC_NUMERIC, saved.c_str());
    if (!switched) MESSAGE("no de_DE locale installed: checked in the C locale only");
}

TEST_CASE("save_vxa writes the document atomically") {
    const auto e = test::tiny_experiment({2, 1, 1});
    Body body;
    body.size = {2, 1, 1};
    body.cells = {1, 2};
    const auto path = (bhm::test::scratch_dir("vxa-champion") / "champion.vxa").string();
    save_vxa(path, e, body);
    CHECK(bhm::test::read_file(path) == vxa_document(e, body));
    CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
    std::filesystem::remove(path);
}
