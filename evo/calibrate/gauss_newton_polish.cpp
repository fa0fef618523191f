// Damped Gauss-Newton steps after the optimiser (gauss_newton_polish.hpp).
#include "evo/calibrate/gauss_newton_polish.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "evo/calibrate/identifiability.hpp"

namespace bhm::evo {

namespace {
// The smallest scaled curvature eigenvalue the polish still steps on: a valley 1e6 times longer
// than wide (the uncertainty already calls 1e3 near singular, kNearSingular); below it the
// Jacobian's finite differences no longer fix the direction.
constexpr double kPolishNearSingular = 1e-12;
}  // namespace

double residual_rms(const std::vector<double>& residuals) {
    if (residuals.empty()) return std::numeric_limits<double>::infinity();
    double sum = 0.0;
    for (double v : residuals)
        sum += v * v;
    return std::sqrt(sum / static_cast<double>(residuals.size()));
}

PolishResult gauss_newton_polish(const PolishProblem& problem, const std::vector<double>& x,
                                 const std::vector<double>& residuals, const Jacobian& jacobian,
                                 const PolishOptions& o) {
    PolishResult out;
    out.x = x;
    out.residuals = residuals;
    out.jacobian = jacobian;
    out.misfit_before = out.misfit_after = residual_rms(residuals);
    out.stop = "step limit reached";
    const std::size_t p = x.size();
    for (int step = 0; step < o.max_steps; ++step) {
        const std::vector<double> delta =
            gauss_newton_step(out.jacobian, out.residuals, kPolishNearSingular);
        if (delta.size() != p) {
            out.stop = "no Gauss-Newton step (the curvature is near singular)";
            return out;
        }
        double largest = 0.0;
        for (double d : delta)
            largest = std::max(largest, std::abs(d));
        if (!(largest > o.x_tolerance)) {
            out.stop = "at the least-squares minimum (the step is within the tolerance)";
            return out;
        }
        bool taken = false;
        double length = 1.0;
        for (int h = 0; h <= o.halvings && !taken; ++h, length *= 0.5) {
            if (out.simulations + 1 + problem.jacobian_cost > o.max_simulations) {
                out.stop = "simulation budget reached";
                return out;
            }
            std::vector<double> trial(p);
            bool moves = false;
            for (std::size_t i = 0; i < p; ++i) {
                trial[i] =
                    std::clamp(out.x[i] + length * delta[i], problem.lower[i], problem.upper[i]);
                moves = moves || trial[i] != out.x[i];
            }
            if (!moves) break;  // the step points out of the box
            std::vector<double> r = problem.residuals(trial);
            ++out.simulations;
            const double misfit = residual_rms(r);
            if (!(misfit < out.misfit_after)) continue;
            out.x = std::move(trial);
            out.residuals = std::move(r);
            out.misfit_after = misfit;
            taken = true;
        }
        if (!taken) {
            out.stop = "no step along the Gauss-Newton direction lowers the misfit";
            return out;
        }
        ++out.steps;
        out.jacobian = problem.jacobian(out.x);
        out.simulations += problem.jacobian_cost;
    }
    return out;
}

}  // namespace bhm::evo
