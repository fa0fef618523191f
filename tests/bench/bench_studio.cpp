// bench_studio: the studio's UI frame rate, headless on llvmpipe, while evolution runs on the
// other core. The 3D view plays a 20x8x7 champion (paper experiment 3's workspace, 1120 voxels)
// in Simulation mode; a run of the same workspace (population 8, threads 1) evolves meanwhile.
// Every frame is the whole UI (panels, 3D view, ImGui drawing) finished with glFinish, so its
// wall time is what a window would need before swapping.
//
//   bench_studio [--frames N] [--size WxH] [--sim-seconds S] [--evolve-seconds S] [--samples N]
//                [--no-evolution]
//                [--frames-csv PATH] [--commit SHA]
//
// One summary row as CSV on stdout (frame times in ms); per-frame times to --frames-csv.
#include <sys/utsname.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/session/body_simulator.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm;
using namespace bhm::app::gui;

namespace {

using bhm::bench::machine_description;
using bhm::bench::seconds_since;

// Paper experiment 3's workspace and frame (20x8x7, one-voxel passive enclosure), Table 1
// materials, with short times so the benchmark's simulations take seconds.
evo::Experiment bench_experiment(double evaluate_s) {
    evo::Experiment e;
    e.name = "bench-exp3";
    e.workspace_size = {20, 8, 7};
    evo::MaterialEntry passive;
    passive.name = "passive tissue";
    evo::MaterialEntry active = passive;
    active.name = "muscle";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(evo::Face::XMin)] = evo::BoundaryKind::Fixed;
    e.boundary.enclosure_thickness = {1, 1, 1, 1, 1, 1};
    e.boundary.enclosure_material = 1;
    e.simulation.settle_s = 0.1;
    e.simulation.evaluate_s = evaluate_s;
    e.fitness.measure = evo::FitnessMeasure::ComFinalYz;
    e.fitness.constraints.attached_to_fixed_face = true;
    e.evolution.population = 8;
    e.evolution.generations = 100000;
    e.evolution.threads = 1;
    return e;
}

// All 1120 cells: the frame passive, the design space active below mid-height, passive above.
evo::Body full_champion(const evo::Experiment& e) {
    evo::Body body;
    body.size = e.workspace_size;
    body.cells.assign(static_cast<std::size_t>(body.cell_count()), 1);
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < body.size[1]; ++y)
            for (int x = 0; x < body.size[0]; ++x)
                body.cells[static_cast<std::size_t>(body.index(x, y, z))] = 2;
    return evo::apply_frame_and_overrides(e, body);
}

// CPU time of the calling thread: the UI's own work, whatever else loads the machine. With
// LP_NUM_THREADS=0 llvmpipe rasterizes on this thread too, so it is the whole frame's CPU cost.
double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

constexpr const char* kUsage =
    "usage: bench_studio [--frames N] [--size WxH] [--sim-seconds S] [--evolve-seconds S]\n"
    "                    [--samples N] [--no-evolution] [--frames-csv PATH] [--commit SHA]\n"
    "The studio's UI frame rate, headless on llvmpipe, while a run evolves on the other core.\n"
    "One summary row as CSV on stdout (frame times in ms); per-frame times to --frames-csv.\n";

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(
        std::clamp(q * (v.size() - 1) + 0.5, 0.0, double(v.size() - 1)))];
}

}  // namespace

