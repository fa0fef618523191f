#pragma once
// What every benchmark writes beside its figures: the machine (one CSV field) and wall time;
// and the guarded entry point its main() shares.
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

namespace bhm::bench {

inline double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

//! "x86_64 <CPU model>" from uname -m and /proc/cpuinfo, commas removed so it stays one CSV field.
inline std::string machine_description() {
    utsname names{};
    std::string text = uname(&names) == 0 ? names.machine : "unknown-arch";
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
            text.push_back(' ');
            text.append(line, std::min(line.size(), line.find(':') + 2));
            break;
        }
    std::replace(text.begin(), text.end(), ',', ' ');
    return text;
}

//! run(argc, argv)'s exit status, or 1 with "NAME: what went wrong" on stderr when it throws.
inline int run_guarded(const char* name, int (*run)(int, char**), int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return 1;
    }
}

}  // namespace bhm::bench
