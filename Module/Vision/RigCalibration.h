// CatadioptricAR Core: calibration of the rig from images of a known board seen in the mirror
// (the paper's section 3.1; Perdigoto and Araujo's calibration of the mirror).
//
// Given the lens (OpenCV's calibration of the bare camera), the mirror's type and a starting
// guess, and several views of a board whose markers' corners were found in the image, it
// estimates the mirror and every view's board pose by minimising the pixels' reprojection error
// through the exact forward projection (Ceres, Huber loss): each corner's board point, posed in
// the camera frame, is projected through the mirror, and its pixel compared with the detected
// one. The derivatives are analytic: through the reflection point by the implicit function
// theorem on the reflection's Lagrange system (r / |r| + (r - P) / |r - P| = lambda grad F(r),
// F(r) = 0, the mirror F = r^T A r + 2 B^T r + C in the camera frame), through the lens by
// automatic differentiation of its formula (LensModels.h), and through the pose in closed form.
// With `freeLens` the focal lengths, principal point and distortion are refined too.
//
// What is estimated of the mirror (its numbers in the camera frame):
//  - sphere (centre and radius): the centre x, y, z and the radius;
//  - the quadric shapes: mirror_to_camera's rotation (about the mirror frame's x and y for a
//    surface of revolution, whose turn about its own axis shows nothing; about all three for an
//    ellipsoid of three different axes) and translation, and the shape's numbers (hyperboloid a
//    and b, paraboloid focal, ellipsoid semi_axes, cone half_angle, the cut sphere's radius);
//    z_range (where the mirror is cut) stays as given. The general "quadric" is not calibrated.
//
// The board sets the scale of the whole rig: a central lens sees a scene and its copy scaled
// about the lens's centre alike, so a board whose printed size is wrong fits as well as the true
// one, with the mirror scaled by the same factor. That is why the mirror's size may not move
// more than maxSizeChange from the start (the nominal size of a bought mirror).
#ifndef catarRigCalibration_h
#define catarRigCalibration_h

#include "CalibrationIO.h"
#include "CameraModel.h"
#include "Markers.h"
#include "PoseEstimation.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace catar
{
/// One view of the board: its corners' pixels and board points (the board's frame is the world).
struct CalibrationView
{
  std::string name; ///< for messages (the image's file name)
  std::vector<PoseObservation> observations;
};

struct CalibrationOptions
{
  bool freeLens = false;    ///< refine fx, fy, cx, cy and the distortion too
  double robustScale = 1.0; ///< px: Huber's loss is quadratic below this residual
  /// px: after a first solve, corners whose residual exceeds this and four times the median's
  /// are left out (CalibrationResult::outliers) and the rest solved again
  double outlierPixels = 1.0;
  double maxRmsPixels = 2.0;   ///< a calibrated fit worse than this is refused
  double maxSizeChange = 0.08; ///< the mirror's size numbers may move this fraction at most
  int minViews = 3;            ///< views with a board pose, at least
  int maxIterations = 100;
  /// Called after each of the solver's iterations: the iteration and the RMS of the residuals.
  std::function<void(int iteration, double rmsPixels)> progress;
};

/// One estimated number: its name (a key: "center_x", "radius", "tilt_x" (degrees, from the
/// start's orientation), "translation_z", "a", "focal", "semi_axes_z", "half_angle", "fx", "k1",
/// ...), value and standard deviation (one sigma, from the residuals' Jacobian and their spread).
struct CalibratedNumber
{
  std::string name;
  std::string unit; ///< "m", "deg", "px" or "" (distortion coefficients)
  double value = 0.0;
  double sigma = 0.0;
};

struct CalibrationResult
{
  bool ok = false;
  std::string error;                 ///< one sentence when !ok
  CameraModel camera;                ///< the calibrated lens and mirror (the pose is the identity)
  double rmsPixels = 0.0;            ///< over every corner of the views used
  int imagesUsed = 0;                ///< views with a board pose, in the calibration
  std::vector<int> usedViews;        ///< their indices
  std::vector<Mat4> boardToCamera;   ///< per used view, the board's pose
  std::vector<double> viewRmsPixels; ///< per used view
  std::vector<std::string> skipped;  ///< views left out, each with why
  std::vector<CalibratedNumber> mirror; ///< the mirror's estimated numbers
  std::vector<CalibratedNumber> lens;   ///< with freeLens, the lens's
  int iterations = 0;
  int outliers = 0; ///< corners left out after the first solve
  /// Per used view, each corner's detected pixel and its residual (projected - detected), px.
  std::vector<std::vector<std::pair<Vec2, Vec2>>> residuals;
};

/// Calibrates the mirror (and with options.freeLens the lens) of `initial` (its lens, the
/// mirror's type and a starting guess) from the views. Refused with a sentence (ok false): an
/// invalid start, a mirror type that cannot be calibrated, fewer than minViews views whose board
/// pose was found, a fit whose RMS exceeds maxRmsPixels or whose mirror size moved more than
/// maxSizeChange (the board does not fit), or numbers the views do not fix (named).
CalibrationResult CalibrateRig(const CameraModel& initial,
  const std::vector<CalibrationView>& views, const CalibrationOptions& options = {});

/// What a calibration's file records of it (CalibrationIO.h's `calibration` map): the RMS, the
/// names of the views used (names[i]: view i's) and every estimated number, the mirror's first.
CalibrationRecord RecordOf(const CalibrationResult& result, const std::vector<std::string>& names);

/// An image of the board in the mirror: RGBA8, the top row first.
struct CalibrationImage
{
  std::string name;
  int width = 0;
  int height = 0;
  const std::uint8_t* rgba = nullptr;
};

/// CalibrateRig from images: the board's markers found in each (DetectMarkers, mirror-imaged),
/// a first calibration on their corners, the corners then moved onto the markers' edges with the
/// calibrated rig and each view's pose (RefineMarkerCorners: OpenCV's corners lie about half a
/// pixel inside, which biases the mirror), and the calibration again from `initial` on those.
/// `views`, when given, receives the views of the second calibration. Refused with a sentence as
/// CalibrateRig, and for an image of another size than the calibration's or a board that is not
/// usable.
CalibrationResult CalibrateRigFromImages(const CameraModel& initial, const MarkerBoard& board,
  const std::vector<CalibrationImage>& images, const CalibrationOptions& options = {},
  std::vector<CalibrationView>* views = nullptr);
} // namespace catar

#endif
