// bhm verify's choice of linear or geometrically nonlinear FEM steps (evo/verify/verify_body):
// automatic from how far our engine's answer turns, so that the paper's +-14.5 % actuation strain
// is solved with large rotations while small loads keep the quick linear solve.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <atomic>
#include <optional>
#include <string>

#include "evo/verify/ccx_run.hpp"
#include "evo/verify/mesh_error.hpp"
#include "evo/verify/verify_body.hpp"
#include "verify_test_bodies.hpp"

using namespace bhm;

namespace {

using bhm::test::skip_without_ccx;

}  // namespace

TEST_CASE("verify geometry: the paper's 14.5 % actuation strain is solved nonlinear and agrees") {
    if (skip_without_ccx()) return;
    const auto s = bhm::test::verify_bilayer(14.47);
    const auto v = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, {});
    MESSAGE("automatic: " << v.verdict() << "; beside it: " << v.beside() << "; FEM steps "
                          << v.geometry_reason << "; ccx " << v.fem_cpu_s << " s CPU");
    REQUIRE(v.status == evo::VerifyStatus::Compared);
    CHECK(v.nlgeom);
    CHECK(v.geometry_reason.rfind("nonlinear: our engine", 0) == 0);
    CHECK(v.engine_rotation_deg > 10.0);
    CHECK(v.agrees);
    CHECK(v.worst < 0.10);
    // Forced linear (the default before issue 40): the continuum's tip runs along the beam.
    evo::VerifyOptions linear;
    linear.geometry = evo::FemGeometry::Linear;
    const auto l = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, linear);
    MESSAGE("--linear: " << l.verdict() << "; beside it: " << l.beside());
    CHECK_FALSE(l.nlgeom);
    CHECK(l.geometry_reason == "linear (--linear)");
    // Measured (2026-12-04): linear, the tip differs by 33.8 % and the centre of mass by 26.1 %
    // (the old verdict, the worst of them, "differs by 33.8 %"); nonlinear, every measure within
    // 10.6 %, the verdict's centre of mass YZ within 6.9 %.
    CHECK(l.worst_any > 0.2);
    CHECK(v.worst_any < l.worst_any / 2);
}

TEST_CASE("verify geometry: a small actuation keeps the linear solve, and says why") {
    if (skip_without_ccx()) return;
    const auto v = evo::verify_body(bhm::test::verify_bilayer(0.5), evo::FitnessMeasure::ComMaxYz, {});
    MESSAGE(v.verdict() << "; FEM steps " << v.geometry_reason);
    CHECK_FALSE(v.nlgeom);
    CHECK(v.geometry_reason.rfind("linear: our engine turns no voxel more than", 0) == 0);
    CHECK(v.engine_rotation_deg < 10.0);
    CHECK(v.engine_rotation_deg > 0.5);  // it did turn: the rotation is read from our answer
}

TEST_CASE("verify geometry: the FEM's own mesh error from a second mesh, beside the verdict") {
    if (skip_without_ccx()) return;
    const auto s = bhm::test::verify_bilayer(0.5);
    const evo::VerifyOptions options;  // C3D8I, 2 per voxel edge
    const auto v = evo::verify_body(s, evo::FitnessMeasure::ComMaxYz, options);
    // Only the FEM is solved again: our engine's answer is reused. Its cancel flag raised, a
    // second engine run would throw VerifyCancelled at its first slice.
    std::atomic<bool> raised{true};
    evo::VerifyOptions second = options;
    second.engine.cancel = &raised;
    std::optional<evo::MeshErrorEstimate> e;
    CHECK_NOTHROW(e = evo::estimate_mesh_error(s, v, second));
    REQUIRE(e);
    CHECK(e->skipped.empty());
    CHECK(e->first_subdivision == 2);
    CHECK(evo::describe_mesh_error(*e).rfind("FEM mesh error ~", 0) == 0);
    CHECK(evo::describe_mesh_error(*e).find("(2 vs 4 per edge)") != std::string::npos);
    MESSAGE(v.verdict() << "; the FEM's centre of mass YZ moves " << 100.0 * e->relative
                        << " % at 4 elements per voxel edge against 2 (ccx " << e->fem_cpu_s
                        << " s CPU)");
    CHECK(e->subdivision == 4);  // twice: the same clamp plane (an even subdivision)
    CHECK(e->relative > 0.0);    // a second, different mesh
    CHECK(e->relative < 0.05);   // the default mesh is close to converged (docs/verify.md)
}
