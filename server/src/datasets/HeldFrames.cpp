// HeldFrames: a least-recently-used list of loaded frames and their bytes.
#include "datasets/HeldFrames.h"

#include <algorithm>

namespace vots::server {

void HeldFrames::touch(const std::string& dataset, int frame) {
    const auto it = std::find_if(mUse.begin(), mUse.end(), [&](const Held& held) {
        return held.dataset == dataset && held.frame == frame;
    });
    if (it != mUse.end()) mUse.splice(mUse.end(), mUse, it);
}

void HeldFrames::makeRoom(std::uint64_t bytes, const std::function<bool()>& admits,
                          const std::function<void(const std::string&, int)>& drop) {
    while (!mUse.empty() && (mBytes + bytes > mBound || !admits())) {
        const Held oldest = mUse.front();
        mUse.pop_front();
        mBytes -= oldest.bytes;
        drop(oldest.dataset, oldest.frame);
    }
}

void HeldFrames::add(const std::string& dataset, int frame, std::uint64_t bytes) {
    mUse.push_back({dataset, frame, bytes});
    mBytes += bytes;
}

void HeldFrames::forget(const std::string& dataset) {
    for (auto it = mUse.begin(); it != mUse.end();) {
        if (it->dataset != dataset) {
            ++it;
            continue;
        }
        mBytes -= it->bytes;
        it = mUse.erase(it);
    }
}

HeldFramesSummary HeldFrames::summary() const {
    HeldFramesSummary out;
    out.bytes = mBytes;
    out.boundBytes = mBound;
    for (const Held& held : mUse)
        out.frames.push_back(held.dataset + "/" + std::to_string(held.frame));
    return out;
}

} // namespace vots::server
