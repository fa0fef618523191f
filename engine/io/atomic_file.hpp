#pragma once
// Files that are either the old version or the complete new one, never a mix: every output of the
// program (checkpoints, JSON, CSV, VXA, replays, PNG frames) goes through here. The bytes go to
// PATH.tmp; every write, the fsync and the close are checked; only then is PATH.tmp renamed over
// PATH. On any failure the temporary is removed, PATH is untouched, and the error names PATH and
// the system's reason, e.g. "out/a.png: cannot write (No space left on device); the previous
// file is unchanged".
//
// It lives in engine/ because it is the lowest layer: the replay writer here, evo/, render/ and
// app/ all share this one implementation. Plain POSIX calls, no threads.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace bhm::engine {

//! Replaces path with contents atomically (see above). Throws std::runtime_error.
void write_file_atomically(const std::string& path, std::string_view contents);

//! The same, streamed: write() any number of times, then commit(). Destroyed without a
//! successful commit(), it removes its temporary and leaves path as it was.
class AtomicFile {
  public:
    explicit AtomicFile(std::string path);  //!< opens PATH.tmp; throws std::runtime_error
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* data, std::size_t bytes);
    void write(std::string_view text) { write(text.data(), text.size()); }
    //! fsync, close, rename into place. Throws std::runtime_error (the temporary is removed).
    //! before_rename (optional) runs between the close and the rename, e.g. to keep the old
    //! file under another name; if it throws, the temporary is removed and path untouched.
    void commit(const std::function<void()>& before_rename = {});
    const std::string& temp_path() const { return temp_; }

  private:
    [[noreturn]] void fail(const std::string& what, int error);
    std::string path_, temp_;
    int fd_ = -1;
    bool committed_ = false;
};

//! "Permission denied" etc. for an errno value; thread-safe (strerror is not).
std::string error_text(int error);

}  // namespace bhm::engine
