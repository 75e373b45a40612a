// CatadioptricAR Core (private): the lens as DetectMirrorOutline sees it (undistorted pixels),
// and the mirror's rim found along the normals of a first ellipse (MirrorRim.cxx). Not installed.
#ifndef catarMirrorRim_h
#define catarMirrorRim_h

#include "CameraModel.h"
#include "ConicFit.h"

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace catar
{
namespace detail
{
/// Undistorted pixel coordinates: K applied to the normalised undistorted coordinates, so that
/// lengths stay about a pixel while the lens distortion is undone.
struct Undistorter
{
  explicit Undistorter(const CameraModel& camera)
    : Camera(camera)
  {
  }
  bool operator()(const Vec2& pixel, Vec2& undistorted) const;
  /// The pixel of undistorted pixel coordinates.
  Vec2 Distorted(const Vec2& undistorted) const;
  const CameraModel& Camera;
};

/// What RimFromProfiles found.
struct RimReport
{
  int angles = 0;     ///< normals looked along (those inside the image)
  int covered = 0;    ///< of those, normals on which the rim shows as an edge
  double shift = 0.0; ///< mean distance (pixels) of the rim outside the first ellipse
  double noise = 0.0; ///< the profiles' derivative noise (grey levels per pixel), one sigma
};

/// The mirror's rim near a first ellipse `guess` (undistorted pixels; what the image's strong
/// edges gave, which may be an edge of the reflection inside the rim, as where the mirror
/// reflects a dark backdrop at its rim with little contrast): the image's grey level is sampled
/// along the ellipse's normals from 3 px inside to a quarter of its least semi-axis outside,
/// smoothed along the rim (the rim is smooth, so weak edges add up) and across it, and its
/// derivative's peaks above five times the noise are edge candidates. A RANSAC with five-point
/// conics among the candidates gives the ellipses that most normals support; of those supported
/// by at least 85 % as many normals as the best, the outermost is the rim (what lies outside a
/// mirror's outline is never the mirror). Its points are the candidates within a pixel of it,
/// placed between samples by a parabola through the derivative's peak; `pixels` are the same
/// points in the image as it is (distorted). False, with a sentence in `error`, when fewer than
/// half the normals inside the image show the rim.
bool RimFromProfiles(const cv::Mat& rgb, const Undistorter& lens, const Ellipse& guess,
  std::vector<Vec2>& pixels, std::vector<Vec2>& undistorted, RimReport& report, std::string& error);
} // namespace detail
} // namespace catar

#endif
