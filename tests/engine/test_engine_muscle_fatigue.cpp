// The muscle model's optional fatigue (engine/muscle.hpp, issue 43): the force left f follows
// df/dt = -(f - floor) / fatigue_s while stimulated and (1 - f) / recovery_s at rest, and the
// voxel takes the activation a f. Truths: the two ODEs solved here on their own (closed form
// under a constant stimulus and at rest; a fine RK4 march of a and f together over a pulse
// train), and the free strain -e a f of a voxel pair under a long tetanus.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "engine/muscle.hpp"
#include "engine_test_bodies.hpp"
#include "muscle_test_support.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// a and f marched together with RK4 at step h (u held over each step; the step divides the pulse
// width, the period and the burst so that no step straddles a switch). Returns a f.
double rk4_fatigued(const Muscle& m, double t_end, double* f_out = nullptr, double h = 1e-5) {
    double a = 0.0, f = 1.0;
    const auto steps = static_cast<long>(std::llround(t_end / h));
    for (long i = 0; i < steps; ++i) {
        const bool on = pulse_on(m, i * h + 0.5 * h);
        auto da = [&](double x) { return on ? (1.0 - x) / m.rise_s : -x / m.decay_s; };
        auto df = [&](double x) {
            return on ? -(x - m.fatigue_floor) / m.fatigue_s : (1.0 - x) / m.recovery_s;
        };
        const double a1 = da(a), a2 = da(a + 0.5 * h * a1), a3 = da(a + 0.5 * h * a2),
                     a4 = da(a + h * a3);
        const double f1 = df(f), f2 = df(f + 0.5 * h * f1), f3 = df(f + 0.5 * h * f2),
                     f4 = df(f + h * f3);
        a += h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
        f += h / 6.0 * (f1 + 2 * f2 + 2 * f3 + f4);
    }
    if (f_out) *f_out = f;
    return a * f;
}

// Stimulated throughout (one pulse as wide as its period), fatiguing to 40 % in 0.5 s.
Muscle tetanic() {
    Muscle m = skeletal();
    m.pulse_width_s = 1.0;
    m.fatigue_s = 0.5;
    m.recovery_s = 1.5;
    m.fatigue_floor = 0.4;
    return m;
}

bool same_bits(double x, double y) {
    return std::memcmp(&x, &y, sizeof x) == 0;
}

}  // namespace

TEST_CASE("fatigue: under a constant stimulus f decays to its floor as the ODE's closed form") {
    const Muscle m = tetanic();
    for (double t : {0.001, 0.01, 0.1, 0.37, 0.5, 0.999, 1.0, 2.5, 7.3}) {
        const muscle::Activation a = muscle::activation(m, t);
        const double f = 0.4 + 0.6 * std::exp(-t / 0.5);
        const double act = 1.0 - std::exp(-t / 0.02);
        CAPTURE(t);
        CHECK(a.stimulated);
        CHECK(std::fabs(a.fatigue - f) < 1e-12);
        CHECK(std::fabs(a.a - act * f) < 1e-12);
        // d(a f)/dt = a' f + a f'.
        const double rate = (1.0 - act) / 0.02 * f + act * -(f - 0.4) / 0.5;
        CHECK(std::fabs(a.rate - rate) < 1e-9 * std::max(1.0, std::fabs(rate)));
    }
    // Long stimulated: the floor's share of the force.
    CHECK(std::fabs(muscle::activation(m, 60.0).a - 0.4) < 1e-12);
}

TEST_CASE("fatigue: at rest f recovers toward 1 as the ODE's closed form") {
    Muscle m = tetanic();
    m.train_on_s = 2.0;  // 2 s stimulated (pulses as wide as their period), 5 s at rest
    m.train_off_s = 5.0;
    const double f_end = 0.4 + 0.6 * std::exp(-2.0 / 0.5);
    const double a_end = 1.0 - std::exp(-2.0 / 0.02);
    for (double t : {2.001, 2.1, 3.0, 4.5, 6.99}) {
        const muscle::Activation a = muscle::activation(m, t);
        const double f = 1.0 - (1.0 - f_end) * std::exp(-(t - 2.0) / 1.5);
        CAPTURE(t);
        CHECK_FALSE(a.stimulated);
        CHECK(std::fabs(a.fatigue - f) < 1e-12);
        CHECK(std::fabs(a.a - a_end * std::exp(-(t - 2.0) / 0.06) * f) < 1e-12);
    }
    // The second burst starts from the recovered f, not from 1.
    const double f7 = 1.0 - (1.0 - f_end) * std::exp(-5.0 / 1.5);
    for (double s : {0.05, 0.8}) {
        const double f = 0.4 + (f7 - 0.4) * std::exp(-s / 0.5);
        CHECK(std::fabs(muscle::activation(m, 7.0 + s).fatigue - f) < 1e-12);
    }
}

