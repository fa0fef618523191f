#pragma once
// The snapshot hand-off between a worker thread and the UI (MuJoCo simulate's pattern): the worker
// publishes an immutable snapshot, the UI takes the newest at the start of a frame and draws from
// it with no lock held. The lock guards only a shared_ptr copy, so neither side ever waits for
// the other's work.
#include <cstdint>
#include <memory>
#include <mutex>

namespace bhm::app::gui {

template <class T>
class LatestSlot {
  public:
    void publish(std::shared_ptr<const T> snapshot) {
        std::lock_guard lock(mutex_);
        latest_ = std::move(snapshot);
        ++version_;
    }
    std::shared_ptr<const T> take() const {
        std::lock_guard lock(mutex_);
        return latest_;
    }
    //! Increases with every publish: the UI compares it to know whether anything is new.
    std::uint64_t version() const {
        std::lock_guard lock(mutex_);
        return version_;
    }

  private:
    mutable std::mutex mutex_;
    std::shared_ptr<const T> latest_;
    std::uint64_t version_ = 0;
};

}  // namespace bhm::app::gui
