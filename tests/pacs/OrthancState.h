// The Orthanc that the pacs fixture started (tests/pacs/pacs_setup.sh): its endpoint and credentials.
#pragma once

#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

namespace vots::test {

/// The fixture's folder (VOTS_ORTHANC_STATE): a missing one fails the test, never skips it.
inline std::string orthancState() {
    const char* state = std::getenv("VOTS_ORTHANC_STATE");
    if (!state || !*state)
        throw std::runtime_error("VOTS_ORTHANC_STATE is not set (run the tests through ctest)");
    return state;
}

inline std::string orthancStateFile(const std::string& name) {
    std::ifstream in(orthancState() + "/" + name);
    std::string value;
    if (!(in >> value))
        throw std::runtime_error("no " + name + " in the Orthanc fixture's state (did it start?)");
    return value;
}

inline pacs::DicomWebEndpoint orthancEndpoint() {
    return pacs::parseDicomWebEndpoint("dicomweb+http://127.0.0.1:" + orthancStateFile("port") +
                                       "/dicom-web");
}

inline pacs::DicomWebAccess orthancAccess() {
    pacs::DicomWebAccess access;
    access.auth = pacs::readDicomWebAuthFile(orthancState() + "/auth");
    return access;
}

/// The series pacs_setup.sh uploads (study UID = series UID + ".0").
inline constexpr const char* RAMP_SERIES = "1.2.826.0.1.3680043.10.1234.201";
inline constexpr const char* CRANIUM_SERIES = "1.2.826.0.1.3680043.10.1234.202";

inline pacs::DicomWebSeries orthancSeries(const std::string& series) {
    return {orthancEndpoint(), series + ".0", series};
}

} // namespace vots::test
