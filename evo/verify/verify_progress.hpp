#pragma once
// How far a verification has come (meshing, CalculiX solving load i of n, our engine at load i of
// n, comparing, then the mesh-error estimate's second mesh) and how it is stopped: a caller's
// cancel flag, polled by the ccx driver (which then kills the solver) and by our engine's
// quasi-static run between slices.
#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>

namespace bhm::evo {

//! SecondMesh: the mesh-error estimate's CalculiX solve (mesh_error.hpp), after the comparison.
enum class VerifyPhase { Meshing, Solving, Engine, Comparing, SecondMesh };

struct VerifyProgress {
    VerifyPhase phase = VerifyPhase::Meshing;
    int load = 0;   //!< 1-based load in progress (Solving, Engine); 0 otherwise
    int loads = 0;  //!< loads in all
};

//! "meshing", "CalculiX solving load 2 of 3", "our engine at load 1 of 3", "comparing",
//! "mesh error: CalculiX solving the second mesh, load 1 of 3".
std::string describe_progress(const VerifyProgress& progress);

//! Thrown when the cancel flag was raised; not a std::runtime_error, so that a caller that keeps
//! going after one body's failed solve (bhm verify RUN_DIR) does not take it for one.
class VerifyCancelled : public std::exception {
  public:
    const char* what() const noexcept override { return "verification cancelled"; }
};

//! What a long verification reports to and hears from its caller (both may be empty).
struct VerifyControl {
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(const VerifyProgress&)> on_progress;
    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
    void report(const VerifyProgress& p) const {
        if (on_progress) on_progress(p);
    }
};

}  // namespace bhm::evo
