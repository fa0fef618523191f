#pragma once
// The few MPI calls the front end makes, over MPI_COMM_WORLD with errors returned (not fatal), so
// a failed send becomes an exception with MPI's own message. Only the main thread of a rank calls
// these (MPI_THREAD_FUNNELED). Payloads are byte strings (evo/evaluate/evaluation_wire.hpp for jobs,
// results and rules; short text for the control messages).
#include <list>
#include <optional>
#include <string>

#include <mpi.h>

namespace bhm::app::mpi {

enum class Tag : int {
    Setup = 1,      //!< 0 -> r: requested threads per rank ("0" = all cores of that node)
    Hello = 2,      //!< r -> 0: "THREADS HOST", once, after Setup
    Rules = 3,      //!< 0 -> r: evo::RulesMessage, before the first job under new rules
    Job = 4,        //!< 0 -> r: evo::JobMessage
    Result = 5,     //!< r -> 0: evo::ResultMessage
    Cancel = 6,     //!< 0 -> r: "BATCH": drop every job of that batch, running ones included
    Stop = 7,       //!< 0 -> r: the run is over; finish and leave
    Heartbeat = 8,  //!< r -> 0: empty, every second: the rank is alive
    Failure = 9,    //!< r -> 0: text of an error the rank cannot recover from
    Pause = 10,     //!< 0 -> r: "1" holds the running simulations where they are, "0" resumes
    // bhm calibrate (app/mpi/mpi_track_batches.*); Hello, Failure and Stop as above.
    TrackSetup = 11,   //!< 0 -> r: evo::TrackSetupMessage, once
    TrackJob = 12,     //!< 0 -> r: evo::TrackJobMessage
    TrackResult = 13,  //!< r -> 0: evo::TrackResultMessage
};

struct Message {
    int source = 0;
    Tag tag = Tag::Heartbeat;
    std::string bytes;
};

//! Throws std::runtime_error "WHAT: MPI's error string" unless rc is MPI_SUCCESS.
void check(int rc, const std::string& what);

//! The next message that has arrived from anyone, without waiting.
std::optional<Message> poll_message();

//! A blocking send: for the small messages ranks > 0 send to rank 0, which always listens.
void send_message(int destination, Tag tag, const std::string& bytes);

//! Non-blocking sends whose buffers live until MPI is done with them: rank 0 never blocks on a
//! rank that stopped listening (it would then miss that rank's silence).
class PendingSends {
  public:
    void start(int destination, Tag tag, std::string bytes);
    //! Forgets the sends that completed.
    void progress();
    //! Waits up to timeout_s for every send to complete; true if they all did.
    bool drain(double timeout_s);

  private:
    struct Pending {
        MPI_Request request = MPI_REQUEST_NULL;
        std::string bytes;
    };
    std::list<Pending> pending_;  // a list: buffers never move while MPI reads them
};

}  // namespace bhm::app::mpi
