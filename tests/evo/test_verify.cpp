// bhm verify's continuum check (evo/verify/): the CalculiX model of a body against closed-form
// beam answers and against the CalculiX suite's own deck (tests/engine/calculix.hpp), our engine
// against it on the bodies where the two agree (a body held by a single voxel among them, on a
// refined mesh, with a tolerance that makes the check fail), bodies outside the continuum's reach,
// and the pieces of the report (the .dat parser, Spearman's rank correlation). Each case solves in
// seconds (the single-voxel one in ~20 s); the CalculiX cases skip (loudly) only where ccx is not
// installed.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "engine/calculix.hpp"  // the CalculiX suite's own C3D20R decks (tests/engine)
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/verify_body.hpp"
#include "evo/verify/verify_report.hpp"

using namespace bhm;

namespace {

constexpr double kL = 0.01;

using bhm::test::skip_without_ccx;

// An nx x ny x nz box of material 1 (passive) whose z < active_layers layers are material 2
// (cte 0.01 /degC), held at its x = 0 layer.
engine::BodySpec held_box(int nx, int ny, int nz, int active_layers, double e_pa) {
    engine::BodySpec s;
    s.nx = nx;
    s.ny = ny;
    s.nz = nz;
    s.voxel_size_m = kL;
    engine::Material passive;
    passive.youngs_modulus_pa = e_pa;
    engine::Material active = passive;
    active.cte_per_c = 0.01;
    s.materials = {passive, active};
    s.material.assign(static_cast<std::size_t>(s.cell_count()), 1);
    s.fixed.assign(static_cast<std::size_t>(s.cell_count()), 0);
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                if (z < active_layers) s.material[s.cell_index(x, y, z)] = 2;
                if (x == 0) s.fixed[s.cell_index(x, y, z)] = 1;
            }
    s.damping.global_ratio = 0.01;
    return s;
}

// The CalculiX suite's model of an nx x ny x nz cantilever (tests/engine/test_engine_calculix.cpp):
// its own C3D20R box from the clamp plane x = 0 (the held voxels' centres) to the free end,
// E = 5 MPa, nu = 0.35; the mean vertical displacement of the section through the last voxels'
// centres.
// `bilayer`: its z = 0 element layer has cte 0.01 and the box is heated 1 degC, without gravity;
// else the whole box is passive under its own weight.
double suite_cantilever(int nx, int ny, int nz, bool bilayer) {
    namespace suite = bhm::engine::test::ccx;
    const suite::Mesh m{{(nx - 0.5) * kL, ny * kL, nz * kL},
                        {2 * nx - 1, (ny + 1) / 2, bilayer ? nz : (nz + 1) / 2}};
    std::ostringstream inp;
    suite::write_mesh(inp, m, {{5e6, 0.35, 1000.0, 0.01}, {5e6, 0.35, 1000.0, 0.0}},
                      [&](int, int, int ez) { return bilayer && ez == 0 ? 0 : 1; });
    suite::write_set(inp, "NSET", "CLAMP",
                     suite::nodes_where(m, [](double x, double, double) { return x < 1e-9; }));
    const double probe_x = (nx - 1) * kL;
    const auto probe = suite::nodes_where(
        m, [&](double x, double, double) { return std::fabs(x - probe_x) < 1e-9; });
    suite::write_set(inp, "NSET", "PROBE", probe);
    inp << "*BOUNDARY\nCLAMP, 1, 3\n";
    if (bilayer)
        inp << "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 0.\n*STEP\n*STATIC\n"
               "*TEMPERATURE\nNALL, 1.\n";
    else
        inp << "*STEP\n*STATIC\n*DLOAD\nEALL, GRAV, 9.81, 0., 0., -1.\n";
    inp << "*NODE PRINT, NSET=PROBE\nU\n*END STEP\n";
    return suite::mean(suite::solve(bilayer ? "suite-bilayer" : "suite-solid", inp.str()), probe,
                       2);
}

