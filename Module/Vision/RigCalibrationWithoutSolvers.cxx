// CalibrateRig in a build without OpenGV and Ceres (CATAR_WITH_POSE off, or either not found):
// every calibration is refused with a sentence that says why.
#include "RigCalibration.h"

namespace catar
{
CalibrationResult CalibrateRig(
  const CameraModel&, const std::vector<CalibrationView>&, const CalibrationOptions&)
{
  CalibrationResult result;
  result.error = "this build of CatadioptricAR cannot calibrate: it was built without OpenGV and "
                 "Ceres (install libopengv-dev and libceres-dev and build again)";
  return result;
}
} // namespace catar
