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

void checkImage(const DerivedImage& image) {
    constexpr int MAX_SIDE = std::numeric_limits<std::uint16_t>::max(); // Rows and Columns are US
    if (image.width < 1 || image.height < 1 || image.width > MAX_SIDE || image.height > MAX_SIDE ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
        throw std::invalid_argument("writeDerivedSeries: an image's pixels do not match its size");
}

/// The finite values of every image, [lo, hi]; {0, 0} when none is finite.
std::array<double, 2> valueSpan(const std::vector<DerivedImage>& images) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const DerivedImage& image : images)
        for (const float v : image.pixels)
            if (std::isfinite(v)) {
                lo = std::min(lo, static_cast<double>(v));
                hi = std::max(hi, static_cast<double>(v));
            }
    if (lo > hi) return {0.0, 0.0};
    return {lo, hi};
}

detail::SeriesStamp stampFor(const DerivedSeries& series) {
    if (!series.valueRange)
        throw std::invalid_argument("DerivedSeriesWriter: the series needs its valueRange");
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
    stamp.rescale = chooseRescale((*series.valueRange)[0], (*series.valueRange)[1]);
    return stamp;
}

} // namespace

struct DerivedSeriesWriter::State {
    DerivedSeries series;
    std::vector<std::string> paths;
    detail::SeriesStamp stamp;
    gdcm::UIDGenerator uids;
    std::vector<std::string> temporaries; // one per image added, beside its path
    std::vector<std::string> published;   // renamed by a finish() still under way
};

DerivedSeriesWriter::DerivedSeriesWriter(DerivedSeries series, std::vector<std::string> paths)
    : mState(std::make_unique<State>()) {
    series.images.clear();
    mState->stamp = stampFor(series);
    mState->series = std::move(series);
    mState->paths = std::move(paths);
}

DerivedSeriesWriter::~DerivedSeriesWriter() {
    for (const std::string& temporary : mState->temporaries)
        std::remove(temporary.c_str());
    for (const std::string& path : mState->published)
        std::remove(path.c_str());
}

void DerivedSeriesWriter::add(const DerivedImage& image) {
    State& s = *mState;
    const std::size_t index = s.temporaries.size();
    if (index >= s.paths.size()) throw std::invalid_argument("DerivedSeriesWriter: more images than paths");
    checkImage(image);
    s.temporaries.push_back(fit::writeTemporaryFor(
        s.paths[index],
        detail::encodeDerivedImage(s.series, image, static_cast<int>(index), s.stamp, s.uids.Generate())));
}

void DerivedSeriesWriter::finish() {
    State& s = *mState;
    if (s.temporaries.size() != s.paths.size())
        throw std::invalid_argument("DerivedSeriesWriter: one image per path");
    // Should one rename fail, the files already renamed go too (the destructor), so no partial series stays.
    for (std::size_t k = 0; k < s.paths.size(); ++k) {
        const std::string temporary = s.temporaries[k];
        s.temporaries[k].clear();
        fit::publishTemporary(temporary, s.paths[k]);
        s.published.push_back(s.paths[k]);
    }
    s.temporaries.clear();
    s.published.clear();
}

void writeDerivedSeries(const DerivedSeries& series, const std::vector<std::string>& paths) {
    if (paths.size() != series.images.size())
        throw std::invalid_argument("writeDerivedSeries: one path per image");
    DerivedSeries header = series;
    if (!header.valueRange) header.valueRange = valueSpan(series.images);
    header.images.clear();
    DerivedSeriesWriter writer(std::move(header), paths);
    for (const DerivedImage& image : series.images)
        writer.add(image);
    writer.finish();
}

} // namespace vots::pacs