TEST_CASE("fatigue: a pulse train in bursts follows a fine numerical integration of a and f") {
    Muscle m = tetanic();
    m.frequency_hz = 40.0;
    m.pulse_width_s = 0.005;
    m.train_on_s = 0.3;
    m.train_off_s = 0.45;
    m.fatigue_s = 0.2;  // with 12.5 % of the time stimulated, it tires over a few bursts
    m.recovery_s = 2.0;
    for (double t : {0.1, 0.299, 0.31, 0.6, 0.77, 1.5, 2.0, 2.9, 4.2}) {
        double f = 0.0;
        const double af = rk4_fatigued(m, t, &f);
        const muscle::Activation a = muscle::activation(m, t);
        CAPTURE(t);
        CHECK(std::fabs(a.fatigue - f) < 1e-6);
        CHECK(std::fabs(a.a - af) < 1e-6);
    }
    // An endless 40 Hz train: f settles where a period's loss and recovery balance, below 1.
    m.train_on_s = m.train_off_s = 0.0;
    double f = 0.0;
    const double af = rk4_fatigued(m, 3.0, &f);
    CHECK(std::fabs(muscle::activation(m, 3.0).a - af) < 1e-6);
    CHECK(f < 0.8);
}

TEST_CASE("fatigue off: the activation is bit for bit the fresh muscle's, whatever else is set") {
    Muscle fresh = tetanic();
    fresh.fatigue_s = fresh.recovery_s = fresh.fatigue_floor = 0.0;
    fresh.frequency_hz = 40.0;
    fresh.pulse_width_s = 0.005;
    fresh.train_on_s = 0.3;
    fresh.train_off_s = 0.45;
    Muscle unset = fresh;  // fatigue_s = 0 leaves recovery and floor without effect
    unset.recovery_s = 3.0;
    unset.fatigue_floor = 0.5;
    CHECK_FALSE(muscle::fatigues(fresh));
    CHECK_FALSE(muscle::fatigues(unset));
    CHECK(muscle::same_signal(fresh, unset));
    Muscle tiring = fresh;
    tiring.fatigue_s = 1.0;
    tiring.recovery_s = 3.0;
    CHECK_FALSE(muscle::same_signal(fresh, tiring));
    for (double t = 0.0; t < 3.0; t += 0.0123) {
        const muscle::Activation a = muscle::activation(fresh, t), b = muscle::activation(unset, t);
        CHECK(same_bits(a.a, b.a));
        CHECK(same_bits(a.rate, b.rate));
        CHECK(a.fatigue == 1.0);
    }
    // Its pulse-train values are still the ODE's (the test of the fresh model, on the
    // generalised maps): a twitch's closed form.
    Muscle one = fresh;
    one.frequency_hz = 1.0;
    one.train_on_s = one.train_off_s = 0.0;
    for (double t : {0.003, 0.01, 0.2})
        CHECK(std::fabs(muscle::activation(one, t).a -
                        (t <= 0.005 ? 1.0 - std::exp(-t / 0.02)
                                    : (1.0 - std::exp(-0.005 / 0.02)) *
                                          std::exp(-(t - 0.005) / 0.06))) < 1e-13);
}

TEST_CASE("fatigue: a free voxel pair's strain decays under a long tetanus as -e a f") {
    Material mat;
    mat.poisson_ratio = 0.0;
    mat.actuation_model = ActuationModel::Muscle;
    mat.muscle = tetanic();
    BodySpec s = solid_box(2, 1, 1, mat);
    s.actuation.start_s = 0.0;
    auto model = Model::build(s);
    World w(model);
    const double L = s.voxel_size_m;
    double worst = 0.0, strain = 0.0;
    for (double t = 0.01; t < 2.0; t += 0.01) {
        REQUIRE(w.advance_to(t));
        strain = (w.voxel_position_m(1)[0] - w.voxel_position_m(0)[0]) / L - 1.0;
        const double tau = w.time_s();
        const double truth =
            -0.1 * (1.0 - std::exp(-tau / 0.02)) * (0.4 + 0.6 * std::exp(-tau / 0.5));
        worst = std::max(worst, std::fabs(strain - truth));
    }
    MESSAGE("largest |strain - (-e a f)| over 2 s of fatiguing tetanus: " << worst << " (e = 0.1)");
    CHECK(worst < 0.003 * 0.1);
    // It has lost most of what it can: from -0.1 toward the floor's -0.04.
    CHECK(strain > -0.045);
    CHECK(strain < -0.04);
}
