// CatadioptricAR Core: how well a pose from the image is known (PoseEstimation.h).
//
// The pose's covariance from the Jacobian of the pixel residuals through the mirror, linearised
// at the pose: Sigma = s^2 (J^T J)^-1, where s is the pixels' noise, estimated from the
// residuals (their sum of squares over the degrees of freedom left) and never taken below a
// floor (four corners of one marker fit any pose near the right one exactly, which says nothing
// of their noise). The parameters are the camera's in the world: a rotation of the camera about
// world axes through its centre, and the centre's position; the uncertainty is reported as the
// one-sigma rotation and displacement along their worst directions.
#ifndef catarPoseUncertainty_h
#define catarPoseUncertainty_h

#include "PoseEstimation.h"

#include <vector>

namespace catar
{
class Projector;

/// The uncertainty of the world-to-camera pose `worldToCamera` fitted to the observations marked
/// in `inliers` (all when empty). `minimumPixelSigma`: the floor of the pixels' noise (px).
PoseUncertainty EstimatePoseUncertainty(const Projector& projector,
  const std::vector<PoseObservation>& observations, const std::vector<unsigned char>& inliers,
  const Mat4& worldToCamera, double minimumPixelSigma);
} // namespace catar

#endif
