#pragma once
// How a subcommand reports a ValidationError: every problem on its own line
// ("file:field: message") on stderr, exit status 1.
#include <iostream>
#include <vector>

#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

inline int report_problems(const std::vector<evo::Problem>& problems) {
    for (const auto& p : problems)
        std::cerr << p.to_string() << "\n";
    return 1;
}

}  // namespace bhm::app
