// One source of truth for the physics envelope: what validates runs, what the engine refuses does
// not validate, and the step budget is refused up front with an estimate.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "engine/limits.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo_test_support.hpp"

using namespace bhm;
using namespace bhm::evo;

namespace {

Body solid_workspace(const Experiment& e, std::uint8_t material) {
    Body b;
    b.size = e.workspace_size;
    b.cells.assign(static_cast<std::size_t>(b.cell_count()), material);
    return b;
}

bool names(const std::vector<Problem>& problems, const std::string& field,
           const std::string& text = "") {
    for (const auto& p : problems)
        if (p.field == field && p.message.find(text) != std::string::npos) return true;
    return false;
}

std::string build_reason(const Experiment& e, const Body& body) {
    try {
        engine::Model::build(make_body_spec(e, apply_frame_and_overrides(e, body)));
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST_CASE("limits: documented-valid random experiments all build and run in the step budget") {
    // Every field drawn across (and beyond) its documented range; those that validate must
    // build, with a step count in [min, max] for the whole settle + evaluate time.
    std::mt19937_64 rng(12345);
    auto log_uniform = [&](double lo, double hi) {
        return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
    };
    auto uniform = [&](double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng);
    };
    int valid = 0;
    for (int trial = 0; trial < 400; ++trial) {
        Experiment e = test::tiny_experiment({3, 2, 2});
        e.voxel_size_m = log_uniform(1e-7, 20.0);
        for (auto& m : e.materials) {
            m.physics.youngs_modulus_pa = log_uniform(0.1, 1e13);
            m.physics.density_kg_m3 = log_uniform(0.1, 1e7);
            m.physics.poisson_ratio = uniform(-1.0, 0.5);
        }
        e.materials[1].physics.cte_per_c = log_uniform(1e-4, 1.0);
        e.actuation.temperature_amplitude_c = uniform(0.0, 100.0);
        e.actuation.frequency_hz = log_uniform(0.01, 1000.0);
        e.simulation.dt_fraction = uniform(0.01, 1.2);
        e.simulation.settle_s = uniform(0.0, 1.0);
        e.simulation.evaluate_s = log_uniform(0.01, 10.0);
        if (!validate_experiment(e, "random").empty()) continue;
        ++valid;
        CAPTURE(trial);
        const Body body = solid_workspace(e, 2);
        REQUIRE(validate_body_against(body, e, "body").empty());
        const auto spec = make_body_spec(e, apply_frame_and_overrides(e, body));
        std::shared_ptr<const engine::Model> model;
        REQUIRE_NOTHROW(model = engine::Model::build(spec));
        const auto steps = engine::limits::steps_for(evaluation_seconds(e), model->dt_s());
        CHECK(steps >= engine::limits::kMinStepsPerSimulation);
        CHECK(steps <= engine::limits::kMaxStepsPerSimulation);
    }
    MESSAGE(valid << " of 400 random experiments validated");
    CHECK(valid > 20);  // the sample does exercise the accepted region
}

TEST_CASE("limits: what the engine refuses, validate refuses on the same field") {
    const Experiment base = test::tiny_experiment({3, 2, 2});
    const Body body = solid_workspace(base, 2);
    REQUIRE(validate_experiment(base, "e").empty());
    REQUIRE(build_reason(base, body).empty());
    struct Case {
        const char* what;
        void (*edit)(Experiment&);
        const char* field;
    };
    const Case cases[] = {
        {"dense", [](Experiment& e) { e.materials[0].physics.density_kg_m3 = 2e6; },
         "materials[0].density_kg_m3"},
        {"stiff", [](Experiment& e) { e.materials[0].physics.youngs_modulus_pa = 2e12; },
         "materials[0].youngs_modulus_pa"},
        {"nu", [](Experiment& e) { e.materials[1].physics.poisson_ratio = -0.95; },
         "materials[1].poisson_ratio"},
        {"strain", [](Experiment& e) { e.actuation.temperature_amplitude_c = 61.0; },
         "actuation.temperature_amplitude_c"},
        {"damping", [](Experiment& e) { e.simulation.bond_damping_ratio = 11.0; },
         "simulation.bond_damping_ratio"},
        {"dt", [](Experiment& e) { e.simulation.dt_fraction = 1.7; }, "simulation.dt_fraction"},
        {"rotary", [](Experiment& e) { e.simulation.rotary_inertia_scale = 0.5; },
         "simulation.rotary_inertia_scale"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.what);
        Experiment e = base;
        c.edit(e);
        CHECK(names(validate_experiment(e, "e"), c.field));
        CHECK_FALSE(build_reason(e, body).empty());
    }
    // The strain bound itself runs: cte 0.01 x 60 degC = 0.6.
    Experiment edge = base;
    edge.actuation.temperature_amplitude_c = 60.0;
    CHECK(validate_experiment(edge, "e").empty());
    CHECK(build_reason(edge, body).empty());
}

TEST_CASE("limits: a simulation beyond the step budget is refused with an estimate") {
    Experiment e = test::tiny_experiment({8, 8, 7});
    e.voxel_size_m = 1e-4;
    e.materials[0].physics.youngs_modulus_pa = 1e12;
    e.simulation.settle_s = 0.25;
    e.simulation.evaluate_s = 1.0;
    e.actuation.frequency_hz = 2.0;
    const auto problems = validate_experiment(e, "e");
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].field == "simulation");
    MESSAGE(problems[0].to_string());
    // dt = 0.9 x 2.2 / (2 pi sqrt(2 E L / m)) (bending's, stiffer than nu = 0.35's P-wave
    // 1.6 E L / m; 2.2x with the implicit bond damping): 1.25 s / 7.05e-10 s = 1.77e9 steps.
    CHECK(problems[0].message.find("needs 1.77") != std::string::npos);
    CHECK(problems[0].message.find("e+09 steps") != std::string::npos);
    CHECK(problems[0].message.find(" h per simulation") != std::string::npos);
}

