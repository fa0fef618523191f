// bhm verify on bodies whose muscle voxels carry their own fibre axes (BodySpec::fibre_axis,
// issue 43): the deck gives each (material, axis) its own element set and orthotropic material,
// so CalculiX expands each voxel along its own fibre. Truths: the deck of a body without
// per-voxel axes, byte for byte; the FEM answer of the same strip whose material carries the
// axis; and CalculiX against our engine within 5 %, as tests/evo/test_verify_muscle.cpp does.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <cmath>
#include <string>

#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/verify_body.hpp"

using namespace bhm;
using bhm::test::skip_without_ccx;

namespace {

constexpr double kStrain = 0.02;

// A 10 x 2 x 2 strip of 5 MPa (nu 0.35), held at x = 0, no gravity: the bottom layer muscle
// whose material has fibres along `material_fibre`, the top passive.
engine::BodySpec strip(int material_fibre) {
    engine::BodySpec s;
    s.nx = 10;
    s.ny = 2;
    s.nz = 2;
    s.voxel_size_m = 0.01;
    engine::Material passive;
    passive.youngs_modulus_pa = 5e6;
    passive.poisson_ratio = 0.35;
    engine::Material muscle = passive;
    muscle.actuation_model = engine::ActuationModel::Muscle;
    muscle.muscle.fibre_axis = material_fibre;
    muscle.muscle.contraction_strain = kStrain;
    s.materials = {passive, muscle};
    s.material.assign(static_cast<std::size_t>(s.cell_count()), 1);
    s.fixed.assign(static_cast<std::size_t>(s.cell_count()), 0);
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                const auto c = static_cast<std::size_t>(s.cell_index(x, y, z));
                if (z == 0) s.material[c] = 2;
                if (x == 0) s.fixed[c] = 1;
            }
    s.environment.gravity_m_s2 = 0.0;
    return s;
}

// The strip whose material says y but whose muscle voxels with x < x_end say x.
engine::BodySpec strip_with_voxel_fibres(int x_end) {
    engine::BodySpec s = strip(1);
    s.fibre_axis.assign(s.material.size(), engine::kMaterialFibreAxis);
    for (int y = 0; y < s.ny; ++y)
        for (int x = 0; x < x_end; ++x)
            s.fibre_axis[static_cast<std::size_t>(s.cell_index(x, y, 0))] = 0;
    return s;
}

std::string deck_of(const engine::BodySpec& s) {
    return evo::ccx_deck(evo::build_fem_model(s, {evo::FemElement::C3D8I, 1}), s,
                         {{"rest", 0.0}, {"peak", 1.0}}, false);
}

evo::VerifyOptions strip_options() {
    evo::VerifyOptions o;
    o.mesh = evo::FemMeshOptions{evo::FemElement::C3D8I, 2};
    o.tolerance = 0.05;
    o.geometry = evo::FemGeometry::Nonlinear;
    return o;
}

}  // namespace

TEST_CASE("verify fibres: the deck gives each voxel's own axis its element set and material") {
    // No per-voxel axes, or every one the material's: the deck as before, byte for byte.
    auto same = strip(1);
    same.fibre_axis.assign(same.material.size(), 1);
    same.fibre_axis[static_cast<std::size_t>(same.cell_index(0, 0, 1))] = 2;  // passive: ignored
    CHECK(deck_of(same) == deck_of(strip(1)));
    // Half the muscle voxels along x: sets M2 (the material's y) and M2X, each its own expansion.
    const std::string deck = deck_of(strip_with_voxel_fibres(5));
    CHECK(deck.find("ELSET=M2\n") != std::string::npos);
    CHECK(deck.find("ELSET=M2X\n") != std::string::npos);
    CHECK(deck.find("*MATERIAL, NAME=MAT2\n*ELASTIC\n5000000, 0.35\n*DENSITY\n1000\n*EXPANSION, "
                    "TYPE=ORTHO, ZERO=0.\n0.007, -0.02, 0.007\n") != std::string::npos);
    CHECK(deck.find("*MATERIAL, NAME=MAT2X\n*ELASTIC\n5000000, 0.35\n*DENSITY\n1000\n*EXPANSION, "
                    "TYPE=ORTHO, ZERO=0.\n-0.02, 0.007, 0.007\n") != std::string::npos);
    CHECK(deck.find("*SOLID SECTION, ELSET=M2X, MATERIAL=MAT2X\n") != std::string::npos);
    CHECK(deck.find("*ELSET, ELSET=EALL\nM1\nM2\nM2X\n") != std::string::npos);
    // 20 muscle voxels, 10 of them along x: one C3D8I element per voxel.
    const auto model =
        evo::build_fem_model(strip_with_voxel_fibres(5), {evo::FemElement::C3D8I, 1});
    int along_x = 0;
    for (int f : model.element_fibre)
        along_x += f == 0;
    CHECK(along_x == 10);
}

TEST_CASE("verify fibres: a strip whose voxels carry fibres along it agrees with CalculiX") {
    if (skip_without_ccx()) return;
    // Every muscle voxel along x, its material along y: the FEM answers as for a material along x.
    const auto own = evo::verify_body(strip_with_voxel_fibres(10),
                                      evo::FitnessMeasure::BendAngleDeg, strip_options());
    const auto material =
        evo::verify_body(strip(0), evo::FitnessMeasure::BendAngleDeg, strip_options());
    REQUIRE(own.loads.size() == 2);
    REQUIRE(material.loads.size() == 2);
    const auto& peak = own.loads[1];
    MESSAGE("voxel fibres x: tip FEM z " << 1e3 * peak.fem.tip_m[2] << " mm, engine "
                                         << 1e3 * peak.engine.tip_m[2] << " mm; material x: FEM "
                                         << 1e3 * material.loads[1].fem.tip_m[2] << " mm; "
                                         << own.verdict());
    for (int k = 0; k < 3; ++k)
        CHECK(peak.fem.tip_m[k] ==
              doctest::Approx(material.loads[1].fem.tip_m[k]).epsilon(1e-6).scale(1e-9));
    CHECK(peak.fem.tip_m[2] < -1e-3);  // the bottom layer shortens along x: the tip goes down
    REQUIRE(peak.differences.tip);
    REQUIRE(peak.differences.bend);
    CHECK(*peak.differences.tip < 0.05);
    CHECK(*peak.differences.bend < 0.05);
    CHECK(own.agrees);

    // Half along x, half along the material's y: each half's own fibre in CalculiX too.
    const auto half = evo::verify_body(strip_with_voxel_fibres(5),
                                       evo::FitnessMeasure::BendAngleDeg, strip_options());
    REQUIRE(half.loads.size() == 2);
    MESSAGE("half along x: tip FEM z " << 1e3 * half.loads[1].fem.tip_m[2] << " mm, engine "
                                       << 1e3 * half.loads[1].engine.tip_m[2] << " mm; "
                                       << half.verdict());
    REQUIRE(half.loads[1].differences.tip);
    CHECK(*half.loads[1].differences.tip < 0.05);
    CHECK(half.agrees);
}
