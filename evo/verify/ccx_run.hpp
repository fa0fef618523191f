#pragma once
// Runs CalculiX (`ccx`, Debian calculix-ccx) as a child process on one input deck in a fresh
// temporary folder and reads the nodal displacements it prints to the .dat file. The one home of
// this driver: the verification suite (tests/engine/calculix.hpp) solves through it too.
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "evo/verify/verify_progress.hpp"

namespace bhm::evo {

using NodalDisplacements = std::map<int, std::array<double, 3>>;

//! True when `ccx` is on the PATH.
bool ccx_available();

struct CcxResult {
    std::vector<NodalDisplacements> blocks;  //!< each printed displacement block, in order
    double wall_s = 0.0;
    double cpu_s = 0.0;  //!< the solver's CPU time (user + system), the load-independent cost
};

//! Watching a solve: `cancel` is polled every 20 ms (raised, the solver is killed and
//! VerifyCancelled thrown); `steps_done` hears how many load steps the solver has completed
//! whenever that count grows (read from its .sta file).
struct CcxWatch {
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(int)> steps_done;
};

//! Solves `deck` (named `name` in the log) with `threads` solver threads, ccx a child process
//! in its own process group that dies with the thread that started it (PR_SET_PDEATHSIG), so a
//! kill -9 of bhm leaves no solver running. Throws std::runtime_error with one line: ccx missing,
//! a failed solve (with the solver's first *ERROR line), or no displacements printed;
//! VerifyCancelled when cancelled. The temporary folder (`bhm-ccx-<pid>-XXXXXX` in the temporary
//! directory) is removed unless `keep_dir` is set (then the deck, .dat and log stay there and the
//! message names it); the first solve of a process sweeps those that killed processes left
//! (sweep_stale_ccx_folders).
CcxResult run_ccx(const std::string& name, const std::string& deck, int threads = 1,
                  const std::string& keep_dir = "", const CcxWatch& watch = {});

//! A solve's temporary folder this long untouched (the folder and every file in it) is stale
//! whoever made it: ccx rewrites its .sta every increment, and our solves take minutes. Also the
//! only test for the older name without a pid and for an owner pid taken by another process.
inline constexpr double kStaleCcxFolderAge_s = 6 * 3600.0;

//! Removes from `parent` the temporary folders of solves that died with their process (a kill -9
//! of bhm: issue 41 R4): `bhm-ccx-<pid>-XXXXXX` whose process is gone, and any `bhm-ccx-*`
//! folder (also the older `bhm-ccx-XXXXXX`) untouched for kStaleCcxFolderAge_s. Only folders of
//! this user, never this process's own, never through a link. Returns how many it removed.
int sweep_stale_ccx_folders(const std::string& parent);

//! Load steps completed according to the text of a ccx .sta file (a step counts once its step
//! time reaches 1; exposed for tests).
int ccx_steps_done(const std::string& sta_text);

//! The displacement blocks of a .dat file's text (exposed for tests).
std::vector<NodalDisplacements> parse_ccx_dat(const std::string& text);

}  // namespace bhm::evo
