// The FEM's nonlinear part from a coarse mesh (evo/verify/coarse_nonlinearity, what the evolution
// loop's checks use): the interpolation reproduces an affine field exactly and leaves held nodes
// at rest; on a curling bilayer the corrected answer matches the fine mesh's own nonlinear solve;
// past the rotation where the correction drifts the fine mesh is solved in full; a body one voxel
// across gets its coarse part from C3D20 from the start, as near the full solve.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <string>

#include "evo/verify/coarse_nonlinearity.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/verify_body.hpp"
#include "support/ccx_skip.hpp"
#include "verify_test_bodies.hpp"

using namespace bhm;

namespace {

// An affine field of position: what both shape-function families reproduce exactly.
std::array<double, 3> affine(const std::array<double, 3>& p) {
    return {1e-3 + 0.02 * p[0] - 0.01 * p[2], -2e-3 + 0.03 * p[1], 0.05 * p[0] + 0.01 * p[1]};
}

// Every load's FEM centre-of-mass displacement of `coarse` within `fraction` of `fine`'s.
void check_com_within(const evo::BodyVerification& fine, const evo::BodyVerification& coarse,
                      double fraction) {
    for (std::size_t k = 0; k < fine.loads.size(); ++k) {
        CAPTURE(fine.loads[k].load);
        const auto& a = fine.loads[k].fem.com_m;
        const auto& b = coarse.loads[k].fem.com_m;
        const double size = std::hypot(a[0], a[1], a[2]);
        CHECK(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < fraction * size);
    }
}
}  // namespace

TEST_CASE(
    "coarse nonlinearity: an affine nonlinear part reaches every fine node exactly, held "
    "nodes stay at rest") {
    const auto spec = bhm::test::verify_bilayer(1.0, 4, 2);
    for (const auto element : {evo::FemElement::C3D20R, evo::FemElement::C3D8I}) {
        CAPTURE(evo::fem_element_name(element));
        const auto fine = evo::build_fem_model(spec, {element, 2});
        const auto coarse = evo::build_fem_model(spec, evo::coarse_mesh_of({element, 2}));
        CHECK(coarse.options.subdivision == 1);
        evo::NodalDisplacements fine_linear, coarse_linear, coarse_nonlinear;
        for (int id = 1; id <= fine.node_count(); ++id)
            fine_linear[id] = {1e-4 * id, 0.0, -1e-4};
        for (int id = 1; id <= coarse.node_count(); ++id) {
            coarse_linear[id] = {0.5, -0.25, 0.125};  // any: only the difference is added
            const auto part = affine(coarse.node_position_m(id));
            coarse_nonlinear[id] = {0.5 + part[0], -0.25 + part[1], 0.125 + part[2]};
        }
        const auto out = evo::with_coarse_nonlinearity(fine, fine_linear, coarse, coarse_linear,
                                                       coarse_nonlinear);
        REQUIRE(static_cast<int>(out.size()) == fine.node_count());
        std::vector<char> fixed(static_cast<std::size_t>(fine.node_count()) + 1, 0);
        for (int id : fine.fixed_nodes)
            fixed[static_cast<std::size_t>(id)] = 1;
        CHECK_FALSE(fine.fixed_nodes.empty());
        for (const auto& [id, u] : out) {
            const auto part = affine(fine.node_position_m(id));
            for (int a = 0; a < 3; ++a) {
                const double expected =
                    fine_linear.at(id)[a] + (fixed[static_cast<std::size_t>(id)] ? 0.0 : part[a]);
                CHECK(u[a] == doctest::Approx(expected).epsilon(1e-12).scale(1.0));
            }
        }
        // Two meshes of different bodies are refused.
        const auto other = evo::build_fem_model(bhm::test::verify_bilayer(1.0, 5, 2), {element, 1});
        CHECK_THROWS_AS(evo::with_coarse_nonlinearity(fine, fine_linear, other, coarse_linear,
                                                      coarse_nonlinear),
                        std::invalid_argument);
    }
}

