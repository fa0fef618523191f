#pragma once
// What every benchmark writes beside its figures: the machine (one CSV field) and wall time.
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
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

}  // namespace bhm::bench
