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
  /// One sigma of the centre along its worst direction (the calibration's length unit), from the
  /// fit's Jacobian and residuals, their correlation along the outline counted (the points in the
  /// outline's order, as DetectMirrorOutline gives them).
  double centreSigma = 0.0;
};

/// Finds the outline of the mirror in a camera frame of width x height RGBA8 pixels (row 0 at
/// the top, no padding; alpha is not used): the boundary between the mirror's image and what
/// surrounds it, as the image of a sphere's limb is: a right circular cone of rays from the camera
/// centre. A first guess from the strong edges (Canny on the lightly blurred colour image; contours
/// and smooth pieces of them, and pairs of pieces, fitted with such cones; the few the edges cover
/// along the greatest length refined by a RANSAC with cones through three edge points' rays; the
/// one covered along the greatest length). Then the rim along the guess's normals: the outermost
/// closed edge on each (profiles smoothed along the rim, so a rim of little contrast, as a real
/// mirror shows before a dark backdrop that it reflects at grazing angles, is found outside the
/// reflection's stronger edges), the points of one right circular cone among them (a RANSAC; a
/// dome's cut is left out), the rim searched again near that cone and its points placed along the
/// normals (between samples). Frames larger than 1024 px a side are searched reduced, and the rim
/// placed on the whole frame. See Documentation/mirror-outline.md.
/// outlinePixels: the outline points (pixel (0,0) is the centre of the top-left pixel), in the
/// image as it is (distorted), every 2 to 3 px where the rim shows. The camera's intrinsics must be
/// for an image of this size; its distortion (CameraModel overload) is undone before the cones are
/// fitted, and its mirror is not used. False, with a sentence in `error`, for an empty or blank
/// (uniform) image, an image of another size than the intrinsics', no outline found (or a rim that
/// shows on less than about a third of it), or an outline that lies on or beyond the image border
/// over more than half its length (the mirror is cut by the frame).
/// Accuracy: on POV-Ray's frames of a mirror of reflectance 0.7 before bright and dark backdrops,
/// spheres and domes, clean and noisy, the centre found from the points is within 0.0007-0.137 % of
/// its distance.
bool DetectMirrorOutline(const CameraModel& camera, int width, int height, const std::uint8_t* rgba,
  std::vector<Vec2>& outlinePixels, std::string& error);
/// What DetectMirrorOutline looks for.
struct MirrorOutlineOptions
{
  /// True: a sphere's limb, the image of a right circular cone of rays from the camera centre
  /// (a sphere, a dome's limb). False: any ellipse, as a circular rim seen aslant makes (a quadric
  /// mirror's rim: QuadricFromRim).
  bool limb = true;
};
/// The same with options.
bool DetectMirrorOutline(const CameraModel& camera, int width, int height, const std::uint8_t* rgba,
  const MirrorOutlineOptions& options, std::vector<Vec2>& outlinePixels, std::string& error);
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

/// How a quadric mirror's rim explains the outline it was placed from (QuadricFromRim).
struct RimOutlineReport
{
  int pointCount = 0;            ///< outline points used
  double rimRadius = 0.0;        ///< the rim circle's radius
  double rimZ = 0.0;             ///< its height in the mirror frame (an end of z_range)
  Vec3 rimCentre = Vec3::Zero(); ///< its centre, camera frame
  Vec3 axis = Vec3::UnitZ();     ///< the mirror's axis (its frame's z), camera frame
  double rmsPixels = 0.0;        ///< RMS distance of the points from the fitted rim's image, pixels
  double axisTurn = 0.0; ///< angle between the first guess's axis and the one found, radians
  double shift = 0.0;    ///< distance between the first guess's rim centre and the one found
  /// One sigma of the rim's centre (worst direction; the calibration's length unit) and of the
  /// axis (radians; 0 when the axis was kept), from the fit's Jacobian and residuals with the
  /// points taken as independent. A rim seen nearly head-on fixes its distance well and its tilt
  /// poorly (a tilt and a shift across look alike): the axis sigma says how poorly.
  double centreSigma = 0.0;
  double axisSigma = 0.0;
  /// When the other tilt a circle's image allows fits as well (costs within 45 times the
  /// residuals' variance: three sigmas, the points counted as a fifth as many for the smoothing
  /// along the rim; a circle seen through a pinhole has two poses that fit exactly), the angle
  /// between the two axes (radians), else 0: the axis is then not known from the rim, only one of
  /// two (the one nearer the guess is taken; the other is otherAxis).
  double ambiguousTilt = 0.0;
  Vec3 otherAxis = Vec3::Zero();
  int iterations = 0; ///< Levenberg-Marquardt iterations
};

/// What QuadricFromRim fits.
struct RimFitOptions
{
  /// True: the rim's centre and the mirror's axis (five numbers). False: the centre only, the
  /// axis kept as the first guess has it (a rig built with the mirror's axis on the camera's).
  bool fitAxis = true;
};

/// A quadric mirror of revolution (a hyperboloid, paraboloid, ellipsoid, cone or cut sphere about
/// its frame's z axis) placed from its rim's outline: the circle where the surface meets the end
/// of z_range where it is widest, whose image is the outline a camera looking into such a mirror
/// sees. `mirror` gives the type, shape numbers and z_range (kept) and a first guess of
/// mirror_to_camera (the nominal mounting), which is replaced: the rim's centre and normal (five
/// numbers) are fitted to the outline points' rays by Levenberg-Marquardt from that guess (each
/// ray's distance from the rim circle where it meets the rim's plane), and the mirror frame is
/// turned as little as takes its axis to the normal found (its turn about the axis, which the rim
/// cannot show, is the guess's). A circle's image fixes its pose up to a twofold choice of tilt
/// (report.ambiguousTilt): where both fit, the one nearer the guess is taken; with
/// RimFitOptions::fitAxis false the guess's axis is kept and the centre alone fitted. False, with a
/// sentence in `error`, for an unusable camera, a mirror that is not a quadric of revolution with
/// mirror_to_camera and z_range (or has no rim there), fewer than 5 points, a point beyond the
/// distortion model's range, or a guess so far off that the rays miss its rim's plane.
bool QuadricFromRim(const CameraModel& camera, const std::vector<Vec2>& outlinePixels,
  MirrorDescription& mirror, RimOutlineReport& report, std::string& error);
/// The same with options.
bool QuadricFromRim(const CameraModel& camera, const std::vector<Vec2>& outlinePixels,
  const RimFitOptions& options, MirrorDescription& mirror, RimOutlineReport& report,
  std::string& error);

/// The image of the rim QuadricFromRim found (report's rimCentre, axis, rimRadius) through
/// `camera`: `count` pixels evenly spaced round it, those in front of the camera (z > 0).
std::vector<Vec2> RimOutline(const CameraModel& camera, const RimOutlineReport& rim, int count);

/// The closed-form sphere mirror of that centre (camera frame) and radius, as a calibration holds
/// it (the mirror SphereFromOutline found).
MirrorDescription MirrorOfOutline(const Vec3& centre, double radius);
} // namespace catar

#endif
