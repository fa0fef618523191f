// Per-voxel fibre axes in evo (issue 43): the body file's "fibres" round-trips and old files load
// unchanged; bad entries are one line naming file and field; framing, hashing and the engine
// input carry them; the CPPN's fibre outputs (evolution.cppn.fibre_outputs) give each muscle
// voxel the axis whose output is largest, worked out here from the inputs by hand.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/body_ops.hpp"
#include "evo/genome/cppn_decoder.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;
using bhm::engine::kMaterialFibreAxis;
using nlohmann::json;

namespace {

constexpr std::uint8_t kM = kMaterialFibreAxis;

// tiny_experiment with its active material a muscle (fibres along x), optionally fibre outputs.
Experiment muscle_experiment(bool fibre_outputs) {
    Experiment e = test::tiny_experiment({4, 3, 3});
    auto& m = e.materials[1].physics;
    m.cte_per_c = 0.0;
    m.actuation_model = bhm::engine::ActuationModel::Muscle;
    m.muscle.fibre_axis = 0;
    m.muscle.contraction_strain = 0.1;
    e.evolution.cppn.fibre_outputs = fibre_outputs;
    return e;
}

std::string first_problem(const json& j) {
    try {
        parse_body(j, "b.json");
    } catch (const ValidationError& e) {
        return e.problems.front().to_string();
    }
    return "";
}

}  // namespace

TEST_CASE("fibres: the body file's per-voxel axes round-trip, and old files load unchanged") {
    const json text = json::parse(R"({"size": [3, 2, 1], "layers": ["120221"],
                                      "fibres": ["xy.z.."]})");
    const Body b = parse_body(text, "b.json");
    CHECK(b.cells == std::vector<std::uint8_t>{1, 2, 0, 2, 2, 1});
    CHECK(b.fibre == std::vector<std::uint8_t>{0, 1, kM, 2, kM, kM});
    const json written = body_to_json(b);
    CHECK(written["fibres"] == json::array({"xy.z.."}));
    CHECK(parse_body(written, "again.json") == b);

    // Without "fibres": no per-voxel axes, and none written back.
    const Body old = parse_body(json::parse(R"({"size": [3, 2, 1], "layers": ["120221"]})"), "o");
    CHECK(old.fibre.empty());
    CHECK_FALSE(body_to_json(old).contains("fibres"));
    // Every cell on its material's axis writes as an old file, and hashes as one.
    Body same = old;
    same.fibre.assign(old.cells.size(), kM);
    CHECK_FALSE(body_to_json(same).contains("fibres"));
    CHECK(hash_body(same) == hash_body(old));
    CHECK(hash_body(b) != hash_body(old));
    Body turned = b;
    turned.fibre[0] = 1;
    CHECK(hash_body(turned) != hash_body(b));
}

TEST_CASE("fibres: bad per-voxel axes are one line naming the file and field") {
    json j =
        json::parse(R"({"size": [3, 1, 2], "layers": ["122", "221"], "fibres": [".x.", "xw."]})");
    CHECK(first_problem(j) ==
          "b.json:fibres[1]: character 1 ('w') is not a fibre axis 'x', 'y', 'z' or '.' (the "
          "material's)");
    j["fibres"] = {".x."};
    CHECK(first_problem(j) ==
          "b.json:fibres: expected an array of 2 strings, one per z layer as \"layers\"");
    j["fibres"] = {".x.", "xy"};
    CHECK(first_problem(j) ==
          "b.json:fibres[1]: expected a string of nx*ny = 3 characters 'x', 'y', 'z' or '.'");
}

TEST_CASE("fibres: framing and the engine input carry each voxel's axis") {
    Experiment e = muscle_experiment(false);
    e.boundary.enclosure_thickness = {1, 0, 0, 0, 0, 0};  // a frame layer at x = 0
    e.boundary.enclosure_material = 1;
    Body b;
    b.size = {2, 1, 1};
    b.cells = {2, 2};
    b.fibre = {1, 2};
    const Body framed = apply_frame_and_overrides(e, b);
    REQUIRE(framed.fibre.size() == framed.cells.size());
    CHECK(framed.cells[framed.index(1, 0, 0)] == 2);
    CHECK(framed.fibre[framed.index(1, 0, 0)] == 1);
    CHECK(framed.fibre[framed.index(2, 0, 0)] == 2);
    CHECK(framed.fibre[framed.index(0, 0, 0)] == kM);  // the frame: its material's
    const auto spec = make_body_spec(e, framed);
    CHECK(spec.fibre_axis == framed.fibre);
    b.fibre.clear();
    CHECK(apply_frame_and_overrides(e, b).fibre.empty());
    CHECK(make_body_spec(e, apply_frame_and_overrides(e, b)).fibre_axis.empty());
}

