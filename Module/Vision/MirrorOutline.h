// CatadioptricAR Core: a spherical mirror's centre from its outline in a camera frame.
//
// The rays from the camera centre that touch a sphere (centre c in the camera frame, radius R)
// form a circular cone: its axis is the unit direction d = c / |c|, its half-angle alpha has
// sin(alpha) = R / |c|. In normalised undistorted image coordinates x = (u, v, 1) the sphere's
// outline is that cone's image, the conic
//   x^T C x = 0,   C = d d^T - cos^2(alpha) I   (up to scale),
// whose matrix has one eigenvalue (sin^2 alpha, eigenvector d) apart from two equal ones
// (-cos^2 alpha). So, with the radius and the camera's intrinsics and distortion known, the
// outline gives the centre: d from the odd eigenvector, alpha from the eigenvalues' ratio,
// |c| = R / sin(alpha).
//
// SphereFromOutline fits a general conic to the outline's normalised points (algebraic least
// squares after Hartley's normalisation), reads the cone from it, then refines the three numbers
// of c by Levenberg-Marquardt on the angular residuals: for each outline pixel, the angle between
// its camera ray and c minus alpha (the ray's angular distance from the cone; no conic involved).
// DetectMirrorOutline finds the outline's pixels in an image; SphereOutline predicts them.
#ifndef catarMirrorOutline_h
#define catarMirrorOutline_h

#include "CameraModel.h"

#include <cstdint>
#include <string>
#include <vector>

namespace catar
{
/// How well a sphere explains the outline it was estimated from.
struct SphereOutlineReport
{
  int pointCount = 0;     ///< outline points used
  double rmsAngle = 0.0;  ///< RMS angle between the points' rays and the tangent cone, radians
  double rmsPixels = 0.0; ///< RMS distance of the points from the estimate's outline, pixels
  double distance = 0.0;  ///< |centre|: the sphere centre's distance from the camera centre
  double halfAngle = 0.0; ///< the tangent cone's half-angle, radians
  int iterations = 0;     ///< Levenberg-Marquardt iterations of the refinement
};

/// Finds the outline of the mirror in a camera frame of width x height RGBA8 pixels (row 0 at
/// the top, no padding; alpha is not used): the boundary between the mirror's image and what
/// surrounds it. Edges (Canny on the lightly blurred colour image) are traced into contours, which
/// are also cut into smooth pieces where other edges cross them; conics fitted to contours, pieces
/// and pairs of the longest pieces propose ellipses (in undistorted pixels, where a sphere's
/// outline is one). The few proposals that the edges cover along the greatest length of their
/// perimeter are each refined by a RANSAC with a five-point conic model among the edge points
/// near them (dropping the reflection's own edges along the rim); the refined ellipse that the
/// edges cover along the greatest length is the outline. Its edge points are then placed between
/// pixels (the gradient maximum along the image axis nearest the edge's normal, parabolic fit).
/// outlinePixels: the outline points (pixel (0,0) is the centre of the top-left pixel), in the
/// image as it is (distorted). The camera's intrinsics must be for an image of this size; its
/// distortion (CameraModel overload) is undone before the conic models are fitted, and its mirror
/// is not used. False, with a sentence in `error`, for an empty or blank (uniform) image, an image
/// of another size than the intrinsics', no outline found, or an outline that lies on or beyond
/// the image border over more than half its length (the mirror is cut by the frame).
/// Accuracy: on rendered frames with a plain surround, the points lie within about 0.1 pixel of
/// the outline on average. Where the surround continues into the rim (a perfect mirror reflects,
/// at grazing angles, what lies behind it), the boundary found is where the reflection first
/// differs, which may be a few pixels inside the true outline.
bool DetectMirrorOutline(const CameraModel& camera, int width, int height, const std::uint8_t* rgba,
  std::vector<Vec2>& outlinePixels, std::string& error);
/// The same for a camera without lens distortion.
bool DetectMirrorOutline(const Intrinsics& intrinsics, int width, int height,
  const std::uint8_t* rgba, std::vector<Vec2>& outlinePixels, std::string& error);

/// The centre (camera frame) of the sphere of the given radius whose outline passes through
/// outlinePixels (at least 5 pixels of the image of `camera`, whose intrinsics and distortion are
/// used; its mirror and pose are not). See the top of this file for the method. report: the
/// points used, the RMS angular residual and the RMS pixel distance of the points from the outline
/// of the sphere found (SphereOutline). False, with a sentence in `error`, when the camera's
/// intrinsics or distortion are unusable, the radius is not positive and finite, there are fewer
/// than 5 points, a point is NaN/Inf or beyond the distortion model's range, the points do not lie
/// on an ellipse (collinear points, a hyperbola, ...), or the cone they give would put the camera
/// inside the sphere.
bool SphereFromOutline(const CameraModel& camera, double radius,
  const std::vector<Vec2>& outlinePixels, Vec3& centre, SphereOutlineReport& report,
  std::string& error);

/// The outline of a sphere (centre in the camera frame, radius) in the image of `camera`
/// (intrinsics and distortion): `count` pixels evenly spaced in angle around the tangent cone's
/// axis. Rays of the cone that do not point in front of the camera (z <= 0) are left out; empty
/// for a camera inside the sphere, an invalid radius or centre, or count < 1. The pixels may lie
/// outside the image.
std::vector<Vec2> SphereOutline(
  const CameraModel& camera, const Vec3& centre, double radius, int count);

/// The closed-form sphere mirror of that centre (camera frame) and radius, as a calibration holds
/// it (the mirror SphereFromOutline found).
MirrorDescription MirrorOfOutline(const Vec3& centre, double radius);
} // namespace catar

#endif
