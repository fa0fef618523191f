// Placeholder until its issue lands.
#include <iostream>

#include "app/arg_parser.hpp"
#include "app/commands.hpp"

namespace bhm::app {

int cmd_evolve(const Args& args) {
    ArgParser parser("evolve", "[OPTIONS]", "Not built yet.");
    return run_command(parser, args, [](ArgParser&) {
        std::cerr << "bhm evolve: not built yet\n";
        return 1;
    });
}

}  // namespace bhm::app
