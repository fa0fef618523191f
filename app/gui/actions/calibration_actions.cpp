#include "app/gui/actions/calibration_actions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>

#include "app/cli/simulation_limits.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "evo/calibrate/fit_parameters.hpp"
#include "evo/calibrate/track_simulation.hpp"
#include "evo/evaluate/simulate.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app::gui {

namespace {

// Status-line number: 4 significant digits.
std::string number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", v);
    return buffer;
}

std::string file_name(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

bool show_body_file(Studio& s, const std::string& path) {
    try {
        const std::string absolute = absolute_path(path);
        const evo::Body body = evo::load_body(absolute);
        const auto& e = s.document.experiment();
        const auto problems = evo::validate_body_against(body, e, absolute);
        if (!problems.empty()) {
            set_status(s, describe_problems("", problems), true);
            return false;
        }
        SimulationRequest request;
        request.id = -2;  // a body file: not from a run
        request.label = "body " + file_name(absolute);
        request.experiment = e;
        request.framed_body =
            std::make_shared<const evo::Body>(evo::apply_frame_and_overrides(e, body));
        s.bodies.follow_champion = false;
        s.bodies.simulator.request(std::move(request));
        set_status(s, "simulating " + absolute);
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

bool load_track(Studio& s, const std::string& path) {
    auto& c = s.calibration;
    if (!s.bodies.shown || !s.bodies.shown->framed_body) {
        set_status(s, "load track: show a body first (a champion, an individual or a body file)",
                   true);
        return false;
    }
    if (c.session.running()) {
        set_status(s, "load track: a calibration is running: cancel it first", true);
        return false;
    }
    try {
        const std::string absolute = absolute_path(path);
        auto track = std::make_shared<const evo::MeasuredTrack>(evo::load_measured_track(absolute));
        // The preview simulates to the track's end, and so does every simulation of a fit: the
        // rule bhm calibrate obeys (issue 41 R1) is checked before anything starts, where a track
        // at time_offset_s 1e6 ran for hours, and a span far from the experiment's is said.
        const auto& shown = *s.bodies.shown;
        const auto model = evo::model_of(shown.experiment, *shown.framed_body);
        if (const std::string why = track_budget_problem(*model, shown.experiment, *track);
            !why.empty()) {
            set_status(s, "load track: " + why, true);
            return false;
        }
        c.track_warning = evo::track_span_warning(*track, shown.experiment);
        c.track = track;
        c.track_path = absolute;
        c.framed_body = s.bodies.shown->framed_body;
        c.experiment = s.bodies.shown->experiment;
        c.body_id = s.bodies.shown->id;
        c.body_label = s.bodies.shown->label;
        CalibrationJob job;
        job.experiment = c.experiment;
        job.framed_body = c.framed_body;
        job.track = track;
        job.threads = c.threads;
        c.session.start(std::move(job));
        set_status(s, "track " + file_name(absolute) + " loaded onto " + c.body_label +
                          ": simulating it at the track's times" +
                          (c.track_warning.empty() ? "" : "; warning: " + c.track_warning));
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

bool fit_name_applies(const std::string& name, const evo::Experiment& experiment) {
    try {
        evo::parse_fit_list(name, experiment);
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

std::string ticked_fit_list(const CalibrationState& c) {
    std::string list;
    for (std::size_t i = 0; i < c.fit_names.size() && i < c.fit_on.size(); ++i)
        if (c.fit_on[i] && fit_name_applies(c.fit_names[i], c.experiment))
            list += (list.empty() ? "" : ",") + c.fit_names[i];
    return list;
}

bool start_calibration(Studio& s) {
    auto& c = s.calibration;
    if (!c.track) {
        set_status(s, "calibrate: load a track first", true);
        return false;
    }
    if (c.session.running()) {
        set_status(s, "calibrate: already running", true);
        return false;
    }
    if (!evo::calibration_available()) {
        set_status(s, "calibrate: bhm was built without NLopt (Debian's libnlopt-cxx-dev)", true);
        return false;
    }
    if (c.max_simulations < 1) {
        set_status(s, "calibrate: the simulation budget must be at least 1", true);
        return false;
    }
    try {
        CalibrationJob job;
        job.experiment = c.experiment;
        job.framed_body = c.framed_body;
        job.track = c.track;
        job.parameters = evo::parse_fit_list(ticked_fit_list(c), c.experiment);
        job.threads = c.threads;
        job.max_simulations = c.max_simulations;
        c.session.start(std::move(job));
        set_status(s, "calibrating " + ticked_fit_list(c) + " against " + file_name(c.track_path));
        return true;
    } catch (const std::exception& e) {
        set_status(s, std::string("calibrate: ") + e.what(), true);
        return false;
    }
}

bool cancel_calibration(Studio& s) {
    if (!s.calibration.session.running()) return false;
    s.calibration.session.cancel();
    set_status(s, "calibration cancelled");
    return true;
}

void show_calibrated_body(Studio& s) {
    const auto& c = s.calibration;
    const auto snap = c.snapshot;
    if (!snap || !snap->result || !s.bodies.shown || s.bodies.shown->framed_body != c.framed_body)
        return;
    // The replay (and a video exported from it) must move as the fitted values say, and a
    // champion compared beside it belongs to another question (issue 39, M7).
    clear_compared_body(s);
    SimulationRequest request;
    request.id = c.body_id;
    request.label = c.body_label + ", calibrated against " + file_name(c.track_path);
    request.experiment = snap->result->calibrated.experiment;
    request.framed_body = c.framed_body;
    s.bodies.follow_champion = false;
    s.bodies.simulator.request(std::move(request));
}

bool apply_calibration(Studio& s) {
    auto& c = s.calibration;
    const auto snap = c.snapshot;
    if (!snap || snap->phase != CalibrationPhase::Finished || !snap->result) {
        set_status(s, "apply: no finished calibration", true);
        return false;
    }
    const auto& r = *snap->result;
    auto next = s.document.experiment();
    try {
        evo::copy_fitted_values(r.calibrated.experiment, snap->parameters, next);
    } catch (const std::exception& e) {
        set_status(s, std::string("apply: ") + e.what(), true);
        return false;
    }
    std::string label = "calibrated against " + file_name(c.track_path) + ":";
    for (const auto& f : r.fitted)
        label += " " + f.parameter.name + " " + number(f.initial_value) + " -> " +
                 number(f.value) + " " + evo::fit_unit(f.parameter) + ",";
    label.pop_back();
    if (!r.converged) label += " (not converged: the fit stopped at its simulation budget)";
    if (!apply_edit(s, next, label)) return false;
    c.applied_job = snap->job;
    show_calibrated_body(s);
    // The live run keeps its physics until Apply to the live run sends them.
    if (run_is_live(s.run.evolution.phase()) && editing_run_document(s))
        set_status(s, label + " (the live run keeps its physics: Apply to the live run changes it)");
    return true;
}

bool apply_calibration_to_run(Studio& s) {
    auto& c = s.calibration;
    const auto snap = c.snapshot;
    if (!snap || snap->phase != CalibrationPhase::Finished || !snap->result) {
        set_status(s, "apply to the live run: no finished calibration", true);
        return false;
    }
    const auto run = s.run.evolution.snapshot();
    if (!run || !run->loaded || !run_is_live(s.run.evolution.phase())) {
        set_status(s, "apply to the live run: no live run", true);
        return false;
    }
    // The run's own rules (its physics as last committed) with the fitted values in place.
    evo::Experiment next = run->experiment;
    std::string what;
    try {
        evo::copy_fitted_values(snap->result->calibrated.experiment, snap->parameters, next);
        const evo::PhysicsRules physics = evo::physics_of(next);
        what = evo::describe_physics_change(run->experiment, physics);
        s.run.evolution.change_physics(physics);
    } catch (const std::exception& e) {
        set_status(s, std::string("apply to the live run: ") + e.what(), true);
        return false;
    }
    c.applied_run_job = snap->job;
    if (editing_run_document(s)) {
        auto doc = s.document.experiment();
        try {
            evo::copy_fitted_values(snap->result->calibrated.experiment, snap->parameters, doc);
        } catch (const std::exception&) {
            doc = s.document.experiment();  // the run has it; the document stays as it is
        }
        if (!(doc == s.document.experiment()) &&
            apply_edit(s, doc, "calibrated against " + file_name(c.track_path) + " (live run)"))
            c.applied_job = snap->job;
    }
    set_status(s, "live run, from generation " + std::to_string(run->generation) + ": " + what +
                      " (calibrated against " + file_name(c.track_path) +
                      "); every member is simulated again under it");
    return true;
}

void update_calibration(Studio& s) {
    auto& c = s.calibration;
    c.snapshot = c.session.snapshot();
    if (!c.snapshot) return;
    const auto& snap = *c.snapshot;
    if (snap.job == c.seen_job && snap.phase == c.seen_phase) return;
    c.seen_job = snap.job;
    c.seen_phase = snap.phase;
    if (snap.phase == CalibrationPhase::Failed) {
        set_status(s, "calibration failed: " + snap.error, true);
    } else if (snap.phase == CalibrationPhase::Cancelled) {
        set_status(s, "calibration cancelled after " + std::to_string(snap.simulations) +
                          " simulations");
    } else if (snap.phase == CalibrationPhase::Finished && snap.result) {
        const auto& r = *snap.result;
        // A fit the budget cut short is not "done": its values are not an optimum (issue 39, M3).
        set_status(s, std::string(r.converged ? "calibration done"
                                              : "calibration stopped at its simulation budget, "
                                                "not converged") +
                          ": misfit " + number(r.misfit_before_m) + " m -> " +
                          number(r.misfit_after_m) + " m, " +
                          std::to_string(r.optimiser_simulations + r.jacobian_simulations + 2) +
                          " simulations" +
                          (r.warnings.empty() ? std::string()
                                              : ", " + std::to_string(r.warnings.size()) +
                                                    " warnings"));
    } else if (snap.phase == CalibrationPhase::Finished && snap.preview) {
        set_status(s, snap.preview->diverged
                          ? "the track's body diverged: " + snap.preview->divergence_reason
                          : "track simulated: misfit " + number(snap.best_misfit_m) +
                                " m against a motion of " +
                                number(evo::track_motion_rms(*snap.track)) + " m" +
                                (s.calibration.track_warning.empty()
                                     ? ""
                                     : "; warning: " + s.calibration.track_warning),
                   snap.preview->diverged);
    }
}

bool calibration_running(const Studio& s) { return s.calibration.session.running(); }

}  // namespace bhm::app::gui
