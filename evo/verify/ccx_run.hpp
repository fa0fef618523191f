#pragma once
// Runs CalculiX (`ccx`, Debian calculix-ccx) as a child process on one input deck in a fresh
// temporary folder and reads the nodal displacements it prints to the .dat file. The one home of
// this driver: the verification suite (tests/engine/calculix.hpp) solves through it too.
#include <array>
#include <map>
#include <string>
#include <vector>

namespace bhm::evo {

using NodalDisplacements = std::map<int, std::array<double, 3>>;

//! True when `ccx` is on the PATH.
bool ccx_available();

struct CcxResult {
    std::vector<NodalDisplacements> blocks;  //!< each printed displacement block, in order
    double wall_s = 0.0;
    double cpu_s = 0.0;  //!< the solver's CPU time (user + system), the load-independent cost
};

//! Solves `deck` (named `name` in the log) with `threads` solver threads. Throws
//! std::runtime_error with one line: ccx missing, a failed solve (with the solver's first *ERROR
//! line), or no displacements printed. The temporary folder is removed unless `keep_dir` is set
//! (then the deck, .dat and log stay there and the message names it).
CcxResult run_ccx(const std::string& name, const std::string& deck, int threads = 1,
                  const std::string& keep_dir = "");

//! The displacement blocks of a .dat file's text (exposed for tests).
std::vector<NodalDisplacements> parse_ccx_dat(const std::string& text);

}  // namespace bhm::evo
