// What a killed solve leaves behind (issue 41 R4): a kill -9 of `bhm verify` left ccx solving for
// a minute and its temporary folder forever. The solver now dies with the process that started it
// (PR_SET_PDEATHSIG) and the next process's first solve sweeps the folders of dead ones. The
// kill case runs a stand-in `ccx` (a shell script that sleeps) put first on the PATH, so it
// needs no CalculiX and never depends on how long a real solve takes.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "evo/verify/ccx_run.hpp"
#include "support/scratch.hpp"
#include "support/wait_limit.hpp"

using namespace bhm;
namespace fs = std::filesystem;

namespace {

// A pid that is surely gone: a child that has exited and been reaped.
long dead_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    REQUIRE(child > 0);
    ::waitpid(child, nullptr, 0);
    return static_cast<long>(child);
}

// A solve folder holding one file, as ccx leaves its .dat.
fs::path make_folder(const fs::path& path) {
    fs::create_directories(path);
    std::ofstream(path / "solve.dat") << "displacements";
    return path;
}

// The folder and its file last changed `hours` ago.
fs::path aged(const fs::path& path, int hours) {
    const auto then = fs::file_time_type::clock::now() - std::chrono::hours(hours);
    for (const auto& entry : fs::directory_iterator(path))
        fs::last_write_time(entry.path(), then);
    fs::last_write_time(path, then);
    return path;
}

// True while process `pid` exists and is not a zombie (a killed orphan may wait, dead, for a
// parent that does not reap it).
bool alive(long pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string id, comm, state;
    if (!(stat >> id >> comm >> state)) return false;
    return state != "Z" && state != "X";
}

}  // namespace

TEST_CASE("verify: the ccx folders of dead processes are swept, a live one's kept") {
    const fs::path temp = test::scratch_dir("ccx-sweep");
    const std::string me = std::to_string(::getpid());
    const auto dead = make_folder(temp / ("bhm-ccx-" + std::to_string(dead_pid()) + "-aB3dE9"));
    const auto mine = make_folder(temp / ("bhm-ccx-" + me + "-aB3dE9"));
    const auto live = make_folder(temp / "bhm-ccx-1-aB3dE9");                     // pid 1 lives
    const auto live_but_stale = aged(make_folder(temp / "bhm-ccx-1-Qq1Qq1"), 7);  // pid reused
    const auto old_unnamed = aged(make_folder(temp / "bhm-ccx-Xy12Zw"), 7);       // before pids
    const auto young_unnamed = make_folder(temp / "bhm-ccx-Xy12Zv");
    // A long solve of a live process: the folder is old, the file ccx keeps writing is not.
    const auto live_long = make_folder(temp / "bhm-ccx-1-Lo9nG1");
    fs::last_write_time(live_long, fs::file_time_type::clock::now() - std::chrono::hours(7));
    const auto other = make_folder(temp / ("bhm-test-" + std::to_string(dead_pid()) + "-aB3dE9"));
    std::ofstream(temp / ("bhm-ccx-" + std::to_string(dead_pid()) + "-file")) << "a file";
    fs::create_directory_symlink(dead, temp / ("bhm-ccx-" + std::to_string(dead_pid()) + "-link"));

    CHECK(evo::sweep_stale_ccx_folders(temp.string()) == 3);
    CHECK_FALSE(fs::exists(dead));  // its process is gone
    CHECK_FALSE(fs::exists(live_but_stale));
    CHECK_FALSE(fs::exists(old_unnamed));
    CHECK(fs::exists(mine / "solve.dat"));  // this process may be solving in it
    CHECK(fs::exists(live / "solve.dat"));
    CHECK(fs::exists(young_unnamed / "solve.dat"));
    CHECK(fs::exists(live_long / "solve.dat"));
    CHECK(fs::exists(other / "solve.dat"));  // not a solve folder
    CHECK(evo::sweep_stale_ccx_folders(temp.string()) == 0);
    CHECK(evo::sweep_stale_ccx_folders((temp / "nowhere").string()) == 0);
    CHECK(evo::sweep_stale_ccx_folders("") == 0);
    fs::remove_all(temp);
}

