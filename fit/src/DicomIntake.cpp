// DicomSeriesIntake: file paths go to a GDCM child through a pipe as they arrive; the child answers each
// with its header and decoded pixels, which a thread of the parent stores in arrival order.
#include "vots/fit/DicomIntake.h"

#include "DicomChild.h"
#include "DicomLayout.h"
#include "DicomSlice.h"
#include "SampleRange.h"

#include "vots/fit/Error.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <functional>
#include <latch>
#include <limits>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

namespace vots::fit {
namespace {

using detail::DicomSliceHeader;

/// What the child says before each thing it sends.
enum class Said : int {
    Idle, // nothing to read for a while: keeps the parent's silence timeout for stuck decodes only
    File, // a file's header follows, then its pixels when it carriesPixels
    End,  // the files are all read
};
constexpr int IDLE_MS = 1000;
/// Headroom over a decoded slice for what a file holds besides its pixels (private elements, overlays).
constexpr std::uint64_t HEADER_ROOM_BYTES = 16ull << 20;

/// Whether the child decodes this file's pixels: an image of the announced size, a single frame of one
/// sample per pixel. Both ends decide it from the header alone, so they agree on what follows.
bool carriesPixels(const std::optional<DicomSliceHeader>& header, const VolumeHeaderInfo& announced) {
    return header && static_cast<std::uint64_t>(header->columns) == announced.dims[0] &&
           static_cast<std::uint64_t>(header->rows) == announced.dims[1] && header->frames == 1 &&
           header->samplesPerPixel == 1 &&
           (header->bitsAllocated == 8 || header->bitsAllocated == 16 || header->bitsAllocated == 32);
}

bool readAll(int fd, void* into, std::size_t size) {
    char* at = static_cast<char*>(into);
    while (size > 0) {
        const ssize_t got = ::read(fd, at, size);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        at += got;
        size -= static_cast<std::size_t>(got);
    }
    return true;
}

} // namespace

struct DicomSeriesIntake::State {
    VolumeHeaderInfo announced;
    std::size_t pixels = 0; // per slice
    Volume samples;         // the samples alone, in arrival order until finish()
    /// Stores the next slice the child sends for `header` at slot `slot` of `samples`.
    std::function<void(const DicomSliceHeader&, detail::ParentReceiver&, std::size_t slot,
                       std::vector<char>& buffer)>
        receiveAt;
    /// Moves slice order[z] (an arrival slot) to slot z, for every z.
    std::function<void(const std::vector<std::size_t>& order)> reorder;

    int paths[2] = {-1, -1}; // the parent writes length-prefixed paths to [1], the child reads [0]
    std::mutex mutex;        // guards added, pending and the pipe's writing end
    std::vector<std::string> added;
    std::string pending;               // path records the pipe had no room for yet
    std::atomic<bool> stopped{false};  // the decoding thread has ended
    std::atomic<bool> stopping{false}; // given up (a cut retrieve): the decoding thread ends soon

    // Written by the decoding thread alone, read after it is joined.
    std::vector<DicomSliceHeader> images; // in arrival order
    // Of each slot's slice as it lands, while the decoding thread would otherwise wait on the child: the
    // volume's contentCrc and valueRange are then combined from them, not read again after the last one.
    std::vector<std::uint32_t> sliceCrcs;
    std::vector<std::array<float, 2>> sliceRanges;
    bool mismatch = false; // a file is not of the announced grid
    std::exception_ptr failure;
    std::thread decoder;

    /// Writes what the pipe takes now; with `wait`, until everything is written or the child stopped.
    void flushLocked(bool wait) {
        while (!pending.empty() && !stopped) {
            const ssize_t written = ::write(paths[1], pending.data(), pending.size());
            if (written > 0) {
                pending.erase(0, static_cast<std::size_t>(written));
                continue;
            }
            if (written < 0 && errno == EINTR) continue;
            if (written < 0 && errno != EAGAIN) return; // the child is gone; its thread says why
            if (!wait) return;
            pollfd room{paths[1], POLLOUT, 0};
            ::poll(&room, 1, 100);
        }
    }

    void queueLocked(const std::string& path) {
        const std::uint32_t length = static_cast<std::uint32_t>(path.size());
        pending.append(reinterpret_cast<const char*>(&length), sizeof length);
        pending.append(path);
    }