const evo::LoadComparison& load_named(const evo::BodyVerification& v, const std::string& name) {
    for (const auto& c : v.loads)
        if (c.load == name) return c;
    FAIL("no load " << name);
    return v.loads.front();
}

}  // namespace

TEST_CASE("verify: a 20x2x2 cantilever under its own weight, FEM against Euler-Bernoulli") {
    if (skip_without_ccx()) return;
    const double e = 5e7;  // stiff enough for a small deflection (about 1 mm)
    auto s = held_box(20, 2, 2, 0, e);
    const auto v = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, {});
    REQUIRE(v.status == evo::VerifyStatus::Compared);
    REQUIRE(v.loads.size() == 1);  // no active voxel: rest only
    // Clamped at the held voxels' centre plane (x = L/2), length 19.5 L, uniform load q = rho g A;
    // the tip voxel's centre is x = 19 L from the clamp: w = q x^2 (6 l^2 - 4 l x + x^2) / 24 EI.
    const double l = 19.5 * kL, x = 19.0 * kL, q = 1000.0 * 9.81 * 4 * kL * kL;
    const double ei = e * std::pow(2 * kL, 4) / 12.0;
    const double w = q * x * x * (6 * l * l - 4 * l * x + x * x) / (24.0 * ei);
    const auto& rest = load_named(v, "rest");
    MESSAGE("tip sag: FEM " << -rest.fem.tip_m[2] << " m, engine " << -rest.engine.tip_m[2]
                            << " m, Euler-Bernoulli " << w << " m; " << v.verdict());
    CHECK(std::fabs(-rest.fem.tip_m[2] / w - 1.0) < 0.02);
    CHECK(v.agrees);
    CHECK(v.verdict().rfind("agrees within", 0) == 0);
}

TEST_CASE("verify: an active/passive bilayer heated 1 degC, FEM against Timoshenko's bilayer") {
    if (skip_without_ccx()) return;
    auto s = held_box(20, 2, 2, 1, 5e6);
    s.environment.gravity_m_s2 = 0.0;
    s.actuation.temperature_amplitude_c = 1.0;
    const auto v = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, {});
    REQUIRE(v.loads.size() == 3);
    // Equal layers: curvature 3 de / (2 h) with h the total thickness; w = kappa x^2 / 2.
    const double kappa = 1.5 * 0.01 / (2 * kL), x = 19.0 * kL;
    const auto& up = load_named(v, "+A");
    const auto& down = load_named(v, "-A");
    MESSAGE("tip rise: FEM " << up.fem.tip_m[2] << " m, engine " << up.engine.tip_m[2]
                             << " m, Timoshenko " << kappa * x * x / 2 << " m; " << v.verdict());
    CHECK(std::fabs(up.fem.tip_m[2] / (kappa * x * x / 2) - 1.0) < 0.04);
    CHECK(down.fem.tip_m[2] == doctest::Approx(-up.fem.tip_m[2]).epsilon(1e-6));  // linear
    CHECK(v.agrees);
    CHECK(v.worst < 0.10);
}

TEST_CASE("verify: the solid and bilayer cantilevers agree with the CalculiX suite's own model") {
    if (skip_without_ccx()) return;
    // The same bodies through bhm verify's model (C3D8I, 2 per voxel edge, clamped at the held
    // voxels' centres by its own rule) and through the suite's deck (C3D20R, clamped at x = 0):
    // two independent meshings of one continuum, compared at the tip voxel's centre.
    const auto solid =
        evo::verify_body(held_box(20, 4, 4, 0, 5e6), evo::FitnessMeasure::ComMaxYz, {});
    const double solid_suite = suite_cantilever(20, 4, 4, false);
    const double solid_ours = load_named(solid, "rest").fem.tip_m[2];
    auto s = held_box(20, 2, 2, 1, 5e6);
    s.environment.gravity_m_s2 = 0.0;
    s.actuation.temperature_amplitude_c = 1.0;
    const auto bilayer = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, {});
    const double bilayer_suite = suite_cantilever(20, 2, 2, true);
    const double bilayer_ours = load_named(bilayer, "+A").fem.tip_m[2];
    MESSAGE("20x4x4 solid under gravity: tip "
            << solid_ours << " m, suite " << solid_suite << " m ("
            << 100.0 * (solid_ours / solid_suite - 1.0) << " %); 20x2x2 bilayer heated 1 degC: tip "
            << bilayer_ours << " m, suite " << bilayer_suite << " m ("
            << 100.0 * (bilayer_ours / bilayer_suite - 1.0) << " %)");
    CHECK(solid_suite < 0.0);
    CHECK(bilayer_suite > 0.0);
    // Measured -0.1 % and +0.7 % (docs/verify.md): 2 % leaves room for ccx versions, not for a
    // wrong clamp plane, load or material (each several times that).
    CHECK(std::fabs(solid_ours / solid_suite - 1.0) < 0.02);
    CHECK(std::fabs(bilayer_ours / bilayer_suite - 1.0) < 0.02);
}

