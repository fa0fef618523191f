#pragma once
// The carriage-return progress line of `bhm simulate`: percent, simulated time, voxel-steps/s, ETA.
// Silent for the first second of wall time (short runs print nothing) and when disabled (stderr
// is not a terminal).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace bhm::app {

//! One progress line without the leading carriage return, e.g.
//! " 45.2%  t 4.97/11.00 s  3.21e+06 voxel-steps/s  ETA 6 s". ETA is "?" while unknown.
std::string format_progress(double sim_s, double total_s, double voxel_steps_per_s, double eta_s);

class ProgressLine {
  public:
    ProgressLine(std::FILE* out, double total_s, int voxels, bool enabled);
    //! Called with the world's current time and step count; prints at most 5 times a second.
    void update(double sim_s, std::int64_t steps);
    //! Ends the line (newline) if anything was printed.
    void finish();

  private:
    using Clock = std::chrono::steady_clock;
    std::FILE* out_;
    double total_s_;
    int voxels_;
    bool enabled_;
    bool printed_ = false;
    Clock::time_point start_ = Clock::now();
    Clock::time_point last_print_{};
};

}  // namespace bhm::app
