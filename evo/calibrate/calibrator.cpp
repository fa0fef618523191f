#include "evo/calibrate/calibrator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "evo/calibrate/gauss_newton_polish.hpp"
#include "evo/calibrate/identifiability.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/worker_pool.hpp"

#ifdef BHM_WITH_NLOPT
#include <nlopt.hpp>
#endif

namespace bhm::evo {

bool calibration_available() {
#ifdef BHM_WITH_NLOPT
    return true;
#else
    return false;
#endif
}

#ifdef BHM_WITH_NLOPT
namespace {

// One standard deviation of x beyond which a parameter is reported as poorly determined: a
// factor of e^0.5 = 1.65 either way (0.5 rad for the phase lag).
constexpr double kPoorlyDetermined = 0.5;
// A Gauss-Newton step from the result beyond both of these (in x: log units, or rad) means the
// fit stopped short of its minimum; within them it is at the minimum as far as the Jacobian's
// finite differences and the optimiser's tolerance tell.
constexpr double kShortOfMinimumSigmas = 3.0;
constexpr double kShortOfMinimum = 0.01;

// The search range as a reader knows it: "x1/5..5" (the default), the factors where a field's
// own range narrowed it (a muscle's time constants), or the added angle.
std::string search_range(const FitParameter& p) {
    if (!p.log_scale) return "-pi..pi";
    if (std::abs(p.lower + std::log(5.0)) < 1e-12 && std::abs(p.upper - std::log(5.0)) < 1e-12)
        return "x1/5..5";
    char text[64];
    std::snprintf(text, sizeof text, "x%.3g..%.3g", std::exp(p.lower), std::exp(p.upper));
    return text;
}

std::string join_names(const std::vector<FitParameter>& ps, const std::vector<int>& group) {
    std::string s;
    for (int i : group) s += (s.empty() ? "" : ", ") + ps[static_cast<std::size_t>(i)].name;
    return s;
}

// Jacobian of the residuals by central differences (one-sided at a bound), 2p simulations on
// the worker pool. Returns jac[k][i].
std::vector<std::vector<double>> residual_jacobian(const TrackProblem& problem,
                                                   TrackBatches& batches,
                                                   const std::vector<double>& x,
                                                   const CalibrationOptions& o) {
    const auto& ps = *problem.parameters;
    const auto& track = *problem.track;
    const std::size_t p = ps.size();
    std::vector<std::vector<double>> xs(2 * p, x);
    std::vector<double> span(p);
    for (std::size_t i = 0; i < p; ++i) {
        const double hi = std::min(ps[i].upper, x[i] + o.jacobian_step);
        const double lo = std::max(ps[i].lower, x[i] - o.jacobian_step);
        xs[2 * i][i] = hi;
        xs[2 * i + 1][i] = lo;
        span[i] = hi - lo;
    }
    std::vector<SimulatedTrack> sims;
    batches.simulate(problem, xs, sims, o.cancel, nullptr);
    std::vector<std::vector<double>> r(2 * p);
    for (std::size_t j = 0; j < sims.size(); ++j) {
        if (sims[j].diverged)
            throw std::runtime_error("the simulation diverged next to the optimum (" +
                                     sims[j].divergence_reason + "): no uncertainty");
        r[j] = track_residuals(track, sims[j]);
    }
    const std::size_t n = r[0].size();
    std::vector<std::vector<double>> jac(n, std::vector<double>(p, 0.0));
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t i = 0; i < p; ++i)
            jac[k][i] = (r[2 * i][k] - r[2 * i + 1][k]) / span[i];
    return jac;
}

}  // namespace
#endif