TEST_CASE("verify: ccx dies with the process that started it, and its folder is swept after") {
    const fs::path scratch = test::scratch_dir("ccx-orphan");
    const fs::path bin = scratch / "bin", temp = scratch / "tmp", pid_file = scratch / "ccx.pid";
    fs::create_directories(bin);
    fs::create_directories(temp);
    {
        std::ofstream script(bin / "ccx");
        script << "#!/bin/sh\necho $$ > '" << pid_file.string() << ".part'\nmv '"
               << pid_file.string() << ".part' '" << pid_file.string() << "'\nexec sleep 120\n";
    }
    fs::permissions(bin / "ccx", fs::perms::owner_all);

    // The process a user kills: it solves through our driver, the stand-in ccx its child.
    const pid_t solver = ::fork();
    REQUIRE(solver >= 0);
    if (solver == 0) {
        const std::string path =
            bin.string() + ":" + (std::getenv("PATH") ? std::getenv("PATH") : "");
        ::setenv("PATH", path.c_str(), 1);
        ::setenv("TMPDIR", temp.c_str(), 1);
        try {
            evo::run_ccx("orphan", "*NODE\n1, 0, 0, 0\n");
        } catch (...) {
        }
        ::_exit(0);
    }
    // Generous waits (a loaded machine), each on its condition (tests/support/wait_limit.hpp).
    const auto a_moment = [] { std::this_thread::sleep_for(std::chrono::milliseconds(20)); };
    long ccx = -1;
    bhm::test::wait_until([&] { return static_cast<bool>(std::ifstream(pid_file) >> ccx); },
                          a_moment);
    ::kill(solver, SIGKILL);  // kill -9, as a user would
    ::waitpid(solver, nullptr, 0);
    REQUIRE_MESSAGE(ccx > 0, "the stand-in ccx never started");

    const bool gone = bhm::test::wait_until([&] { return !alive(ccx); }, a_moment);
    if (!gone) ::kill(static_cast<pid_t>(ccx), SIGKILL);  // the test leaves no orphan either
    CHECK_MESSAGE(gone, "ccx (pid " << ccx << ") outlived the process that started it");

    // Its folder stayed (nobody removed it), named after the dead process: the next sweep takes it.
    int folders = 0;
    for (const auto& entry : fs::directory_iterator(temp))
        folders += entry.path().filename().string().rfind("bhm-ccx-" + std::to_string(solver) + "-",
                                                          0) == 0;
    CHECK(folders == 1);
    CHECK(evo::sweep_stale_ccx_folders(temp.string()) == 1);
    CHECK(fs::is_empty(temp));
    fs::remove_all(scratch);
}

TEST_CASE("verify: a ccx that crashes without an *ERROR line is reported by how it ended") {
    // Measured on a champion's Neo-Hookean solve: ccx ended without an *ERROR line and the report
    // read "ccx failed to solve body: Using up to 1 cpu(s) for spooles.", its last line.
    const fs::path scratch = test::scratch_dir("ccx-crash");
    const fs::path bin = scratch / "bin";
    fs::create_directories(bin);
    {
        std::ofstream script(bin / "ccx");
        script << "#!/bin/sh\necho 'Using up to 1 cpu(s) for spooles.'\nkill -SEGV $$\n";
    }
    fs::permissions(bin / "ccx", fs::perms::owner_all);
    const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
    ::setenv("PATH", (bin.string() + ":" + old_path).c_str(), 1);
    std::string what;
    try {
        evo::run_ccx("crash", "*NODE\n1, 0, 0, 0\n");
    } catch (const std::runtime_error& e) {
        what = e.what();
    }
    ::setenv("PATH", old_path.c_str(), 1);
    MESSAGE(what);
    CHECK(what.rfind("ccx failed to solve crash: killed by signal 11 after \"Using up to", 0) == 0);
    CHECK(what.find('\n') == std::string::npos);
}
