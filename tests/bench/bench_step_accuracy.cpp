// bench_step_accuracy: the step-accuracy gate's bodies (the paper's anchor scenes,
// tests/engine/test_engine_step_accuracy.cpp, and the corpus bodies of
// tests/evo/test_step_accuracy_corpus.cpp) run with a trial setting against the gate's converged
// reference, and each body's error printed, for probing why the step cannot grow (issue 42,
// docs/benchmarks.md "Issue 42: the step size itself"). The reference is always the gate's: the
// body as given at dt_fraction 0.2, explicit damping, rotary_inertia_scale 1; the probe options
// that change the body (--nu0, --mu0, --no-floor, --no-gravity) change it in both.
//
//   bench_step_accuracy [--dt-fraction F] [--rot-scale S] [--sweeps N] [--nu0] [--mu0]
//                       [--no-floor] [--no-gravity] [--only NAME] [--anchors-only] [--corpus-only]
//                       [--trials F:S,F:S,...]
//
// One CSV line per body: name, dt_s of the trial, RMS error (m), swing (m), error % of swing.
// --trials runs several (dt_fraction, rotary_inertia_scale) trials against one reference run per
// body (the reference at dt_fraction 0.2 costs several trials), one line per body and trial with
// the trial's F and S first, and the worst per trial at the end.
// Run from the repository root.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "tests/bench/bench_machine.hpp"
#include "tests/engine/engine_test_bodies.hpp"
#include "tests/support/step_accuracy.hpp"

namespace {

using bhm::engine::BodySpec;

struct Named {
    std::string name;
    BodySpec spec;
    double end_s;
    int samples;
};

// As tests/evo/test_step_accuracy_corpus.cpp's corpus_bodies.
void add_corpus(std::vector<Named>& out, const std::string& file, int min_voxels, int max_voxels,
                int count) {
    const std::string path = "tests/bench/corpus/" + file + ".json";
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path + " (run from the repository root)");
    const nlohmann::json corpus = nlohmann::json::parse(in);
    const std::string preset = corpus.at("experiment").get<std::string>();
    const bhm::evo::Experiment experiment =
        bhm::evo::load_experiment("assets/experiments/" + preset + ".json");
    int taken = 0;
    for (const auto& entry : corpus.at("bodies")) {
        if (taken == count) break;
        const auto body = bhm::evo::apply_frame_and_overrides(
            experiment, bhm::evo::parse_body(entry.at("body"), path));
        BodySpec spec = bhm::evo::make_body_spec(experiment, body, experiment.evolution.seed);
        int voxels = 0;
        for (auto m : spec.material)
            voxels += m != 0;
        if (voxels < min_voxels || voxels > max_voxels) continue;
        spec.actuation.start_s = 0.05;
        out.push_back({file + "/" + entry.at("name").get<std::string>(), spec, 0.2, 40});
        ++taken;
    }
}