TEST_CASE("verify: a body held by a single voxel agrees with the refined continuum at rest") {
    if (skip_without_ccx()) return;
    // A 10x3x3 body whose held layer keeps only its middle voxel (issue 27: weakly held bodies).
    // Until issue 40 the engine's lone link from the held voxel bent about twice as far as the
    // continuum's neck: 82 % more sag than this FEM at rest (+141 % at +1 degC on the bilayer).
    // The narrow neck's re-entrant corners need a fine mesh: C3D20R with 4 elements per voxel
    // edge (the default C3D8I with 2 was 25 % stiff here, C3D20R with 2 5 %).
    auto s = held_box(10, 3, 3, 0, 5e6);
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            if (y != 1 || z != 1) s.material[s.cell_index(0, y, z)] = 0;
    evo::VerifyOptions fine;
    fine.mesh = evo::FemMeshOptions{evo::FemElement::C3D20R, 4};
    const auto v = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, fine);
    MESSAGE(v.verdict());
    REQUIRE(v.loads.size() == 1);  // no active voxel: rest only
    CHECK(v.agrees);
    CHECK(v.worst < 0.08);
    CHECK(v.verdict().rfind("agrees within", 0) == 0);
    // A tolerance tighter than the difference is a "differs" verdict (on the default mesh).
    evo::VerifyOptions tight;
    tight.tolerance = 0.001;
    const auto strict = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, tight);
    CHECK_FALSE(strict.agrees);
    CHECK(strict.verdict().rfind("differs by", 0) == 0);
}

TEST_CASE("verify: free, detached and too large bodies are reported, not solved") {
    auto free_body = held_box(4, 2, 2, 1, 5e6);
    free_body.fixed.assign(free_body.fixed.size(), 0);
    const auto v = evo::verify_body(free_body, evo::FitnessMeasure::ComFinal3d, {});
    CHECK(v.status == evo::VerifyStatus::OutOfReach);
    CHECK(v.verdict().find("no voxel is held") != std::string::npos);

    auto detached = held_box(6, 1, 1, 0, 5e6);
    detached.material[detached.cell_index(3, 0, 0)] = 0;  // x = 4, 5 float apart
    CHECK(evo::continuum_reach_problem(detached) ==
          "2 of 5 voxels are not attached to a held voxel (a detached or escaped part)");
    CHECK(evo::continuum_reach_problem(held_box(6, 1, 1, 0, 5e6)).empty());

    evo::VerifyOptions small;
    small.max_voxels = 10;
    CHECK_THROWS_WITH_AS(
        evo::verify_body(held_box(6, 2, 1, 0, 5e6), evo::FitnessMeasure::ComFinal3d, small),
        "body too large to verify: 12 voxels, at most 10 (--max-voxels)", std::runtime_error);
}

