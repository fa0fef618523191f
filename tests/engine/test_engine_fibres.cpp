// Per-voxel fibre axes (BodySpec::fibre_axis, issue 43): a muscle voxel contracts along its own
// axis where the body gives one, else along its material's. Truths: the free strain of an active
// stress along the fibre (-e along it, +nu e across); Timoshenko's bilayer (1925) for a strip
// whose muscle layer's voxels carry fibres that their material does not; and the body without
// per-voxel axes, whose run the same body with every axis "the material's" must repeat bit for bit.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/muscle.hpp"
#include "engine/poses.hpp"
#include "engine_test_bodies.hpp"
#include "muscle_test_support.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;
using bhm::test::relative;

namespace {

Material muscle_material(int fibre_axis, double nu, double strain) {
    Material m;
    m.poisson_ratio = nu;
    m.actuation_model = ActuationModel::Muscle;
    m.muscle.fibre_axis = fibre_axis;
    m.muscle.contraction_strain = strain;
    m.muscle.rise_s = 0.01;
    m.muscle.pulse_width_s = 1.0;  // u = 1 throughout: a = 1 - e^(-t / 0.01)
    return m;
}

// A 20 x 2 x 2 strip (long along `along`), its bottom layer muscle whose material has fibres
// along `material_fibre` but whose voxels each carry `voxel_fibre`; the top passive, held at its
// - end, fully activated. The far end layer's mean displacement (x, y, z) after it has settled.
std::array<double, 3> strip_tip(int along, int material_fibre, int voxel_fibre, double e) {
    Material passive;
    passive.poisson_ratio = 0.0;
    const int nx = along == 0 ? 20 : 2, ny = along == 0 ? 2 : 20;
    BodySpec s = solid_box(nx, ny, 2, passive);
    s.materials.push_back(muscle_material(material_fibre, 0.0, e));
    s.fixed.assign(s.material.size(), 0);
    s.fibre_axis.assign(s.material.size(), kMaterialFibreAxis);
    for (int z = 0; z < 2; ++z)
        for (int i = 0; i < 20; ++i)
            for (int j = 0; j < 2; ++j) {
                const int x = along == 0 ? i : j, y = along == 0 ? j : i;
                const auto c = static_cast<std::size_t>(s.cell_index(x, y, z));
                if (z == 0) {
                    s.material[c] = 2;
                    s.fibre_axis[c] = static_cast<std::uint8_t>(voxel_fibre);
                }
                if (i == 0) s.fixed[c] = 1;
            }
    s.actuation.start_s = 0.0;
    s.damping.global_ratio = 0.02;
    auto model = Model::build(s);
    World w(model);
    auto tip = [&] {
        std::array<double, 3> sum{};
        int count = 0;
        for (int v = 0; v < model->voxel_count(); ++v) {
            const auto c = model->voxel_coords(v);
            if (c[along] != 19) continue;
            for (int k = 0; k < 3; ++k)
                sum[k] += w.voxel_position_m(v)[k] - (c[k] + 0.5) * s.voxel_size_m;
            ++count;
        }
        for (double& x : sum)
            x /= count;
        return sum;
    };
    REQUIRE(w.advance_to(1.5));
    const auto early = tip();
    REQUIRE(w.advance_to(2.0));
    const auto late = tip();
    CHECK(std::fabs(late[2] - early[2]) <= 1e-3 * std::fabs(late[2]) + 1e-7);  // settled
    return late;
}

// Timoshenko (1925), equal moduli and thicknesses: curvature 3 de / (2 h); the tip 19 voxels from
// the clamp plane moves kappa l^2 / 2.
double timoshenko_tip(double mismatch) {
    const double L = 0.01, h = 2 * L, l = 19 * L;
    return 1.5 * mismatch / h * l * l / 2.0;
}

}  // namespace

