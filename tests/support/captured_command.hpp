#pragma once
// Runs a `bhm` subcommand in-process with std::cout and std::cerr captured, for the CLI suites:
// their exit code and both streams, the streams restored even when the command throws.
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace bhm::test {

struct CapturedRun {
    int exit_code;
    std::string out, err;
};

template <class Command>
CapturedRun run_captured(Command command, const std::vector<std::string>& args) {
    std::ostringstream out, err;
    auto* old_out = std::cout.rdbuf(out.rdbuf());
    auto* old_err = std::cerr.rdbuf(err.rdbuf());
    int code = -1;
    try {
        code = command(args);
    } catch (...) {
        std::cout.rdbuf(old_out);
        std::cerr.rdbuf(old_err);
        throw;
    }
    std::cout.rdbuf(old_out);
    std::cerr.rdbuf(old_err);
    return {code, out.str(), err.str()};
}

}  // namespace bhm::test