CalibrationResult calibrate(const Experiment& e, const Body& body, const MeasuredTrack& track,
                            const std::vector<FitParameter>& ps, const CalibrationOptions& o) {
#ifndef BHM_WITH_NLOPT
    (void)e, (void)body, (void)track, (void)ps, (void)o;
    throw std::runtime_error(
        "bhm was built without NLopt (Debian's libnlopt-cxx-dev), so it cannot calibrate");
#else
    const auto start = std::chrono::steady_clock::now();
    const std::size_t p = ps.size();
    const TrackProblem problem{&e, &ps, &body, &track};
    const std::shared_ptr<TrackBatches> batches =
        o.batches ? o.batches
                  : std::make_shared<ThreadTrackBatches>(resolve_thread_count(o.threads));
    CalibrationResult out;
    out.motion_rms_m = track_motion_rms(track);
    std::vector<double> x(p, 0.0);
    out.before = simulate_track(apply_fit(e, ps, x), body, track, o.cancel);
    out.misfit_before_m = track_misfit(track, out.before);
    // A diverged trial is worse than any real one but finite, so BOBYQA's model stays usable.
    const double diverged_misfit =
        1e3 * std::max({out.motion_rms_m, 1e-3 * e.voxel_size_m,
                        std::isfinite(out.misfit_before_m) ? out.misfit_before_m : 0.0});
    double best = std::isfinite(out.misfit_before_m) ? out.misfit_before_m : diverged_misfit;
    std::vector<double> best_x = x;
    int sims = 0;
    auto objective = [&](const std::vector<double>& trial) {
        const auto sim = simulate_track(apply_fit(e, ps, trial), body, track, o.cancel);
        ++sims;
        const double m = sim.diverged ? diverged_misfit : track_misfit(track, sim);
        if (m < best) {
            best = m;
            best_x = trial;
        }
        if (o.progress) o.progress(sims, best);
        // BOBYQA models its objective as a quadratic: the mean square is one near the optimum,
        // the RMS has a cusp there.
        return m * m;
    };
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(p));
    std::vector<double> lower(p), upper(p), step(p);
    for (std::size_t i = 0; i < p; ++i) {
        lower[i] = ps[i].lower;
        upper[i] = ps[i].upper;
        step[i] = 0.1 * (upper[i] - lower[i]);
    }
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_xtol_abs(o.x_tolerance);
    // The misfit of a mostly quasi-static track is bumpy in the weakly seen parameters (E at a
    // slow drive), so a local search from the experiment's values alone can stop in a side valley.
    // First a scan of the box (a Halton sequence, all at once on the worker pool), then BOBYQA
    // from the experiment's values and from the best scan points.
    const int budget = std::max(o.max_simulations, static_cast<int>(2 * p + 2));
    // The Gauss-Newton polish after BOBYQA gets whatever BOBYQA leaves, and no reserve: that is
    // where it helps (BOBYQA stopped early, calling itself converged in a narrow valley). A
    // reserve of a tenth was measured on a simulated muscle catheter fit, where BOBYQA lost more
    // to it than the polish won back (docs/calibration.md).
    const int search_budget = budget;
    const int scan = std::min(budget / 3, std::max(8, 8 * static_cast<int>(p)));
    std::vector<std::vector<double>> scan_x(static_cast<std::size_t>(scan), std::vector<double>(p));
    constexpr int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47};
    for (int j = 0; j < scan; ++j)
        for (std::size_t i = 0; i < p; ++i) {
            const int base = kPrimes[i % std::size(kPrimes)];
            double f = 1.0, u = 0.0;
            for (int k = j + 1; k > 0; k /= base) f /= base, u += f * (k % base);
            scan_x[static_cast<std::size_t>(j)][i] = lower[i] + u * (upper[i] - lower[i]);
        }
    std::vector<double> scan_misfit(static_cast<std::size_t>(scan));
    // Progress from the scan too (a third of the budget): one report at a time, under a lock.
    int scan_done = 0;
    double scan_best = best;
    std::vector<SimulatedTrack> scan_sims;
    batches->simulate(problem, scan_x, scan_sims, o.cancel,
                      [&](std::size_t, const SimulatedTrack& sim) {  // one call at a time
                          const double m = sim.diverged ? diverged_misfit : track_misfit(track, sim);
                          ++scan_done;
                          scan_best = std::min(scan_best, m);
                          if (o.progress) o.progress(sims + scan_done, scan_best);
                      });
    for (std::size_t j = 0; j < scan_sims.size(); ++j)
        scan_misfit[j] =
            scan_sims[j].diverged ? diverged_misfit : track_misfit(track, scan_sims[j]);
    sims += scan;
    out.scan_simulations = scan;
    std::vector<int> order(static_cast<std::size_t>(scan));
    for (int j = 0; j < scan; ++j) order[static_cast<std::size_t>(j)] = j;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return scan_misfit[static_cast<std::size_t>(a)] < scan_misfit[static_cast<std::size_t>(b)];
    });
    for (int j : order)
        if (scan_misfit[static_cast<std::size_t>(j)] < best) {
            best = scan_misfit[static_cast<std::size_t>(j)];
            best_x = scan_x[static_cast<std::size_t>(j)];
        }
    if (o.progress) o.progress(sims, best);
    std::vector<std::vector<double>> starts = {x};
    for (std::size_t k = 0; k < std::min<std::size_t>(2, order.size()); ++k)
        starts.push_back(scan_x[static_cast<std::size_t>(order[k])]);

    // BOBYQA's trust region can shrink onto a shallow valley before reaching its floor; restarting
    // from the best point of the search with a fresh, smaller region finds the rest; passes stop
    // once one no longer improves that search's misfit by 1 %.
    // Whether the pass that found the best point stopped by its own criterion rather than at the
    // budget; false while no pass has reached the best point (the scan's best).
    bool best_converged = false;
    for (const auto& start : starts) {
        std::vector<double> here = start;
        double here_best = std::numeric_limits<double>::infinity();
        auto tracked = [&](const std::vector<double>& trial) {
            const double m = objective(trial);
            if (m < here_best) here_best = m, here = trial;
            return m;
        };
        using Tracked = decltype(tracked);
        opt.set_min_objective(
            [](const std::vector<double>& trial, std::vector<double>&, void* data) {
                return (*static_cast<Tracked*>(data))(trial);
            },
            &tracked);
        for (int pass = 0; pass < 4; ++pass) {
            if (sims + static_cast<int>(2 * p + 2) > search_budget) break;
            const double before_pass = here_best;
            std::vector<double> pass_step(p);
            for (std::size_t i = 0; i < p; ++i)
                pass_step[i] = std::min(step[i] / static_cast<double>(1 << pass),
                                        0.5 * std::max(upper[i] - here[i], here[i] - lower[i]));
            opt.set_initial_step(pass_step);
            opt.set_maxeval(search_budget - sims);
            x = here;
            double final_value = 0.0;
            bool pass_converged = false;
            try {
                const nlopt::result r = opt.optimize(x, final_value);
                pass_converged = r != nlopt::MAXEVAL_REACHED;
                out.stop_reason = r == nlopt::MAXEVAL_REACHED ? "simulation budget reached"
                                  : r == nlopt::XTOL_REACHED  ? "parameters converged"
                                  : r == nlopt::FTOL_REACHED  ? "misfit converged"
                                  : r == nlopt::SUCCESS       ? "converged"
                                                              : "optimiser stopped (" +
                                                                  std::to_string(static_cast<int>(r)) + ")";
            } catch (const nlopt::roundoff_limited&) {
                if (o.cancel && o.cancel->load()) throw EvaluationCancelled();
                out.stop_reason = "optimiser limited by round-off";
                pass_converged = true;  // as far as the misfit's precision allows
            } catch (...) {
                // NLopt's C++ wrapper swallows the objective's exceptions and throws its own
                // (nlopt failure): a cancelled simulation must still say it was cancelled.
                if (o.cancel && o.cancel->load()) throw EvaluationCancelled();
                throw;
            }
            ++out.optimiser_passes;
            // This start holds the best point found so far (its objective is the squared
            // misfit): whether the best point is an optimum is whether this pass converged.
            if (std::sqrt(here_best) <= best * (1.0 + 1e-12)) best_converged = pass_converged;
            if (pass > 0 && here_best > 0.99 * before_pass) break;
        }
    }
    out.converged = best_converged;
    if (!out.converged) out.stop_reason = "simulation budget reached";
    out.x = best_x;
    out.calibrated = apply_fit(e, ps, out.x);
    out.after = simulate_track(out.calibrated, body, track, o.cancel);
    out.misfit_after_m = track_misfit(track, out.after);

    auto jac = residual_jacobian(problem, *batches, out.x, o);
    out.jacobian_simulations = static_cast<int>(2 * p);

    // The Gauss-Newton polish from BOBYQA's result, on the Jacobian just taken, with the budget
    // BOBYQA left; the Jacobian at the point it reaches is the one the
    // uncertainty below uses.
    std::vector<std::pair<std::vector<double>, SimulatedTrack>> trials;
    PolishProblem polish{lower, upper, nullptr, nullptr, static_cast<int>(2 * p)};
    polish.residuals = [&](const std::vector<double>& trial) {
        SimulatedTrack sim = simulate_track(apply_fit(e, ps, trial), body, track, o.cancel);
        ++sims;
        auto r = track_residuals(track, sim);
        best = std::min(best, residual_rms(r));
        if (o.progress) o.progress(sims, best);
        trials.emplace_back(trial, std::move(sim));
        return r;
    };
    polish.jacobian = [&](const std::vector<double>& at) {
        auto j = residual_jacobian(problem, *batches, at, o);
        sims += static_cast<int>(2 * p);
        if (o.progress) o.progress(sims, best);
        return j;
    };
    PolishOptions polish_options;
    polish_options.max_simulations = std::max(0, budget - sims);
    polish_options.x_tolerance = o.x_tolerance;
    const PolishResult polished = gauss_newton_polish(
        polish, out.x, track_residuals(track, out.after), jac, polish_options);
    out.polish_steps = polished.steps;
    out.polish_simulations = polished.simulations;
    out.polish_stop = polished.stop;
    out.misfit_before_polish_m = out.misfit_after_m;
    if (polished.steps > 0) {
        out.x = polished.x;
        for (auto& [at, sim] : trials)
            if (at == out.x) out.after = std::move(sim);
        out.calibrated = apply_fit(e, ps, out.x);
        out.misfit_after_m = track_misfit(track, out.after);
        jac = polished.jacobian;
    }
    out.optimiser_simulations = sims;
    out.good_fit = out.misfit_after_m <= o.good_fit_fraction * out.motion_rms_m;
    const std::size_t n = jac.size();
    const double ssr = out.misfit_after_m * out.misfit_after_m * static_cast<double>(n);
    // Degrees of freedom: the values less the parameters and the fitted offsets (one per point
    // and axis, track_residuals).
    const std::size_t offsets = track.t_s.empty() ? 0 : n / track.t_s.size();
    const std::size_t dof = n > p + offsets ? n - p - offsets : n;
    out.identifiability = analyse_identifiability(jac, ssr / static_cast<double>(dof));
    const auto& id = out.identifiability;
    if (!out.converged)
        out.warnings.push_back(
            "not converged: the fit stopped at its simulation budget (" + std::to_string(budget) +
            "), so the values are the best found, not the best fit, and may be further off than "
            "their standard deviations; calibrate again with a larger budget");
    // The optimiser's own stop does not prove a minimum: in a narrow valley (a fused muscle
    // train's rise_s against its contraction strain, correlation 0.9) BOBYQA stopped with
    // rise_s 18 standard deviations from the truth and called it converged. The polish steps
    // toward the minimum; one more Gauss-Newton step from where it stopped, on the Jacobian
    // there, says whether the minimum is still far (its budget ran out, or no step helped).
    if (out.converged && !id.near_singular) {
        const auto step = gauss_newton_step(jac, track_residuals(track, out.after));
        for (std::size_t i = 0; i < step.size(); ++i) {
            const double sigmas = std::abs(step[i]) / id.sigma_x[i];
            if (!(std::abs(step[i]) > kShortOfMinimum) || !(sigmas > kShortOfMinimumSigmas))
                continue;
            out.converged = false;
            out.stop_reason = "stopped short of the least-squares minimum";
            char size[32];
            std::snprintf(size, sizeof size, "%.3g", sigmas);
            out.warnings.push_back(
                "not converged: the optimiser stopped short of the least-squares minimum (a "
                "Gauss-Newton step from the result would move " +
                ps[i].name + " by " + size +
                " standard deviations), so the values may be further off than their standard "
                "deviations; calibrate again from the result, or against a track that separates "
                "the parameters (for a muscle, widely spaced twitches)");
            break;
        }
    }
    for (std::size_t i = 0; i < p; ++i) {
        FittedParameter f;
        f.parameter = ps[i];
        f.x = out.x[i];
        f.initial_value = fit_value(e, ps[i], 0.0);
        f.value = fit_value(e, ps[i], out.x[i]);
        // d value / d x = value for a log-scale parameter, 1 for the phase lag.
        f.sigma = id.sigma_x[i] * (ps[i].log_scale ? std::abs(f.value) : 1.0);
        f.at_bound = out.x[i] <= ps[i].lower + 1e-3 || out.x[i] >= ps[i].upper - 1e-3;
        if (f.at_bound)
            out.warnings.push_back(ps[i].name + " ended at a bound of its search range (" +
                                   search_range(ps[i]) + "): the optimum may lie beyond");
        out.fitted.push_back(f);
    }
    for (std::size_t i = 0; i < p; ++i)
        if (std::isfinite(id.sigma_x[i]) && id.sigma_x[i] > kPoorlyDetermined)
            out.warnings.push_back(ps[i].name + " is poorly determined by the track (one standard "
                                   "deviation is " +
                                   std::to_string(id.sigma_x[i]) +
                                   (ps[i].log_scale ? " in log units" : " rad") + ")");
    for (int i : id.no_effect)
        out.warnings.push_back(ps[static_cast<std::size_t>(i)].name +
                               " does not change the simulated track: it cannot be fitted from it");
    for (const auto& group : id.trade_offs)
        out.warnings.push_back(join_names(ps, group) +
                               " trade off: the track cannot tell them apart, so their fitted "
                               "values are one of many equally good combinations");
    if (id.near_singular && id.trade_offs.empty() && id.no_effect.empty())
        out.warnings.push_back("the misfit's curvature is near singular: the uncertainties are "
                               "not meaningful");
    if (!out.good_fit)
        out.warnings.push_back(
            "poor fit: the misfit after calibration is " +
            std::to_string(out.motion_rms_m > 0 ? out.misfit_after_m / out.motion_rms_m : 0.0) +
            " of the track's motion; the body, the track or the fitted parameters do not match");
    out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
#endif
}

}  // namespace bhm::evo
