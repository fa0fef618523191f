#pragma once
// An output folder that is either the old complete one or the new complete one, never a mix
// (issue 41 R5): what atomic_file does for one file, for a command's whole --out folder.
//
// The new folder is written into a sibling, ".NAME.staging-PID-XXXXXX" (every file through
// atomic_file, each write checked), and commit() swaps it in: renameat2(RENAME_EXCHANGE) trades
// the two names in one step, then the old folder, now under the staging name, is removed. Where
// the file system cannot exchange, the old folder is first renamed aside (".NAME.old-PID-...")
// and removed only after the new one is in place. Destroyed without commit() (an error, a
// cancelled command), the staging folder is removed and the old folder is untouched. A killed
// process leaves only its staging folder, which the next StagedFolder beside it removes once its
// owner (the pid in the name) is gone.
//
// Replacing a folder whole removes everything in it, so a folder holding anything the command
// does not write (`--out .`, a home folder, the evolve loop's RUN/verify/individual-N) is refused
// before any work: the caller says which entry names are its own.
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace bhm::engine {

class StagedFolder {
  public:
    //! Whether an entry of an existing folder is one the command writes (so may be replaced).
    using OwnsEntry = std::function<bool(const std::string& name)>;

    //! Checks path (a folder or nothing; an existing folder holds only owned entries), creates
    //! its parent folders and the staging folder. Throws std::runtime_error, one line naming the
    //! folder and the reason, e.g. "run/verify: cannot create a folder in run (Permission denied)".
    //! Call it before any long work: a folder that cannot be written then costs nothing.
    StagedFolder(std::string path, const OwnsEntry& owns);
    ~StagedFolder();
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    //! Where to write: the staging folder.
    const std::string& staging() const { return staging_; }
    //! staging()/name.
    std::string file(const std::string& name) const;
    //! The folder the command's outputs go to (as given).
    const std::string& path() const { return path_; }
    //! Puts the staged folder in place of path (see above). Throws std::runtime_error naming the
    //! folder; then path is the old folder, or (only if even the way back failed) the old folder
    //! is kept under its ".old-" name, which the message names.
    void commit();
    //! A message naming a staged file turned into one naming the file at path (errors of the
    //! writers name the file they wrote).
    std::string as_final(const std::string& message) const;

  private:
    std::string path_, staging_;
    bool committed_ = false;
};

//! The same promise for a command's outputs that are single files in different folders (bhm
//! export's --vxa, --body-out, --mesh ...): each is written whole under a staged name beside it
//! (PATH.staged-PID), and only when every one is written are they renamed into place. Destroyed
//! without commit(), the staged files are removed and no output is touched (issue 41 R6).
class StagedFiles {
  public:
    StagedFiles() = default;
    ~StagedFiles();
    StagedFiles(const StagedFiles&) = delete;
    StagedFiles& operator=(const StagedFiles&) = delete;

    //! The name to write path's new contents to (PATH.staged-PID), remembered for commit();
    //! first removes the staged copies of path that killed writers left (below).
    std::string stage(const std::string& path);
    //! Renames every staged file over its path, in the order staged. Throws std::runtime_error
    //! naming the file that could not be replaced (those before it are already in place).
    void commit();
    //! A message naming a staged file turned into one naming the output itself.
    std::string as_final(const std::string& message) const;

  private:
    std::vector<std::pair<std::string, std::string>> files_;  //!< (path, staged name)
    bool committed_ = false;
};

//! Removes ".NAME.staging-PID-*" and ".NAME.old-PID-*" folders in parent whose process is gone;
//! the number removed. A ".old-" folder is put back as NAME when NAME is missing (a kill between
//! the two renames of the fallback) instead of being removed.
int sweep_stale_staging(const std::string& parent, const std::string& name);

//! Removes "PATH.staged-PID" files beside path whose process is gone (a writer killed between
//! staging and commit); the number removed.
int sweep_stale_staged_files(const std::string& path);

}  // namespace bhm::engine