int main(int argc, char** argv) {
    int frames = 300, width = 1280, height = 800;
    double sim_seconds = 1.0;
    double evolve_seconds = 0.1;
    bool evolution = true;
    int samples = 0;  // MSAA samples of the 3D view; 0 keeps the studio's choice
    std::string frames_csv;
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
                return argv[++i];
            };
            if (a == "--frames")
                frames = std::stoi(value());
            else if (a == "--size") {
                const std::string s = value();
                width = std::stoi(s.substr(0, s.find('x')));
                height = std::stoi(s.substr(s.find('x') + 1));
            } else if (a == "--sim-seconds")
                sim_seconds = std::stod(value());
            else if (a == "--evolve-seconds")
                evolve_seconds = std::stod(value());
            else if (a == "--samples")
                samples = std::stoi(value());
            else if (a == "--no-evolution")
                evolution = false;
            else if (a == "--frames-csv")
                frames_csv = value();
            else if (a == "--commit")
                commit = value();
            else if (a == "--help" || a == "-h") {
                std::cout << kUsage;
                return 0;
            } else
                throw std::runtime_error("unknown option " + a + " (see --help)");
        }
        if (frames < 10) throw std::runtime_error("--frames must be >= 10");
    } catch (const std::exception& e) {
        std::cerr << "bench_studio: " << e.what() << "\n";
        return 2;
    }

    const evo::Experiment e = bench_experiment(sim_seconds);
    Studio studio;
    // The run evolves the same workspace with short evaluations, so generations (and the
    // snapshots they publish: 8 bodies of 1120 cells each) keep coming during the measurement.
    studio.document.reset(bench_experiment(evolve_seconds), "");
    // The champion's replay first, alone on the machine (it is what the view plays).
    SimulationRequest request;
    request.id = 1;
    request.label = "20x8x7 benchmark champion";
    request.experiment = e;
    request.framed_body = std::make_shared<const evo::Body>(full_champion(e));
    const auto sim_start = std::chrono::steady_clock::now();
    auto shown = std::make_shared<const SimulatedBody>(simulate_body(request));
    std::cerr << "bench_studio: champion replay of " << shown->replay.frames.size() << " frames, "
              << shown->replay.voxel_cell.size() << " voxels, simulated in "
              << seconds_since(sim_start) << " s\n";

    HeadlessStudio session(studio, width, height);
    std::filesystem::path run_dir = std::filesystem::temp_directory_path() / "bench-studio-run";
    std::filesystem::remove_all(run_dir);
    if (evolution) {
        studio.run.dir_field = run_dir.string();
        if (!start_run(studio)) {
            std::cerr << "bench_studio: " << studio.ui.status << "\n";
            return 1;
        }
    }
    // Show the benchmark champion, playing, and keep it there (no live-champion switching).
    studio.bodies.follow_champion = false;
    studio.bodies.shown = shown;
    studio.clock.playing = true;
    studio.clock.loop = true;
    set_view_mode(studio, ViewMode::Simulation);
    if (samples > 0) studio.view.samples = samples;
    samples = studio.view.samples;
    for (int i = 0; i < 5; ++i)
        session.frame();  // warm-up: shaders, buffers, layout

    std::vector<double> ms;
    ms.reserve(static_cast<std::size_t>(frames));
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_s();
    for (int i = 0; i < frames; ++i) {
        const auto t = std::chrono::steady_clock::now();
        session.frame(1.0 / 60.0);
        ms.push_back(1000.0 * seconds_since(t));
    }
    const double wall = seconds_since(start);
    const double ui_cpu_ms = 1000.0 * (thread_cpu_s() - cpu_start) / frames;
    const auto run = studio.run.evolution.snapshot();
    const int generations = run ? run->generation : 0;
    const long long simulations = run ? static_cast<long long>(run->evaluations) : 0;
    studio.run.evolution.stop();

    if (!frames_csv.empty()) {
        std::ofstream out(frames_csv);
        out << "frame,ms\n";
        for (std::size_t i = 0; i < ms.size(); ++i)
            out << i << "," << ms[i] << "\n";
    }
    const double mean = std::accumulate(ms.begin(), ms.end(), 0.0) / ms.size();
    const long over =
        std::count_if(ms.begin(), ms.end(), [](double v) { return v > 1000.0 / 30.0; });
    std::cout << "width,height,samples,voxels,evolution,frames,wall_s,mean_fps,mean_ms,p50_ms,p95_"
                 "ms,max_ms,"
                 "frames_over_33ms,max_snapshot_ms,ui_thread_cpu_ms,lp_num_threads,load_avg_1min,"
                 "generations_done,"
                 "simulations_done,gl_renderer,hardware_threads,"
                 "machine,commit\n";
    std::string renderer = session.gl_renderer();
    std::replace(renderer.begin(), renderer.end(), ',', ' ');
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    double load = 0.0;
    std::ifstream("/proc/loadavg") >> load;
    std::printf(
        "%d,%d,%d,%zu,%d,%d,%.2f,%.1f,%.2f,%.2f,%.2f,%.2f,%ld,%.3f,%.2f,%s,%.2f,%d,%lld,%s,%u,%s,%"
        "s\n",
        width, height, samples, shown->replay.voxel_cell.size(), evolution ? 1 : 0, frames, wall,
        frames / wall, mean, percentile(ms, 0.5), percentile(ms, 0.95),
        *std::max_element(ms.begin(), ms.end()), over, studio.ui.max_update_ms, ui_cpu_ms,
        lp_threads ? lp_threads : "default", load, generations, simulations, renderer.c_str(),
        std::thread::hardware_concurrency(), machine_description().c_str(), commit.c_str());
    return 0;
}
