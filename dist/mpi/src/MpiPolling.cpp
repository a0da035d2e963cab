// Polled point-to-point MPI: matched probes and nonblocking transfers tested against a deadline.
#include "MpiPolling.h"

#include <memory>
#include <thread>

namespace vots::dist {
namespace {

// Polling, not blocking: Open MPI's blocking calls spin a core, and a rank that has died never completes
// them.
constexpr auto POLL_PERIOD = std::chrono::milliseconds(2);

// Receive buffers whose transfer did not end by its deadline: MPI may still write into them, so they are
// kept for the life of the process (one per lost rank at most: a lost rank is never asked again).
std::vector<std::unique_ptr<std::vector<char>>>& abandonedBuffers() {
    static std::vector<std::unique_ptr<std::vector<char>>> buffers;
    return buffers;
}

} // namespace

std::mutex& mpiCallLock() {
    static std::mutex lock;
    return lock;
}

std::optional<std::vector<char>> receiveBefore(int source, int tag,
                                               std::optional<PollClock::time_point> deadline,
                                               const KeepWaiting& keepWaiting) {
    for (;;) {
        int arrived = 0;
        MPI_Message message = MPI_MESSAGE_NULL;
        MPI_Status status;
        {
            std::lock_guard lock(mpiCallLock());
            if (MPI_Improbe(source, tag, MPI_COMM_WORLD, &arrived, &message, &status) != MPI_SUCCESS)
                return std::nullopt;
        }
        if (arrived) {
            // The matched receive, nonblocking: a sender that dies mid-message leaves it incomplete, and the
            // deadline still holds (a blocking receive would wait for ever).
            int count = 0;
            auto bytes = std::make_unique<std::vector<char>>();
            MPI_Request request = MPI_REQUEST_NULL;
            {
                std::lock_guard lock(mpiCallLock());
                MPI_Get_count(&status, MPI_BYTE, &count);
                bytes->resize(static_cast<std::size_t>(count));
                if (MPI_Imrecv(bytes->data(), count, MPI_BYTE, &message, &request) != MPI_SUCCESS)
                    return std::nullopt;
            }
            const auto end = deadline ? *deadline : PollClock::time_point::max();
            if (completedBefore(request, end, keepWaiting)) return std::move(*bytes);
            std::lock_guard lock(mpiCallLock());
            abandonedBuffers().push_back(std::move(bytes));
            return std::nullopt;
        }
        if (deadline && PollClock::now() >= *deadline) return std::nullopt;
        if (keepWaiting && !keepWaiting()) return std::nullopt;
        std::this_thread::sleep_for(POLL_PERIOD);
    }
}

bool completedBefore(MPI_Request& request, PollClock::time_point deadline, const KeepWaiting& keepWaiting) {
    for (;;) {
        int done = 0;
        {
            std::lock_guard lock(mpiCallLock());
            if (MPI_Test(&request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) return false;
        }
        if (done) return true;
        if (PollClock::now() >= deadline) return false;
        if (keepWaiting && !keepWaiting()) return false;
        std::this_thread::sleep_for(POLL_PERIOD);
    }
}

std::vector<int> takeArrived(int tag) {
    std::vector<int> sources;
    std::lock_guard lock(mpiCallLock());
    for (;;) {
        int arrived = 0;
        MPI_Message message = MPI_MESSAGE_NULL;
        MPI_Status status;
        if (MPI_Improbe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &arrived, &message, &status) != MPI_SUCCESS ||
            !arrived)
            return sources;
        // Empty and already here: the matched receive completes at once.
        if (MPI_Mrecv(nullptr, 0, MPI_BYTE, &message, MPI_STATUS_IGNORE) != MPI_SUCCESS) return sources;
        sources.push_back(status.MPI_SOURCE);
    }
}

bool startSend(const std::vector<char>& bytes, int dest, int tag, MPI_Request& request) {
    std::lock_guard lock(mpiCallLock());
    return MPI_Isend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD,
                     &request) == MPI_SUCCESS;
}

bool sendDone(MPI_Request& request) {
    if (request == MPI_REQUEST_NULL) return true;
    int done = 0;
    std::lock_guard lock(mpiCallLock());
    return MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done;
}

} // namespace vots::dist
