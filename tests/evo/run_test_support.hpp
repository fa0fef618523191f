#pragma once
// Shared fixtures for the tests that drive whole EvolutionRuns: options, a per-process temporary
// folder, histories compared without their wall-clock column, and the stop-then-resume half of
// the "a resumed run equals its uninterrupted twin" tests.
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "evo/evaluate/evaluator.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/run/evolution_run.hpp"
#include "support/scratch.hpp"

namespace bhm::evo::test {

inline RunOptions run_options(int generations, int threads, const std::string& dir = "",
                              std::shared_ptr<Evaluator> evaluator = nullptr) {
    RunOptions o;
    o.generations = generations;
    o.threads = threads;
    o.out_dir = dir;
    o.evaluator = std::move(evaluator);
    return o;
}

//! The history without wall_s (the only field that depends on the machine's speed).
inline std::vector<HistoryRow> without_wall(std::vector<HistoryRow> rows) {
    for (auto& r : rows)
        r.wall_s = 0.0;
    return rows;
}

//! fitness.csv without its wall_s column (column 8, the only one that depends on the machine).
inline std::string csv_without_wall(const std::string& csv) {
    std::stringstream in(csv), out;
    std::string line;
    constexpr int kWallColumn = 8;  // generation,...,diverged,wall_s,...
    while (std::getline(in, line)) {
        std::size_t start = 0;
        for (int c = 0; c < kWallColumn; ++c)
            start = line.find(',', start) + 1;
        const std::size_t end = line.find(',', start);
        out << line.substr(0, start) << (end == std::string::npos ? "" : line.substr(end + 1))
            << "\n";
    }
    return out.str();
}

//! An empty path under the temporary folder, unique to this suite (`suite`) and process.
inline std::filesystem::path fresh_dir(const std::string& suite, const std::string& name) {
    return bhm::test::scratch_dir(suite + "-" + name, false);
}

//! Runs `experiment` in `dir` with one thread until generation `stop_at` is reported, stops it as
//! Ctrl-C would, and returns the run resumed from that folder with `generations` and `threads`.
//! Returns null if the first run did not stop on request.
inline std::unique_ptr<EvolutionRun> stopped_then_resumed(const Experiment& experiment,
                                                          const std::string& dir, int generations,
                                                          int threads, int stop_at) {
    {
        EvolutionRun first(experiment, run_options(generations, 1, dir));
        first.set_report_callback([&](auto r) {
            if (r->generation == stop_at) first.request_stop();
        });
        if (first.run() != StopReason::StopRequested) return nullptr;
    }
    return EvolutionRun::resume(run_options(generations, threads, dir));
}

//! One experiment run twice to `generations` on `threads`: uninterrupted in `whole_dir`, and in
//! `parts_dir` stopped after generation `stop_at` and resumed (stopped_then_resumed), both run to
//! the end. `resumed` is null if the first part did not stop on request.
struct RunTwins {
    std::unique_ptr<EvolutionRun> whole, resumed;
};
inline RunTwins run_twins(const Experiment& experiment, const std::string& whole_dir,
                          const std::string& parts_dir, int generations, int threads, int stop_at) {
    RunTwins t;
    t.whole =
        std::make_unique<EvolutionRun>(experiment, run_options(generations, threads, whole_dir));
    t.whole->run();
    t.resumed = stopped_then_resumed(experiment, parts_dir, generations, threads, stop_at);
    if (t.resumed) t.resumed->run();
    return t;
}

//! The twins above are one run: the resumed one stopped on request, took no warning, and ends
//! with the uninterrupted one's history (wall clock aside), generator, champion (genome,
//! controller, body, fitness) and population member by member.
inline void check_twins_equal(const RunTwins& t) {
    REQUIRE(t.resumed);
    CHECK(t.resumed->resume_warnings().empty());
    const RunState& u = t.whole->state();
    const RunState& r = t.resumed->state();
    CHECK(without_wall(r.history) == without_wall(u.history));
    CHECK(r.rng == u.rng);
    REQUIRE(r.champion);
    REQUIRE(u.champion);
    CHECK(r.champion->individual.genome == u.champion->individual.genome);
    CHECK(r.champion->individual.controller == u.champion->individual.controller);
    CHECK(r.champion->individual.phenotype.body == u.champion->individual.phenotype.body);
    CHECK(r.champion->individual.report.fitness == u.champion->individual.report.fitness);
    REQUIRE(r.population.size() == u.population.size());
    for (std::size_t i = 0; i < u.population.size(); ++i) {
        CHECK(r.population[i].id == u.population[i].id);
        CHECK(r.population[i].genome == u.population[i].genome);
        CHECK(r.population[i].controller == u.population[i].controller);
        CHECK(r.population[i].phenotype.body == u.population[i].phenotype.body);
        CHECK(r.population[i].report.fitness == u.population[i].report.fitness);
    }
}

//! A checkpoint payload as a build before format 4 wrote it: `version` (1 to 3) and each cache
//! entry {hash, report} as the positional array [hash, diverged, steps, simulated_s, measures,
//! divergence_reason, exploits, behaviour, {ended_early, periodic_residual}] (no fitness, no
//! sim_wall_s).
inline void as_positional_cache(nlohmann::json& payload, int version) {
    payload["format_version"] = version;
    for (auto& entry : payload["cache"]) {
        const nlohmann::json& r = entry.at("report");
        nlohmann::json measures = nlohmann::json::array();
        for (const char* name : kFitnessNames)
            measures.push_back(r.at("measures").at(name));
        entry = nlohmann::json::array({entry.at("hash"),
                                       r.at("diverged"),
                                       r.at("steps"),
                                       r.at("simulated_s"),
                                       measures,
                                       r.at("divergence_reason"),
                                       r.at("exploits"),
                                       r.at("behaviour"),
                                       {{"ended_early", r.at("ended_early")},
                                        {"periodic_residual", r.at("periodic_residual")}}});
    }
}

}  // namespace bhm::evo::test
