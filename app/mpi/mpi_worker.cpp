#include "app/mpi/mpi_worker.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "app/mpi/mpi_transport.hpp"
#include "evo/evaluate/evaluation_wire.hpp"
#include "evo/evaluate/worker_pool.hpp"

namespace bhm::app::mpi {

namespace {

using Clock = std::chrono::steady_clock;

struct Fault {
    enum class Kind { None, Hang, Exit, Fail } kind = Kind::None;
    std::uint64_t from_batch = 0;  //!< acts out instead of sending a result of this batch or later
};

Fault fault_for(int rank) {
    Fault f;
    const char* spec = std::getenv("BHM_MPI_TEST_FAULT");
    if (!spec) return f;
    int fault_rank = -1;
    unsigned long long batch = 0;
    char kind[8] = {};
    if (std::sscanf(spec, "%d:%llu:%7s", &fault_rank, &batch, kind) != 3 || fault_rank != rank)
        return f;
    f.from_batch = batch;
    const std::string k = kind;
    f.kind = k == "hang"   ? Fault::Kind::Hang
             : k == "exit" ? Fault::Kind::Exit
             : k == "fail" ? Fault::Kind::Fail
                           : Fault::Kind::None;
    return f;
}

struct Job {
    std::shared_ptr<const evo::RulesMessage> rules;
    std::shared_ptr<std::atomic<bool>> cancelled;  //!< shared by every job of one batch
    evo::JobMessage message;
};

struct Reply {
    Tag tag = Tag::Result;
    std::string bytes;
    std::uint64_t batch_id = 0;
};

//! The simulation threads and the two queues they share with the main thread.
class Simulators {
  public:
    explicit Simulators(int threads, const std::atomic<bool>& paused) : paused_(paused) {
        for (int t = 0; t < threads; ++t)
            threads_.emplace_back([this] { work(); });
    }
    ~Simulators() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
            for (auto& job : jobs_)
                job.cancelled->store(true);
        }
        wake_.notify_all();
        for (auto& t : threads_)
            t.join();
    }
    void push(Job job) {
        {
            std::lock_guard lock(mutex_);
            jobs_.push_back(std::move(job));
        }
        wake_.notify_one();
    }
    //! Drops the queued jobs of a cancelled batch (running ones see its flag).
    void drop_cancelled() {
        std::lock_guard lock(mutex_);
        std::erase_if(jobs_, [](const Job& j) { return j.cancelled->load(); });
    }
    //! Encoded results and failure texts ready to send, oldest first.
    std::vector<Reply> take_outbox() {
        std::lock_guard lock(mutex_);
        std::vector<Reply> out(std::make_move_iterator(outbox_.begin()),
                               std::make_move_iterator(outbox_.end()));
        outbox_.clear();
        return out;
    }

  private:
    void work() {
        for (;;) {
            Job job;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
                if (stopping_) return;
                job = std::move(jobs_.front());
                jobs_.pop_front();
            }
            if (job.cancelled->load()) continue;
            Reply reply;
            reply.batch_id = job.message.batch_id;
            try {
                evo::ResultMessage result;
                result.batch_id = job.message.batch_id;
                result.index = job.message.index;
                result.report =
                    evo::evaluate_body(job.rules->rules, job.message.body,
                                       evo::EvaluationControl{job.cancelled.get(), &paused_});
                reply.bytes = evo::encode_result(result);
            } catch (const evo::EvaluationCancelled&) {
                continue;
            } catch (const std::exception& e) {
                reply.tag = Tag::Failure;
                reply.bytes = std::string("simulation failed: ") + e.what();
            }
            std::lock_guard lock(mutex_);
            outbox_.push_back(std::move(reply));
        }
    }

    const std::atomic<bool>& paused_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::deque<Job> jobs_;
    std::deque<Reply> outbox_;
    std::vector<std::thread> threads_;
};

[[noreturn]] void act_out(const Fault& fault) {
    if (fault.kind == Fault::Kind::Exit) std::_Exit(1);
    for (;;)  // hung: alive, but silent, until the job is killed
        ::pause();
}

}  // namespace

int serve_evaluations(int rank, const std::string& host) {
    const Fault fault = fault_for(rank);
    std::atomic<bool> paused{false};  // declared before the threads that read it
    std::unique_ptr<Simulators> simulators;
    std::shared_ptr<const evo::RulesMessage> rules;
    std::map<std::uint64_t, std::shared_ptr<std::atomic<bool>>> batch_flags;
    auto last_beat = Clock::now();

    const auto fail = [&](const std::string& text) {
        send_message(0, Tag::Failure, text);  // rank 0 adds which rank and host
    };
    for (;;) {
        bool busy = false;
        while (auto m = poll_message()) {
            busy = true;
            if (m->source != 0) continue;
            try {
                switch (m->tag) {
                    case Tag::Setup: {
                        const int threads = evo::resolve_thread_count(std::atoi(m->bytes.c_str()));
                        simulators = std::make_unique<Simulators>(threads, paused);
                        send_message(0, Tag::Hello, std::to_string(threads) + " " + host);
                        break;
                    }
                    case Tag::Rules:
                        rules =
                            std::make_shared<const evo::RulesMessage>(evo::decode_rules(m->bytes));
                        break;
                    case Tag::Job: {
                        auto job = evo::decode_job(m->bytes);
                        if (!simulators || !rules || job.rules_id != rules->rules_id) {
                            fail("a job arrived before its setup or rules");
                            break;
                        }
                        auto& flag = batch_flags[job.batch_id];
                        if (!flag) {
                            flag = std::make_shared<std::atomic<bool>>(false);
                            // Older batches are over; their jobs hold their own flag.
                            batch_flags.erase(batch_flags.begin(), batch_flags.find(job.batch_id));
                        }
                        simulators->push({rules, flag, std::move(job)});
                        break;
                    }
                    case Tag::Cancel: {
                        const auto batch = std::strtoull(m->bytes.c_str(), nullptr, 10);
                        auto it = batch_flags.find(batch);
                        if (it != batch_flags.end()) it->second->store(true);
                        if (simulators) simulators->drop_cancelled();
                        break;
                    }
                    case Tag::Pause:
                        paused.store(m->bytes == "1");
                        break;
                    case Tag::Stop:
                        return 0;  // ~Simulators cancels and joins the threads
                    default:
                        break;
                }
            } catch (const std::exception& e) {
                fail(e.what());  // e.g. a message from another bhm build: rank 0 stops the run
            }
        }
        if (simulators) {
            for (const auto& reply : simulators->take_outbox()) {
                if (fault.kind == Fault::Kind::Fail && reply.batch_id >= fault.from_batch) {
                    fail("injected failure (BHM_MPI_TEST_FAULT)");  // then carry on serving
                    continue;
                }
                if (fault.kind != Fault::Kind::None && reply.batch_id >= fault.from_batch)
                    act_out(fault);
                send_message(0, reply.tag, reply.bytes);
                busy = true;
            }
        }
        const auto now = Clock::now();
        if (now - last_beat >= std::chrono::seconds(1)) {
            send_message(0, Tag::Heartbeat, "");
            last_beat = now;
        }
        if (!busy) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

}  // namespace bhm::app::mpi
