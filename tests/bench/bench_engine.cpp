// Engine speed in voxel-steps per second on named scenes, one thread each, plus two simulations
// on two threads (how well independent Worlds sharing one Model scale, as evolution runs them),
// then on the corpus of realistic bodies in tests/bench/corpus (random CPPN bodies of each paper
// preset): per corpus the minimum, median and maximum voxel-steps/s over its bodies and the
// simulations per second of the paper's full 1 s + 10 s evaluation (model build included).
// Writes CSV to stdout, one row per scene and per corpus:
//   name,bodies,voxels,links,steps,wall_s,cpu_s,voxel_steps_per_s,min_voxel_steps_per_s,
//   median_voxel_steps_per_s,max_voxel_steps_per_s,simulations_per_s_11s,build_us,machine,commit
//   bench_engine [--steps-scale X] [--commit SHA] [--corpus DIR] [--assets DIR] [--scenes-only]
//                [--corpus-only] [--min-voxels N] [--max-voxels N] [--per-body] [--fingerprint]
//                [--poisson-off] [--scene NAME]
// --poisson-off sets every material's Poisson ratio to 0, which turns the Poisson coupling
// (engine/internal/poisson.hpp) off: the difference to a normal run is that coupling's cost (its own pass
// and the shorter stable step of its volumetric stiffness).
// Rates are per CPU second of the stepping thread (CLOCK_THREAD_CPUTIME_ID), so a machine shared
// with other jobs distorts them less than wall time would; the "_2threads" row is the exception:
// it measures scaling, so it uses wall time and counts both worlds (voxels and links are the sum,
// steps are per world, the rate is the aggregate; its factor vs one thread goes to stderr).
// A corpus row's voxels and links are the means over its bodies, steps the total; the corpus
// figures cover bodies with min-voxels <= voxels <= max-voxels (default: all).
// The commit comes from --commit or $BHM_COMMIT (scripts/bench.sh passes git rev-parse --short
// HEAD). Run from the repository root (the corpus and presets are found by relative path).
#include <sys/utsname.h>
#include <time.h>

#include <algorithm>
#include <barrier>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"
#include "tests/support/engine_fingerprint.hpp"

namespace {

using bhm::engine::BodySpec;
using bhm::engine::Material;
using bhm::test::EngineScene;
using bhm::test::state_fingerprint;
using Clock = std::chrono::steady_clock;

double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Result {
    std::string scene;
    int voxels = 0, links = 0;
    std::int64_t steps = 0;

    double wall_s = 0.0;
    double cpu_s = 0.0;
    double build_s = 0.0;   //!< Model::build + World construction
    bool use_wall = false;  //!< rate per wall second (the two-thread row)
    int edge_springs = 0;   //!< springs across voxel edges (mixed bodies; --per-body)
    double voxel_steps_per_s() const {
        return static_cast<double>(voxels) * static_cast<double>(steps) /
               (use_wall ? wall_s : cpu_s);
    }
};

void step_world(bhm::engine::World& world, std::int64_t steps, const std::string& scene) {
    for (std::int64_t i = 0; i < steps; ++i)
        world.step();
    // A diverged world stops stepping, which would time as impossibly fast: refuse the figure.
    if (world.diverged())
        throw std::runtime_error(scene + ": the simulation diverged (" + world.divergence_reason() +
                                 "); its timing would be meaningless");
}

// The spec as timed: with --poisson-off, every material's nu is 0 (the coupling off).
BodySpec as_timed(BodySpec spec, bool poisson_off) {
    if (poisson_off)
        for (Material& m : spec.materials)
            m.poisson_ratio = 0.0;
    return spec;
}

Result run_single(const std::string& name, const BodySpec& spec, std::int64_t steps,
                  bool fingerprint = false) {
    const double build_start = thread_cpu_s();
    const auto model = bhm::engine::Model::build(spec);
    bhm::engine::World world(model);
    const double build_s = thread_cpu_s() - build_start;
    const auto start = Clock::now();
    const double cpu_start = thread_cpu_s();
    step_world(world, steps, name);
    Result r{name, model->voxel_count(), model->link_count(), steps, 0.0, 0.0, build_s};
    r.edge_springs = model->edge_spring_count();
    r.cpu_s = thread_cpu_s() - cpu_start;
    r.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
    if (fingerprint)
        std::cerr << "fingerprint " << name << " " << steps << " steps: " << std::hex
                  << state_fingerprint(world) << std::dec << "\n";
    return r;
}

// Two Worlds of one shared Model, each stepped by its own thread, started together.
Result run_two_threads(const EngineScene& scene, std::int64_t steps) {
    const auto model = bhm::engine::Model::build(scene.spec);
    bhm::engine::World worlds[2] = {bhm::engine::World(model), bhm::engine::World(model)};
    std::barrier start_line(3);
    std::exception_ptr errors[2];
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t)
        threads.emplace_back([&, t] {
            start_line.arrive_and_wait();
            try {
                step_world(worlds[t], steps, scene.name + "_2threads");
            } catch (...) {
                errors[t] = std::current_exception();
            }
        });
    start_line.arrive_and_wait();
    const auto start = Clock::now();
    for (auto& th : threads)
        th.join();
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    for (auto& e : errors)
        if (e) std::rethrow_exception(e);
    Result r{scene.name + "_2threads", 2 * model->voxel_count(), 2 * model->link_count(), steps,
             wall};
    r.use_wall = true;
    return r;
}

