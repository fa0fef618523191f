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
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace {

using bhm::engine::BodySpec;
using bhm::engine::Material;
using Clock = std::chrono::steady_clock;

double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Paper Table 1: E = 5 MPa, density 1000, Poisson 0.35, friction 1 / 0.5; CTE 0 passive,
// 0.01 active.
Material passive_material() {
    return Material{5e6, 1000.0, 0.35, 0.0, 1.0, 0.5};
}
Material active_material() {
    return Material{5e6, 1000.0, 0.35, 0.01, 1.0, 0.5};
}

// A filled nx x ny x nz block, its x = 0 layer held, material per cell from material_at(x).
template <class MaterialAt>
BodySpec block_fixed_at_x_min(int nx, int ny, int nz, MaterialAt material_at) {
    BodySpec spec;
    spec.nx = nx;
    spec.ny = ny;
    spec.nz = nz;
    spec.materials = {passive_material(), active_material()};
    spec.material.resize(static_cast<std::size_t>(spec.cell_count()));
    spec.fixed.resize(static_cast<std::size_t>(spec.cell_count()));
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                const auto c = static_cast<std::size_t>(spec.cell_index(x, y, z));
                spec.material[c] = static_cast<std::uint8_t>(material_at(x));
                spec.fixed[c] = x == 0 ? 1 : 0;
            }
    // Actuate from the first step: the benchmark times the actuated steps of an evaluation.
    spec.actuation.start_s = 0.0;
    return spec;
}

struct Scene {
    std::string name;
    BodySpec spec;
    std::int64_t steps;  //!< fixed per scene: ~3 s of wall time at 1.5e7 voxel-steps/s
};

