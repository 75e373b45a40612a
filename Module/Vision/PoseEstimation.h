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
};

struct PoseResult
{
  bool ok = false;
  std::string error; ///< one sentence when !ok
  Mat4 worldToCamera = Mat4::Identity();
  std::vector<unsigned char> inliers; ///< per observation (1: inlier); empty when !ok
  int inlierCount = 0;
  double rmsPixels = 0.0; ///< over the inliers, through the mirror (forward projection)
};

/// The world-to-camera pose from pixel observations of known world points (at least 4 whose pixels
/// see the mirror). `camera` gives intrinsics, distortion and mirror (its pose is ignored).
/// Refused with a sentence in `error` (never NaN in the result): an invalid camera, non-finite
/// input (the first bad row named), fewer than 4 usable observations, (nearly) collinear world
/// points, nearly parallel reflected rays, or no pose that RANSAC finds with 4 inliers or more.
PoseResult EstimatePose(const CameraModel& camera, const std::vector<PoseObservation>& observations,
  const PoseOptions& options = {});
} // namespace catar

#endif
