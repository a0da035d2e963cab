// A volume input that may be a series on a PACS: the --dicomweb-* options and the retrieve into a spool.
#pragma once

#include "vots/fit/VolumeHeader.h"
#include "vots/pacs/SeriesRetrieve.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>

namespace CLI {
class App;
}

namespace vots::cli {

struct DicomWebOptions {
    std::string authFile; // --dicomweb-auth: "basic USER:PASSWORD" or "bearer TOKEN"
    std::string caFile;   // --dicomweb-ca: PEM certificates for https
};

/// Adds --dicomweb-auth FILE and --dicomweb-ca FILE to a command.
void addDicomWebOptions(CLI::App& command, DicomWebOptions& options);

/// The credentials and trust anchors the options name (no credentials without --dicomweb-auth).
pacs::DicomWebAccess dicomWebAccessOf(const DicomWebOptions& options);

/// What the volume readers read for an INPUT: the path itself, or for a dicomweb+http(s):// URL the
/// spool folder its series was retrieved into, removed with this object (and on every error).
class VolumeInput {
public:
    /// `admit` sees a PACS series' announced grid before its pixels are asked for and throws to refuse.
    VolumeInput(const std::string& input, const DicomWebOptions& options,
                const std::function<void(const fit::VolumeHeaderInfo&)>& admit, bool progress);

    /// The file or folder to read.
    const std::string& path() const { return mPath; }
    /// The input as the user named it (the URL for a PACS series).
    const std::string& named() const { return mNamed; }
    bool fromPacs() const { return mRetrieved != nullptr; }
    /// The name a loaded volume should carry: a PACS series' SeriesInstanceUID (not its spool folder's
    /// name); empty for other inputs, whose readers name them.
    const std::string& volumeName() const { return mVolumeName; }

    /// Runs `read` with the spool folder's name in its fit::InputError replaced by the series URL.
    template <typename Read> auto reading(Read&& read) const {
        try {
            return std::forward<Read>(read)();
        } catch (const std::exception& e) {
            rethrowNamingTheUrl(e);
            throw;
        }
    }

private:
    void rethrowNamingTheUrl(const std::exception& e) const;

    std::string mNamed;
    std::string mVolumeName;
    std::string mPath;
    std::unique_ptr<pacs::RetrievedSeries> mRetrieved;
};

} // namespace vots::cli
