#include "engine/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace bhm::engine {

std::string error_text(int error) {
    char buffer[256] = {0};
    // GNU strerror_r may return a static string instead of filling the buffer; XSI fills it.
    const auto result = strerror_r(error, buffer, sizeof buffer);
    if constexpr (std::is_pointer_v<std::decay_t<decltype(result)>>)
        return result ? std::string(result) : "error " + std::to_string(error);
    else
        return result == 0 ? std::string(buffer) : "error " + std::to_string(error);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), temp_(path_ + ".tmp") {
    if (path_.empty()) throw std::runtime_error("(empty path): cannot write a file without a name");
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) {
        const int error = errno;
        throw std::runtime_error(path_ + ": cannot write (" + error_text(error) + ")");
    }
}

AtomicFile::~AtomicFile() {
    if (committed_) return;
    if (fd_ >= 0) ::close(fd_);
    ::unlink(temp_.c_str());
}

void AtomicFile::fail(const std::string& what, int error) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    ::unlink(temp_.c_str());
    // The errno of the failing call, taken before the clean-up could change it.
    throw std::runtime_error(path_ + ": " + what + " (" + error_text(error) +
                             "); the previous file is unchanged");
}

void AtomicFile::write(const void* data, std::size_t bytes) {
    if (fd_ < 0) throw std::logic_error(path_ + ": write after commit or failure");
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
        const ssize_t n = ::write(fd_, p, bytes);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", errno);
        }
        if (n == 0) fail("cannot write", EIO);
        p += n;
        bytes -= static_cast<std::size_t>(n);
    }
}

void AtomicFile::commit(const std::function<void()>& before_rename) {
    if (fd_ < 0) throw std::logic_error(path_ + ": commit after commit or failure");
    // fsync before the rename: after a power cut the name never points at unwritten blocks.
    if (::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) fail("cannot write", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(temp_.c_str());
        throw std::runtime_error(path_ + ": cannot write (" + error_text(error) +
                                 "); the previous file is unchanged");
    }
    if (before_rename) {
        try {
            before_rename();
        } catch (...) {
            ::unlink(temp_.c_str());
            throw;
        }
    }
    if (::rename(temp_.c_str(), path_.c_str()) != 0) {
        const int error = errno;
        ::unlink(temp_.c_str());
        throw std::runtime_error(path_ + ": cannot replace the file (" + error_text(error) +
                                 "); the previous file is unchanged");
    }
    committed_ = true;
}

void write_file_atomically(const std::string& path, std::string_view contents) {
    AtomicFile file(path);
    file.write(contents);
    file.commit();
}

}  // namespace bhm::engine
