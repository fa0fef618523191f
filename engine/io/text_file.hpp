#pragma once
// One home for "read a whole file" and for numbers written as text. Every reader of the program
// (experiment and body JSON, run directories, checkpoints, replays, VXA, scripts, settings) reads
// through read_text, so each has a size cap and none can be fed an endless stream: /dev/zero, a
// pipe or a folder is refused at once with the file's name instead of filling memory or failing
// later with a library's message ("basic_filebuf::underflow error").
//
// Lives in engine/io/ beside atomic_file because it is the lowest layer every other one shares.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bhm::engine {

//! Caps on what a reader accepts. Generous for what the program writes, small beside memory.
inline constexpr std::uint64_t kMiB = 1024 * 1024;
inline constexpr std::uint64_t kTextFileCap = 64 * kMiB;  //!< JSON, VXA, scripts, settings
inline constexpr std::uint64_t kLargeFileCap =
    2048 * kMiB;  //!< replays and checkpoints (a long, dense replay is ~100s of MB)

//! A file that could not be read whole: what() is "PATH: reason", path() and reason() the parts,
//! so a reader that reports problems per field can file it under its own "(file)" heading.
class FileReadError : public std::runtime_error {
  public:
    FileReadError(std::string path, std::string reason);
    const std::string& path() const { return path_; }
    const std::string& reason() const { return reason_; }

  private:
    std::string path_, reason_;
};

//! The whole contents of the regular file at path, at most max_bytes long. Throws FileReadError
//! for a missing file, a folder, anything that is not a regular file (a device, pipe or socket
//! would stream forever or block), a file over the cap (naming the cap), or a read error.
std::string read_text(const std::string& path, std::uint64_t max_bytes = kTextFileCap);

//! Shortest text that reads back as the same value, independent of the locale (std::to_chars):
//! 0.35 -> "0.35", 5e6 -> "5e+06". Non-finite values give "inf", "-inf" and "nan".
std::string format_number(double value);
std::string format_number(float value);

}  // namespace bhm::engine
