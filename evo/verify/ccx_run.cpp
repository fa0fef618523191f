#include "evo/verify/ccx_run.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"

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

int ccx_steps_done(const std::string& sta_text) {
    std::istringstream in(sta_text);
    std::string line;
    int done = 0;
    while (std::getline(in, line)) {
        std::istringstream row(line);
        int step = 0, increment = 0, attempt = 0, iterations = 0;
        double total_time = 0.0, step_time = 0.0;
        if (row >> step >> increment >> attempt >> iterations >> total_time >> step_time &&
            step_time >= 1.0 - 1e-6)
            done = std::max(done, step);
    }
    return done;
}

namespace {

double children_cpu_s() {
    rusage usage{};
    ::getrusage(RUSAGE_CHILDREN, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// What ccx has written so far: "" while the file does not exist yet (the .sta early in a run).
std::string read_text(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return "";
    return engine::read_text(path.string(), engine::kLargeFileCap);
}

// The solver's first *ERROR line, else its last line: one line for the message.
std::string first_error(const fs::path& log) {
    std::istringstream in(read_text(log));
    std::string line, last = "ccx printed nothing";
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
            line.pop_back();
        const auto start = line.find_first_not_of(' ');
        if (start == std::string::npos) continue;
        if (line.find("*ERROR") != std::string::npos) return line.substr(start);
        last = line.substr(start);
    }
    return last;
}

constexpr const char* kFolderPrefix = "bhm-ccx-";

// The owner's pid in a solve folder's name ("bhm-ccx-1234-AbC123"); -1 for the older name
// without one ("bhm-ccx-AbC123": mkdtemp's letters never hold a '-').
long folder_owner(const std::string& name) {
    const std::string rest = name.substr(std::string(kFolderPrefix).size());
    const auto dash = rest.find('-');
    if (dash == std::string::npos || dash == 0 || dash > 9) return -1;
    const std::string pid = rest.substr(0, dash);
    if (pid.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stol(pid);
}

bool process_gone(long pid) {
    return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// Seconds since anything in the folder last changed: the folder itself or any file directly in
// it (a long solve keeps rewriting its .sta and .dat without touching the folder).
double untouched_s(const fs::path& dir) {
    std::error_code ec;
    auto newest = fs::last_write_time(dir, ec);
    if (ec) return 0.0;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code time_ec;
        const auto t = fs::last_write_time(it->path(), time_ec);
        if (!time_ec && t > newest) newest = t;
    }
    return std::chrono::duration<double>(fs::file_time_type::clock::now() - newest).count();
}

}  // namespace

int sweep_stale_ccx_folders(const std::string& parent) {
    if (parent.empty()) return 0;
    std::error_code ec;
    fs::directory_iterator it(parent, ec);
    if (ec) return 0;
    const long me = static_cast<long>(::getpid());
    int removed = 0;
    for (const fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
        const fs::path path = it->path();
        const std::string name = path.filename().string();
        if (name.rfind(kFolderPrefix, 0) != 0 || name.size() == std::string(kFolderPrefix).size())
            continue;
        // lstat: a real folder of ours, not a link, not another user's (/tmp is shared).
        struct stat info {};
        if (::lstat(path.c_str(), &info) != 0 || !S_ISDIR(info.st_mode) ||
            info.st_uid != ::geteuid())
            continue;
        const long owner = folder_owner(name);
        if (owner == me) continue;
        const bool orphan = owner > 0 && process_gone(owner);
        if (!orphan && untouched_s(path) <= kStaleCcxFolderAge_s) continue;
        std::error_code remove_ec;
        fs::remove_all(path, remove_ec);
        if (!remove_ec) ++removed;
    }
    return removed;
}

CcxResult run_ccx(const std::string& name, const std::string& deck, int threads,
                  const std::string& keep_dir, const CcxWatch& watch) {
    if (!ccx_available())
        throw std::runtime_error(
            "ccx (CalculiX) is not on the PATH; install the Debian package "
            "calculix-ccx");
    fs::path dir;
    if (keep_dir.empty()) {
        // Once per process, before its first folder: what solves of killed processes left.
        static std::once_flag swept;
        std::call_once(swept, [] {
            std::error_code ec;
            const fs::path temp = fs::temp_directory_path(ec);
            if (!ec) sweep_stale_ccx_folders(temp.string());
        });
        // The pid in the name: a later process removes it once this one is gone.
        std::string pattern =
            (fs::temp_directory_path() / (kFolderPrefix + std::to_string(::getpid()) + "-XXXXXX"))
                .string();
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
    // The child's arguments and environment, built before fork (after it only async-signal-safe
    // calls are allowed in a threaded program).
    std::vector<std::string> env_text;
    for (char** e = environ; e && *e; ++e) {
        const std::string entry = *e;
        if (entry.rfind("OMP_NUM_THREADS=", 0) != 0 &&
            entry.rfind("CCX_NPROC_EQUATION_SOLVER=", 0) != 0)
            env_text.push_back(entry);
    }
    env_text.push_back("OMP_NUM_THREADS=" + std::to_string(threads));
    env_text.push_back("CCX_NPROC_EQUATION_SOLVER=" + std::to_string(threads));
    std::vector<char*> envp;
    for (auto& e : env_text)
        envp.push_back(e.data());
    envp.push_back(nullptr);
    std::string arg0 = "ccx", arg1 = "-i", arg2 = name;
    char* argv[] = {arg0.data(), arg1.data(), arg2.data(), nullptr};
    const std::string dir_text = dir.string();
    const auto start = std::chrono::steady_clock::now();
    const double cpu_before = children_cpu_s();
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("cannot start ccx: fork failed");
    if (pid == 0) {
        // Dies with us: a kill -9 of bhm left ccx solving for a minute (issue 41 R4). The signal
        // comes when the thread that forked ends, and that thread waits below until ccx has;
        // it survives the exec. Had the parent already died before prctl, we have been handed
        // to another parent and would never get it: leave at once.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(125);
        ::setpgid(0, 0);  // its own group: a cancel kills whatever it started too
        if (::chdir(dir_text.c_str()) != 0) ::_exit(126);
        const int log_fd = ::open("ccx.log", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int null_fd = ::open("/dev/null", O_RDONLY);
        if (log_fd < 0 || null_fd < 0) ::_exit(126);
        ::dup2(null_fd, 0);
        ::dup2(log_fd, 1);
        ::dup2(log_fd, 2);
        ::execvpe("ccx", argv, envp.data());
        ::_exit(127);
    }
    ::setpgid(pid, pid);  // also from here: no race with a kill before the child ran setpgid
    int status = 0, reported = 0;
    const fs::path sta = dir / (name + ".sta");
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR) throw std::runtime_error("lost the ccx child process");
        if (watch.cancel && watch.cancel->load(std::memory_order_relaxed)) {
            ::kill(-pid, SIGKILL);
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            throw VerifyCancelled();
        }
        if (watch.steps_done) {
            std::error_code ec;
            if (fs::exists(sta, ec)) {
                const int steps = ccx_steps_done(read_text(sta));
                if (steps > reported) watch.steps_done(reported = steps);
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    const int rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (rc == 127 || rc == 126)
        throw std::runtime_error("ccx (CalculiX) could not be started in " + dir_text);
    CcxResult result;
    result.cpu_s = children_cpu_s() - cpu_before;
    result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string where = keep_dir.empty() ? "" : " (see " + (dir / "ccx.log").string() + ")";
    if (rc != 0) {
        // Without an *ERROR line ccx did not stop on its own (a crash, or killed): say how it
        // ended, since its last line ("Using up to 1 cpu(s) for spooles.") says nothing.
        std::string why = first_error(dir / "ccx.log");
        if (why.find("*ERROR") == std::string::npos)
            why =
                (WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status)) +
                                           (WTERMSIG(status) == SIGKILL ? " (out of memory?)" : "")
                                     : "exited with status " + std::to_string(rc)) +
                " after \"" + why + "\"";
        throw std::runtime_error("ccx failed to solve " + name + ": " + why + where);
    }
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
