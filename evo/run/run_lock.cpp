#include "evo/run/run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "engine/io/atomic_file.hpp"

namespace bhm::evo {

namespace {

std::string host_name() {
    char name[256] = {0};
    if (::gethostname(name, sizeof name - 1) != 0) return "?";
    return name;
}

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    ::gmtime_r(&now, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

std::string read_fd(int fd) {
    std::string text;
    char buffer[512];
    for (off_t at = 0;;) {
        const ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
        if (n <= 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        at += n;
        if (text.size() > 4096) break;
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == '\0'))
        text.pop_back();
    return text;
}

//! Without flock: is the pid written in the file alive on this host?
bool owner_alive(const std::string& text) {
    long pid = 0;
    char host[256] = {0};
    if (std::sscanf(text.c_str(), "pid %ld on host %255[^,]", &pid, host) != 2) return false;
    if (host_name() != host) return true;  // cannot tell: assume it is
    return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

}  // namespace

std::string run_lock_owner(const std::string& dir) {
    const std::string path = (std::filesystem::path(dir) / kRunLockFile).string();
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return "";
    std::string text = read_fd(fd);
    ::close(fd);
    return text;
}

RunDirectoryLock::RunDirectoryLock(const std::string& dir, const std::string& program)
    : path_((std::filesystem::path(dir) / kRunLockFile).string()) {
    owner_ = "pid " + std::to_string(::getpid()) + " on host " + host_name() + ", " + program +
             ", since " + utc_now();
    for (int attempt = 0; attempt < 10; ++attempt) {
        const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) {
            const int error = errno;
            throw std::runtime_error(dir + ": cannot lock the run directory (" +
                                     engine::error_text(error) + ")");
        }
        bool locked = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
        const int error = locked ? 0 : errno;
        if (!locked && error == EWOULDBLOCK) {
            const std::string owner = read_fd(fd);
            ::close(fd);
            throw RunDirectoryBusy(dir + ": in use by " +
                                   (owner.empty() ? "another process" : owner) + " (" + path_ +
                                   "); wait for it to finish or stop it first");
        }
        if (!locked) {  // no flock here (some network file systems): trust a living pid
            const std::string owner = read_fd(fd);
            if (!owner.empty() && owner_alive(owner)) {
                ::close(fd);
                throw RunDirectoryBusy(dir + ": in use by " + owner + " (" + path_ +
                                       "); wait for it to finish or stop it first");
            }
        }
        // The previous owner may have removed the file between our open and our lock: then we
        // hold a lock on a name nobody sees, so start again.
        struct stat by_fd {
        }, by_name{};
        if (::fstat(fd, &by_fd) != 0 || ::stat(path_.c_str(), &by_name) != 0 ||
            by_fd.st_ino != by_name.st_ino || by_fd.st_dev != by_name.st_dev) {
            ::close(fd);
            continue;
        }
        const std::string text = owner_ + "\n";
        if (::ftruncate(fd, 0) != 0 ||
            ::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
            const int write_error = errno;
            ::close(fd);
            throw std::runtime_error(path_ + ": cannot write the lock file (" +
                                     engine::error_text(write_error) + ")");
        }
        fd_ = fd;
        return;
    }
    throw RunDirectoryBusy(dir + ": the lock file " + path_ + " keeps changing hands");
}

RunDirectoryLock::~RunDirectoryLock() {
    // Unlink while still holding the lock, so no one can take a lock on a file about to vanish
    // without noticing (the inode check above).
    ::unlink(path_.c_str());
    ::close(fd_);
}

}  // namespace bhm::evo
