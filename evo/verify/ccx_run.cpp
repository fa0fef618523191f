#include "evo/verify/ccx_run.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <sys/resource.h>
#include <unistd.h>

#include "engine/io/atomic_file.hpp"

namespace bhm::evo {

namespace fs = std::filesystem;

bool ccx_available() {
    return std::system("command -v ccx > /dev/null 2>&1") == 0;
}

std::vector<NodalDisplacements> parse_ccx_dat(const std::string& text) {
    std::vector<NodalDisplacements> blocks;
    std::istringstream in(text);
    std::string line;
    bool inside = false;
    while (std::getline(in, line)) {
        if (line.find("displacements") != std::string::npos) {
            blocks.emplace_back();
            inside = true;
            continue;
        }
        if (!inside) continue;
        std::istringstream row(line);
        int id = 0;
        std::array<double, 3> u{};
        if (row >> id >> u[0] >> u[1] >> u[2])
            blocks.back()[id] = u;
        else if (!blocks.back().empty() && line.find_first_not_of(" \t\r") != std::string::npos)
            inside = false;  // another kind of output follows
    }
    return blocks;
}

namespace {

double children_cpu_s() {
    rusage usage{};
    ::getrusage(RUSAGE_CHILDREN, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The solver's first *ERROR line, else its last line: one line for the message.
std::string first_error(const fs::path& log) {
    std::ifstream in(log);
    std::string line, last = "ccx printed nothing";
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        const auto start = line.find_first_not_of(' ');
        if (start == std::string::npos) continue;
        if (line.find("*ERROR") != std::string::npos) return line.substr(start);
        last = line.substr(start);
    }
    return last;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

CcxResult run_ccx(const std::string& name, const std::string& deck, int threads,
                  const std::string& keep_dir) {
    if (!ccx_available())
        throw std::runtime_error("ccx (CalculiX) is not on the PATH; install the Debian package "
                                 "calculix-ccx");
    fs::path dir;
    if (keep_dir.empty()) {
        std::string pattern = (fs::temp_directory_path() / "bhm-ccx-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw std::runtime_error("cannot create a temporary folder for ccx in " +
                                     fs::temp_directory_path().string());
        dir = pattern;
    } else {
        dir = keep_dir;
        fs::create_directories(dir);
    }
    struct Cleanup {
        fs::path dir;
        bool remove;
        ~Cleanup() {
            std::error_code ignored;
            if (remove) fs::remove_all(dir, ignored);
        }
    } cleanup{dir, keep_dir.empty()};
    engine::write_file_atomically((dir / (name + ".inp")).string(), deck);
    const std::string cmd = "cd '" + dir.string() + "' && OMP_NUM_THREADS=" +
                            std::to_string(threads) + " CCX_NPROC_EQUATION_SOLVER=" +
                            std::to_string(threads) + " ccx -i " + name + " > ccx.log 2>&1";
    const auto start = std::chrono::steady_clock::now();
    const double cpu_before = children_cpu_s();
    const int rc = std::system(cmd.c_str());
    CcxResult result;
    result.cpu_s = children_cpu_s() - cpu_before;
    result.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string where = keep_dir.empty() ? "" : " (see " + (dir / "ccx.log").string() + ")";
    if (rc != 0)
        throw std::runtime_error("ccx failed to solve " + name + ": " + first_error(dir / "ccx.log") +
                                 where);
    const std::string log = read_text(dir / "ccx.log");
    if (log.find("*ERROR") != std::string::npos)
        throw std::runtime_error("ccx failed to solve " + name + ": " +
                                 first_error(dir / "ccx.log") + where);
    result.blocks = parse_ccx_dat(read_text(dir / (name + ".dat")));
    if (result.blocks.empty())
        throw std::runtime_error("ccx wrote no displacements for " + name + where);
    return result;
}

}  // namespace bhm::evo
