#include "engine/io/staged_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "engine/io/atomic_file.hpp"

namespace bhm::engine {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStagingTag = ".staging-";
constexpr const char* kOldTag = ".old-";

// The folder as one absolute name without a trailing slash ("out/" and "out" are the same
// folder; "." is the current one). A link to a folder stands for the folder it points to: the
// swap replaces the folder, never the link.
fs::path folder_name(const std::string& path) {
    fs::path p = fs::absolute(fs::path(path)).lexically_normal();
    if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(p, ec))) {
        const fs::path target = fs::canonical(p, ec);
        if (!ec) p = target;
    }
    return p;
}

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The pid in ".NAME<tag>PID-XXXXXX" (mkdtemp's six letters), or -1 when name is not of that form.
long owner_of(const std::string& entry, const std::string& name, const std::string& tag) {
    const std::string prefix = "." + name + tag;
    if (entry.rfind(prefix, 0) != 0) return -1;
    const std::string rest = entry.substr(prefix.size());
    const auto dash = rest.find('-');
    if (dash == std::string::npos || dash == 0 || dash > 9 || rest.size() != dash + 7) return -1;
    const std::string pid = rest.substr(0, dash);
    if (pid.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stol(pid);
}

bool process_gone(long pid) { return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

// A new, empty sibling of folder: parent/.NAME<tag>PID-XXXXXX.
fs::path make_sibling(const fs::path& folder, const std::string& tag, const std::string& shown) {
    std::string pattern = (folder.parent_path() / ("." + folder.filename().string() + tag +
                                                   std::to_string(::getpid()) + "-XXXXXX"))
                              .string();
    if (::mkdtemp(pattern.data()) == nullptr) {
        const int error = errno;
        throw std::runtime_error(shown + ": cannot create a folder in " +
                                 folder.parent_path().string() + " (" + error_text(error) + ")");
    }
    return pattern;
}

// Best effort: after a power cut the parent's entries name the new folder.
void sync_folder(const fs::path& folder) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

int sweep_stale_staging(const std::string& parent, const std::string& name) {
    int removed = 0;
    std::error_code ec;
    fs::directory_iterator it(parent, ec);
    if (ec) return 0;
    std::vector<fs::path> stale_staging, stale_old;
    for (const auto& entry : it) {
        const std::string entry_name = entry.path().filename().string();
        const long staging_pid = owner_of(entry_name, name, kStagingTag);
        const long old_pid = owner_of(entry_name, name, kOldTag);
        if (staging_pid > 0 && process_gone(staging_pid)) stale_staging.push_back(entry.path());
        if (old_pid > 0 && process_gone(old_pid)) stale_old.push_back(entry.path());
    }
    for (const auto& p : stale_staging)
        if (fs::remove_all(p, ec) > 0 && !ec) ++removed;
    const fs::path folder = fs::path(parent) / name;
    for (const auto& p : stale_old) {
        // Killed between moving the old folder aside and moving the new one in: the old one is
        // the complete folder, so it goes back.
        if (!fs::exists(fs::symlink_status(folder, ec)) && ::rename(p.c_str(), folder.c_str()) == 0)
            continue;
        if (fs::remove_all(p, ec) > 0 && !ec) ++removed;
    }
    return removed;
}

StagedFolder::StagedFolder(std::string path, const OwnsEntry& owns) : path_(std::move(path)) {
    if (path_.empty()) throw std::runtime_error("(empty path): cannot write a folder without a name");
    const fs::path folder = folder_name(path_);
    std::error_code ec;
    const auto status = fs::status(folder, ec);
    if (fs::exists(status) && !fs::is_directory(status))
        throw std::runtime_error(path_ + ": is a file, not a folder");
    if (fs::is_directory(status)) {
        if (folder == folder.root_path())
            throw std::runtime_error(path_ + ": cannot replace the root folder");
        fs::directory_iterator it(folder, ec);
        if (ec)
            throw std::runtime_error(path_ + ": cannot read the folder (" + ec.message() + ")");
        for (const auto& entry : it) {
            const std::string name = entry.path().filename().string();
            // PATH.tmp: a file of atomic_file left by a killed writer of the same command.
            if (owns(name) || ends_with(name, ".tmp")) continue;
            throw std::runtime_error(path_ + ": holds " + name +
                                     ", which this command does not write; the folder is "
                                     "replaced whole, so give a new or an empty folder");
        }
    }
    fs::create_directories(folder.parent_path(), ec);
    if (ec || !fs::is_directory(folder.parent_path()))
        throw std::runtime_error(path_ + ": cannot create the folder " +
                                 folder.parent_path().string() +
                                 (ec ? " (" + ec.message() + ")" : std::string()));
    sweep_stale_staging(folder.parent_path().string(), folder.filename().string());
    staging_ = make_sibling(folder, kStagingTag, path_).string();
}

StagedFolder::~StagedFolder() {
    if (committed_ || staging_.empty()) return;
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
}

std::string StagedFolder::file(const std::string& name) const {
    return (fs::path(staging_) / name).string();
}

std::string StagedFolder::as_final(const std::string& message) const {
    std::string out = message;
    const std::string from = staging_ + "/";
    const std::string to = (fs::path(path_) / "").string();
    for (auto at = out.find(from); at != std::string::npos; at = out.find(from, at + to.size()))
        out.replace(at, from.size(), to);
    return out;
}

void StagedFolder::commit() {
    if (committed_) throw std::logic_error(path_ + ": committed twice");
    const fs::path folder = folder_name(path_);
    std::error_code ec;
    const bool exists = fs::exists(fs::symlink_status(folder, ec));
    if (!exists) {
        if (::rename(staging_.c_str(), folder.c_str()) != 0) {
            const int error = errno;
            throw std::runtime_error(path_ + ": cannot move the new folder into place (" +
                                     error_text(error) + ")");
        }
    } else if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, folder.c_str(),
                           RENAME_EXCHANGE) == 0) {
        // The old folder is now under the staging name.
        fs::remove_all(staging_, ec);
    } else if (errno == EINVAL || errno == ENOSYS || errno == EOPNOTSUPP) {
        // No exchange on this file system: the old folder aside first, removed once the new one
        // is in place.
        const fs::path aside = make_sibling(folder, kOldTag, path_);
        fs::remove(aside, ec);  // rename wants the name free (an empty folder would do too)
        if (::rename(folder.c_str(), aside.c_str()) != 0) {
            const int error = errno;
            throw std::runtime_error(path_ + ": cannot move the old folder aside (" +
                                     error_text(error) + "); it is unchanged");
        }
        if (::rename(staging_.c_str(), folder.c_str()) != 0) {
            const int error = errno;
            const bool back = ::rename(aside.c_str(), folder.c_str()) == 0;
            throw std::runtime_error(path_ + ": cannot move the new folder into place (" +
                                     error_text(error) + ")" +
                                     (back ? "; the old folder is unchanged"
                                           : "; the old folder is kept as " + aside.string()));
        }
        fs::remove_all(aside, ec);
    } else {
        const int error = errno;
        throw std::runtime_error(path_ + ": cannot replace the folder (" + error_text(error) +
                                 "); the old folder is unchanged");
    }
    committed_ = true;
    sync_folder(folder.parent_path());
}

StagedFiles::~StagedFiles() {
    if (committed_) return;
    for (const auto& [path, staged] : files_) ::unlink(staged.c_str());
}

std::string StagedFiles::stage(const std::string& path) {
    sweep_stale_staged_files(path);
    files_.emplace_back(path, path + ".staged-" + std::to_string(::getpid()));
    return files_.back().second;
}

int sweep_stale_staged_files(const std::string& path) {
    const fs::path target = path;
    const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string prefix = target.filename().string() + ".staged-";
    std::error_code ec;
    fs::directory_iterator it(parent, ec);
    if (ec) return 0;  // nothing to sweep; the write itself will name the problem
    int removed = 0;
    for (const auto& entry : it) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string pid = name.substr(prefix.size());
        if (pid.empty() || pid.size() > 9 ||
            pid.find_first_not_of("0123456789") != std::string::npos)
            continue;
        if (process_gone(std::stol(pid)) && ::unlink(entry.path().c_str()) == 0) ++removed;
    }
    return removed;
}

void StagedFiles::commit() {
    if (committed_) throw std::logic_error("staged files committed twice");
    committed_ = true;
    for (std::size_t i = 0; i < files_.size(); ++i) {
        const auto& [path, staged] = files_[i];
        if (::rename(staged.c_str(), path.c_str()) != 0) {
            const int error = errno;
            for (std::size_t j = i; j < files_.size(); ++j) ::unlink(files_[j].second.c_str());
            throw std::runtime_error(path + ": cannot replace the file (" + error_text(error) +
                                     ")");
        }
    }
}

std::string StagedFiles::as_final(const std::string& message) const {
    std::string out = message;
    for (const auto& [path, staged] : files_)
        for (auto at = out.find(staged); at != std::string::npos;
             at = out.find(staged, at + path.size()))
            out.replace(at, staged.size(), path);
    return out;
}

}  // namespace bhm::engine