TEST_CASE(
    "coarse nonlinearity: a curling bilayer's answer matches the fine nonlinear solve, and "
    "past 30 degrees the fine mesh is solved in full") {
    if (bhm::test::skip_without_ccx()) return;
    evo::VerifyOptions full;
    full.mesh = evo::FemMeshOptions{evo::FemElement::C3D20R, 2};
    full.geometry = evo::FemGeometry::Nonlinear;
    evo::VerifyOptions coarse = full;
    coarse.nonlinear_from_coarse_mesh = true;

    // A = 5 degC: our engine turns a voxel by about 21 degrees.
    const auto spec = bhm::test::verify_bilayer(5.0, 10, 2);
    const auto f = evo::verify_body(spec, evo::FitnessMeasure::ComFinal3d, full);
    const auto c = evo::verify_body(spec, evo::FitnessMeasure::ComFinal3d, coarse);
    MESSAGE("full: " << f.verdict() << " (ccx " << f.fem_cpu_s << " s CPU); coarse: " << c.verdict()
                     << " (ccx " << c.fem_cpu_s << " s CPU); " << c.geometry_reason);
    CHECK_FALSE(f.nlgeom_from_coarse_mesh);
    CHECK(c.nlgeom_from_coarse_mesh);
    CHECK(c.geometry_reason.find("1 per voxel edge") != std::string::npos);
    REQUIRE(f.loads.size() == 3);
    REQUIRE(c.loads.size() == 3);
    check_com_within(f, c, 0.02);
    CHECK(std::fabs(c.worst - f.worst) < 0.005);
    CHECK(c.agrees == f.agrees);

    // A = 14.47 degC, the paper's strain: 61 degrees, solved in full whatever the option.
    const auto big = evo::verify_body(bhm::test::verify_bilayer(14.47, 10, 2),
                                      evo::FitnessMeasure::ComFinal3d, coarse);
    CHECK_FALSE(big.nlgeom_from_coarse_mesh);
    CHECK(big.geometry_reason.find("solved in full") != std::string::npos);
}

TEST_CASE(
    "coarse nonlinearity: a body one voxel across gets C3D20 on the coarse mesh from the start, "
    "within 2 % of the fine mesh's own nonlinear solve") {
    if (bhm::test::skip_without_ccx()) return;
    // A 10 x 1 x 2 bilayer: a section 1 voxel across, so the automatic mesh is C3D20R with 2 per
    // voxel edge and one coarse element spans the section (docs/verify.md, "loop40d").
    const auto spec = bhm::test::verify_bilayer(5.0, 10, 2, 1);
    evo::VerifyOptions full;
    full.geometry = evo::FemGeometry::Nonlinear;
    // One law (Saint Venant-Kirchhoff, solved first), compared under itself: the second is solved
    // only where the first differs, and nothing differs at this tolerance.
    full.second_law_only_where_first_differs = true;
    full.tolerance = 10.0;
    evo::VerifyOptions coarse = full;
    coarse.nonlinear_from_coarse_mesh = true;
    evo::VerifyOptions reduced_first = coarse;
    reduced_first.coarse_full_integration_where_narrow = false;

    const auto f = evo::verify_body(spec, evo::FitnessMeasure::ComFinal3d, full);
    const auto c = evo::verify_body(spec, evo::FitnessMeasure::ComFinal3d, coarse);
    const auto r = evo::verify_body(spec, evo::FitnessMeasure::ComFinal3d, reduced_first);
    MESSAGE("full: " << f.verdict() << "; C3D20 up front: " << c.verdict() << " ("
                     << c.geometry_reason << "); C3D20R first: " << r.verdict());
    REQUIRE(f.mesh.mesh.element == evo::FemElement::C3D20R);
    REQUIRE(f.mesh.narrowest.width_voxels == 1);
    REQUIRE(c.nlgeom_from_coarse_mesh);
    REQUIRE(r.nlgeom_from_coarse_mesh);
    int coarse_solves = 0;
    for (const auto& solve : c.fem_solves) {
        CAPTURE(solve.law);
        CHECK(solve.element == (solve.coarse ? "C3D20" : "C3D20R"));
        coarse_solves += solve.coarse ? 1 : 0;
    }
    CHECK(coarse_solves >= 2);  // the coarse linear answer and at least one law's nonlinear one
    CHECK(c.geometry_reason.find("C3D20 (full integration") != std::string::npos);
    for (const auto& solve : r.fem_solves)
        CHECK(solve.element == "C3D20R");
    // Truth: the fine mesh's own nonlinear solve, under the same law.
    REQUIRE(f.material_law == "Saint Venant-Kirchhoff");
    REQUIRE(c.material_law == "Saint Venant-Kirchhoff");
    REQUIRE(f.loads.size() == 3);
    REQUIRE(c.loads.size() == 3);
    check_com_within(f, c, 0.02);
}