int run(int argc, char** argv) {
    double dt_fraction = 0.9, rot_scale = 1.0;
    int sweeps = -1;
    bool nu0 = false, mu0 = false, no_floor = false, no_gravity = false, anchors = true,
         corpus = true;
    std::string only, trials_arg;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--dt-fraction")
            dt_fraction = std::stod(value());
        else if (a == "--rot-scale")
            rot_scale = std::stod(value());
        else if (a == "--sweeps")
            sweeps = std::stoi(value());
        else if (a == "--nu0")
            nu0 = true;
        else if (a == "--mu0")
            mu0 = true;
        else if (a == "--no-floor")
            no_floor = true;
        else if (a == "--no-gravity")
            no_gravity = true;
        else if (a == "--only")
            only = value();
        else if (a == "--anchors-only")
            corpus = false;
        else if (a == "--corpus-only")
            anchors = false;
        else if (a == "--trials")
            trials_arg = value();
        else
            throw std::runtime_error("unknown argument " + a);
    }
    std::vector<Named> bodies;
    if (anchors) {
        using bhm::engine::test::Scene;
        for (Scene s : {Scene::AllActive, Scene::Banded, Scene::Framed}) {
            const std::string n = "anchor-" + std::to_string(static_cast<int>(s));
            bodies.push_back({n + "@14.47", bhm::engine::test::paper_scene(s, 14.47), 0.3, 60});
            bodies.push_back({n + "@39", bhm::engine::test::paper_scene(s, 39.0), 0.45, 60});
        }
    }
    if (corpus) {
        for (const char* file : {"paper-exp1", "paper-exp1-attached", "paper-exp2"})
            add_corpus(bodies, file, 10, 300, 7);
        for (const char* file :
             {"paper-exp1-champions", "paper-exp2-champions", "paper-exp1-attached-champions"})
            add_corpus(bodies, file, 10, 450, 2);
    }
    struct Trial {
        double dt_fraction, rot_scale, worst;
    };
    std::vector<Trial> trials;
    for (std::size_t at = 0; at < trials_arg.size();) {
        std::size_t end = trials_arg.find(',', at);
        if (end == std::string::npos) end = trials_arg.size();
        const std::string t = trials_arg.substr(at, end - at);
        const std::size_t colon = t.find(':');
        if (colon == std::string::npos) throw std::runtime_error("--trials wants F:S, got " + t);
        trials.push_back({std::stod(t.substr(0, colon)), std::stod(t.substr(colon + 1)), 0.0});
        at = end + 1;
    }
    const bool listed = !trials.empty();
    if (!listed) trials.push_back({dt_fraction, rot_scale, 0.0});
    std::puts(listed ? "dt_fraction,rot_scale,body,dt_s,rms_m,swing_m,error_pct"
                     : "body,dt_s,rms_m,swing_m,error_pct");
    for (Named& b : bodies) {
        if (!only.empty() && b.name.find(only) == std::string::npos) continue;
        BodySpec& s = b.spec;
        for (auto& m : s.materials) {
            if (nu0) m.poisson_ratio = 0.0;
            if (mu0) m.static_friction = m.dynamic_friction = 0.0;
        }
        if (no_floor) s.environment.floor = false;
        if (no_gravity) s.environment.gravity_m_s2 = 0.0;
        BodySpec reference = s;
        reference.dt_fraction = bhm::test::kReferenceDtFraction;
        reference.damping.implicit_sweeps = 0;
        reference.rotary_inertia_scale = 1.0;
        const auto ref = bhm::test::sampled_positions(reference, b.end_s, b.samples);
        for (Trial& t : trials) {
            BodySpec trial = s;
            trial.dt_fraction = t.dt_fraction;
            trial.rotary_inertia_scale = t.rot_scale;
            if (sweeps >= 0) trial.damping.implicit_sweeps = sweeps;
            const auto got = bhm::test::sampled_positions(trial, b.end_s, b.samples);
            const double dt = bhm::engine::Model::build(trial)->dt_s();
            bhm::test::TrajectoryError e{INFINITY, 1.0};
            if (!ref.empty() && got.size() == ref.size())
                e = bhm::test::trajectory_error(got, ref, b.samples);
            if (listed) std::printf("%g,%g,", t.dt_fraction, t.rot_scale);
            std::printf("%s,%.6g,%.6g,%.6g,%.4f\n", b.name.c_str(), dt, e.rms_m, e.swing_m,
                        100.0 * e.relative());
            std::fflush(stdout);
            t.worst = std::max(t.worst, e.relative());
        }
    }
    for (const Trial& t : trials) {
        if (listed)
            std::printf("# worst F %g S %g: %.4f %%\n", t.dt_fraction, t.rot_scale,
                        100.0 * t.worst);
        else
            std::printf("# worst %.4f %%\n", 100.0 * t.worst);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return bhm::bench::run_guarded("bench_step_accuracy", run, argc, argv);
}
