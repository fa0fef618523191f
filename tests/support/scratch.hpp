#pragma once
// Scratch and output folders and file reading shared by every suite. ctest runs each test case in
// its own process and several build trees may test at once on one machine, so a folder is named
// after the test and the process id.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace bhm::test {

//! An empty folder (created unless create is false) under the temporary directory, unique to
//! `name` and this process; whatever an earlier run left there is removed first.
inline std::filesystem::path scratch_dir(const std::string& name, bool create = true) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("bhm-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    if (create) std::filesystem::create_directories(dir);
    return dir;
}

//! An empty folder under the build tree's test-output/ (left there after the test, for a person to
//! look at), named "<suite>-<name>"; whatever an earlier run left there is removed first.
inline std::filesystem::path output_dir(const std::string& suite, const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(BHM_BINARY_DIR) / "test-output" / (suite + "-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

//! The whole content of a file, byte for byte ("" when it cannot be opened).
inline std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace bhm::test
