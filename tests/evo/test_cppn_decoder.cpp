// Decoding: hand-built CPPNs give lattices worked out by hand; connectivity and framing.
#include <doctest/doctest.h>

#include <cmath>

#include "evo/evaluate/constraints.hpp"
#include "evo/genome/body_ops.hpp"
#include "evo/genome/cppn_decoder.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

namespace {
const CppnMaterials kMaterials{1, 2, {}};  // passive = 1, active = 2

std::string layer_string(const Body& b, int z) {
    std::string s;
    for (int y = 0; y < b.size[1]; ++y)
        for (int x = 0; x < b.size[0]; ++x)
            s += static_cast<char>('0' + b.cells[b.index(x, y, z)]);
    return s;
}
}  // namespace

TEST_CASE("inputs: x, y, z on [-1, 1], d from -1 at the centre to 1 at the corners, bias 1") {
    CppnDecoder decoder({5, 3, 1}, kMaterials);
    const auto& in = decoder.inputs();
    const double xs[5] = {-1.0, -0.5, 0.0, 0.5, 1.0};
    for (int x = 0; x < 5; ++x)
        CHECK(in[kInputX][x] == doctest::Approx(xs[x]));
    CHECK(in[kInputY][0] == doctest::Approx(-1.0));
    CHECK(in[kInputY][5] == doctest::Approx(0.0));
    CHECK(in[kInputY][10] == doctest::Approx(1.0));
    CHECK(in[kInputZ][7] == doctest::Approx(0.0));   // one cell along z maps to 0
    CHECK(in[kInputD][7] == doctest::Approx(-1.0));  // centre (2, 1)
    CHECK(in[kInputD][0] == doctest::Approx(1.0));   // corner, norm sqrt(2) = the largest
    // (1, 1): norm 0.5 of the largest sqrt(2) -> -1 + 2 * 0.5 / sqrt(2)
    CHECK(in[kInputD][6] == doctest::Approx(-1.0 + 2.0 * 0.5 / std::sqrt(2.0)));
    for (double b : in[kInputBias])
        CHECK(b == 1.0);
}

TEST_CASE("a hand-built CPPN decodes to the lattice worked out by hand") {
    // material = x - 0.2 (filled where x > 0.2: columns 3 and 4 of 5);
    // active = abs(y) - 0.5 through a hidden abs node (active on rows 0 and 2, passive on row 1).
    Genome g;
    g.hidden = {Activation::Abs};
    g.edges = {{kInputX, kOutputMaterial, 1.0},
               {kInputBias, kOutputMaterial, -0.2},
               {kInputY, 7, 1.0},
               {7, kOutputActive, 1.0},
               {kInputBias, kOutputActive, -0.5}};
    CppnDecoder decoder({5, 3, 1}, kMaterials);
    const Body b = decoder.decode(g);
    CHECK(b.size == std::array<int, 3>{5, 3, 1});
    CHECK(layer_string(b, 0) == "000220001100022");
}

TEST_CASE("each node's value is computed once and shared by all its consumers") {
    // h7 = square(x); h8 = sin(h7); material = h7 + h8 - 0.4; active = h7 - 0.9.
    Genome g;
    g.hidden = {Activation::Square, Activation::Sin};
    g.edges = {{kInputX, 7, 1.0},
               {7, 8, 1.0},
               {7, kOutputMaterial, 1.0},
               {8, kOutputMaterial, 1.0},
               {kInputBias, kOutputMaterial, -0.4},
               {7, kOutputActive, 1.0},
               {kInputBias, kOutputActive, -0.9}};
    CppnDecoder decoder({5, 1, 1}, kMaterials);
    const Body b = decoder.decode(g);
    std::string expected;
    for (double x : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
        const double h7 = x * x, h8 = std::sin(h7);
        expected += h7 + h8 - 0.4 > 0 ? (h7 - 0.9 > 0 ? '2' : '1') : '0';
    }
    CHECK(expected == "21012");
    CHECK(layer_string(b, 0) == expected);
}

TEST_CASE("a decoder without the material it needs says which") {
    Genome g;
    g.edges = {{kInputBias, kOutputMaterial, 1.0}, {kInputBias, kOutputActive, 1.0}};
    CppnDecoder no_active({2, 1, 1}, CppnMaterials{1, 0, {}});
    CHECK_THROWS_WITH_AS(no_active.decode(g), doctest::Contains("no active material"),
                         std::invalid_argument);
    auto e = test::tiny_experiment();
    e.materials.pop_back();
    CHECK_THROWS_WITH_AS(Developer{e}, doctest::Contains("active material"), std::invalid_argument);
}

TEST_CASE("material mapping: first active and first passive of the palette") {
    auto e = test::tiny_experiment();
    e.materials.insert(e.materials.begin(), e.materials[1]);  // active, passive, active
    const auto m = cppn_materials(e);
    CHECK(m.active == 1);
    CHECK(m.passive == 2);
}

