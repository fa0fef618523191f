#include "app/gui/shell/redraw_gate.hpp"

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

bool needs_animation(const Studio& s) {
    const RunPhase phase = s.run.evolution.phase();
    const bool evolving = run_is_live(phase) && phase != RunPhase::Paused;
    return s.clock.playing || evolving || s.bodies.simulator.busy() ||
           s.bodies.compare_simulator.busy() || s.calibration.session.running() ||
           s.exports.frame_job.active || s.view.dragging || s.verify.worker.running();
}

bool RedrawGate::should_draw(const Studio& s, double now_s) {
    // Every published snapshot (run, simulated bodies) moves the stamp.
    const std::uint64_t stamp =
        s.run.evolution.version() * 1000003u + s.bodies.simulator.version() * 1009u +
        s.bodies.compare_simulator.version() + s.calibration.session.version() * 7919u;
    if (input_ || stamp != stamp_) settle_ = kSettleFrames;
    input_ = false;
    stamp_ = stamp;
    bool draw = needs_animation(s) || now_s - last_draw_s_ >= kQuietPeriodS;
    if (settle_ > 0) {
        --settle_;
        draw = true;
    }
    if (draw) last_draw_s_ = now_s;
    return draw;
}

}  // namespace bhm::app::gui
