#include "app/cli/simulate_progress.hpp"

#include <algorithm>
#include <cmath>

namespace bhm::app {

namespace {
constexpr double kQuietFirst_s = 1.0;   // runs shorter than this print no progress at all
constexpr double kMinInterval_s = 0.2;  // no more than 5 redraws a second
}  // namespace

std::string format_progress(double sim_s, double total_s, double voxel_steps_per_s, double eta_s) {
    const double percent = total_s > 0.0 ? std::clamp(100.0 * sim_s / total_s, 0.0, 100.0) : 100.0;
    char eta[32];
    if (std::isfinite(eta_s) && eta_s >= 0.0)
        std::snprintf(eta, sizeof eta, "%.0f s", std::ceil(eta_s));
    else
        std::snprintf(eta, sizeof eta, "?");
    char line[160];
    std::snprintf(line, sizeof line, "%5.1f%%  t %.2f/%.2f s  %.3g voxel-steps/s  ETA %s", percent,
                  sim_s, total_s, voxel_steps_per_s, eta);
    return line;
}

ProgressLine::ProgressLine(std::FILE* out, double total_s, int voxels, bool enabled)
    : out_(out), total_s_(total_s), voxels_(voxels), enabled_(enabled) {}

void ProgressLine::update(double sim_s, std::int64_t steps) {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double wall_s = std::chrono::duration<double>(now - start_).count();
    if (wall_s < kQuietFirst_s) return;
    if (printed_ && std::chrono::duration<double>(now - last_print_).count() < kMinInterval_s)
        return;
    const double rate = static_cast<double>(voxels_) * static_cast<double>(steps) / wall_s;
    const double eta = sim_s > 0.0 ? wall_s * (total_s_ - sim_s) / sim_s : -1.0;
    // \033[K clears what a longer previous line left on the right.
    std::fprintf(out_, "\r%s\033[K", format_progress(sim_s, total_s_, rate, eta).c_str());
    std::fflush(out_);
    printed_ = true;
    last_print_ = now;
}

void ProgressLine::finish() {
    if (printed_) std::fprintf(out_, "\n");
    printed_ = false;
}

}  // namespace bhm::app
