// The pieces of bhm verify that the studio's "Verify in FEM" leans on: the FEM's deformed voxels
// as poses (checked against rigid motions and a stretch worked out by hand), the load steps read
// from ccx's .sta file, and a cancel that stops a verification before anything is solved.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <numbers>

#include "evo/verify/ccx_run.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/fem_shape.hpp"
#include "evo/verify/verify_body.hpp"

using namespace bhm;

namespace {

engine::BodySpec one_voxel(int nx = 1) {
    engine::BodySpec s;
    s.nx = nx;
    s.ny = 1;
    s.nz = 1;
    s.voxel_size_m = 0.01;
    s.materials = {engine::Material{}};
    s.material.assign(static_cast<std::size_t>(nx), 1);
    s.fixed.assign(static_cast<std::size_t>(nx), 0);
    s.fixed[0] = 1;
    return s;
}

}  // namespace

TEST_CASE("verify shape: a voxel turned 30 deg about z and moved is a pose turned and moved") {
    for (const auto element : {evo::FemElement::C3D8I, evo::FemElement::C3D20R}) {
        const auto spec = one_voxel();
        const auto model = evo::build_fem_model(spec, {element, 2});
        const double a = std::numbers::pi / 6.0, c = std::cos(a), s = std::sin(a);
        const double centre = 0.005;
        const std::array<double, 3> t{0.001, -0.002, 0.003};
        evo::NodalDisplacements u;
        for (int id = 1; id <= model.node_count(); ++id) {
            const auto p = model.node_position_m(id);
            const double x = p[0] - centre, y = p[1] - centre;
            u[id] = {c * x - s * y - x + t[0], s * x + c * y - y + t[1], t[2]};
        }
        const std::vector<std::array<double, 3>> rest{{0.5, 0.6, 0.7}};  // any frame
        const auto pose = evo::fem_voxel_shape(model, u, rest);
        REQUIRE(pose.voxel_count() == 1);
        for (int k = 0; k < 3; ++k) {
            CHECK(pose.position_m[k] == doctest::Approx(rest[0][k] + t[k]).epsilon(1e-6));
            CHECK(pose.size_m[k] == doctest::Approx(0.01).epsilon(1e-6));
        }
        // Half the angle about z: (cos 15, 0, 0, sin 15).
        CHECK(pose.orientation[0] == doctest::Approx(std::cos(a / 2)).epsilon(1e-6));
        CHECK(pose.orientation[1] == doctest::Approx(0.0).epsilon(1e-6));
        CHECK(pose.orientation[2] == doctest::Approx(0.0).epsilon(1e-6));
        CHECK(pose.orientation[3] == doctest::Approx(std::sin(a / 2)).epsilon(1e-6));
    }
}

TEST_CASE("verify shape: a voxel stretched 10 % along x keeps its axes and grows along x") {
    const auto spec = one_voxel(2);
    const auto model = evo::build_fem_model(spec, {});
    evo::NodalDisplacements u;
    for (int id = 1; id <= model.node_count(); ++id)
        u[id] = {0.1 * model.node_position_m(id)[0], 0.0, 0.0};
    const std::vector<std::array<double, 3>> rest{{0.005, 0.005, 0.005}, {0.015, 0.005, 0.005}};
    const auto pose = evo::fem_voxel_shape(model, u, rest);
    REQUIRE(pose.voxel_count() == 2);
    CHECK(pose.size_m[0] == doctest::Approx(0.011));
    CHECK(pose.size_m[1] == doctest::Approx(0.01));
    CHECK(pose.orientation[0] == doctest::Approx(1.0));
    // The second voxel's centre (x = 0.015) moves by 0.0015.
    CHECK(pose.position_m[3] == doctest::Approx(0.0165));
}

TEST_CASE("verify shape: load steps done, read from ccx's .sta file") {
    // As ccx 2.20 writes it: a linear step is one increment; a nonlinear one several, done when
    // its step time reaches 1.
    const std::string sta =
        "SUMMARY OF JOB INFORMATION\n"
        "  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME\n"
        "     1          1     1     1  0.100000E+01  0.100000E+01  0.100000E+01\n"
        "     2          1     1     4  0.125000E+01  0.250000E+00  0.250000E+00\n";
    CHECK(evo::ccx_steps_done(sta) == 1);
    CHECK(evo::ccx_steps_done(sta + "     2          2     1     3  0.200000E+01  "
                                    "0.100000E+01  0.750000E+00\n") == 2);
    CHECK(evo::ccx_steps_done("") == 0);
}

TEST_CASE("verify shape: a raised cancel flag stops a verification before it solves") {
    auto spec = one_voxel(3);
    std::atomic<bool> cancel{true};
    evo::VerifyOptions options;
    options.control.cancel = &cancel;
    int reports = 0;
    options.control.on_progress = [&](const evo::VerifyProgress&) { ++reports; };
    CHECK_THROWS_AS(evo::verify_body(spec, evo::FitnessMeasure::BendAngleDeg, options),
                    evo::VerifyCancelled);
    CHECK(reports == 0);
    CHECK(evo::describe_progress({evo::VerifyPhase::Solving, 2, 3}) ==
          "CalculiX solving load 2 of 3");
}
