#pragma once
// The CalculiX cases' one guard: true (and a warning in every report) where ccx is not installed.
#include <doctest/doctest.h>

#include "evo/verify/ccx_run.hpp"

namespace bhm::test {

inline bool skip_without_ccx() {
    if (evo::ccx_available()) return false;
    MESSAGE("SKIPPED: CalculiX (ccx) is not installed; scripts/setup.sh installs calculix-ccx");
    WARN(false);  // shows in every report that the comparison did not run
    return true;
}

}  // namespace bhm::test
