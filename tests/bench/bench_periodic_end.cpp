// bench_periodic_end: the accuracy gate and the gain of evaluations that end when the motion
// repeats (evo/evaluate/periodic_end.hpp, issue 23), on the body corpus (tests/bench/corpus/).
// Every body is evaluated twice with its preset's settings, once with simulation.end_when_periodic
// on and once off (the full 1 s + 10 s), and every fitness measure of the first is checked
// against the second: within max(0.5 %, 1e-3 voxel lengths or degrees), or the run went the
// full length. One CSV row per body on stdout; the largest error, the fraction ended early and
// the CPU time ratio on stderr. Exit status 1 when a body fails the gate.
//
//   bench_periodic_end [--corpus DIR] [--assets DIR] [--min-voxels N] [--max-voxels N] [--every K]
//                      [--tolerance-scale X] [--body NAME]... [FILE-STEM...]
// --body NAME keeps only the bodies of that name (repeatable: random-05 of paper-exp3). --every K keeps every K-th body of each file (a spread of sizes in less time); FILE-STEMs pick
// corpus files (e.g. paper-exp1 paper-exp3-champions), all by default. --tolerance-scale
// multiplies the presets' periodic_tolerance (10 shows what a tenfold looser one does).
// --early-only skips the full run (no gate: the columns of the early run only, for a profile).
// integrated_s is the simulated time the early run actually stepped (the rest of a settling at
// rest is skipped, evo/evaluate/settle_rest.hpp), settle_integrated_s its part before settle_s.
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/periodic_end.hpp"
#include "evo/evaluate/simulate.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/body_spec_of.hpp"

using namespace bhm::evo;

namespace {

double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int run(int argc, char** argv) {
    std::string corpus_dir = "tests/bench/corpus", assets = "assets/experiments";
    int min_voxels = 0, max_voxels = 1 << 30, every = 1;
    double tolerance_scale = 1.0;
    bool early_only = false;
    std::vector<std::string> stems, only_bodies;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--corpus")
            corpus_dir = value();
        else if (a == "--assets")
            assets = value();
        else if (a == "--min-voxels")
            min_voxels = std::stoi(value());
        else if (a == "--max-voxels")
            max_voxels = std::stoi(value());
        else if (a == "--every")
            every = std::max(1, std::stoi(value()));
        else if (a == "--tolerance-scale")
            tolerance_scale = std::stod(value());
        else if (a == "--early-only")
            early_only = true;
        else if (a == "--body")
            only_bodies.push_back(value());
        else if (a == "--help" || a == "-h") {
            std::cout << "usage: bench_periodic_end [--corpus DIR] [--assets DIR] [--min-voxels N] "
                         "[--max-voxels N]"
                         " [--every K] [--tolerance-scale X] [--early-only] [--body NAME]... [FILE-STEM...]\n";
            return 0;
        } else
            stems.push_back(a);
    }
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(corpus_dir))
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::cout << "file,body,voxels,ended_early,stopped_s,periodic_residual,gate_error,"
                 "cpu_full_s,cpu_early_s,integrated_s,settle_integrated_s\n";
    int bodies = 0, early = 0, failed = 0;
    double worst = 0.0, cpu_full = 0.0, cpu_early = 0.0;
    std::string worst_body;
    for (const auto& path : files) {
        const std::string stem = path.stem().string();
        if (!stems.empty() && std::find(stems.begin(), stems.end(), stem) == stems.end()) continue;
        std::ifstream in(path);
        const auto corpus = nlohmann::json::parse(in);
        Experiment on =
            load_experiment(assets + "/" + corpus.at("experiment").get<std::string>() + ".json");
        on.simulation.end_when_periodic = true;
        on.simulation.periodic_tolerance *= tolerance_scale;
        Experiment off = on;
        off.simulation.end_when_periodic = false;
        int index = 0;
        for (const auto& entry : corpus.at("bodies")) {
            if (index++ % every != 0) continue;
            if (!only_bodies.empty() &&
                std::find(only_bodies.begin(), only_bodies.end(),
                          entry.at("name").get<std::string>()) == only_bodies.end())
                continue;
            const Body body =
                apply_frame_and_overrides(on, parse_body(entry.at("body"), path.string()));
            const int voxels = static_cast<int>(
                std::count_if(body.cells.begin(), body.cells.end(), [](auto c) { return c != 0; }));
            if (voxels < min_voxels || voxels > max_voxels) continue;
            double t0 = thread_cpu_s();
            const FitnessReport e = evaluate_body(on, body);
            double t1 = thread_cpu_s();
            const FitnessReport f = early_only ? e : evaluate_body(off, body);
            double t2 = thread_cpu_s();
            const double error = e.ended_early ? periodic_end_error(e, f) : 0.0;
            ++bodies;
            early += e.ended_early ? 1 : 0;
            failed += error > 1.0 ? 1 : 0;
            cpu_early += t1 - t0;
            cpu_full += t2 - t1;
            const std::string name = stem + "/" + entry.at("name").get<std::string>();
            if (error > worst) {
                worst = error;
                worst_body = name;
            }
            const double dt = model_of(on, body)->dt_s();
            const double integrated_s = static_cast<double>(e.steps) * dt;
            const double settle_s = on.simulation.settle_s;
            const double settle_integrated_s =
                integrated_s - std::max(0.0, e.simulated_s - settle_s);
            char row[512];
            std::snprintf(row, sizeof row, "%s,%s,%d,%d,%.4f,%.3g,%.4f,%.3f,%.3f,%.4f,%.4f",
                          stem.c_str(), entry.at("name").get<std::string>().c_str(), voxels,
                          e.ended_early ? 1 : 0, e.simulated_s, e.periodic_residual, error, t2 - t1,
                          t1 - t0, integrated_s, settle_integrated_s);
            std::cout << row << std::endl;
            if (error > 0.3) {
                std::cerr << name << (error > 1.0 ? " over the gate:" : " near the gate:");
                for (std::size_t m = 0; m < e.measures.size(); ++m)
                    std::cerr << " " << kFitnessNames[m] << " " << e.measures[m] << " (full "
                              << f.measures[m] << ")";
                std::cerr << "\n";
            }
        }
    }
    std::cerr << bodies << " bodies, " << early << " ended early ("
              << (bodies ? 100.0 * early / bodies : 0.0) << " %), largest gate error " << worst
              << " of the allowed (" << (worst_body.empty() ? "none" : worst_body) << "), "
              << failed << " over the gate; CPU " << cpu_full << " s full, " << cpu_early
              << " s with the early end (" << (cpu_early > 0 ? cpu_full / cpu_early : 0.0)
              << "x)\n";
    return failed > 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "bench_periodic_end: " << e.what() << "\n";
        return 1;
    }
}