// One corpus: a preset's bodies, each timed for about `voxel_steps` voxel-steps.
struct CorpusResult {
    std::string name;
    std::vector<Result> bodies;
    double full_evaluations_s = 0.0;  //!< CPU time of one 1 s + 10 s evaluation of every body
};

CorpusResult run_corpus(const std::string& path, const std::string& assets, double steps_scale,
                        int min_voxels, int max_voxels, bool per_body, bool fingerprint,
                        bool poisson_off) {
    const bhm::test::Corpus corpus = bhm::test::load_corpus(path, assets);
    const double evaluation_s = bhm::evo::evaluation_seconds(corpus.experiment);
    CorpusResult out{corpus.name, {}, 0.0};
    for (const bhm::test::CorpusBody& body : corpus.bodies) {
        if (body.voxels < min_voxels || body.voxels > max_voxels) continue;
        const BodySpec spec = as_timed(body.spec, poisson_off);
        Result r = run_single(body.name, spec, bhm::test::corpus_body_steps(body.voxels, steps_scale),
                              fingerprint);
        const double dt = bhm::engine::Model::build(spec)->dt_s();
        const double full_steps = std::ceil(evaluation_s / dt);
        out.full_evaluations_s += r.build_s + full_steps * r.cpu_s / static_cast<double>(r.steps);
        if (per_body)
            std::cerr << body.name << ": " << r.voxels << " voxels, " << r.links << " links, "
                      << r.edge_springs << " edge springs, " << r.voxel_steps_per_s() << " voxel-steps/s\n";
        out.bodies.push_back(r);
    }
    return out;  // empty when no body is in the voxel range: the caller skips it
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\n'))
        s.pop_back();
    std::size_t i = 0;
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t'))
        ++i;
    return s.substr(i);
}

// "x86_64 AMD EPYC 7B13": uname -m and the CPU model of /proc/cpuinfo.
std::string machine_description() {
    utsname names{};
    std::string arch = uname(&names) == 0 ? names.machine : "unknown-arch";
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) == 0 || line.rfind("Model", 0) == 0) {
            if (auto colon = line.find(':'); colon != std::string::npos)
                return arch + " " + trim(line.substr(colon + 1));
        }
    }
    return arch;
}

