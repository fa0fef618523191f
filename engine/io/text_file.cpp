#include "engine/io/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>

#include "engine/io/atomic_file.hpp"

namespace bhm::engine {

FileReadError::FileReadError(std::string path, std::string reason)
    : std::runtime_error(path + ": " + reason),
      path_(std::move(path)),
      reason_(std::move(reason)) {}

namespace {

// Closes the descriptor on every path out of read_text.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

std::string describe_cap(std::uint64_t bytes) {
    if (bytes >= kMiB && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string read_text(const std::string& path, std::uint64_t max_bytes) {
    if (path.empty()) throw FileReadError("(empty path)", "no file name given");
    // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat below refuses it anyway.
    const Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
    if (file.fd < 0) {
        const int error = errno;
        if (error == ENOENT) throw FileReadError(path, "no such file");
        if (error == EISDIR) throw FileReadError(path, "is a directory, not a file");
        throw FileReadError(path, "cannot open for reading (" + error_text(error) + ")");
    }
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) {
        const int error = errno;
        throw FileReadError(path, "cannot read (" + error_text(error) + ")");
    }
    if (S_ISDIR(info.st_mode)) throw FileReadError(path, "is a directory, not a file");
    if (!S_ISREG(info.st_mode))
        throw FileReadError(path, "is not a regular file (a device, pipe or socket); give a file");
    const auto too_large = [&] {
        throw FileReadError(path, "is larger than the " + describe_cap(max_bytes) +
                                      " this reader accepts; is it the right file?");
    };
    if (static_cast<std::uint64_t>(info.st_size) > max_bytes) too_large();
    // A regular file we opened without O_NONBLOCK semantics mattering; read until the end, but
    // never past the cap even if the file grows while we read.
    std::string text;
    text.resize(static_cast<std::size_t>(info.st_size));
    std::size_t used = 0;
    for (;;) {
        if (used == text.size()) {
            if (text.size() > max_bytes) too_large();
            text.resize(text.size() + 64 * 1024);
        }
        const ssize_t n = ::read(file.fd, text.data() + used, text.size() - used);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int error = errno;
            throw FileReadError(path, "read failed (" + error_text(error) + ")");
        }
        if (n == 0) break;
        used += static_cast<std::size_t>(n);
    }
    if (used > max_bytes) too_large();
    text.resize(used);
    return text;
}

std::string format_number(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string format_number(float value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

}  // namespace bhm::engine
