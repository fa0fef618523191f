#pragma once
// One writer per run directory. Two `bhm evolve` (or the studio and a CLI run) writing the same
// directory interleave their files, so the writer holds DIR/run.lock: an flock(2) lock on that
// file, whose text names the owner ("pid 1234 on host node7, bhm evolve, since ...Z"). The
// kernel drops the lock when its process dies, kill -9 included, so a lock file left behind is
// stale by definition and simply taken over. A second writer is refused with the owner's name.
// On a file system without flock the owner's pid is checked instead (alive on this host: busy).
#include <stdexcept>
#include <string>

namespace bhm::evo {

inline constexpr const char* kRunLockFile = "run.lock";

//! Thrown when another process (or another run in this one) owns the directory.
struct RunDirectoryBusy : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class RunDirectoryLock {
  public:
    //! Takes DIR's lock (DIR must exist). Throws RunDirectoryBusy naming the owner, or
    //! std::runtime_error naming DIR when the lock file cannot be made (e.g. not writable).
    RunDirectoryLock(const std::string& dir, const std::string& program);
    ~RunDirectoryLock();  //!< releases the lock and removes the lock file
    RunDirectoryLock(const RunDirectoryLock&) = delete;
    RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

    const std::string& path() const { return path_; }
    //! The owner text this process wrote ("pid ... on host ..., PROGRAM, since ...").
    const std::string& owner() const { return owner_; }

  private:
    std::string path_, owner_;
    int fd_ = -1;
};

//! The owner named in DIR/run.lock, or "" when there is no lock file.
std::string run_lock_owner(const std::string& dir);

}  // namespace bhm::evo