TEST_CASE("limits: a simulation that would run (nearly) zero steps is refused, never run") {
    Experiment e = test::tiny_experiment({2, 2, 2});
    e.voxel_size_m = 10.0;
    for (auto& m : e.materials)
        m.physics.youngs_modulus_pa = 1.0;
    e.actuation.frequency_hz = 0.1;
    e.simulation.settle_s = 0.25;
    e.simulation.evaluate_s = 1.0;
    const auto problems = validate_experiment(e, "e");
    CHECK(names(problems, "simulation", "would take only 0 steps"));
    // The engine itself refuses to run zero steps rather than report an empty success.
    const auto model = engine::Model::build(
        make_body_spec(e, apply_frame_and_overrides(e, solid_workspace(e, 1))));
    REQUIRE(model->dt_s() > 2.0 * evaluation_seconds(e));
    engine::World world(model);
    CHECK_THROWS_AS(engine::run(world, evaluation_seconds(e), 30.0, nullptr),
                    std::invalid_argument);
}

TEST_CASE("limits: an actuation period sampled by too few steps is refused") {
    Experiment e = test::tiny_experiment({2, 2, 2});
    for (auto& m : e.materials)
        m.physics.youngs_modulus_pa = 1e3;  // dt ~ 1.4e-3 s
    e.actuation.frequency_hz = 100.0;       // 7 steps per period
    e.simulation.evaluate_s = 1.0;
    CHECK(names(validate_experiment(e, "e"), "simulation", "actuation period"));
}

TEST_CASE("limits: an empty body is refused by validate, as the engine refuses it") {
    const Experiment e = test::tiny_experiment({3, 2, 2});
    const Body empty = solid_workspace(e, 0);
    CHECK(names(validate_body_against(empty, e, "body"), "layers", "no voxels"));
    CHECK(build_reason(e, empty).find("no voxels") != std::string::npos);
}

