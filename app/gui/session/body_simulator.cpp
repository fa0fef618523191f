#include "app/gui/session/body_simulator.hpp"

#include <chrono>
#include <cmath>

#include "app/cli/simulation_report.hpp"
#include "app/gui/session/replay_player.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/simulate.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace bhm::app::gui {

std::vector<int> surface_voxels(const engine::Replay& replay) {
    const int nx = replay.nx, ny = replay.ny, nz = replay.nz;
    std::vector<std::uint8_t> filled(static_cast<std::size_t>(nx) * ny * nz, 0);
    for (const auto cell : replay.voxel_cell)
        filled[static_cast<std::size_t>(cell)] = 1;
    auto occupied = [&](int x, int y, int z) {
        return x >= 0 && y >= 0 && z >= 0 && x < nx && y < ny && z < nz &&
               filled[static_cast<std::size_t>(x + nx * (y + ny * z))] != 0;
    };
    std::vector<int> surface;
    for (std::size_t v = 0; v < replay.voxel_cell.size(); ++v) {
        const int cell = replay.voxel_cell[v];
        const int x = cell % nx, y = (cell / nx) % ny, z = cell / (nx * ny);
        if (!occupied(x - 1, y, z) || !occupied(x + 1, y, z) || !occupied(x, y - 1, z) ||
            !occupied(x, y + 1, z) || !occupied(x, y, z - 1) || !occupied(x, y, z + 1))
            surface.push_back(static_cast<int>(v));
    }
    return surface;
}

SimulatedBody simulate_body(const SimulationRequest& request, const std::atomic<bool>* cancel) {
    const auto start = std::chrono::steady_clock::now();
    const evo::Experiment& experiment = request.experiment;
    // The same recipe as evo::evaluate_body (spec, phases, sampling, measures), run the whole
    // time, so the numbers shown match the fitness evolution measured.
    auto model = evo::model_of(experiment, *request.framed_body);
    SimulationRecorder recorder(*model, experiment.simulation.settle_s, true);
    evo::SimulationOptions options;
    options.end_early = false;
    evo::SimulationHooks hooks;
    hooks.record = [&](const engine::World& w) { recorder.observe(w); };
    hooks.poll = [&](const engine::World&) {
        if (cancel && cancel->load(std::memory_order_relaxed)) throw evo::EvaluationCancelled();
    };
    const evo::SimulationResult sim = evo::simulate(experiment, model, options, hooks);

    SimulatedBody out;
    out.id = request.id;
    out.label = request.label;
    out.experiment = experiment;
    out.framed_body = request.framed_body;
    out.replay = recorder.replay();
    std::vector<double> density;
    for (const auto& m : experiment.materials)
        density.push_back(m.physics.density_kg_m3);
    out.com_m = centre_of_mass_per_frame(out.replay, density);
    out.surface_voxels = surface_voxels(out.replay);
    out.measures = sim.report.measures;
    out.diverged = sim.report.diverged;
    out.divergence_reason = sim.report.divergence_reason;
    out.fitness = evo::fitness_under(sim.report, experiment.fitness.measure);
    // Analysis data, once, here on the worker: the UI only reads it.
    out.series = body_time_series(experiment, out.replay, out.com_m);
    out.drive = voxel_drive(experiment, *request.framed_body, out.replay);
    out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

BodySimulator::~BodySimulator() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        cancel_ = true;
    }
    wake_.notify_all();
    if (worker_.joinable()) worker_.join();
}

void BodySimulator::request(SimulationRequest request) {
    {
        std::lock_guard lock(mutex_);
        pending_id_ = request.id;
        pending_label_ = request.label;
        queued_ = std::move(request);
        busy_ = true;
        cancel_ = true;  // the running one, if any, gives way
        if (!worker_.joinable()) worker_ = std::thread([this] { worker_loop(); });
    }
    wake_.notify_all();
}

void BodySimulator::cancel() {
    std::lock_guard lock(mutex_);
    queued_.reset();
    cancel_ = true;
    pending_id_ = -1;
    pending_label_.clear();
    ++epoch_;
}

std::string BodySimulator::pending_label() const {
    std::lock_guard lock(mutex_);
    return pending_label_;
}

std::string BodySimulator::last_error() const {
    std::lock_guard lock(mutex_);
    return last_error_;
}

void BodySimulator::worker_loop() {
    for (;;) {
        SimulationRequest job;
        std::uint64_t epoch = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return quit_ || queued_.has_value(); });
            if (quit_) return;
            job = std::move(*queued_);
            queued_.reset();
            cancel_ = false;
            epoch = epoch_;
        }
        try {
            auto result = std::make_shared<SimulatedBody>(simulate_body(job, &cancel_));
            std::lock_guard lock(mutex_);
            if (epoch == epoch_) {  // not cancelled while it finished
                results_.publish(std::move(result));
                last_error_.clear();
                if (!queued_) pending_label_.clear();  // with the result: never both shown
            }
        } catch (const evo::EvaluationCancelled&) {
            // A newer request is queued (or we are quitting): nothing to publish.
        } catch (const std::exception& e) {
            std::lock_guard lock(mutex_);
            if (epoch == epoch_) last_error_ = job.label + ": " + e.what();
        }
        std::lock_guard lock(mutex_);
        if (!queued_) {
            busy_ = false;
            pending_id_ = -1;
            pending_label_.clear();
        }
    }
}

}  // namespace bhm::app::gui