// CSV field: quoted when it holds a comma or a quote.
std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string csv_row(const Result& r, const std::string& machine, const std::string& commit) {
    char numbers[320];
    const double rate = r.voxel_steps_per_s();
    std::snprintf(numbers, sizeof numbers, "1,%d,%d,%lld,%.4f,%.4f,%.4g,%.4g,%.4g,%.4g,,%.1f",
                  r.voxels, r.links, static_cast<long long>(r.steps), r.wall_s, r.cpu_s, rate, rate,
                  rate, rate, 1e6 * r.build_s);
    return csv_field(r.scene) + "," + numbers + "," + csv_field(machine) + "," + csv_field(commit);
}

std::string csv_row(const CorpusResult& c, const std::string& machine, const std::string& commit) {
    std::vector<double> rates, builds;
    double voxels = 0, links = 0, wall = 0, cpu = 0, voxel_steps = 0;
    long long steps = 0;
    for (const Result& r : c.bodies) {
        rates.push_back(r.voxel_steps_per_s());
        builds.push_back(r.build_s);
        voxels += r.voxels;
        links += r.links;
        steps += r.steps;
        wall += r.wall_s;
        cpu += r.cpu_s;
        voxel_steps += static_cast<double>(r.voxels) * static_cast<double>(r.steps);
    }
    const auto n = static_cast<double>(c.bodies.size());
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        const std::size_t m = v.size() / 2;
        return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
    };
    char numbers[320];
    std::snprintf(numbers, sizeof numbers,
                  "%zu,%.1f,%.1f,%lld,%.4f,%.4f,%.4g,%.4g,%.4g,%.4g,%.4g,%.1f", c.bodies.size(),
                  voxels / n, links / n, steps, wall, cpu, voxel_steps / cpu,
                  *std::min_element(rates.begin(), rates.end()), median(rates),
                  *std::max_element(rates.begin(), rates.end()), n / c.full_evaluations_s,
                  1e6 * median(builds));
    return csv_field("corpus_" + c.name) + "," + numbers + "," + csv_field(machine) + "," +
           csv_field(commit);
}

constexpr const char* kUsage =
    "usage: bench_engine [--steps-scale X] [--commit SHA] [--corpus DIR] [--assets DIR] "
    "[--scenes-only] [--corpus-only] [--min-voxels N] [--max-voxels N] [--per-body] "
    "[--fingerprint] [--poisson-off] [--scene NAME]\n";

