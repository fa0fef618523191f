#include "app/mpi/mpi_track_batches.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/mpi/mpi_transport.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/worker_pool.hpp"

namespace bhm::app::mpi {

namespace {

using Clock = std::chrono::steady_clock;

void nap() {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
}

}  // namespace

MpiTrackBatches::MpiTrackBatches(int size, int local_threads, const evo::TrackSetupMessage& setup,
                                 double timeout_s)
    : local_threads_(local_threads < 1 ? 1 : local_threads) {
    const std::string bytes = evo::encode_track_setup(setup);
    PendingSends sends;
    for (int r = 1; r < size; ++r)
        sends.start(r, Tag::TrackSetup, bytes);
    std::vector<std::optional<Rank>> hello(static_cast<std::size_t>(size));
    int missing = size - 1;
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (missing > 0) {
        sends.progress();
        if (auto m = poll_message()) {
            if (m->tag == Tag::Failure)
                throw std::runtime_error("rank " + std::to_string(m->source) + ": " + m->bytes);
            if (m->tag != Tag::Hello || hello[static_cast<std::size_t>(m->source)]) continue;
            Rank r;
            r.rank = m->source;
            std::istringstream in(m->bytes);
            in >> r.threads >> r.host;
            if (r.threads < 1) r.threads = 1;
            hello[static_cast<std::size_t>(m->source)] = r;
            --missing;
            continue;
        }
        if (Clock::now() > deadline) {
            for (int r = 1; r < size; ++r)
                if (!hello[static_cast<std::size_t>(r)])
                    throw std::runtime_error("rank " + std::to_string(r) + " did not answer the "
                                             "calibration's setup within " +
                                             std::to_string(static_cast<int>(timeout_s)) + " s");
        }
        nap();
    }
    sends.drain(timeout_s);
    for (auto& h : hello)
        if (h) ranks_.push_back(*h);
}

MpiTrackBatches::~MpiTrackBatches() = default;

int MpiTrackBatches::concurrency() const {
    int n = local_threads_;
    for (const auto& r : ranks_) n += r.threads;
    return n;
}

std::string MpiTrackBatches::describe(const std::string& host) const {
    std::ostringstream out;
    out << ranks_.size() + 1 << " MPI ranks, " << concurrency()
        << " simulation threads: rank 0 on " << host << " (" << local_threads_ << ")";
    for (const auto& r : ranks_) out << ", " << r.rank << " on " << r.host << " (" << r.threads << ")";
    return out.str();
}

void MpiTrackBatches::simulate(
    const evo::TrackProblem& problem, const std::vector<std::vector<double>>& xs,
    std::vector<evo::SimulatedTrack>& results, const std::atomic<bool>* cancel,
    const std::function<void(std::size_t, const evo::SimulatedTrack&)>& on_result) {
    ++batch_;
    const std::size_t n = xs.size();
    results.assign(n, evo::SimulatedTrack{});
    // One queue for every rank: rank 0's threads take from it, the main thread hands the next
    // index to a rank as soon as it has a free thread.
    std::mutex mutex;
    std::deque<std::size_t> queue;
    for (std::size_t i = 0; i < n; ++i) queue.push_back(i);
    std::vector<std::size_t> landed;  // finished by rank 0's threads, not yet reported
    std::exception_ptr local_error;
    std::atomic<bool> stop_local{false};
    auto take = [&]() -> std::optional<std::size_t> {
        std::lock_guard lock(mutex);
        if (queue.empty()) return std::nullopt;
        const std::size_t i = queue.front();
        queue.pop_front();
        return i;
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < local_threads_; ++t)
        threads.emplace_back([&] {
            try {
                while (!stop_local.load()) {
                    const auto i = take();
                    if (!i) return;
                    evo::SimulatedTrack sim = evo::simulate_track_at(problem, xs[*i], &stop_local);
                    std::lock_guard lock(mutex);
                    results[*i] = std::move(sim);
                    landed.push_back(*i);
                }
            } catch (...) {
                std::lock_guard lock(mutex);
                if (!local_error) local_error = std::current_exception();
                stop_local.store(true);
            }
        });
    auto finish = [&] {
        stop_local.store(true);
        for (auto& t : threads) t.join();
        threads.clear();
    };

    std::size_t reported = 0;
    auto report = [&](std::size_t i) {
        ++reported;
        if (on_result) on_result(i, results[i]);
    };
    std::vector<int> outstanding(ranks_.size(), 0);
    PendingSends sends;
    try {
        while (reported < n) {
            if (cancel && cancel->load()) {
                finish();
                throw evo::EvaluationCancelled();
            }
            bool busy = false;
            for (std::size_t k = 0; k < ranks_.size(); ++k)
                while (outstanding[k] < ranks_[k].threads) {
                    const auto i = take();
                    if (!i) break;
                    sends.start(ranks_[k].rank, Tag::TrackJob,
                                evo::encode_track_job(
                                    {batch_, static_cast<std::uint32_t>(*i), xs[*i]}));
                    ++outstanding[k];
                    busy = true;
                }
            sends.progress();
            while (auto m = poll_message()) {
                busy = true;
                if (m->tag == Tag::Failure)
                    throw std::runtime_error("rank " + std::to_string(m->source) + ": " +
                                             m->bytes);
                if (m->tag != Tag::TrackResult) continue;
                evo::TrackResultMessage r = evo::decode_track_result(m->bytes);
                if (r.batch != batch_ || r.index >= n) continue;  // of an abandoned batch
                for (std::size_t k = 0; k < ranks_.size(); ++k)
                    if (ranks_[k].rank == m->source) --outstanding[k];
                results[r.index] = std::move(r.track);
                report(r.index);
            }
            std::vector<std::size_t> mine;
            {
                std::lock_guard lock(mutex);
                if (local_error) std::rethrow_exception(local_error);
                mine.swap(landed);
            }
            for (const std::size_t i : mine) report(i);
            if (!busy && mine.empty()) nap();
        }
    } catch (...) {
        finish();
        throw;
    }
    finish();
    sends.drain(5.0);
}

int serve_track_batches(int rank, const std::string& host) {
    std::optional<evo::TrackSetupMessage> setup;
    std::vector<evo::FitParameter> parameters;
    evo::TrackProblem problem;
    std::mutex mutex;
    std::condition_variable wake;
    std::deque<evo::TrackJobMessage> jobs;
    std::deque<std::pair<Tag, std::string>> outbox;
    bool stopping = false;
    std::atomic<bool> cancel{false};
    std::vector<std::thread> threads;
    auto work = [&] {
        for (;;) {
            evo::TrackJobMessage job;
            {
                std::unique_lock lock(mutex);
                wake.wait(lock, [&] { return stopping || !jobs.empty(); });
                if (stopping) return;
                job = std::move(jobs.front());
                jobs.pop_front();
            }
            std::pair<Tag, std::string> reply;
            try {
                evo::TrackResultMessage result{job.batch, job.index,
                                               evo::simulate_track_at(problem, job.x, &cancel)};
                reply = {Tag::TrackResult, evo::encode_track_result(result)};
            } catch (const evo::EvaluationCancelled&) {
                return;
            } catch (const std::exception& e) {
                reply = {Tag::Failure, e.what()};
            }
            std::lock_guard lock(mutex);
            outbox.push_back(std::move(reply));
        }
    };
    auto stop = [&] {
        {
            std::lock_guard lock(mutex);
            stopping = true;
        }
        cancel.store(true);
        wake.notify_all();
        for (auto& t : threads) t.join();
    };
    try {
        for (;;) {
            bool busy = false;
            while (auto m = poll_message()) {
                busy = true;
                if (m->source != 0) continue;
                if (m->tag == Tag::Stop) {
                    stop();
                    return 0;
                }
                if (m->tag == Tag::TrackSetup && !setup) {
                    try {
                        setup = evo::decode_track_setup(m->bytes);
                        parameters = evo::parse_fit_list(setup->fit_list, setup->experiment);
                        problem = {&setup->experiment, &parameters, &setup->framed_body,
                                   &setup->track};
                        const int n = evo::resolve_thread_count(setup->requested_threads);
                        for (int t = 0; t < n; ++t) threads.emplace_back(work);
                        send_message(0, Tag::Hello, std::to_string(n) + " " + host);
                    } catch (const std::exception& e) {
                        send_message(0, Tag::Failure, e.what());
                    }
                } else if (m->tag == Tag::TrackJob && setup) {
                    {
                        std::lock_guard lock(mutex);
                        jobs.push_back(evo::decode_track_job(m->bytes));
                    }
                    wake.notify_one();
                }
            }
            std::deque<std::pair<Tag, std::string>> out;
            {
                std::lock_guard lock(mutex);
                out.swap(outbox);
            }
            for (const auto& [tag, bytes] : out) send_message(0, tag, bytes);
            if (!busy && out.empty()) nap();
        }
    } catch (const std::exception& e) {
        stop();
        std::fprintf(stderr, "bhm calibrate (rank %d): %s\n", rank, e.what());
        return 1;
    }
}

}  // namespace bhm::app::mpi
