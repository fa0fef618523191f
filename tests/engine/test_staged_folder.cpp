// The staged output folder of every --out (issue 41 R5): the old complete folder or the new
// complete one, never a mix, whatever fails part way; a folder of someone else's files refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/staged_folder.hpp"
#include "support/scratch.hpp"

using namespace bhm::engine;
namespace fs = std::filesystem;

namespace {

bool owned(const std::string& name) { return name == "report.json" || name == "a.csv"; }

std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

TEST_CASE("a staged folder appears whole, and replaces an old one whole") {
    const fs::path dir = bhm::test::scratch_dir("staged-replace");
    const fs::path out = dir / "out";
    {
        StagedFolder staged(out.string(), owned);
        CHECK_FALSE(fs::exists(out));  // nothing at the final name while it is written
        write_file_atomically(staged.file("report.json"), "first");
        write_file_atomically(staged.file("a.csv"), "1");
        staged.commit();
    }
    CHECK(entries(dir) == std::vector<std::string>{"out"});
    CHECK(bhm::test::read_file(out / "report.json") == "first");
    {
        StagedFolder staged((out.string() + "/"), owned);  // the same folder
        write_file_atomically(staged.file("report.json"), "second");
        CHECK(bhm::test::read_file(out / "report.json") == "first");
        staged.commit();
    }
    // The new folder only: a.csv of the old one is gone with it; no staging or old folder left.
    CHECK(entries(dir) == std::vector<std::string>{"out"});
    CHECK(entries(out) == std::vector<std::string>{"report.json"});
    CHECK(bhm::test::read_file(out / "report.json") == "second");
    fs::remove_all(dir);
}

TEST_CASE("a staged folder that fails part way leaves the old folder exactly as it was") {
    const fs::path dir = bhm::test::scratch_dir("staged-failure");
    const fs::path out = dir / "out";
    fs::create_directories(out);
    write_file_atomically((out / "report.json").string(), "old report");
    std::string error;
    try {
        StagedFolder staged(out.string(), owned);
        write_file_atomically(staged.file("a.csv"), "new");
        // A failing write midway (as a full disk or a kill would stop it): a folder where the
        // report's temporary goes.
        fs::create_directories(staged.file("report.json.tmp"));
        try {
            write_file_atomically(staged.file("report.json"), "new report");
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(staged.as_final(e.what()));
        }
        staged.commit();
    } catch (const std::runtime_error& e) {
        error = e.what();
    }
    CHECK(error.rfind((out / "report.json").string() + ": cannot write", 0) == 0);
    CHECK(entries(dir) == std::vector<std::string>{"out"});
    CHECK(entries(out) == std::vector<std::string>{"report.json"});
    CHECK(bhm::test::read_file(out / "report.json") == "old report");
    fs::remove_all(dir);
}

TEST_CASE("a folder holding files the command does not write is refused before any work") {
    const fs::path dir = bhm::test::scratch_dir("staged-foreign");
    write_file_atomically((dir / "report.json").string(), "old");
    write_file_atomically((dir / "notes.txt").string(), "mine");
    CHECK_THROWS_WITH_AS(StagedFolder(dir.string(), owned),
                         (dir.string() + ": holds notes.txt, which this command does not write; "
                                         "the folder is replaced whole, so give a new or an "
                                         "empty folder")
                             .c_str(),
                         std::runtime_error);
    CHECK_THROWS_WITH_AS(StagedFolder((dir / "notes.txt").string(), owned),
                         ((dir / "notes.txt").string() + ": is a file, not a folder").c_str(),
                         std::runtime_error);
    CHECK(entries(dir) == std::vector<std::string>{"notes.txt", "report.json"});
    fs::remove_all(dir);
}

TEST_CASE("a killed writer's staging folder is swept; an old folder moved aside comes back") {
    const fs::path dir = bhm::test::scratch_dir("staged-sweep");
    // 999999999 is above any pid_max: a process that is gone.
    fs::create_directories(dir / ".out.staging-999999999-AbC123" / "rank-01");
    fs::create_directories(dir / ".out.old-999999999-XyZ789");
    write_file_atomically((dir / ".out.old-999999999-XyZ789" / "report.json").string(), "old");
    fs::create_directories(dir / ".other.staging-999999999-AbC123");  // another folder's
    const std::string own_staging = ".out.staging-" + std::to_string(::getpid()) + "-QwE456";
    fs::create_directories(dir / own_staging);  // a live writer's: kept
    CHECK(sweep_stale_staging(dir.string(), "out") == 1);
    CHECK(entries(dir) == std::vector<std::string>{".other.staging-999999999-AbC123", own_staging,
                                                   "out"});
    CHECK(bhm::test::read_file(dir / "out" / "report.json") == "old");
    fs::remove_all(dir);
}

TEST_CASE("a killed writer's staged copy of a file is swept by the next writer of that file") {
    const fs::path dir = bhm::test::scratch_dir("staged-files-sweep");
    fs::create_directories(dir);
    const std::string own = "out.vxa.staged-" + std::to_string(::getpid());
    // 999999999 is above any pid_max: a process that is gone.
    write_file_atomically((dir / "out.vxa.staged-999999999").string(), "killed");
    write_file_atomically((dir / "out.vxa.staged-1").string(), "a live writer's (init's)");
    write_file_atomically((dir / "other.vxa.staged-999999999").string(), "another file's");
    {
        StagedFiles files;
        const std::string staged = files.stage((dir / "out.vxa").string());
        CHECK(fs::path(staged).filename() == own);
        write_file_atomically(staged, "new");
        files.commit();
    }
    CHECK(entries(dir) ==
          std::vector<std::string>{"other.vxa.staged-999999999", "out.vxa", "out.vxa.staged-1"});
    CHECK(bhm::test::read_file(dir / "out.vxa") == "new");
    CHECK(sweep_stale_staged_files((dir / "other.vxa").string()) == 1);
    fs::remove_all(dir);
}
