#pragma once
// doctest::Approx adds a scale of 1.0 to its tolerance: |a - b| < eps * (1 + max(|a|, |b|)). In SI
// units most engine quantities are far below 1 (a 1 mm sag is 1e-3 m), so a plain Approx(x).epsilon
// (0.05) accepts anything within 0.05 m and cannot fail. relative() is a purely relative check:
// |a - b| < eps * max(|a|, |b|). Expected values must be non-zero.
#include <doctest/doctest.h>

#include <limits>

namespace bhm::test {

// The default tolerance is doctest's own (100 float epsilons), made relative.
inline doctest::Approx relative(double expected,
                                double epsilon = std::numeric_limits<float>::epsilon() * 100) {
    return doctest::Approx(expected).epsilon(epsilon).scale(0.0);
}

}  // namespace bhm::test
