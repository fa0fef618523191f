#pragma once
// Richardson extrapolation of a quantity solved on three meshes, shared by the CalculiX reference
// tests (the converged references issue 40 asks for).
#include <cmath>
#include <optional>

namespace bhm::test {

struct Extrapolation {
    double limit = 0.0, order = 0.0;
};

//! The limit of f(h) = f0 + C h^p through three meshes (h in order of refinement), the order p
//! solved by bisection in [0.1, 8]; nullopt where the three are not monotone or no order fits.
inline std::optional<Extrapolation> richardson(const double h[3], const double f[3]) {
    if ((f[0] - f[1]) * (f[1] - f[2]) <= 0.0) return std::nullopt;
    const double ratio = (f[0] - f[1]) / (f[1] - f[2]);
    auto gap = [&](double p) {
        return (std::pow(h[0], p) - std::pow(h[1], p)) / (std::pow(h[1], p) - std::pow(h[2], p)) -
               ratio;
    };
    double lo = 0.1, hi = 8.0;
    if (gap(lo) * gap(hi) > 0.0) return std::nullopt;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (gap(lo) * gap(mid) <= 0.0 ? hi : lo) = mid;
    }
    const double p = 0.5 * (lo + hi);
    const double c = (f[1] - f[2]) / (std::pow(h[1], p) - std::pow(h[2], p));
    return Extrapolation{f[2] - c * std::pow(h[2], p), p};
}

}  // namespace bhm::test
