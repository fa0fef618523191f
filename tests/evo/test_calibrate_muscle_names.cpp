// bhm calibrate's muscle parameters (issue 43): rise_s, decay_s and contraction_strain scale the
// muscle materials' fields and only theirs, their search range stays inside the fields' own
// (engine/muscle.hpp), and a parameter of the other actuation model is refused with the field
// that says why. The round trip through a fit is tests/app/test_calibrate_command.cpp's.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/muscle.hpp"
#include "evo/calibrate/fit_parameters.hpp"
#include "evo/evo_test_support.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::evo;
using bhm::test::relative;

namespace {

// tiny_experiment's palette with its active material under the muscle model.
Experiment muscle_experiment() {
    Experiment e = bhm::evo::test::tiny_experiment({4, 1, 2});
    auto& m = e.materials[1].physics;
    m.cte_per_c = 0.0;
    m.actuation_model = bhm::engine::ActuationModel::Muscle;
    m.muscle.contraction_strain = 0.2;
    m.muscle.rise_s = 0.03;
    m.muscle.decay_s = 50.0;  // near kMaxTimeConstantS (100 s): its range is narrowed
    return e;
}

}  // namespace

TEST_CASE("calibrate's muscle parameters scale only the muscle materials, inside their ranges") {
    const Experiment e = muscle_experiment();
    const auto ps = parse_fit_list("rise_s,decay_s,contraction_strain", e);
    REQUIRE(ps.size() == 3);
    CHECK(ps[0].kind == FitKind::MuscleRise);
    CHECK(ps[0].material == -1);
    // rise_s 0.03 s: 1/5..5 times lies inside [1e-4, 100] s.
    CHECK(ps[0].lower == relative(-std::log(5.0), 1e-12));
    CHECK(ps[0].upper == relative(std::log(5.0), 1e-12));
    // decay_s 50 s may grow by 2 times only (100 s), contraction_strain 0.2 by 3 (0.6).
    CHECK(ps[1].upper == relative(std::log(bhm::engine::muscle::kMaxTimeConstantS / 50.0), 1e-12));
    CHECK(ps[2].upper ==
          relative(std::log(bhm::engine::muscle::kMaxContractionStrain / 0.2), 1e-12));
    CHECK(ps[2].lower == relative(-std::log(5.0), 1e-12));

    const FitPoint p = apply_fit(e, ps, {std::log(2.0), std::log(0.5), std::log(1.5)});
    const auto& muscle = p.experiment.materials[1].physics.muscle;
    CHECK(muscle.rise_s == relative(0.06, 1e-12));
    CHECK(muscle.decay_s == relative(25.0, 1e-12));
    CHECK(muscle.contraction_strain == relative(0.3, 1e-12));
    // The passive (sine-model) material keeps its default twitch fields untouched.
    CHECK(p.experiment.materials[0] == e.materials[0]);
    CHECK(fit_value(e, ps[0], std::log(2.0)) == relative(0.06, 1e-12));
    CHECK(std::string(fit_unit(ps[0])) == "s");

    // Per material, and copied into another experiment's material as the studio applies a fit.
    const auto one = parse_fit_list("rise_s:active", e);
    CHECK(one[0].material == 1);
    Experiment target = e;
    target.materials[1].physics.muscle.rise_s = 0.5;
    copy_fitted_values(apply_fit(e, one, {std::log(3.0)}).experiment, one, target);
    CHECK(target.materials[1].physics.muscle.rise_s == relative(0.09, 1e-12));
    CHECK(target.materials[0] == e.materials[0]);
}

TEST_CASE("a parameter of the other actuation model is refused with the field that says why") {
    const Experiment sine = bhm::evo::test::tiny_experiment({4, 1, 2});
    CHECK_THROWS_WITH(parse_fit_list("rise_s", sine),
                      "--fit: 'rise_s' does not apply: no material of the experiment uses the "
                      "muscle model (materials[k].actuation_model), so none has a muscle.rise_s");
    const Experiment e = muscle_experiment();
    CHECK_THROWS_WITH(parse_fit_list("contraction_strain:passive", e),
                      "--fit: 'contraction_strain:passive' does not apply: material 'passive' "
                      "uses the sine model (materials[0].actuation_model), which has no "
                      "muscle.contraction_strain");
    CHECK_THROWS_WITH(parse_fit_list("E,amplitude", e),
                      "--fit: 'amplitude' does not apply: the experiment's actuation is the "
                      "muscle model (materials[1].actuation_model), which ignores "
                      "actuation.temperature_amplitude_c; fit rise_s, decay_s or "
                      "contraction_strain");
    CHECK_THROWS_WITH(parse_fit_list("phase_lag", e),
                      doctest::Contains("which ignores actuation.phase_offset_rad"));
    CHECK_THROWS_WITH(parse_fit_list("rise_s,rise_s:active", e),
                      "--fit: 'rise_s:active' overlaps 'rise_s'");
    // E, density, damping and friction apply under either model.
    CHECK(parse_fit_list("E,density:active,global_damping,friction", e).size() == 4);

    // Two muscle materials sharing one signal and a third with its own: fitting one of the pair
    // apart would make three signals, more than the engine drives (kMaxSignals 2).
    Experiment three = e;
    three.materials.push_back(e.materials[1]);
    three.materials.back().name = "twin";
    three.materials.push_back(e.materials[1]);
    three.materials.back().name = "slow";
    three.materials.back().physics.muscle.rise_s = 0.1;
    CHECK(parse_fit_list("rise_s", three).size() == 1);  // one factor on all keeps two signals
    CHECK_THROWS_WITH(parse_fit_list("rise_s:twin", three),
                      doctest::Contains("--fit: 'rise_s:twin' would split a muscle signal the "
                                        "materials share: materials["));
}
