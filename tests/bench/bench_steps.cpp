// bench_steps: thread CPU seconds of N World steps of the first K bodies of one corpus file, and
// a hash of their final centres of mass (equal hashes: the same trajectories, bit for bit). For
// A/B measurements of an engine change on a shared machine (issue 42): copy one build's binary
// away, run both alternately for many rounds and compare the minimum CPU seconds of each, which
// the other jobs' load inflates least (docs/benchmarks.md, "Issue 42: the step's levers").
//
//   bench_steps CORPUS-FILE [--bodies K] [--steps N | --sim-s T] [--rot-scale S]
//               [--dt-fraction F] [--assets DIR]
//
// One line on stdout: cpu_s, voxel-steps per CPU second, the hash, and the CPU seconds per
// simulated second of a voxel (cpu_s over the sum of voxels x simulated seconds). --sim-s steps
// each body to T simulated seconds instead of N steps, and --rot-scale and --dt-fraction set the
// bodies' rotary_inertia_scale and dt_fraction, so a longer step is compared per simulated
// second (issue 42). Run from the repository root.
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <string>

#include "engine/model.hpp"
#include "engine/world.hpp"
#include "tests/bench/bench_machine.hpp"
#include "tests/support/engine_fingerprint.hpp"

namespace {

double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

constexpr const char* kUsage =
    "usage: bench_steps CORPUS-FILE [--bodies K] [--steps N | --sim-s T] [--rot-scale S] "
    "[--dt-fraction F] [--assets DIR]";

int run(int argc, char** argv) {
    std::string file, assets = "assets/experiments";
    long bodies = 6, steps = 1500;
    double sim_s = 0.0, rot_scale = 1.0, dt_fraction = 0.0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto number = [&](const char* name) {
            if (i + 1 >= argc) throw std::runtime_error(std::string(name) + " needs a value");
            char* end = nullptr;
            const long n = std::strtol(argv[++i], &end, 10);
            if (*end != '\0' || n < 1)
                throw std::runtime_error(std::string(name) + " must be a positive whole number");
            return n;
        };
        if (a == "--bodies")
            bodies = number("--bodies");
        else if (a == "--steps")
            steps = number("--steps");
        else if (a == "--sim-s" && i + 1 < argc)
            sim_s = std::stod(argv[++i]);
        else if (a == "--dt-fraction" && i + 1 < argc)
            dt_fraction = std::stod(argv[++i]);
        else if (a == "--rot-scale" && i + 1 < argc)
            rot_scale = std::stod(argv[++i]);
        else if (a == "--assets" && i + 1 < argc)
            assets = argv[++i];
        else if (a == "--help") {
            std::puts(kUsage);
            return 0;
        } else if (file.empty() && a.rfind("--", 0) != 0)
            file = a;
        else
            throw std::runtime_error("unknown argument " + a + "\n" + kUsage);
    }
    if (file.empty()) throw std::runtime_error(std::string("no corpus file\n") + kUsage);
    const bhm::test::Corpus corpus = bhm::test::load_corpus(file, assets);
    double cpu = 0.0;
    double voxel_steps = 0.0, voxel_seconds = 0.0;
    std::size_t hash = 0;
    for (long b = 0; b < bodies && b < static_cast<long>(corpus.bodies.size()); ++b) {
        const bhm::test::CorpusBody& body = corpus.bodies[static_cast<std::size_t>(b)];
        bhm::engine::BodySpec spec = body.spec;
        spec.rotary_inertia_scale = rot_scale;
        if (dt_fraction > 0.0) spec.dt_fraction = dt_fraction;
        bhm::engine::World world(bhm::engine::Model::build(spec));
        const double dt = world.model().dt_s();
        const long n = sim_s > 0.0 ? static_cast<long>(std::ceil(sim_s / dt)) : steps;
        const double start = thread_cpu_s();
        for (long s = 0; s < n; ++s)
            world.step();
        cpu += thread_cpu_s() - start;
        voxel_steps += static_cast<double>(n) * body.voxels;
        voxel_seconds += static_cast<double>(n) * dt * body.voxels;
        const auto com = world.centre_of_mass_m();
        for (double x : com)
            hash = hash * 31 + std::hash<double>{}(x);
        if (world.diverged()) std::fprintf(stderr, "%s diverged\n", body.name.c_str());
    }
    std::printf("%.4f %.3f %zx %.6g\n", cpu, voxel_steps / cpu / 1e6, hash, cpu / voxel_seconds);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return bhm::bench::run_guarded("bench_steps", run, argc, argv);
}