TEST_CASE("fibres per voxel: a free muscle voxel with its own axis y shortens along y only") {
    // The material says x; every voxel says y: the block shortens along y by e and thickens
    // along x and z by nu e (the free strain of an active stress along y).
    const double e = 0.1, nu = 0.35;
    BodySpec s = solid_box(2, 2, 2, muscle_material(0, nu, e));
    s.fibre_axis.assign(s.material.size(), 1);
    s.actuation.start_s = 0.0;
    auto model = Model::build(s);
    World w(model);
    REQUIRE(w.advance_to(0.3));  // a = 1 - e^-30
    const auto lo = w.voxel_position_m(voxel_at(*model, 0, 0, 0));
    const auto hi = w.voxel_position_m(voxel_at(*model, 1, 1, 1));
    VoxelPoses poses;
    w.read_poses(poses);
    for (int i = 0; i < 3; ++i) {
        const double strain = (hi[i] - lo[i]) / s.voxel_size_m - 1.0;
        const double truth = i == 1 ? -e : nu * e;
        CAPTURE(i);
        CHECK(strain == relative(truth, 0.01));
        CHECK(poses.size_m[i] / s.voxel_size_m - 1.0 == relative(truth, 1e-4));
    }
}

TEST_CASE(
    "fibres per voxel: a body whose cells all take their material's axis runs bit for bit "
    "as one without per-voxel axes") {
    BodySpec s = solid_box(3, 2, 2, muscle_material(2, 0.35, 0.05));
    Material passive;
    s.materials.push_back(passive);
    s.material[0] = 2;
    s.actuation.start_s = 0.0;
    BodySpec same = s;
    same.fibre_axis.assign(s.material.size(), kMaterialFibreAxis);
    same.fibre_axis[3] = 2;  // its material's own axis, given explicitly
    same.fibre_axis[0] = 0;  // a passive cell's axis is ignored
    auto a = Model::build(s), b = Model::build(same);
    World wa(a), wb(b);
    REQUIRE(wa.advance_to(0.2));
    REQUIRE(wb.advance_to(0.2));
    for (int v = 0; v < a->voxel_count(); ++v)
        for (int k = 0; k < 3; ++k)
            CHECK(wa.voxel_position_m(v)[k] == wb.voxel_position_m(v)[k]);  // exact
}

TEST_CASE(
    "fibres per voxel: a muscle-on-passive strip bends in the plane its voxels' fibres "
    "allow, not its material's") {
    const double e = 0.01;
    const double truth = -timoshenko_tip(e);  // the muscle layer below shortens: the tip drops
    // Along x: fibres along x (the material says y) bend it in x-z as Timoshenko's bilayer;
    // fibres across it (y; the material says x) shorten only its 2-voxel width, in y-z.
    const auto along_x = strip_tip(0, 1, 0, e);
    const auto across_x = strip_tip(0, 0, 1, e);
    // Along y: the same turned a quarter: fibres along y bend it in y-z.
    const auto along_y = strip_tip(1, 0, 1, e);
    const auto across_y = strip_tip(1, 1, 0, e);
    MESSAGE("strip along x, voxel fibres x: tip z "
            << along_x[2] << " m (Timoshenko " << truth << "), y " << along_x[1]
            << "; voxel fibres y: tip z " << across_x[2] << " m");
    MESSAGE("strip along y, voxel fibres y: tip z " << along_y[2] << " m, x " << along_y[0]
                                                    << "; voxel fibres x: tip z " << across_y[2]
                                                    << " m");
    CHECK(along_x[2] == relative(truth, 0.02));
    CHECK(along_y[2] == relative(truth, 0.02));
    // The bend stays in the plane of the strip's axis and z: no sideways tip motion.
    CHECK(std::fabs(along_x[1]) < 0.005 * std::fabs(truth));
    CHECK(std::fabs(along_y[0]) < 0.005 * std::fabs(truth));
    // Fibres across: no bending along the strip (nu 0).
    CHECK(std::fabs(across_x[2]) < 0.005 * std::fabs(truth));
    CHECK(std::fabs(across_y[2]) < 0.005 * std::fabs(truth));
}

TEST_CASE("fibres per voxel: bad entries are refused with the field named") {
    BodySpec s = solid_box(2, 1, 1, muscle_material(0, 0.35, 0.1));
    s.fibre_axis = {0, 3};
    CHECK(build_refusal(s).find("fibre_axis[1]") != std::string::npos);
    s.fibre_axis = {0};
    CHECK(build_refusal(s).find("fibre_axis has 1 entries, expected 0 or 2") != std::string::npos);
    s.fibre_axis = {2, kMaterialFibreAxis};
    CHECK(build_refusal(s).empty());
}
