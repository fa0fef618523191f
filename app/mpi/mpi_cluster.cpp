#include "app/mpi/mpi_cluster.hpp"

#include <mpi.h>

#include <iostream>
#include <sstream>
#include <stdexcept>

#include "app/mpi/mpi_evaluator.hpp"
#include "app/mpi/mpi_track_batches.hpp"
#include "app/mpi/mpi_transport.hpp"
#include "app/mpi/mpi_worker.hpp"

namespace bhm::app {

namespace {

class MpiCluster final : public EvolveCluster {
  public:
    MpiCluster() {
        int provided = 0;
        mpi::check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided),
                   "MPI_Init_thread");
        // Errors come back as codes (then exceptions) so rank 0 can say what went wrong.
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        if (provided < MPI_THREAD_FUNNELED) {
            MPI_Finalize();
            throw std::runtime_error("this MPI library offers no MPI_THREAD_FUNNELED support");
        }
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
        char name[MPI_MAX_PROCESSOR_NAME];
        int length = 0;
        MPI_Get_processor_name(name, &length);
        host_.assign(name, static_cast<std::size_t>(length));
    }
    ~MpiCluster() override {
        if (rank_ == 0) {
            // Every other rank waits for this; a lost rank never gets here (abort()). A send to
            // a rank that already died fails: nothing more to say to it, and no throwing here.
            try {
                mpi::PendingSends stops;
                for (int r = 1; r < size_; ++r)
                    stops.start(r, mpi::Tag::Stop, "");
                if (evaluator_) evaluator_->flush(5.0);
                stops.drain(5.0);
            } catch (const std::exception&) {
            }
        }
        MPI_Finalize();
    }

    int rank() const override { return rank_; }
    int size() const override { return size_; }
    int serve() override { return mpi::serve_evaluations(rank_, host_); }
    int serve_calibration() override { return mpi::serve_track_batches(rank_, host_); }

    std::shared_ptr<evo::TrackBatches> connect_calibration(
        int local_threads, const evo::TrackSetupMessage& setup) override {
        if (size_ == 1) return nullptr;
        track_batches_ = std::make_shared<mpi::MpiTrackBatches>(size_, local_threads, setup, 60.0);
        return track_batches_;
    }

    std::shared_ptr<evo::Evaluator> connect(const ClusterSettings& settings) override {
        if (size_ == 1) return nullptr;
        evaluator_ = std::make_shared<mpi::MpiEvaluator>(
            size_, settings.local_threads, settings.requested_threads, settings.rank_timeout_s);
        return evaluator_;
    }

    std::string describe() const override {
        if (track_batches_) return track_batches_->describe(host_);
        if (!evaluator_) return "";
        std::ostringstream out;
        out << size_ << " MPI ranks, " << evaluator_->concurrency()
            << " simulation threads: rank 0 on " << host_ << " (" << evaluator_->local_threads()
            << ")";
        for (const auto& r : evaluator_->ranks())
            out << ", " << r.rank << " on " << r.host << " (" << r.threads << ")";
        return out.str();
    }

    [[noreturn]] void abort(int status) override {
        std::cerr.flush();
        MPI_Abort(MPI_COMM_WORLD, status);
        std::exit(status);  // MPI_Abort does not return; this keeps [[noreturn]] honest
    }

  private:
    int rank_ = 0;
    int size_ = 1;
    std::string host_;
    std::shared_ptr<mpi::MpiEvaluator> evaluator_;
    std::shared_ptr<mpi::MpiTrackBatches> track_batches_;
};

}  // namespace

std::unique_ptr<EvolveCluster> make_mpi_cluster() {
    return std::make_unique<MpiCluster>();
}

}  // namespace bhm::app
