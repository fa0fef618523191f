// The checked atomic writer every output goes through: a complete new file or the old one, and
// errors that name the file and the system's own reason.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/io/atomic_file.hpp"
#include "support/scratch.hpp"

using namespace bhm::engine;
namespace fs = std::filesystem;

namespace {

}  // namespace

TEST_CASE("an atomic write replaces the file and leaves no temporary behind") {
    const fs::path dir = bhm::test::scratch_dir("atomic-replace");
    const fs::path file = dir / "a.txt";
    write_file_atomically(file.string(), "old");
    write_file_atomically(file.string(), std::string(100000, 'x'));
    CHECK(bhm::test::read_file(file) == std::string(100000, 'x'));
    CHECK_FALSE(fs::exists(dir / "a.txt.tmp"));
    fs::remove_all(dir);
}

TEST_CASE("an abandoned streamed write leaves the old file as it was") {
    const fs::path dir = bhm::test::scratch_dir("atomic-abandon");
    const fs::path file = dir / "a.txt";
    write_file_atomically(file.string(), "old");
    {
        AtomicFile f(file.string());
        f.write("half of the new");
        CHECK(fs::exists(f.temp_path()));
    }  // no commit: as when an exception leaves the writer half way
    CHECK(bhm::test::read_file(file) == "old");
    CHECK_FALSE(fs::exists(dir / "a.txt.tmp"));
    fs::remove_all(dir);
}

TEST_CASE("a failing rename says why with the system's reason, not the clean-up's") {
    // The target is a non-empty folder: rename(2) fails (EISDIR or ENOTEMPTY). The old message
    // read "cannot replace the file (Success)" because removing the temporary reset errno.
    const fs::path dir = bhm::test::scratch_dir("atomic-rename");
    const fs::path target = dir / "taken";
    fs::create_directories(target / "inside");
    try {
        write_file_atomically(target.string(), "new");
        FAIL("the write should have failed");
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        CHECK(message.find(target.string()) == 0);
        CHECK(message.find("cannot replace the file") != std::string::npos);
        CHECK(message.find("Success") == std::string::npos);
        CHECK((message.find("Is a directory") != std::string::npos ||
               message.find("not empty") != std::string::npos));
    }
    CHECK(fs::is_directory(target / "inside"));
    CHECK_FALSE(fs::exists(dir / "taken.tmp"));
    fs::remove_all(dir);
}

TEST_CASE("a write into a missing folder names the file and the reason") {
    const fs::path dir = bhm::test::scratch_dir("atomic-missing");
    const std::string path = (dir / "no" / "such" / "a.txt").string();
    const std::string expected = path + ": cannot write (No such file or directory)";
    CHECK_THROWS_WITH_AS(write_file_atomically(path, "x"), doctest::Contains(expected.c_str()),
                         std::runtime_error);
    CHECK_THROWS_AS(write_file_atomically("", "x"), std::runtime_error);
    fs::remove_all(dir);
}

TEST_CASE("a hook that fails before the rename leaves the target untouched") {
    const fs::path dir = bhm::test::scratch_dir("atomic-hook");
    const fs::path file = dir / "a.txt";
    write_file_atomically(file.string(), "old");
    AtomicFile f(file.string());
    f.write("new");
    CHECK_THROWS_AS(f.commit([] { throw std::runtime_error("no"); }), std::runtime_error);
    CHECK(bhm::test::read_file(file) == "old");
    CHECK_FALSE(fs::exists(dir / "a.txt.tmp"));
    fs::remove_all(dir);
}
