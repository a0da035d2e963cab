// `vots serve --dicomweb NAME=URL [--dicomweb-auth NAME=FILE] [--dicomweb-ca NAME=FILE]`: the PACS to browse.
#pragma once

#include "vots/server/Server.h"

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace vots::cli {

struct ServeDicomWebArgs {
    std::vector<std::string> services; // NAME=URL
    std::vector<std::string> auths;    // NAME=FILE
    std::vector<std::string> cas;      // NAME=FILE
    int cacheGb = 16;                  // GiB of retrieved series kept in the cache folder
};

/// Adds the three repeatable options and --dicomweb-cache-gb to `vots serve`.
void addServeDicomWebOptions(CLI::App& command, ServeDicomWebArgs& args);

/// The services the options name, their auth files read. Throws fit::InputError with one line for a
/// malformed NAME=VALUE, a NAME that is not a plain identifier or is given twice, an auth or CA for an
/// unnamed service, a bad URL or auth file (naming the file, never its contents).
std::vector<server::DicomWebService> dicomWebServicesOf(const ServeDicomWebArgs& args);

} // namespace vots::cli