    void childReads(detail::ChildSender& child) const {
        for (;;) {
            pollfd ready{paths[0], POLLIN, 0};
            const int polled = ::poll(&ready, 1, IDLE_MS);
            if (polled < 0 && errno == EINTR) continue;
            if (polled == 0) {
                const Said idle = Said::Idle;
                child.send(&idle, sizeof idle);
                continue;
            }
            std::uint32_t length = 0;
            std::string path;
            if (!readAll(paths[0], &length, sizeof length))
                throw InputError("the DICOM reader lost its files");
            if (length == 0) break;
            path.resize(length);
            if (!readAll(paths[0], path.data(), length)) throw InputError("the DICOM reader lost its files");
            child.announce(path);
            const std::optional<DicomSliceHeader> header = detail::readSliceHeader(path);
            const Said file = Said::File;
            child.send(&file, sizeof file);
            detail::sendSliceHeader(header, child);
            if (carriesPixels(header, announced)) {
                const std::array<int, 3> dims{static_cast<int>(announced.dims[0]),
                                              static_cast<int>(announced.dims[1]), 1};
                detail::DecodedFile decoded; // single-frame files only: nothing to keep between them
                detail::decodeAndSend(*header, dims, child, decoded);
            }
        }
        const Said end = Said::End;
        child.send(&end, sizeof end);
    }

    void receiveStoredSlice(const DicomSliceHeader& header, detail::ParentReceiver& parent, std::size_t slot,
                            std::vector<char>& buffer) {
        receiveAt(header, parent, slot, buffer);
        sliceCrcs[slot] = samples.planesCrc(static_cast<int>(slot), 1);
        sliceRanges[slot] = finiteRange(samples, slot * pixels, (slot + 1) * pixels);
    }

