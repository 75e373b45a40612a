// EstimatePose in a build without OpenGV and Ceres (CATAR_WITH_POSE off, or either not found):
// every pose is refused with a sentence that says why.
#include "PoseEstimation.h"

namespace catar
{
PoseResult EstimatePose(const CameraModel&, const std::vector<PoseObservation>&, const PoseOptions&)
{
  PoseResult result;
  result.error = "this build of CatadioptricAR has no pose from the image: it was built without "
                 "OpenGV and Ceres (install libopengv-dev and libceres-dev and build again)";
  return result;
}
} // namespace catar
