// Writes a derived series: new UIDs, one rescale for the whole series, every file to a temporary, then all
// renamed at once.
#include "vots/pacs/DerivedSeries.h"

#include "DerivedSeriesFile.h"

#include "vots/fit/AtomicFile.h"

#include <gdcmUIDGenerator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <stdexcept>

namespace vots::pacs {
namespace {

void checkSeries(const DerivedSeries& series, const std::vector<std::string>& paths) {
    if (paths.size() != series.images.size())
        throw std::invalid_argument("writeDerivedSeries: one path per image");
    constexpr int MAX_SIDE = std::numeric_limits<std::uint16_t>::max(); // Rows and Columns are US
    for (const DerivedImage& image : series.images)
        if (image.width < 1 || image.height < 1 || image.width > MAX_SIDE || image.height > MAX_SIDE ||
            image.pixels.size() !=
                static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
            throw std::invalid_argument("writeDerivedSeries: an image's pixels do not match its size");
}

/// The finite values of every image, [lo, hi]; {0, 0} when none is finite.
std::array<double, 2> valueSpan(const DerivedSeries& series) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const DerivedImage& image : series.images)
        for (const float v : image.pixels)
            if (std::isfinite(v)) {
                lo = std::min(lo, static_cast<double>(v));
                hi = std::max(hi, static_cast<double>(v));
            }
    if (lo > hi) return {0.0, 0.0};
    return {lo, hi};
}

detail::SeriesStamp stampFor(const DerivedSeries& series) {
    gdcm::UIDGenerator uids;
    detail::SeriesStamp stamp;
    const fit::DicomIdentity identity = series.source.value_or(fit::DicomIdentity{});
    stamp.studyInstanceUid = identity.studyInstanceUid.empty() ? uids.Generate() : identity.studyInstanceUid;
    stamp.seriesInstanceUid = uids.Generate();
    stamp.frameOfReferenceUid =
        identity.frameOfReferenceUid.empty() ? uids.Generate() : identity.frameOfReferenceUid;
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char date[16], time[16];
    std::strftime(date, sizeof date, "%Y%m%d", &utc);
    std::strftime(time, sizeof time, "%H%M%S", &utc);
    stamp.date = date;
    stamp.time = time;
    const auto [lo, hi] = valueSpan(series);
    stamp.rescale = chooseRescale(lo, hi);
    return stamp;
}

/// Files written to their temporary names; removed again unless committed.
class PendingFiles {
public:
    PendingFiles() = default;
    PendingFiles(const PendingFiles&) = delete;
    PendingFiles& operator=(const PendingFiles&) = delete;
    ~PendingFiles() {
        for (const auto& [temporary, path] : mFiles)
            std::remove(temporary.c_str());
        for (const std::string& path : mPublished)
            std::remove(path.c_str());
    }
    void add(const std::string& path, const std::vector<std::uint8_t>& bytes) {
        mFiles.emplace_back(fit::writeTemporaryFor(path, bytes), path);
    }
    /// Renames every temporary to its path; should one rename fail, the files already renamed go too.
    void commit() {
        while (!mFiles.empty()) {
            const auto [temporary, path] = mFiles.front();
            mFiles.erase(mFiles.begin());
            fit::publishTemporary(temporary, path);
            mPublished.push_back(path);
        }
        mPublished.clear();
    }

private:
    std::vector<std::pair<std::string, std::string>> mFiles; // {temporary, final path}
    std::vector<std::string> mPublished;                     // renamed by a commit still under way
};

} // namespace

void writeDerivedSeries(const DerivedSeries& series, const std::vector<std::string>& paths) {
    checkSeries(series, paths);
    const detail::SeriesStamp stamp = stampFor(series);
    gdcm::UIDGenerator uids;
    PendingFiles pending;
    for (std::size_t k = 0; k < paths.size(); ++k)
        pending.add(paths[k],
                    detail::encodeDerivedImage(series, static_cast<int>(k), stamp, uids.Generate()));
    pending.commit();
}

} // namespace vots::pacs
