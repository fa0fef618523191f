#pragma once
// The Gauss-Newton polish that follows bhm calibrate's BOBYQA (evo/calibrate/calibrator.hpp).
// BOBYQA's quadratic model can stop in a narrow valley short of the least-squares minimum (a
// fused muscle train's rise_s against its contraction strain); Gauss-Newton, from the Jacobian of
// the residuals, steps along the valley: delta = -(J^T J)^-1 J^T r, tried at 1, 1/2, ..., 1/32 of
// its length (clipped to the bounds) and taken only where the misfit drops, then again from the
// new point, within a simulation budget.
#include <functional>
#include <string>
#include <vector>

namespace bhm::evo {

using Jacobian = std::vector<std::vector<double>>;  //!< jac[k][i] = d residual_k / d x_i

struct PolishProblem {
    std::vector<double> lower, upper;  //!< bounds of x
    //! The residuals at x (one simulation); empty when it diverged.
    std::function<std::vector<double>(const std::vector<double>& x)> residuals;
    //! The Jacobian of the residuals at x, costing `jacobian_cost` simulations.
    std::function<Jacobian(const std::vector<double>& x)> jacobian;
    int jacobian_cost = 0;
};

struct PolishOptions {
    int max_simulations = 0;    //!< line-search trials and Jacobians at accepted points
    int max_steps = 8;          //!< Gauss-Newton steps taken at most
    int halvings = 5;           //!< a step is tried at 1, 1/2, ..., 1/2^halvings of its length
    double x_tolerance = 1e-4;  //!< a step moving no x by more ends the polish: at the minimum
};

struct PolishResult {
    std::vector<double> x, residuals;                //!< the polished point and its residuals
    Jacobian jacobian;                               //!< at x
    double misfit_before = 0.0, misfit_after = 0.0;  //!< RMS of the residuals
    int steps = 0;                                   //!< steps taken (each lowered the misfit)
    int simulations = 0;  //!< trials plus the Jacobians at the points the steps reached
    std::string stop;     //!< why it stopped, for a reader
};

//! Polishes x (with its residuals and Jacobian, already known) by damped Gauss-Newton steps.
PolishResult gauss_newton_polish(const PolishProblem& problem, const std::vector<double>& x,
                                 const std::vector<double>& residuals, const Jacobian& jacobian,
                                 const PolishOptions& options);

//! RMS of residuals; infinity when there are none (a diverged simulation).
double residual_rms(const std::vector<double>& residuals);

}  // namespace bhm::evo
