// CatadioptricAR Core: the camera's pose from the image (generalized absolute pose).
//
// Given pixels of known world points in an image of a non-central catadioptric camera, finds the
// world-to-camera pose (p_camera = R p_world + t). Each pixel's reflected ray (a line in the camera
// frame that leaves the mirror point, not a ray through one centre) must pass through its world
// point: OpenGV's GP3P in RANSAC finds the pose, inliers are decided by the pixel reprojection
// error through the mirror, and Ceres refines the pose on the inliers (Miraldo and Araujo's
// generalized pose, as the paper this project implements).
#ifndef catarPoseEstimation_h
#define catarPoseEstimation_h

#include "CameraModel.h"

#include <string>
#include <vector>

namespace catar
{
/// One correspondence: the pixel (OpenCV convention, (0,0) the centre of the top-left pixel) where
/// the world point is seen.
struct PoseObservation
{
  Vec2 pixel = Vec2::Zero();
  Vec3 world = Vec3::Zero();
};

struct PoseOptions
{
  double inlierThreshold = 2.0; ///< pixels: reprojection error through the mirror for an inlier
  int maxIterations = 1000;     ///< RANSAC
  double confidence = 0.999;    ///< RANSAC: probability of drawing one all-inlier sample
  unsigned seed = 0;            ///< RANSAC is deterministic for a given seed
  bool refine = true;           ///< Ceres refinement of the pixel reprojection error

  // The guards (PoseResult::reliable). A pose that passes RANSAC is still flagged unreliable
  // when one of these fails; Documentation/markers.md says how they were measured.
  double minimumPixelSigma = 0.5;    ///< px: the floor of the pixels' noise in the uncertainty
  double maxPositionSigma = 0.008;   ///< m: the camera centre's one-sigma bound
  double maxAngleSigmaDegrees = 0.4; ///< the camera rotation's one-sigma bound
  double minInlierFraction = 0.5;    ///< inliers of all observations, at least
  /// PoseFromMarkers: a pose from one marker alone may be reliable (its four corners through a
  /// mirror are nearly ambiguous: off by 5-17 cm with every corner fitting within 0.4 px).
  bool allowSingleMarker = false;
};

/// How well a pose is known (PoseUncertainty.h): one sigma, from the pixel residuals' Jacobian.
struct PoseUncertainty
{
  /// False when the pixels do not fix the pose (J^T J singular, or a point with no image at the
  /// pose): then every sigma is infinite.
  bool known = false;
  double pixelSigma = 0.0;        ///< px: the noise used (estimated, at least the floor)
  double positionSigma = 0.0;     ///< m: the camera centre's error, worst direction
  double angleSigmaDegrees = 0.0; ///< the camera's rotation, worst axis
  /// (camera rotation about world axes [rad]; camera centre in the world [m]), 6 x 6
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

struct PoseResult
{
  bool ok = false;
  std::string error; ///< one sentence when !ok
  Mat4 worldToCamera = Mat4::Identity();
  std::vector<unsigned char> inliers; ///< per observation (1: inlier); empty when !ok
  int inlierCount = 0;
  double rmsPixels = 0.0;      ///< over the inliers, through the mirror (forward projection)
  PoseUncertainty uncertainty; ///< when ok
  /// ok, and no guard of PoseOptions flags it; else `warning` says which and with what numbers.
  bool reliable = false;
  std::string warning;
};

/// The world-to-camera pose from pixel observations of known world points (at least 4 whose pixels
/// see the mirror). `camera` gives intrinsics, distortion and mirror (its pose is ignored).
/// Refused with a sentence in `error` (never NaN in the result): an invalid camera, non-finite
/// input (the first bad row named), fewer than 4 usable observations, (nearly) collinear world
/// points, nearly parallel reflected rays, or no pose that RANSAC finds with 4 inliers or more.
/// A pose found is flagged unreliable (ok, !reliable, a warning) when its uncertainty exceeds
/// the options' bounds or its inliers are fewer than minInlierFraction of the observations.
PoseResult EstimatePose(const CameraModel& camera, const std::vector<PoseObservation>& observations,
  const PoseOptions& options = {});
} // namespace catar

#endif