TEST_CASE("fibres: the CPPN's fibre outputs give muscle voxels the axis of their largest output") {
    // Outputs 5 (present) = bias, 6 (active) = x: filled everywhere, muscle where x > 0.
    // Fibre outputs 7, 8, 9 = x, y, z: the axis is argmax(x, y, z), the first of equal ones.
    Genome g;
    g.output_count = 5;
    g.edges = {{kInputBias, 5, 1.0},
               {kInputX, 6, 1.0},
               {kInputX, 7, 1.0},
               {kInputY, 8, 1.0},
               {kInputZ, 9, 1.0}};
    const Experiment e = muscle_experiment(true);
    const Developer developer(e);
    CHECK(developer.cppn_output_count() == 5);
    const Body raw = developer.decode_raw(g);
    const auto& space = developer.space();
    REQUIRE(raw.fibre.size() == raw.cells.size());
    auto coordinate = [](int i, int n) { return n > 1 ? -1.0 + 2.0 * i / (n - 1) : 0.0; };
    for (int z = 0; z < space.size[2]; ++z)
        for (int y = 0; y < space.size[1]; ++y)
            for (int x = 0; x < space.size[0]; ++x) {
                const double p[3] = {coordinate(x, space.size[0]), coordinate(y, space.size[1]),
                                     coordinate(z, space.size[2])};
                const auto c = static_cast<std::size_t>(raw.index(x, y, z));
                CAPTURE(x);
                CAPTURE(y);
                CAPTURE(z);
                if (!(p[0] > 0.0)) {
                    CHECK(raw.cells[c] == 1);
                    CHECK(raw.fibre[c] == kM);  // passive: no axis of its own
                    continue;
                }
                CHECK(raw.cells[c] == 2);
                int best = 0;
                if (p[1] > p[best]) best = 1;
                if (p[2] > p[best]) best = 2;
                CHECK(raw.fibre[c] == best);
            }
    // The pattern on the 4 x 3 x 3 lattice, z layers bottom first (x = 1/3 and 1 are muscle).
    const Phenotype p = developer.develop(g);
    CHECK(body_to_json(p.body)["fibres"] ==
          json::array({"..xx..xx..yx", "..xx..xx..yx", "..zx..zx..yx"}));
    // Deterministic, and it round-trips: through the body file and through the genome's JSON.
    CHECK(developer.develop(g) == p);
    CHECK(parse_body(body_to_json(p.body), "p.json") == p.body);
    const Genome back = genome_from_json(genome_to_json(g), e.evolution.cppn.weight_range);
    CHECK(developer.develop(back).body == p.body);
    // Written with its layout, the outputs say which are the fibres' (read: by count alone).
    const auto named = genome_to_json(g, 3);
    const auto& names = named["outputs"];
    REQUIRE(names.size() == static_cast<std::size_t>(g.output_count));
    CHECK(names[names.size() - 3] == "fibre_x");
    CHECK(names[names.size() - 1] == "fibre_z");
    CHECK(names[0] == "material");
    CHECK(genome_from_json(named, e.evolution.cppn.weight_range) == g);
    // The engine sees them.
    CHECK(make_body_spec(e, p.body).fibre_axis == p.body.fibre);
    // A genome without the fibre outputs does not fit this experiment, nor this one that.
    Genome plain = g;
    plain.output_count = 2;
    plain.edges.resize(2);
    CHECK_THROWS_AS(developer.decode_raw(plain), std::invalid_argument);
    const Developer without(muscle_experiment(false));
    CHECK(without.cppn_output_count() == 2);
    CHECK(without.decode_raw(plain).fibre.empty());
    CHECK_THROWS_AS(without.decode_raw(g), std::invalid_argument);
}

TEST_CASE("fibres: evolution.cppn.fibre_outputs round-trips and needs a muscle material") {
    const Experiment e = muscle_experiment(true);
    const json j = experiment_to_json(e);
    CHECK(j["evolution"]["cppn"]["fibre_outputs"] == true);
    CHECK(parse_experiment(j, "e.json") == e);
    CHECK(validate_experiment(e, "e.json").empty());
    // Off: the key is not written (files without it stay as they were).
    CHECK_FALSE(experiment_to_json(muscle_experiment(false))["evolution"]["cppn"].contains(
        "fibre_outputs"));
    // On with only sine materials: one line naming the field.
    Experiment sine = test::tiny_experiment();
    sine.evolution.cppn.fibre_outputs = true;
    const auto problems = validate_experiment(sine, "e.json");
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].to_string() ==
          "e.json:evolution.cppn.fibre_outputs: needs a muscle material (actuation_model "
          "\"muscle\") whose fibres it can turn");
}

TEST_CASE("fibres: the shipped example body with per-voxel axes is valid for the muscle catheter") {
    const std::string root = BHM_SOURCE_DIR;
    const auto loaded =
        load_experiment_and_body(root + "/assets/experiments/muscle-catheter.json",
                                 root + "/assets/bodies/muscle-catheter-fibres.body.json");
    REQUIRE(loaded.body);
    const Body& b = *loaded.body;
    // The same cells as the example body without them; muscle along x for x < 5, across after.
    CHECK(b.cells == load_body(root + "/assets/bodies/muscle-catheter.body.json").cells);
    for (std::size_t c = 0; c < b.cells.size(); ++c) {
        const int x = static_cast<int>(c) % b.size[0];
        CHECK(b.fibre[c] == (b.cells[c] == 2 ? (x < 5 ? 0 : 1) : kM));
    }
    const Body framed = apply_frame_and_overrides(loaded.experiment, b);
    CHECK(make_body_spec(loaded.experiment, framed).fibre_axis == framed.fibre);
    CHECK(framed.fibre.size() == framed.cells.size());
}
