#include "app/mpi/mpi_evaluator.hpp"

#include <atomic>
#include <exception>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "evo/evaluate/evaluation_wire.hpp"

namespace bhm::app::mpi {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

std::string rank_name(const RemoteRank& r) {
    return "rank " + std::to_string(r.rank) + (r.host.empty() ? "" : " on " + r.host);
}

}  // namespace

//! Rank 0's share of a batch: `threads` threads take the next index from the shared counter the
//! dispatcher also takes from. Joins on destruction, so no thread outlives the batch's slots.
class LocalWorkers {
  public:
    LocalWorkers(int threads, const evo::EvaluationBatch& batch,
                 std::vector<evo::FitnessReport>& results, std::atomic<std::size_t>& next)
        : batch_(batch), results_(results), next_(next) {
        for (int t = 0; t < threads; ++t)
            threads_.emplace_back([this] { work(); });
    }
    ~LocalWorkers() {
        abandon_.store(true);
        for (auto& t : threads_)
            t.join();
    }
    LocalWorkers(const LocalWorkers&) = delete;
    LocalWorkers& operator=(const LocalWorkers&) = delete;

    void abandon() { abandon_.store(true); }
    std::size_t done() const { return done_.load(); }
    //! Rethrows the first error a local simulation raised (EvaluationCancelled is not one).
    void rethrow_error() {
        std::lock_guard lock(error_mutex_);
        if (error_) std::rethrow_exception(error_);
    }

  private:
    void work() {
        const std::size_t n = batch_.bodies.size();
        while (!abandon_.load()) {
            const std::size_t i = next_.fetch_add(1);
            if (i >= n) return;
            try {
                results_[i] = evo::evaluate_body(*batch_.rules, *batch_.bodies[i],
                                                 evo::EvaluationControl{&abandon_, batch_.pause});
            } catch (const evo::EvaluationCancelled&) {
                return;
            } catch (...) {
                std::lock_guard lock(error_mutex_);
                if (!error_) error_ = std::current_exception();
                abandon_.store(true);
                return;
            }
            if (batch_.on_result) batch_.on_result(i);
            done_.fetch_add(1);
        }
    }

    const evo::EvaluationBatch& batch_;
    std::vector<evo::FitnessReport>& results_;
    std::atomic<std::size_t>& next_;
    std::atomic<bool> abandon_{false};
    std::atomic<std::size_t> done_{0};
    std::mutex error_mutex_;
    std::exception_ptr error_;
    std::vector<std::thread> threads_;
};