[[noreturn]] void usage_error(const std::string& message) {
    std::cerr << "bench_engine: " << message << "\n" << kUsage;
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    double steps_scale = 1.0;
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    std::string corpus_dir = "tests/bench/corpus", assets = "assets/experiments";
    bool scenes_wanted = true, corpus_wanted = true, per_body = false, fingerprint = false,
         poisson_off = false;
    int min_voxels = 0, max_voxels = 1 << 30;
    std::string scene_filter;  // --scene: only the scenes whose name contains it
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool takes_value = arg == "--steps-scale" || arg == "--commit" || arg == "--corpus" ||
                                 arg == "--assets" || arg == "--min-voxels" ||
                                 arg == "--max-voxels" || arg == "--scene";
        if (takes_value && i + 1 >= argc) usage_error("option '" + arg + "' needs a value");
        if (arg == "--steps-scale") {
            char* end = nullptr;
            steps_scale = std::strtod(argv[++i], &end);
            if (*end != '\0' || !(steps_scale > 0.0))
                usage_error("--steps-scale needs a positive number");
        } else if (arg == "--min-voxels" || arg == "--max-voxels") {
            char* end = nullptr;
            const long v = std::strtol(argv[++i], &end, 10);
            if (*end != '\0' || v < 0) usage_error(arg + " needs a non-negative integer");
            (arg == "--min-voxels" ? min_voxels : max_voxels) = static_cast<int>(v);
        } else if (arg == "--commit") {
            commit = argv[++i];
        } else if (arg == "--corpus") {
            corpus_dir = argv[++i];
        } else if (arg == "--assets") {
            assets = argv[++i];
        } else if (arg == "--scene") {
            scene_filter = argv[++i];
            corpus_wanted = false;
        } else if (arg == "--scenes-only") {
            corpus_wanted = false;
        } else if (arg == "--corpus-only") {
            scenes_wanted = false;
        } else if (arg == "--per-body") {
            per_body = true;
        } else if (arg == "--fingerprint") {
            fingerprint = true;
        } else if (arg == "--poisson-off") {
            poisson_off = true;
        } else if (arg == "--help" || arg == "-h") {
            std::cout << kUsage
                      << "--per-body: each corpus body's rate on stderr.\n"
                         "--fingerprint: a hash of each simulation's final state on stderr.\n"
                         "--poisson-off: every material's Poisson ratio set to 0 (the "
                         "coupling's cost).\n"
                         "--scene NAME: only the scenes whose name contains NAME (no corpus).\n"
                         "Times the engine on fixed scenes and on the body corpus; CSV on "
                         "stdout.\n";
            return 0;
        } else {
            usage_error("unknown argument '" + arg + "'");
        }
    }

    const std::string machine = machine_description();
    std::ostringstream csv;
    csv << "name,bodies,voxels,links,steps,wall_s,cpu_s,voxel_steps_per_s,min_voxel_steps_per_s,"
           "median_voxel_steps_per_s,max_voxel_steps_per_s,simulations_per_s_11s,build_us,"
           "machine,commit\n";
    try {
        if (scenes_wanted) {
            double single_cantilever_wall_rate = 0.0;
            auto list = bhm::test::anchor_scenes();
            std::erase_if(list, [&](const EngineScene& scene) {
                return scene.name.find(scene_filter) == std::string::npos;
            });
            if (list.empty()) usage_error("--scene '" + scene_filter + "' names no scene");
            for (EngineScene& scene : list)
                scene.spec = as_timed(scene.spec, poisson_off);
            for (const EngineScene& scene : list) {
                const auto steps = bhm::test::scene_steps(scene, steps_scale);
                const Result r = run_single(scene.name, scene.spec, steps, fingerprint);
                if (scene.name == list.front().name)
                    single_cantilever_wall_rate =
                        static_cast<double>(r.voxels) * static_cast<double>(r.steps) / r.wall_s;
                csv << csv_row(r, machine, commit) << "\n";
                std::cerr << r.scene << ": " << r.voxels << " voxels, " << r.steps << " steps in "
                          << r.cpu_s << " CPU s = " << r.voxel_steps_per_s() << " voxel-steps/s\n";
            }
            // Two threads on the cantilever (the first scene), unless --scene left it out.
            const EngineScene& cantilever = list.front();
            if (cantilever.name == "cantilever_20x8x7") {
                const Result two =
                    run_two_threads(cantilever, bhm::test::scene_steps(cantilever, steps_scale));
                csv << csv_row(two, machine, commit) << "\n";
                std::cerr << two.scene << ": aggregate " << two.voxel_steps_per_s()
                          << " voxel-steps/s = "
                          << two.voxel_steps_per_s() / single_cantilever_wall_rate
                          << "x one thread by wall time (hardware threads: "
                          << std::thread::hardware_concurrency() << ")\n";
            }
        }
        if (corpus_wanted) {
            std::vector<std::string> files;
            for (const auto& entry : std::filesystem::directory_iterator(corpus_dir))
                if (entry.path().extension() == ".json") files.push_back(entry.path().string());
            if (files.empty()) throw std::runtime_error(corpus_dir + ": no corpus file (*.json)");
            std::sort(files.begin(), files.end());
            for (const auto& file : files) {
                const CorpusResult c = run_corpus(file, assets, steps_scale, min_voxels,
                                                  max_voxels, per_body, fingerprint, poisson_off);
                if (c.bodies.empty()) continue;  // no body of this corpus in the voxel range
                csv << csv_row(c, machine, commit) << "\n";
                std::cerr << "corpus " << c.name << ": " << c.bodies.size() << " bodies, "
                          << c.bodies.size() / c.full_evaluations_s
                          << " full 11 s simulations per CPU second\n";
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_engine: " << e.what() << "\n";
        return 1;
    }

    std::cout << csv.str();
    return 0;
}
