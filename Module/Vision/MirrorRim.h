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

/// Where RimFromProfiles looks (pixels of the image it is given).
struct RimSearch
{
  double inside = 3.0;      ///< from this far inside the first ellipse
  double outside = 6.0;     ///< to this far outside it
  double acrossSigma = 2.0; ///< the profiles' smoothing across the rim, to find it
  double alongSigma = 10.0; ///< and along it (arc length): weak edges add up
  /// The rim is known to lie in the band (found on a reduced frame): on each normal the strongest
  /// edge is taken, with no noise threshold and no search for closed edges.
  bool place = false;
  /// Where given (points in order along the rim, undistorted pixels): the normals start there,
  /// along the first ellipse's normal, instead of every 2 px round the whole ellipse.
  const std::vector<Vec2>* feet = nullptr;
};

/// The mirror's rim near a first ellipse `guess` (undistorted pixels; what the image's strong
/// edges gave, which may be an edge of the reflection inside the rim, as where the mirror
/// reflects a dark backdrop at its rim with little contrast): the image's grey level is sampled
/// along the ellipse's normals (every 2 px of its perimeter, at most 4096) across the `search`
/// band, smoothed along the rim and across it, and its derivative's peaks above five times the
/// noise (estimated on the band's outer quarter) are edges. Closed edges are then taken from the
/// inside out: the path through the edges, one per normal, that collects the most, then the most
/// wholly outside it, and so on while one shows on at least half the normals; the last (outermost:
/// what lies outside a mirror's outline is never the mirror) is the rim. Its points are placed on
/// each normal by the derivative's peak with 1 px of smoothing across (a wider blur is pulled by
/// edges nearby), between samples by a parabola; `pixels` are the same points in the image as it
/// is (distorted). `image`: 8-bit RGB or RGBA. False, with a sentence in `error`, when the rim
/// shows on fewer than half the normals inside the image.
bool RimFromProfiles(const cv::Mat& image, const Undistorter& lens, const Ellipse& guess,
  const RimSearch& search, std::vector<Vec2>& pixels, std::vector<Vec2>& undistorted,
  RimReport& report, std::string& error);
} // namespace detail
} // namespace catar

#endif