TEST_CASE("verify: a failed solve is one line naming the solver's error") {
    if (skip_without_ccx()) return;
    try {
        evo::run_ccx("broken", "*NODE\n1, 0, 0, 0\n*STEP\n*STATIC\n*NOT A KEYWORD\n*END STEP\n");
        FAIL("no error");
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        MESSAGE(what);
        CHECK(what.rfind("ccx failed to solve broken: ", 0) == 0);
        CHECK(what.find('\n') == std::string::npos);
    }
}

TEST_CASE("verify: the .dat parser keeps each displacement block") {
    const std::string dat =
        "\n displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n"
        "         1  1.000000E-03 -2.000000E-03  0.000000E+00\n"
        "         2  4.000000E-03  5.000000E-03  6.000000E-03\n\n"
        " displacements (vx,vy,vz) for set NALL and time  0.2000000E+01\n\n"
        "         1  7.000000E-03  8.000000E-03  9.000000E-03\n";
    const auto blocks = evo::parse_ccx_dat(dat);
    REQUIRE(blocks.size() == 2);
    CHECK(blocks[0].size() == 2);
    CHECK(blocks[0].at(1)[1] == doctest::Approx(-2e-3));
    CHECK(blocks[1].at(1)[2] == doctest::Approx(9e-3));
}

TEST_CASE("verify: Spearman's rank correlation") {
    CHECK(evo::spearman({1, 2, 3, 4}, {10, 20, 30, 40}) == doctest::Approx(1.0));
    CHECK(evo::spearman({1, 2, 3, 4}, {4, 3, 2, 1}) == doctest::Approx(-1.0));
    // d = (0, 0, 1, -1): rho = 1 - 6 * 2 / (4 * 15) = 0.8
    CHECK(evo::spearman({1, 2, 3, 4}, {1, 2, 4, 3}) == doctest::Approx(0.8));
    CHECK(std::isnan(evo::spearman({1}, {2})));
    CHECK(std::isnan(evo::spearman({1, 1, 1}, {1, 2, 3})));
}

TEST_CASE("verify: a voxel held inside a body holds its rotation in the FEM too") {
    if (skip_without_ccx()) return;
    // A 12x3x3 passive bar held only at the middle voxel of its x = 1 cross-section, all six of
    // whose neighbours are free: the engine holds that voxel's centre and rotation, so the bar
    // hangs from it as a cantilever. Clamped at its centre node only, the FEM's bar could turn
    // about that node (no stiffness against it: 2.5e9 m of sag, a singular solve). Holding the
    // voxel's rotation, it sags as a cantilever held through one voxel: more than the same bar
    // with its whole x = 1 layer held (the continuum's neck is softer), less than ten times, and
    // within a factor 2 of our engine holding the same voxel.
    auto layer = held_box(12, 3, 3, 0, 5e6);
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y) {
            layer.fixed[layer.cell_index(0, y, z)] = 0;
            layer.fixed[layer.cell_index(1, y, z)] = 1;
        }
    auto one = layer;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            if (y != 1 || z != 1) one.fixed[one.cell_index(1, y, z)] = 0;
    const auto whole = evo::verify_body(layer, evo::FitnessMeasure::ComMaxYz, {});
    const auto v = evo::verify_body(one, evo::FitnessMeasure::ComMaxYz, {});
    REQUIRE(v.status == evo::VerifyStatus::Compared);
    const double sag_layer = -load_named(whole, "rest").fem.tip_m[2];
    const double sag_one = -load_named(v, "rest").fem.tip_m[2];
    const double sag_engine = -load_named(v, "rest").engine.tip_m[2];
    MESSAGE("tip sag held by the x = 1 layer: FEM "
            << sag_layer << " m; held by its middle voxel: FEM " << sag_one << " m, engine "
            << sag_engine << " m; " << v.verdict());
    CHECK(sag_layer > 0.0);
    CHECK(sag_one > sag_layer);
    CHECK(sag_one < 10.0 * sag_layer);  // clamped at a point, it was 1e9 m (a singular solve)
    // Both models hold the same voxel: within a factor 2 of each other.
    CHECK(sag_one < 2.0 * sag_engine);
    CHECK(sag_engine < 2.0 * sag_one);
}
