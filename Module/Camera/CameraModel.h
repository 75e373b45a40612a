// CatadioptricAR Core: the non-central catadioptric camera model.
//
// A central camera (intrinsics K, a lens model: pinhole with OpenCV's distortion or fisheye;
// LensModels.h) looks at a mirror (Mirror.h).
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
#include <vector>

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

  bool operator==(const Intrinsics& o) const
  {
    return fx == o.fx && fy == o.fy && cx == o.cx && cy == o.cy && skew == o.skew &&
      width == o.width && height == o.height;
  }
  bool operator!=(const Intrinsics& o) const { return !(*this == o); }
};

/// The lens model: how a camera-frame direction becomes a pixel (LensModels.h has the formulas).
enum class LensType : int
{
  Pinhole = 0, ///< perspective, with OpenCV's distortion (cv::projectPoints)
  Fisheye = 1  ///< Kannala-Brandt (cv::fisheye::projectPoints), fields of view past 180 degrees
};

/// The name of a lens type in calibration files ("pinhole", "fisheye"), and back; false for an
/// unknown name.
const char* LensName(LensType lens);
bool LensFromName(const std::string& name, LensType& lens);

/// The lens distortion, in OpenCV's order and names. Pinhole: the full vector of cv::projectPoints
/// (k1 k2 p1 p2 k3, the rational k4 k5 k6, the thin prism s1..s4 and the sensor tilt tauX tauY in
/// radians), of which calibrations use the first 4, 5, 8, 12 or 14. Fisheye: cv::fisheye's k1 k2
/// k3 k4, held in the fields of those names (the others zero).
struct Distortion
{
  double k1 = 0.0;
  double k2 = 0.0;
  double p1 = 0.0;
  double p2 = 0.0;
  double k3 = 0.0;
  double k4 = 0.0;
  double k5 = 0.0;
  double k6 = 0.0;
  double s1 = 0.0;
  double s2 = 0.0;
  double s3 = 0.0;
  double s4 = 0.0;
  double tauX = 0.0;
  double tauY = 0.0;

  static constexpr int kCount = 14;
  /// The 14 numbers in OpenCV's order (the fields above in order).
  const double* Data() const { return &this->k1; }
  double* Data() { return &this->k1; }
  bool IsZero() const;
  bool Tilted() const { return this->tauX != 0.0 || this->tauY != 0.0; }
  bool operator==(const Distortion& other) const;
  bool operator!=(const Distortion& other) const { return !(*this == other); }

  /// The lens's coefficients as its calibration files write them: pinhole, the shortest of
  /// OpenCV's lengths 5, 8, 12, 14 that holds every non-zero number; fisheye, k1 k2 k3 k4.
  std::vector<double> Coefficients(LensType lens) const;
  /// Sets them from such a list: pinhole, 4, 5, 8, 12 or 14 numbers; fisheye, 4. False (and the
  /// distortion unchanged) for another count.
  bool SetCoefficients(LensType lens, const std::vector<double>& coefficients);
};
static_assert(sizeof(Distortion) == Distortion::kCount * sizeof(double), "the fields are a vector");

/// The non-central catadioptric camera: lens, mirror and pose.
struct CameraModel
{
  Intrinsics intrinsics;
  LensType lens = LensType::Pinhole;
  Distortion distortion;
  MirrorDescription mirror; ///< the mirror, camera frame (default: Mirror.h's default type)
  Mat4 worldToCamera = Mat4::Identity();

  /// Empty when the model is usable; otherwise a sentence that says what is wrong
  /// (non-positive focal length, a mirror that ValidateMirror refuses, non-rigid pose, NaN...).
  std::string Validate() const;

  /// The same image size, intrinsics, lens type and distortion (the mirror and pose aside).
  bool SameLens(const CameraModel& o) const
  {
    return intrinsics == o.intrinsics && lens == o.lens && distortion == o.distortion;
  }

  /// The 3x3 camera matrix K.
  Mat3 K() const;

  /// Pixel of a camera-frame direction, through the lens model: identical to cv::projectPoints
  /// (pinhole, z > 0) or cv::fisheye::projectPoints (fisheye).
  Vec2 DirectionToPixel(const Vec3& direction) const;

  /// Whether the lens images the direction: pinhole, z > 0; fisheye, less than 180 degrees from
  /// the axis (the model's own range is the caller's: DirectionToPixel then PixelToDirection).
  bool Sees(const Vec3& direction) const;

  /// The unit camera-frame direction of a pixel: the inverse of DirectionToPixel, solved with
  /// Newton's method to rounding. False when the inversion does not converge (a pixel beyond the
  /// lens model's valid range).
  bool PixelToDirection(const Vec2& pixel, Vec3& direction) const;

  /// Normalised undistorted image coordinates (x/z, y/z) of a pixel: PixelToDirection divided by
  /// its z; false also where the direction is not in front (z <= 0, a fisheye past 90 degrees).
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

/// Applies OpenCV's pinhole distortion to normalised coordinates (x/z, y/z).
Vec2 Distort(const Distortion& d, const Vec2& xy);
} // namespace catar

#endif
