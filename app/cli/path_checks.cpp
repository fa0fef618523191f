#include "app/cli/path_checks.hpp"

#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>

#include "app/cli/arg_parser.hpp"
#include "engine/io/atomic_file.hpp"

namespace bhm::app {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& path,
                         const std::string& why) {
    throw std::runtime_error(option + " " + path + ": " + why);
}

void require_non_empty(const std::string& option, const std::string& path) {
    if (path.empty())
        throw UsageError(option + " is empty (an unset shell variable?); give a path");
}

void require_writable_dir(const std::string& option, const std::string& path, const fs::path& dir) {
    if (::access(dir.c_str(), W_OK | X_OK) != 0) {
        const int error = errno;
        refuse(
            option, path,
            "the folder " + dir.string() + " is not writable (" + engine::error_text(error) + ")");
    }
}

fs::path folder_of(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

}  // namespace

void check_output_file(const std::string& option, const std::string& path) {
    require_non_empty(option, path);
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (fs::is_directory(status)) refuse(option, path, "is a folder, not a file");
    if (fs::exists(status) && !fs::is_regular_file(status))
        refuse(option, path, "is not a regular file (a device or a pipe cannot be replaced)");
    const fs::path folder = folder_of(path);
    const auto folder_status = fs::status(folder, ec);
    if (!fs::exists(folder_status))
        refuse(option, path, "the folder " + folder.string() + " does not exist");
    if (!fs::is_directory(folder_status))
        refuse(option, path, folder.string() + " is a file, not a folder");
    require_writable_dir(option, path, folder);
}

void check_output_dir(const std::string& option, const std::string& path) {
    require_non_empty(option, path);
    std::error_code ec;
    fs::path at = fs::path(path);
    // The nearest part of the path that exists decides: it must be a writable folder.
    while (!at.empty() && !fs::exists(fs::symlink_status(at, ec)) && at.has_parent_path() &&
           at.parent_path() != at)
        at = at.parent_path();
    if (at.empty() || !fs::exists(fs::status(at, ec))) at = ".";
    if (!fs::is_directory(fs::status(at, ec)))
        refuse(option, path,
               at == fs::path(path) ? "is a file, not a folder"
                                    : at.string() + " is a file, not a folder");
    require_writable_dir(option, path, at);
}

void check_existing_dir(const std::string& option, const std::string& path) {
    require_non_empty(option, path);
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status)) refuse(option, path, "no such folder");
    if (!fs::is_directory(status)) refuse(option, path, "is a file, not a folder");
    require_writable_dir(option, path, path);
}

}  // namespace bhm::app