MpiEvaluator::MpiEvaluator(int world_size, int local_threads, int requested_threads,
                           double rank_timeout_s)
    : local_threads_(local_threads), timeout_s_(rank_timeout_s) {
    const auto start = Clock::now();
    for (int r = 1; r < world_size; ++r) {
        RemoteRank remote;
        remote.rank = r;
        remote.in_flight = -1;  // no Hello yet
        remote.last_heard = start;
        ranks_.push_back(remote);
        sends_.start(r, Tag::Setup, std::to_string(requested_threads));
    }
    int waiting = world_size - 1;
    while (waiting > 0) {
        if (auto m = poll_message()) {
            if (m->tag == Tag::Failure)
                throw std::runtime_error("rank " + std::to_string(m->source) + ": " + m->bytes);
            if (m->tag != Tag::Hello) continue;
            RemoteRank& r = rank_of(m->source);
            std::istringstream text(m->bytes);
            text >> r.threads >> r.host;
            if (!text || r.threads < 1)
                throw std::runtime_error("rank " + std::to_string(r.rank) + ": bad hello '" +
                                         m->bytes + "'");
            if (r.in_flight < 0) --waiting;
            r.in_flight = 0;
            continue;
        }
        if (seconds_between(start, Clock::now()) > timeout_s_) {
            std::string silent;
            for (const auto& r : ranks_)
                if (r.in_flight < 0)
                    silent += (silent.empty() ? "" : ", ") + std::to_string(r.rank);
            throw evo::EvaluatorLost("rank(s) " + silent + " did not answer within " +
                                     std::to_string(static_cast<int>(timeout_s_)) +
                                     " s of the start (--rank-timeout)");
        }
        sends_.progress();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

void MpiEvaluator::send_pause(bool paused) {
    if (paused == ranks_paused_) return;
    for (const auto& r : ranks_)
        sends_.start(r.rank, Tag::Pause, paused ? "1" : "0");
    ranks_paused_ = paused;
}

int MpiEvaluator::concurrency() const {
    int total = local_threads_;
    for (const auto& r : ranks_)
        total += r.threads;
    return total;
}

RemoteRank& MpiEvaluator::rank_of(int source) {
    if (source < 1 || source > static_cast<int>(ranks_.size()))
        throw std::runtime_error("message from unknown rank " + std::to_string(source));
    return ranks_[static_cast<std::size_t>(source - 1)];
}

void MpiEvaluator::evaluate(const evo::EvaluationBatch& batch,
                            std::vector<evo::FitnessReport>& results) {
    const std::size_t n = batch.bodies.size();
    results.assign(n, evo::FitnessReport{});
    if (n == 0) return;
    const std::uint64_t batch_id = ++batch_id_;
    if (!sent_rules_ || *sent_rules_ != *batch.rules) {
        const std::string bytes = evo::encode_rules({++rules_id_, *batch.rules});
        for (const auto& r : ranks_)
            sends_.start(r.rank, Tag::Rules, bytes);
        sent_rules_ = *batch.rules;
    }
    send_pause(batch.pause && batch.pause->load());
    // Rank 0's own pauses (selection, checkpoints) are not a rank's silence.
    const auto batch_start = Clock::now();
    for (auto& r : ranks_) {
        r.in_flight = 0;
        r.last_heard = batch_start;
    }

    std::atomic<std::size_t> next{0};
    LocalWorkers local(local_threads_, batch, results, next);
    try {
        dispatch(batch, batch_id, results, next, local);
    } catch (...) {
        // Whatever ended the batch early, nobody keeps simulating it.
        local.abandon();
        for (auto& r : ranks_) {
            r.in_flight = 0;
            try {
                sends_.start(r.rank, Tag::Cancel, std::to_string(batch_id));
            } catch (const std::exception&) {
                // A rank that cannot be reached has nothing to cancel; keep the first error.
            }
        }
        throw;
    }
}

void MpiEvaluator::dispatch(const evo::EvaluationBatch& batch, std::uint64_t batch_id,
                            std::vector<evo::FitnessReport>& results,
                            std::atomic<std::size_t>& next, LocalWorkers& local) {
    const std::size_t n = batch.bodies.size();
    std::size_t remote_done = 0;
    bool exhausted = false;
    for (;;) {
        for (auto& r : ranks_) {
            while (!exhausted && r.in_flight < r.threads) {
                const std::size_t i = next.fetch_add(1);
                if (i >= n) {
                    exhausted = true;
                    break;
                }
                evo::JobMessage job;
                job.batch_id = batch_id;
                job.rules_id = rules_id_;
                job.index = static_cast<std::uint32_t>(i);
                job.body = *batch.bodies[i];
                sends_.start(r.rank, Tag::Job, evo::encode_job(job));
                ++r.in_flight;
            }
        }
        bool heard = false;
        while (auto m = poll_message()) {
            heard = true;
            RemoteRank& r = rank_of(m->source);
            r.last_heard = Clock::now();
            if (m->tag == Tag::Failure) throw std::runtime_error(rank_name(r) + ": " + m->bytes);
            if (m->tag != Tag::Result) continue;
            auto result = evo::decode_result(m->bytes);
            if (result.batch_id != batch_id) continue;  // from an abandoned batch
            if (result.index >= n)
                throw std::runtime_error(rank_name(r) + ": result index out of range");
            results[result.index] = std::move(result.report);
            --r.in_flight;
            ++remote_done;
            if (batch.on_result) batch.on_result(result.index);
        }
        local.rethrow_error();
        if (local.done() + remote_done == n) return;
        if (batch.cancel && batch.cancel->load()) throw evo::EvaluationCancelled();
        const auto now = Clock::now();
        for (const auto& r : ranks_) {
            const double silent_s = seconds_between(r.last_heard, now);
            if (r.in_flight > 0 && silent_s > timeout_s_) {
                std::ostringstream text;
                text << rank_name(r) << " sent nothing for " << static_cast<int>(silent_s)
                     << " s while simulating " << r.in_flight << " bod"
                     << (r.in_flight == 1 ? "y" : "ies") << " (--rank-timeout " << timeout_s_
                     << "): it died or hangs";
                throw evo::EvaluatorLost(text.str());
            }
        }
        send_pause(batch.pause && batch.pause->load());
        sends_.progress();
        if (!heard) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

}  // namespace bhm::app::mpi
