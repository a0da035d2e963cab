// Private to the DICOM reader: what a multi-frame instance keeps in its functional groups.
#pragma once

#include "DicomScan.h"

#include <gdcmDataSet.h>
#include <gdcmStringFilter.h>

namespace vots::fit::detail {

/// Fills what a multi-frame instance keeps in its functional groups: the shared groups stand in for the
/// top-level orientation, spacing and rescale an Enhanced CT/MR leaves out (and give frameGap), and each
/// per-frame group places its frame (framePlaces: position, temporal position, rescale); framePlaces stays
/// empty when no group places a frame.
void readFunctionalGroups(const gdcm::StringFilter& filter, const gdcm::DataSet& data,
                          DicomSliceHeader& slice);

} // namespace vots::fit::detail
