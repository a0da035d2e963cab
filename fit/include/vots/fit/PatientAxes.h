// Grid directions in patient space (LPS): normalising what a file states, naming axis-aligned ones.
#pragma once

#include <array>
#include <optional>
#include <string>

namespace vots::fit {

/// Unit vector per grid axis (x, y, z) in patient coordinates: +x the patient's left, +y posterior,
/// +z superior (DICOM's LPS). The same layout as Volume::patientAxes.
using PatientAxes = std::array<std::array<double, 3>, 3>;

constexpr PatientAxes IDENTITY_PATIENT_AXES{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};

/// The three direction vectors (any length, e.g. spacing-scaled columns of an affine) scaled to unit
/// length; nullopt when one is zero or not finite, or when they do not span space (collinear or coplanar).
std::optional<PatientAxes> normalizedPatientAxes(const PatientAxes& directions);

/// "L", "R", "P", "A", "S" or "I" when the unit vector lies along one patient direction (within 1e-6),
/// else "" (an oblique axis).
std::string patientDirectionName(const std::array<double, 3>& axis);

/// From RAS (NIfTI's and FreeSurfer's patient space) to our LPS: the first two coordinates of every axis
/// and of the origin change sign (a zero stays +0).
void rasToLps(PatientAxes& axes, std::array<double, 3>& origin);

/// Whether every axis is along one patient direction: a signed permutation of L, P, S.
bool isAxisAligned(const PatientAxes& axes);

} // namespace vots::fit