TEST_CASE("largest face-connected component, ties go to the first in index order") {
    Body b;
    b.size = {5, 2, 1};
    // Row 0: 1 1 0 1 0   Row 1: 0 0 0 1 1  -> components {0,1} (2 cells) and {3,8,9} (3 cells);
    // (3,0)-(3,1) are face neighbours, (1,0)-(3,0) are not.
    b.cells = {1, 1, 0, 1, 0, 0, 0, 0, 1, 2};
    int count = 0;
    face_connected_labels(b, &count);
    CHECK(count == 2);
    const Body kept = largest_face_connected_component(b);
    CHECK(kept.cells == std::vector<std::uint8_t>{0, 0, 0, 1, 0, 0, 0, 0, 1, 2});

    b.cells = {1, 0, 1, 0, 0, 0, 0, 0, 0, 0};  // two singletons: the first one stays
    CHECK(largest_face_connected_component(b).cells ==
          std::vector<std::uint8_t>{1, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    // Diagonal neighbours are not connected.
    b.cells = {1, 0, 0, 0, 0, 0, 1, 0, 0, 0};
    face_connected_labels(b, &count);
    CHECK(count == 2);
}

TEST_CASE("development: the CPPN paints the design space inside the enclosure") {
    auto e = test::tiny_experiment({6, 5, 4});
    e.boundary.enclosure_thickness = {1, 1, 1, 1, 1, 1};
    e.boundary.enclosure_material = 1;
    const Developer dev(e);
    CHECK(dev.space().origin == std::array<int, 3>{1, 1, 1});
    CHECK(dev.space().size == std::array<int, 3>{4, 3, 2});

    Genome all_active;
    all_active.edges = {{kInputBias, kOutputMaterial, 1.0}, {kInputBias, kOutputActive, 1.0}};
    const Phenotype p = dev.develop(all_active);
    CHECK(p.body.size == e.workspace_size);
    CHECK(p.voxels == 6 * 5 * 4);         // frame + a full design space
    CHECK(p.active_voxels == 4 * 3 * 2);  // only the designed cells are active
    CHECK(p.designed_voxels == 4 * 3 * 2);
    CHECK(p.body.cells[p.body.index(0, 0, 0)] == 1);
    CHECK(p.body.cells[p.body.index(1, 1, 1)] == 2);
    CHECK(p.hash == hash_body(p.body));
}

TEST_CASE("constraints reject what they should") {
    auto e = test::tiny_experiment({4, 3, 3});
    const Developer dev(e);
    const auto& c = e.fitness.constraints;
    auto check = [&](const Genome& g) {
        return constraint_violation(c, e.boundary, dev.space(), dev.develop(g));
    };
    Genome g;
    // Material where x < 0: touches the fixed x- face; active everywhere.
    g.edges = {{kInputX, kOutputMaterial, -1.0}, {kInputBias, kOutputActive, 1.0}};
    CHECK(check(g).empty());

    Genome detached = g;  // material where x > 0: misses the x = 0 layer
    detached.edges[0].weight = 1.0;
    CHECK(check(detached) == "not attached to the fixed x- face");
    auto free_rules = e.fitness.constraints;
    free_rules.attached_to_fixed_face = false;
    CHECK(constraint_violation(free_rules, e.boundary, dev.space(), dev.develop(detached)).empty());

    Genome passive = g;  // active output negative everywhere
    passive.edges[1].weight = -1.0;
    CHECK(check(passive).find("active voxels") != std::string::npos);

    Genome empty;
    CHECK(check(empty) == "empty design");

    auto fill_rules = e.fitness.constraints;
    fill_rules.min_fill_fraction = 0.6;  // g fills x in {0, 1} of 4: half
    CHECK(constraint_violation(fill_rules, e.boundary, dev.space(), dev.develop(g)).find("fill") ==
          0);
    fill_rules.min_fill_fraction = 0.5;
    CHECK(constraint_violation(fill_rules, e.boundary, dev.space(), dev.develop(g)).empty());
}

TEST_CASE("attachment with an enclosure means touching the design layer next to the fixed face") {
    auto e = test::tiny_experiment({6, 3, 3});
    e.boundary.enclosure_thickness = {1, 1, 0, 0, 0, 0};
    e.boundary.enclosure_material = 1;
    const Developer dev(e);
    Genome near;  // design x in [0, 4): x < 0 fills design columns 0, 1 (workspace 1, 2)
    near.edges = {{kInputX, kOutputMaterial, -1.0}, {kInputBias, kOutputActive, 1.0}};
    Genome far = near;
    far.edges[0].weight = 1.0;
    CHECK(constraint_violation(e.fitness.constraints, e.boundary, dev.space(), dev.develop(near))
              .empty());
    CHECK(constraint_violation(e.fitness.constraints, e.boundary, dev.space(), dev.develop(far)) ==
          "not attached to the fixed x- face");
}
