#pragma once
// Runs a shell command as a user would and returns its exit status and its output (stdout and
// stderr together), for the tests that drive the bhm executable.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace bhm::test {

struct ShellResult {
    int status;          //!< exit code, or 128 + signal
    std::string output;  //!< stdout and stderr
};

inline ShellResult run_shell(const std::string& command) {
    std::FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string out;
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        out.append(buffer, n);
    const int raw = pclose(pipe);
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw), out};
}

}  // namespace bhm::test