std::vector<Scene> scenes() {
    std::vector<Scene> list;
    // 20x8x7 passive cantilever under gravity, no floor.
    BodySpec cantilever = block_fixed_at_x_min(20, 8, 7, [](int) { return 1; });
    cantilever.environment.floor = false;
    list.push_back({"cantilever_20x8x7", cantilever, 40000});
    // The paper's design space filled with muscle: 8x8x7 all active, 2 Hz, on the floor.
    list.push_back(
        {"active_block_8x8x7", block_fixed_at_x_min(8, 8, 7, [](int) { return 2; }), 100000});
    // 20x8x7 with 4-voxel bands along x: active, passive, active, ...
    list.push_back({"bands_20x8x7",
                    block_fixed_at_x_min(20, 8, 7, [](int x) { return (x / 4) % 2 == 0 ? 2 : 1; }),
                    40000});
    // Two stiffnesses (issue 24): the cantilever with layers z = 1 and 5 of a 10x stiffer
    // passive material, every vertical link between them mixed.
    BodySpec layered = cantilever;
    Material stiff = passive_material();
    stiff.youngs_modulus_pa *= 10.0;
    layered.materials.push_back(stiff);
    for (int z = 0; z < layered.nz; ++z)
        for (int y = 0; y < layered.ny; ++y)
            for (int x = 0; x < layered.nx; ++x)
                if (z == 1 || z == 5) layered.material[layered.cell_index(x, y, z)] = 3;
    list.push_back({"layered_20x8x7", layered, 40000});
    // The worst case of the springs across edges (issue 24): the cantilever as a 10x
    // checkerboard, every stiff voxel joined to its stiff edge neighbours (one spring per voxel
    // and a half).
    BodySpec checkerboard = layered;
    for (int z = 0; z < checkerboard.nz; ++z)
        for (int y = 0; y < checkerboard.ny; ++y)
            for (int x = 0; x < checkerboard.nx; ++x)
                checkerboard.material[checkerboard.cell_index(x, y, z)] = (x + y + z) % 2 ? 3 : 1;
    list.push_back({"checkerboard_20x8x7", checkerboard, 40000});
    return list;
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

// FNV-1a over every voxel's final position and orientation: equal fingerprints before and after
// an engine change show it kept the results bit for bit (--fingerprint).
std::uint64_t state_fingerprint(const bhm::engine::World& world) {
    std::uint64_t hash = 1469598103934665603ull;
    auto mix = [&](double value) {
        unsigned char bytes[sizeof value];
        std::memcpy(bytes, &value, sizeof value);
        for (unsigned char b : bytes)
            hash = (hash ^ b) * 1099511628211ull;
    };
    for (int v = 0; v < world.model().voxel_count(); ++v) {
        for (double x : world.voxel_position_m(v))
            mix(x);
        for (double q : world.voxel_orientation(v))
            mix(q);
    }
    return hash;
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
Result run_two_threads(const Scene& scene, std::int64_t steps) {
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

CorpusResult run_corpus(const std::string& path, const std::string& assets, double voxel_steps,
                        int min_voxels, int max_voxels, bool per_body, bool fingerprint,
                        bool poisson_off) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open the corpus file");
    nlohmann::json corpus;
    try {
        corpus = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": not valid JSON (" + e.what() + ")");
    }
    const std::string preset = corpus.at("experiment").get<std::string>();
    const bhm::evo::Experiment experiment =
        bhm::evo::load_experiment(assets + "/" + preset + ".json");
    const double evaluation_s = bhm::evo::evaluation_seconds(experiment);
    // Named after the file: a preset can have several corpora (random bodies, champions).
    CorpusResult out{std::filesystem::path(path).stem().string(), {}, 0.0};
    for (const auto& entry : corpus.at("bodies")) {
        const std::string name = preset + "/" + entry.at("name").get<std::string>();
        // Framed as evolution simulates it (a no-op for workspace-sized framed bodies), phases
        // from the run's seed as evaluate_body draws them.
        const auto body = bhm::evo::apply_frame_and_overrides(
            experiment, bhm::evo::parse_body(entry.at("body"), path));
        const BodySpec spec = as_timed(
            bhm::evo::make_body_spec(experiment, body, experiment.evolution.seed), poisson_off);
        int voxels = 0;
        for (auto m : spec.material)
            voxels += m != 0;
        if (voxels < min_voxels || voxels > max_voxels) continue;
        const auto steps =
            std::max<std::int64_t>(200, static_cast<std::int64_t>(voxel_steps / voxels));
        Result r = run_single(name, spec, steps, fingerprint);
        const double dt = bhm::engine::Model::build(spec)->dt_s();
        const double full_steps = std::ceil(evaluation_s / dt);
        out.full_evaluations_s += r.build_s + full_steps * r.cpu_s / static_cast<double>(r.steps);
        if (per_body)
            std::cerr << name << ": " << r.voxels << " voxels, " << r.links << " links, "
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
            auto list = scenes();
            std::erase_if(list, [&](const Scene& scene) {
                return scene.name.find(scene_filter) == std::string::npos;
            });
            if (list.empty()) usage_error("--scene '" + scene_filter + "' names no scene");
            for (Scene& scene : list)
                scene.spec = as_timed(scene.spec, poisson_off);
            for (const Scene& scene : list) {
                const auto steps = std::max<std::int64_t>(
                    1, static_cast<std::int64_t>(static_cast<double>(scene.steps) * steps_scale));
                const Result r = run_single(scene.name, scene.spec, steps, fingerprint);
                if (scene.name == list.front().name)
                    single_cantilever_wall_rate =
                        static_cast<double>(r.voxels) * static_cast<double>(r.steps) / r.wall_s;
                csv << csv_row(r, machine, commit) << "\n";
                std::cerr << r.scene << ": " << r.voxels << " voxels, " << r.steps << " steps in "
                          << r.cpu_s << " CPU s = " << r.voxel_steps_per_s() << " voxel-steps/s\n";
            }
            // Two threads on the cantilever (the first scene), unless --scene left it out.
            const Scene& cantilever = list.front();
            if (cantilever.name == "cantilever_20x8x7") {
                const auto steps = std::max<std::int64_t>(
                    1, static_cast<std::int64_t>(static_cast<double>(cantilever.steps) *
                                                 steps_scale));
                const Result two = run_two_threads(cantilever, steps);
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
                const CorpusResult c = run_corpus(file, assets, 2e6 * steps_scale, min_voxels,
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
