// Engine speed in voxel-steps per second on named scenes, one thread each, plus two simulations
// on two threads (how well independent Worlds sharing one Model scale, as evolution runs them).
// Writes CSV to stdout: scene,voxels,links,steps,wall_s,voxel_steps_per_s,machine,commit.
//   bench_engine [--steps-scale X] [--commit SHA]
// The commit comes from --commit or $BHM_COMMIT (scripts/bench.sh passes git rev-parse --short
// HEAD). The "_2threads" row counts both worlds: voxels and links are the sum, steps are per world,
// and voxel_steps_per_s is the aggregate; its scaling factor vs one thread goes to stderr.
#include <sys/utsname.h>

#include <barrier>
#include <chrono>
#include <cstdio>
#include <cstdlib>
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

namespace {

using bhm::engine::BodySpec;
using bhm::engine::Material;
using Clock = std::chrono::steady_clock;

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
    return list;
}

struct Result {
    std::string scene;
    int voxels = 0, links = 0;
    std::int64_t steps = 0;
    double wall_s = 0.0;
    double voxel_steps_per_s() const {
        return static_cast<double>(voxels) * static_cast<double>(steps) / wall_s;
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

Result run_single(const Scene& scene, std::int64_t steps) {
    const auto model = bhm::engine::Model::build(scene.spec);
    bhm::engine::World world(model);
    const auto start = Clock::now();
    step_world(world, steps, scene.name);
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    return {scene.name, model->voxel_count(), model->link_count(), steps, wall};
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
    return {scene.name + "_2threads", 2 * model->voxel_count(), 2 * model->link_count(), steps,
            wall};
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
    char numbers[160];
    std::snprintf(numbers, sizeof numbers, "%d,%d,%lld,%.4f,%.4g", r.voxels, r.links,
                  static_cast<long long>(r.steps), r.wall_s, r.voxel_steps_per_s());
    return csv_field(r.scene) + "," + numbers + "," + csv_field(machine) + "," + csv_field(commit);
}

[[noreturn]] void usage_error(const std::string& message) {
    std::cerr << "bench_engine: " << message << "\n"
              << "usage: bench_engine [--steps-scale X] [--commit SHA]\n";
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    double steps_scale = 1.0;
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if ((arg == "--steps-scale" || arg == "--commit") && i + 1 >= argc)
            usage_error("option '" + arg + "' needs a value");
        if (arg == "--steps-scale") {
            char* end = nullptr;
            steps_scale = std::strtod(argv[++i], &end);
            if (*end != '\0' || !(steps_scale > 0.0))
                usage_error("--steps-scale needs a positive number");
        } else if (arg == "--commit") {
            commit = argv[++i];
        } else if (arg == "--help" || arg == "-h") {
            std::cout << "usage: bench_engine [--steps-scale X] [--commit SHA]\n"
                         "Times the engine on fixed scenes; CSV on stdout (or FILE).\n";
            return 0;
        } else {
            usage_error("unknown argument '" + arg + "'");
        }
    }

    const std::string machine = machine_description();
    std::ostringstream csv;
    csv << "scene,voxels,links,steps,wall_s,voxel_steps_per_s,machine,commit\n";
    try {
        double single_cantilever_rate = 0.0;
        const auto list = scenes();
        for (const Scene& scene : list) {
            const auto steps = std::max<std::int64_t>(
                1, static_cast<std::int64_t>(static_cast<double>(scene.steps) * steps_scale));
            const Result r = run_single(scene, steps);
            if (scene.name == list.front().name) single_cantilever_rate = r.voxel_steps_per_s();
            csv << csv_row(r, machine, commit) << "\n";
            std::cerr << r.scene << ": " << r.voxels << " voxels, " << r.steps << " steps in "
                      << r.wall_s << " s = " << r.voxel_steps_per_s() << " voxel-steps/s\n";
        }
        const Scene& cantilever = list.front();
        const auto steps = std::max<std::int64_t>(
            1, static_cast<std::int64_t>(static_cast<double>(cantilever.steps) * steps_scale));
        const Result two = run_two_threads(cantilever, steps);
        csv << csv_row(two, machine, commit) << "\n";
        std::cerr << two.scene << ": aggregate " << two.voxel_steps_per_s()
                  << " voxel-steps/s = " << two.voxel_steps_per_s() / single_cantilever_rate
                  << "x one thread (hardware threads: " << std::thread::hardware_concurrency()
                  << ")\n";
    } catch (const std::exception& e) {
        std::cerr << "bench_engine: " << e.what() << "\n";
        return 1;
    }

    std::cout << csv.str();
    return 0;
}
