#include "app/mpi/mpi_transport.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

namespace bhm::app::mpi {

void check(int rc, const std::string& what) {
    if (rc == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(rc, text, &length);
    throw std::runtime_error(what + ": " + std::string(text, static_cast<std::size_t>(length)));
}

std::optional<Message> poll_message() {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (!arrived) return std::nullopt;
    int count = 0;
    check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
    Message m;
    m.source = status.MPI_SOURCE;
    m.tag = static_cast<Tag>(status.MPI_TAG);
    m.bytes.resize(static_cast<std::size_t>(count));
    check(MPI_Recv(m.bytes.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv from rank " + std::to_string(status.MPI_SOURCE));
    return m;
}

void send_message(int destination, Tag tag, const std::string& bytes) {
    check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_CHAR, destination,
                   static_cast<int>(tag), MPI_COMM_WORLD),
          "MPI_Send to rank " + std::to_string(destination));
}

void PendingSends::start(int destination, Tag tag, std::string bytes) {
    auto& p = pending_.emplace_back();
    p.bytes = std::move(bytes);
    check(MPI_Isend(p.bytes.data(), static_cast<int>(p.bytes.size()), MPI_CHAR, destination,
                    static_cast<int>(tag), MPI_COMM_WORLD, &p.request),
          "MPI_Isend to rank " + std::to_string(destination));
}

void PendingSends::progress() {
    for (auto it = pending_.begin(); it != pending_.end();) {
        int done = 0;
        check(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        it = done ? pending_.erase(it) : std::next(it);
    }
}

bool PendingSends::drain(double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
        progress();
        if (pending_.empty()) return true;
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

}  // namespace bhm::app::mpi
