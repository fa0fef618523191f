#pragma once
// Uncertainty and identifiability of a least-squares fit from its Jacobian (Gauss-Newton): the
// curvature of the misfit at the optimum is J^T J, the covariance sigma^2 (J^T J)^-1 with sigma^2
// the residual variance. Parameters whose estimates are strongly correlated, or a J^T J that is
// near singular, trade off: the track cannot tell them apart.
#include <string>
#include <vector>

namespace bhm::evo {

//! Correlation beyond which two parameters are reported as trading off.
inline constexpr double kTradeOffCorrelation = 0.95;
//! Smallest eigenvalue of the scaled curvature (a correlation-like matrix, eigenvalues summing to
//! the parameter count) below which it counts as near singular.
inline constexpr double kNearSingular = 1e-6;

struct Identifiability {
    std::vector<double> sigma_x;  //!< standard deviation of each x (NaN where not identifiable)
    std::vector<std::vector<double>> correlation;  //!< NaN where not defined
    double smallest_eigenvalue = 0.0;              //!< of the scaled J^T J
    bool near_singular = false;
    std::vector<int> no_effect;  //!< parameters whose Jacobian column is zero
    //! Groups that trade off: pairs with |corr| > kTradeOffCorrelation, and the parameters that
    //! carry the direction of the smallest eigenvalue when near singular.
    std::vector<std::vector<int>> trade_offs;
};

//! jacobian[k][i] = d residual_k / d x_i; residual_variance = SSR / (n - p) (or SSR / n).
Identifiability analyse_identifiability(const std::vector<std::vector<double>>& jacobian,
                                        double residual_variance);

//! The Gauss-Newton step from the point where `jacobian` and `residuals` were taken:
//! delta = -(J^T J)^-1 J^T r, where a linear model's misfit is least (the fit's check that it
//! stopped at its minimum, not in a narrow valley short of it). Empty when J^T J is near singular
//! or a column is zero (the step is not defined): its smallest scaled eigenvalue below
//! `near_singular` (the polish, gauss_newton_polish.hpp, steps along narrower valleys than the
//! uncertainty trusts).
std::vector<double> gauss_newton_step(const std::vector<std::vector<double>>& jacobian,
                                      const std::vector<double>& residuals,
                                      double near_singular = kNearSingular);

//! Eigenvalues (ascending) and eigenvectors (columns, same order) of a symmetric matrix
//! (cyclic Jacobi): small matrices only.
void symmetric_eigen(std::vector<std::vector<double>> a, std::vector<double>& values,
                     std::vector<std::vector<double>>& vectors);

}  // namespace bhm::evo
