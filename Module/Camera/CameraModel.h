// CatadioptricAR Core: the non-central catadioptric camera model.
//
// A perspective camera (intrinsics K, OpenCV lens distortion) looks at a mirror (Mirror.h).
// Conventions (see Documentation/layout-and-conventions.md):
//  - camera frame as OpenCV: x right, y down, z forward; the camera centre is the origin;
//  - pixel (0,0) is the centre of the top-left pixel; K maps camera-frame rays to pixels exactly
//    as cv::projectPoints does (plus an optional skew term K(0,1));
//  - the pose is world-to-camera: p_camera = R p_world + t, stored as a 4x4 matrix.
#ifndef catarCameraModel_h
#define catarCameraModel_h

#include "MirrorDescription.h"
#include "Types.h"

#include <Eigen/Core>

#include <string>

namespace catar
{
/// Pinhole intrinsics and image size in pixels.
/// The largest image: at most kMaxImageSide pixels a side and kMaxImagePixels in all (2^28, a
/// 1 GiB RGBA frame). Larger sizes are refused where they enter (calibration and scene files,
/// the camera's setters, field data), never left to fail in an allocation.
constexpr int kMaxImageSide = 32768;
constexpr long long kMaxImagePixels = 1LL << 28;

struct Intrinsics
{
  double fx = 800.0;
  double fy = 800.0;
  double cx = 399.5;
  double cy = 299.5;
  double skew = 0.0; ///< K(0,1); 0 for OpenCV-calibrated cameras
  int width = 800;
  int height = 600;
};

/// OpenCV's five-parameter lens distortion (k1, k2, p1, p2, k3).
struct Distortion
{
  double k1 = 0.0;
  double k2 = 0.0;
  double p1 = 0.0;
  double p2 = 0.0;
  double k3 = 0.0;
  bool IsZero() const { return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0; }
};

/// The non-central catadioptric camera: lens, mirror and pose.
struct CameraModel
{
  Intrinsics intrinsics;
  Distortion distortion;
  MirrorDescription mirror; ///< the mirror, camera frame (default: Mirror.h's default type)
  Mat4 worldToCamera = Mat4::Identity();

  /// Empty when the model is usable; otherwise a sentence that says what is wrong
  /// (non-positive focal length, a mirror that ValidateMirror refuses, non-rigid pose, NaN...).
  std::string Validate() const;

  /// The 3x3 camera matrix K.
  Mat3 K() const;

  /// Pixel of a camera-frame direction (z > 0), with distortion: identical to cv::projectPoints.
  Vec2 DirectionToPixel(const Vec3& direction) const;

  /// Normalised undistorted image coordinates (x/z, y/z) of a pixel: the inverse of
  /// DirectionToPixel, solved with Newton's method to ~1e-15. Returns false when the inversion does
  /// not converge (a pixel beyond the distortion model's valid range).
  bool PixelToNormalized(const Vec2& pixel, Vec2& normalized) const;

  /// Is the pixel inside the image? Pixel (0,0) is the centre of the top-left pixel, so the image
  /// covers [-0.5, width-0.5) x [-0.5, height-0.5).
  bool InImage(const Vec2& pixel) const;

  /// World point to camera frame, and the camera centre in world coordinates.
  Vec3 WorldToCamera(const Vec3& pWorld) const;
  Vec3 CameraToWorld(const Vec3& pCamera) const;
  Vec3 CameraToWorldDirection(const Vec3& dCamera) const;

  /// Returns a copy for an image of another size: K is scaled so that the same rays land on the
  /// same relative positions (pixel centres convention kept).
  CameraModel Resized(int width, int height) const;
};

/// Applies OpenCV's distortion to normalised coordinates (x/z, y/z).
Vec2 Distort(const Distortion& d, const Vec2& xy);
} // namespace catar

#endif
