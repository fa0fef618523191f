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

//! The material library's warnings for an experiment just loaded (a file skipped or damaged that
//! the experiment does not name), one "bhm: warning: " line each on stderr.
inline void say_library_warnings(const evo::Experiment& experiment) {
    for (const auto& line : evo::library_warnings_for(experiment))
        std::cerr << "bhm: warning: " << line << "\n";
}

//! print_problems, then the exit status of a refused input: 1.
inline int report_problems(const std::vector<evo::Problem>& problems) {
    print_problems(problems);
    return 1;
}

}  // namespace bhm::app
