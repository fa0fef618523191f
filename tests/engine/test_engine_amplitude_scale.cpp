// BodySpec::amplitude_scale (issue 44: an evolved controller's per-voxel drive): a scale of 1
// everywhere is the body without one to the last bit, and a scale s on every active voxel drives
// the body as the material's own cte times s does (the same free strain, the same motion).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "tests/engine/engine_test_bodies.hpp"

using namespace bhm::engine;

namespace {

struct Final {
    std::vector<std::array<double, 3>> positions;
    std::array<double, 3> com{};
};

Final run_for(const BodySpec& spec, double t_s) {
    World world(Model::build(spec));
    REQUIRE(world.advance_to(t_s));
    Final out;
    for (int v = 0; v < world.model().voxel_count(); ++v)
        out.positions.push_back(world.voxel_position_m(v));
    out.com = world.centre_of_mass_m();
    return out;
}

}  // namespace

TEST_CASE("amplitude_scale of 1 everywhere is bit-identical to no amplitude_scale") {
    BodySpec plain = test::free_actuated_body();
    BodySpec ones = plain;
    ones.amplitude_scale.assign(ones.material.size(), 1.0f);
    const Final a = run_for(plain, 0.05), b = run_for(ones, 0.05);
    CHECK(a.positions == b.positions);
}

TEST_CASE("amplitude_scale s moves a body as a cte of s times its material's does") {
    // Held at x-, no floor: the tip's swing depends on the free strain only. Halving the scale and
    // halving the cte give the same strain per voxel; the stable step differs by a hair (it counts
    // the drive's largest size), so the two agree to well within a percent, not to the bit.
    Material active;
    active.cte_per_c = 0.01;
    BodySpec scaled = test::solid_box(6, 2, 2, active);
    test::fix_x_min_layer(scaled);
    scaled.actuation.start_s = 0.0;
    scaled.actuation.frequency_hz = 5.0;
    scaled.phase_rad.assign(scaled.material.size(), 0.0f);
    for (int c = 0; c < scaled.cell_count(); ++c)  // a travelling wave: the body bends and twists
        scaled.phase_rad[c] = static_cast<float>(0.9 * c);
    BodySpec halved_cte = scaled;
    scaled.amplitude_scale.assign(scaled.material.size(), 0.5f);
    halved_cte.materials[0].cte_per_c = 0.005;
    BodySpec full = halved_cte;
    full.materials[0].cte_per_c = 0.01;
    const Final a = run_for(scaled, 0.08), b = run_for(halved_cte, 0.08), c = run_for(full, 0.08);
    const double rest_x = 3.0 * scaled.voxel_size_m;  // the unactuated centre: 3 voxels along x
    const double moved_a = std::hypot(a.com[0] - rest_x, a.com[1] - scaled.voxel_size_m,
                                      a.com[2] - scaled.voxel_size_m);
    const double moved_b = std::hypot(b.com[0] - rest_x, b.com[1] - scaled.voxel_size_m,
                                      b.com[2] - scaled.voxel_size_m);
    const double moved_c = std::hypot(c.com[0] - rest_x, c.com[1] - scaled.voxel_size_m,
                                      c.com[2] - scaled.voxel_size_m);
    REQUIRE(moved_b > 1e-6);
    CHECK(std::fabs(moved_a - moved_b) < 0.01 * moved_b);
    CHECK(moved_c > 1.5 * moved_b);  // the scale did scale something
}

TEST_CASE("amplitude_scale s shortens a muscle as a contraction strain of s times its own does") {
    // A held 4 x 2 x 2 muscle bar, 20 Hz pulses from t = 0, no gravity: its tip's pull along the
    // fibre (x) follows the free shortening. As for the sine model the stable step counts the
    // drive's largest size, so the two agree to well within a percent, not to the bit.
    Material muscle;
    muscle.actuation_model = ActuationModel::Muscle;
    muscle.muscle.contraction_strain = 0.1;
    muscle.muscle.frequency_hz = 20.0;
    muscle.muscle.pulse_width_s = 0.01;
    BodySpec scaled = test::solid_box(4, 2, 2, muscle);
    test::fix_x_min_layer(scaled);
    scaled.actuation.start_s = 0.0;
    BodySpec halved = scaled;
    scaled.amplitude_scale.assign(scaled.material.size(), 0.5f);
    halved.materials[0].muscle.contraction_strain = 0.05;
    BodySpec full = halved;
    full.materials[0].muscle.contraction_strain = 0.1;
    const double rest_x = 2.0 * scaled.voxel_size_m;
    const double a = rest_x - run_for(scaled, 0.05).com[0];
    const double b = rest_x - run_for(halved, 0.05).com[0];
    const double c = rest_x - run_for(full, 0.05).com[0];
    REQUIRE(b > 1e-6);  // it shortened toward the held face
    CHECK(std::fabs(a - b) < 0.01 * b);
    CHECK(c > 1.5 * b);
}

TEST_CASE("a different amplitude scale is a different free strain to the Poisson coupling") {
    // Two halves of one material and phase, one at scale 1 and one at 0.25: with the scale left out
    // of same_free_strain the halves would share an equal split; the model must differ from the one
    // where both halves are at 1 beyond the amplitude itself, so compare against a body made of two
    // materials of ctes 0.01 and 0.0025, which the coupling already treats as different strains.
    Material active;
    active.cte_per_c = 0.01;
    active.poisson_ratio = 0.45;
    BodySpec scaled = test::solid_box(4, 2, 2, active);
    test::fix_x_min_layer(scaled);
    scaled.actuation.start_s = 0.0;
    scaled.actuation.frequency_hz = 5.0;
    BodySpec two_materials = scaled;
    Material quarter = active;
    quarter.cte_per_c = 0.0025;
    two_materials.materials.push_back(quarter);
    scaled.amplitude_scale.assign(scaled.material.size(), 1.0f);
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 2; x < 4; ++x) {
                scaled.amplitude_scale[scaled.cell_index(x, y, z)] = 0.25f;
                two_materials.material[scaled.cell_index(x, y, z)] = 2;
            }
    const Final a = run_for(scaled, 0.06), b = run_for(two_materials, 0.06);
    // The same step (the full-drive material sets it in both) and the same coefficients up to
    // the rounding of cte A s against (cte s) A: equal to far below a micrometre.
    double worst = 0.0;
    for (std::size_t v = 0; v < a.positions.size(); ++v)
        for (int i = 0; i < 3; ++i)
            worst = std::max(worst, std::fabs(a.positions[v][i] - b.positions[v][i]));
    CHECK(worst < 1e-9);
}

TEST_CASE("amplitude_scale outside [0, 1] or of the wrong size is refused naming the field") {
    BodySpec s = test::free_actuated_body();
    s.amplitude_scale.assign(3, 1.0f);
    CHECK_THROWS_WITH_AS(Model::build(s), doctest::Contains("amplitude_scale"),
                         std::invalid_argument);
    s.amplitude_scale.assign(s.material.size(), 1.5f);
    CHECK_THROWS_WITH_AS(Model::build(s), doctest::Contains("amplitude_scale"),
                         std::invalid_argument);
}