    void parentStores(detail::ParentReceiver& parent) {
        std::vector<float> scratch(pixels);
        std::vector<char> buffer;
        for (std::size_t next = 0;;) {
            Said said = Said::Idle;
            parent.nextInto(reinterpret_cast<char*>(&said), sizeof said);
            if (stopping) throw InputError("the DICOM reader was stopped");
            if (said == Said::Idle) continue;
            if (said == Said::End) break;
            std::string path;
            {
                std::lock_guard lock(mutex);
                path = added.at(next++);
            }
            const std::optional<DicomSliceHeader> header = detail::receiveSliceHeader(path, parent);
            if (!header) continue; // not an image: the caller counts images against files
            const std::size_t slot = images.size();
            images.push_back(*header);
            if (!carriesPixels(header, announced)) {
                mismatch = true;
                continue;
            }
            const bool fits =
                slot < announced.dims[2] && detail::valueTypeOf({*header}) == announced.sourceType;
            mismatch = mismatch || !fits;
            if (mismatch)
                detail::receiveSlice(*header, pixels, parent, buffer, scratch.data());
            else
                receiveStoredSlice(*header, parent, slot, buffer);
        }
    }
};

DicomSeriesIntake::DicomSeriesIntake(const VolumeHeaderInfo& announced, SampleStorage storage)
    : mState(std::make_unique<State>()) {
    State& s = *mState;
    s.announced = announced;
    s.pixels = static_cast<std::size_t>(announced.dims[0] * announced.dims[1]);
    const std::size_t slices = static_cast<std::size_t>(announced.dims[2]);
    for (int a = 0; a < 3; ++a)
        s.samples.dims[a] = static_cast<int>(announced.dims[a]); // for planesCrc
    s.sliceCrcs.resize(slices);
    s.sliceRanges.resize(slices);
    detail::withStoredSamples(s.samples, announced.sourceType, storage, [&](auto& samples) {
        samples.resize(s.pixels * slices);
        s.receiveAt = [&s, &samples](const DicomSliceHeader& header, detail::ParentReceiver& parent,
                                     std::size_t slot, std::vector<char>& buffer) {
            detail::receiveSlice(header, s.pixels, parent, buffer, samples.data() + slot * s.pixels);
        };
        s.reorder = [&s, &samples](const std::vector<std::size_t>& order) {
            // Cycle by cycle, with one slice held aside: the samples are never held twice.
            using Sample = typename std::decay_t<decltype(samples)>::value_type;
            std::vector<Sample> aside(s.pixels);
            std::vector<bool> placed(order.size(), false);
            const auto slice = [&](std::size_t z) { return samples.data() + z * s.pixels; };
            for (std::size_t start = 0; start < order.size(); ++start) {
                if (placed[start] || order[start] == start) continue;
                std::copy(slice(start), slice(start) + s.pixels, aside.data());
                std::size_t z = start;
                while (order[z] != start) {
                    std::copy(slice(order[z]), slice(order[z]) + s.pixels, slice(z));
                    placed[z] = true;
                    z = order[z];
                }
                std::copy(aside.begin(), aside.end(), slice(z));
                placed[z] = true;
            }
        };
    });
    if (::pipe2(s.paths, O_CLOEXEC) != 0)
        throw InputError(std::string("cannot start the DICOM reader: ") + std::strerror(errno));
    (void)::fcntl(s.paths[1], F_SETFL, O_NONBLOCK);
    (void)::fcntl(s.paths[1], F_SETPIPE_SZ, 1 << 20); // room for a few thousand paths; less is fine
    const std::uint64_t largest = s.pixels * 4u + HEADER_ROOM_BYTES;
    // The caller waits here until the child is forked: a fork while the caller's retrieve threads
    // allocate can leave the child a lock that no thread of it will release (sanitizer allocators are
    // not fork-safe), and the child would then hang until its silence timeout.
    std::latch forked(1);
    s.decoder = std::thread([&s, &forked, largest] {
        bool told = false;
        const auto tell = [&] {
            if (!std::exchange(told, true)) forked.count_down();
        };
        try {
            detail::runIsolated([&](detail::ChildSender& child) { s.childReads(child); },
                                [&](detail::ParentReceiver& parent) {
                                    tell();
                                    s.parentStores(parent);
                                },
                                detail::childLimitsHolding(largest));
        } catch (...) {
            s.failure = std::current_exception();
        }
        tell();
        s.stopped = true;
    });
    forked.wait();
}

DicomSeriesIntake::~DicomSeriesIntake() {
    State& s = *mState;
    if (s.decoder.joinable()) {
        // The thread stops at the child's next word (one second at most); the end, when the pipe has
        // no half-written path, stops the child sooner.
        s.stopping = true;
        {
            std::lock_guard lock(s.mutex);
            if (s.pending.empty()) {
                s.queueLocked({});
                s.flushLocked(true);
            }
        }
        s.decoder.join();
    }
    ::close(s.paths[0]);
    ::close(s.paths[1]);
}

void DicomSeriesIntake::add(const std::string& path) {
    State& s = *mState;
    std::lock_guard lock(s.mutex);
    s.added.push_back(path);
    s.queueLocked(path);
    s.flushLocked(false);
}

DicomIntakeResult DicomSeriesIntake::finish(const std::string& name) {
    State& s = *mState;
    {
        std::lock_guard lock(s.mutex);
        s.queueLocked({});
        s.flushLocked(true);
    }
    s.decoder.join();
    if (s.failure) std::rethrow_exception(s.failure);
    DicomIntakeResult result;
    result.files = static_cast<int>(s.added.size());
    result.images = static_cast<int>(s.images.size());
    if (s.mismatch || s.images.size() != s.announced.dims[2]) return result;
    std::map<std::string, std::size_t> slotOf;
    for (std::size_t slot = 0; slot < s.images.size(); ++slot)
        slotOf[s.images[slot].path] = slot;
    detail::DicomSeriesLayout layout = detail::layoutOfSlices(std::move(s.images), name);
    if (layout.valueType != s.announced.sourceType) return result;
    std::vector<std::size_t> order;
    for (const DicomSliceHeader& slice : layout.slices)
        order.push_back(slotOf.at(slice.path));
    s.reorder(order);
    Volume volume = detail::gridOfLayout(layout, name);
    std::uint32_t crc = volume.gridCrc();
    std::array<float, 2> range{std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity()};
    const std::uint64_t sliceBytes = s.pixels * sizeof(float); // contentCrc reads samples as floats
    for (const std::size_t slot : order) {
        crc = combineCrc(crc, s.sliceCrcs.at(slot), sliceBytes);
        range = {std::min(range[0], s.sliceRanges.at(slot)[0]),
                 std::max(range[1], s.sliceRanges.at(slot)[1])};
    }
    volume.values = std::move(s.samples.values);
    volume.compact = std::move(s.samples.compact);
    result.volume = std::move(volume);
    result.contentCrc = crc;
    result.valueRange = usableRange(range);
    return result;
}

} // namespace vots::fit
