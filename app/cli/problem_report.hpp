#pragma once
// How a subcommand reports a ValidationError: every problem on its own line
// ("file:field: message") on stderr, exit status 1.
#include <iostream>
#include <vector>

#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

//! Every problem (or warning) on its own line on stderr.
inline void print_problems(const std::vector<evo::Problem>& problems) {
    for (const auto& p : problems)
        std::cerr << p.to_string() << "\n";
}

//! print_problems, then the exit status of a refused input: 1.
inline int report_problems(const std::vector<evo::Problem>& problems) {
    print_problems(problems);
    return 1;
}

}  // namespace bhm::app
