#include "evo/calibrate/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace bhm::evo {

void symmetric_eigen(std::vector<std::vector<double>> a, std::vector<double>& values,
                     std::vector<std::vector<double>>& vectors) {
    const std::size_t n = a.size();
    std::vector<std::vector<double>> v(n, std::vector<double>(n, 0.0));
    for (std::size_t i = 0; i < n; ++i) v[i][i] = 1.0;
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0;
        for (std::size_t p = 0; p < n; ++p)
            for (std::size_t q = p + 1; q < n; ++q) off += a[p][q] * a[p][q];
        if (off < 1e-30) break;
        for (std::size_t p = 0; p < n; ++p)
            for (std::size_t q = p + 1; q < n; ++q) {
                if (a[p][q] == 0.0) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) /
                                 (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (std::size_t k = 0; k < n; ++k) {
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (std::size_t k = 0; k < n; ++k) {
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (std::size_t k = 0; k < n; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto i, auto j) { return a[i][i] < a[j][j]; });
    values.assign(n, 0.0);
    vectors.assign(n, std::vector<double>(n, 0.0));
    for (std::size_t c = 0; c < n; ++c) {
        values[c] = a[order[c]][order[c]];
        for (std::size_t k = 0; k < n; ++k) vectors[k][c] = v[k][order[c]];
    }
}

Identifiability analyse_identifiability(const std::vector<std::vector<double>>& jacobian,
                                        double residual_variance) {
    const std::size_t p = jacobian.empty() ? 0 : jacobian[0].size();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Identifiability out;
    out.sigma_x.assign(p, nan);
    out.correlation.assign(p, std::vector<double>(p, nan));
    // Curvature H = J^T J, scaled to unit diagonal: S = D^-1 H D^-1.
    std::vector<std::vector<double>> h(p, std::vector<double>(p, 0.0));
    for (const auto& row : jacobian)
        for (std::size_t i = 0; i < p; ++i)
            for (std::size_t j = 0; j < p; ++j) h[i][j] += row[i] * row[j];
    std::vector<int> live;
    for (std::size_t i = 0; i < p; ++i) {
        if (h[i][i] > 0.0) live.push_back(static_cast<int>(i));
        else out.no_effect.push_back(static_cast<int>(i));
    }
    const std::size_t m = live.size();
    std::vector<std::vector<double>> s(m, std::vector<double>(m, 0.0));
    for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b) {
            const auto i = static_cast<std::size_t>(live[a]), j = static_cast<std::size_t>(live[b]);
            s[a][b] = h[i][j] / std::sqrt(h[i][i] * h[j][j]);
        }
    std::vector<double> values;
    std::vector<std::vector<double>> vectors;
    symmetric_eigen(s, values, vectors);
    out.smallest_eigenvalue = m ? values[0] : 0.0;
    out.near_singular = !out.no_effect.empty() || (m && values[0] < kNearSingular);
    if (m && values[0] < kNearSingular) {
        std::vector<int> group;
        for (std::size_t a = 0; a < m; ++a)
            if (std::abs(vectors[a][0]) > 0.3) group.push_back(live[a]);
        if (group.size() > 1) out.trade_offs.push_back(group);
        return out;  // no covariance of a singular curvature
    }
    // S^-1 from the eigenvectors; the correlation is S^-1's (independent of sigma^2, so defined
    // for a noise-free fit too), the covariance sigma^2 D^-1 S^-1 D^-1.
    std::vector<std::vector<double>> inv(m, std::vector<double>(m, 0.0));
    for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b)
            for (std::size_t c = 0; c < m; ++c) inv[a][b] += vectors[a][c] * vectors[b][c] / values[c];
    for (std::size_t a = 0; a < m; ++a) {
        const auto i = static_cast<std::size_t>(live[a]);
        out.sigma_x[i] = std::sqrt(std::max(0.0, residual_variance * inv[a][a] / h[i][i]));
        for (std::size_t b = 0; b < m; ++b) {
            const auto j = static_cast<std::size_t>(live[b]);
            out.correlation[i][j] = inv[a][b] / std::sqrt(inv[a][a] * inv[b][b]);
            if (b > a && std::abs(out.correlation[i][j]) > kTradeOffCorrelation)
                out.trade_offs.push_back({live[a], live[b]});
        }
    }
    return out;
}

std::vector<double> gauss_newton_step(const std::vector<std::vector<double>>& jacobian,
                                      const std::vector<double>& residuals, double near_singular) {
    const std::size_t p = jacobian.empty() ? 0 : jacobian[0].size();
    if (p == 0 || residuals.size() != jacobian.size()) return {};
    std::vector<std::vector<double>> h(p, std::vector<double>(p, 0.0));
    std::vector<double> g(p, 0.0);  // J^T r
    for (std::size_t k = 0; k < jacobian.size(); ++k)
        for (std::size_t i = 0; i < p; ++i) {
            g[i] += jacobian[k][i] * residuals[k];
            for (std::size_t j = 0; j < p; ++j)
                h[i][j] += jacobian[k][i] * jacobian[k][j];
        }
    for (std::size_t i = 0; i < p; ++i)
        if (!(h[i][i] > 0.0)) return {};
    // Solved in the unit-diagonal scaling, as analyse_identifiability judges singularity.
    std::vector<std::vector<double>> s(p, std::vector<double>(p, 0.0));
    for (std::size_t i = 0; i < p; ++i)
        for (std::size_t j = 0; j < p; ++j)
            s[i][j] = h[i][j] / std::sqrt(h[i][i] * h[j][j]);
    std::vector<double> values;
    std::vector<std::vector<double>> vectors;
    symmetric_eigen(s, values, vectors);
    if (!(values[0] >= near_singular)) return {};
    // delta = -D^-1 S^-1 D^-1 g, D = sqrt(diag H).
    std::vector<double> scaled_g(p), delta(p, 0.0);
    for (std::size_t i = 0; i < p; ++i)
        scaled_g[i] = g[i] / std::sqrt(h[i][i]);
    for (std::size_t c = 0; c < p; ++c) {
        double along = 0.0;
        for (std::size_t i = 0; i < p; ++i)
            along += vectors[i][c] * scaled_g[i];
        for (std::size_t i = 0; i < p; ++i)
            delta[i] -= vectors[i][c] * along / values[c];
    }
    for (std::size_t i = 0; i < p; ++i)
        delta[i] /= std::sqrt(h[i][i]);
    return delta;
}

}  // namespace bhm::evo