TEST_CASE("limits: the step range brackets every body's actual step") {
    Experiment e = test::tiny_experiment({4, 3, 3});
    e.materials[1].physics.youngs_modulus_pa = 5e7;  // 10x stiffer, same density
    e.materials[1].physics.density_kg_m3 = 3000.0;
    std::vector<engine::Material> physics;
    for (const auto& m : e.materials)
        physics.push_back(m.physics);
    const auto range = engine::limits::step_range(physics, e.voxel_size_m, 0.9,
                                                  e.actuation.temperature_amplitude_c,
                                                  e.simulation.implicit_damping_sweeps);
    for (std::uint8_t material : {1, 2}) {
        Body body = solid_workspace(e, material);
        if (material == 2) body.cells[0] = 1;  // a mixed link
        const double dt =
            engine::Model::build(make_body_spec(e, apply_frame_and_overrides(e, body)))->dt_s();
        CHECK(dt >= range.shortest_s * (1.0 - 1e-12));
        CHECK(dt <= range.longest_s * (1.0 + 1e-12));
    }
}

// simulation.rotary_inertia_scale (issue 42): absent reads as the cube's inertia and a file at 1 is
// written without it (existing experiments and run directories byte for byte); set, it reaches the
// engine, whose step lengthens by at most sqrt(s) (every rotational mode's omega ~ 1 / sqrt(I); the
// axial mode does not move) and stays inside the validated step range.
TEST_CASE("limits: the rotary inertia scale is read, written, refused and carried to the step") {
    Experiment e = test::tiny_experiment({4, 3, 3});
    nlohmann::json j = experiment_to_json(e);
    CHECK_FALSE(j["simulation"].contains("rotary_inertia_scale"));
    CHECK(parse_experiment(j, "e.json").simulation.rotary_inertia_scale == 1.0);

    e.simulation.rotary_inertia_scale = 1.5;
    j = experiment_to_json(e);
    CHECK(j["simulation"]["rotary_inertia_scale"] == 1.5);
    CHECK(parse_experiment(j, "e.json") == e);

    for (double bad : {0.5, 101.0}) {
        CAPTURE(bad);
        j["simulation"]["rotary_inertia_scale"] = bad;
        try {
            (void)parse_experiment(j, "e.json");
            FAIL("a rotary inertia scale outside [1, 100] was accepted");
        } catch (const ValidationError& error) {
            const std::string what = error.what();
            CHECK(what.find('\n') == std::string::npos);  // one line, one problem
            CHECK(what.find("simulation.rotary_inertia_scale") != std::string::npos);
            CHECK(what.find("must be in [1, 100]") != std::string::npos);
        }
    }

    const Body body = solid_workspace(e, 2);
    const auto dt_at = [&](double scale) {
        Experiment at = e;
        at.simulation.rotary_inertia_scale = scale;
        const auto spec = make_body_spec(at, apply_frame_and_overrides(at, body));
        CHECK(spec.rotary_inertia_scale == scale);
        return engine::Model::build(spec)->dt_s();
    };
    const double dt1 = dt_at(1.0), dt15 = dt_at(1.5);
    CHECK(dt15 > dt1 * 1.01);
    CHECK(dt15 <= dt1 * std::sqrt(1.5) * (1.0 + 1e-12));
    std::vector<engine::Material> physics;
    for (const auto& m : e.materials)
        physics.push_back(m.physics);
    const auto range = engine::limits::step_range(physics, e.voxel_size_m, e.simulation.dt_fraction,
                                                  e.actuation.temperature_amplitude_c,
                                                  e.simulation.implicit_damping_sweeps, 1.5);
    CHECK(dt15 >= range.shortest_s * (1.0 - 1e-12));
    CHECK(dt15 <= range.longest_s * (1.0 + 1e-12));
}
