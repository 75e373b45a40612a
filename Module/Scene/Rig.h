// CatadioptricAR Core: the rig in 3D, in world coordinates: where the camera is, what its lens
// sees (the frustum) and the part of the mirror it sees, so that it can be drawn beside the scene.
//
// Everything comes from the camera's own model, with no particular mirror shape named:
//  - the camera centre is -R^T t of the world-to-camera pose;
//  - the frustum's far end is the image border (pixel centres convention: the image covers
//    [-0.5, width - 0.5] x [-0.5, height - 0.5]) back-projected through the lens (intrinsics and
//    distortion; the mirror is not used) to a given depth, the camera-frame z;
//  - the mirror is sampled where the camera sees it: a grid of pixels over the part of the image
//    that shows the mirror, each back-projected through the lens and met with the mirror
//    (Mirror::Intersect: the first point of the mirror on the ray and the normal there). Cells of
//    the grid are triangulated in pixel space, marching-squares style: where a cell's corners
//    disagree (one sees the mirror, the other not), the boundary point on the cell's edge is found
//    by bisection along the edge, to about 1e-9 of a cell. Every point is thus a point of the
//    mirror the camera sees, exactly (to the mirror's intersection accuracy);
//  - the outline is the boundary of that triangulation: where the mirror's image ends in the
//    image (its rim, or the image border where the frame cuts the mirror).
// Known limit: a mirror that hides a part of itself from the camera (a deep bowl seen from inside)
// has triangles across the fold where the seen surface jumps.
#ifndef catarRig_h
#define catarRig_h

#include "CameraModel.h"

#include <array>
#include <string>
#include <vector>

namespace catar
{
class Projector;

/// How finely the rig is drawn.
struct RigOptions
{
  /// Grid cells along the longer side of the part of the image that shows the mirror (2 or more).
  int mirrorResolution = 48;
  /// Depth (camera-frame z) of the frustum's far end; 0 or less: 1.25 times the depth of the
  /// farthest mirror point seen (1.25 times the mirror's viewpoint depth when none is seen, or 1).
  double frustumLength = 0.0;
  /// Points per image side on the frustum's far border when the lens distorts (then the border's
  /// image is curved); without distortion the four corners alone.
  int borderSamples = 16;
  /// Threads for the mirror's sampling (< 1: the pool's default).
  int threads = 0;
};

/// The rig, world coordinates.
struct RigGeometry
{
  Vec3 centre = Vec3::Zero(); ///< the camera centre
  double frustumLength = 0.0; ///< the depth used (the option, or the automatic one)

  /// The frustum's far border, a closed loop (the first point is not repeated) in image order:
  /// top-left corner, along the top row, top-right corner, down the right column, ... Points of
  /// pixels beyond the distortion model's range are left out.
  std::vector<Vec3> border;
  std::vector<Vec2> borderPixels; ///< the pixel of each border point
  /// Indices into border of the image's corners that have a point (top-left, top-right,
  /// bottom-right, bottom-left; -1 for a corner left out).
  std::array<int, 4> corners = { { -1, -1, -1, -1 } };

  /// The mirror as the camera sees it: points, unit normals facing the camera, the pixel of each
  /// point, and triangles (indices into points) wound so that their normals face the camera.
  std::vector<Vec3> mirrorPoints;
  std::vector<Vec3> mirrorNormals;
  std::vector<Vec2> mirrorPixels;
  std::vector<std::array<int, 3>> mirrorTriangles;
  /// The triangulation's boundary: closed loops of indices into mirrorPoints (the first index is
  /// not repeated).
  std::vector<std::vector<int>> outlines;
};

/// The rig of the projector's camera. False, with a sentence in `error`, when the camera is not
/// valid or the options are not usable (a non-finite frustum length, a resolution below 2).
/// A camera that does not see its mirror at all gives no mirror triangles and no outline, and is
/// not an error.
bool BuildRig(
  const Projector& projector, const RigOptions& options, RigGeometry& rig, std::string& error);
} // namespace catar

#endif
