// CatadioptricAR Core: the spherical mirror, one implementation of Mirror.h's interface: its
// description (centre, radius), the reflection point and the first point a camera ray meets
// (Projector.h adds the camera: pixels, world frame, back projection).
//
// Forward projection: given a 3D point P (camera frame), find the mirror point r on the sphere such
// that the ray from the camera centre to r reflects (angle of incidence = angle of reflection) and
// passes through P; then r's pixel. The camera centre O, the sphere centre C and P span a plane
// that contains r (Agrawal et al., ECCV 2010; Alhazen's problem). In that plane, with the origin
// at C, unit radius, the camera at A = (a, 0) and P at B = (bx, by), by >= 0, the mirror point is
// z = (cos t, sin t) and the reflection law reads
//   h(t) = phi_A(t) + phi_B(t) = 0,   phi_X = signed angle from the normal z to X - z,
// which is strictly decreasing on the arc seen by both A and B, so the physical reflection is
// unique and bracketed. With u = tan(t/2) the law becomes the quartic
//   by(a+1) u^4 + 2(2a bx + a + bx) u^3 - 6 a by u^2 + 2(a + bx - 2a bx) u + by(a-1) = 0,
// whose only root inside the bracket is that reflection (the quartic vanishes where h is 0 or
// +-pi, and h stays inside (-pi, pi) there). Both solvers end with the same safeguarded Newton
// (bisection fallback) on this quartic inside the bracket, computed without any trigonometric
// function (the bracket's ends are compared as tangents of half angles); they differ in where
// it starts:
//  - Quartic (closed form): at the quartic's root in the bracket from Ferrari's method (one or
//    two polishing steps);
//  - Iterative: at the far-field guess t = beta/2 (a few steps more, no Ferrari).
#ifndef catarSphereMirror_h
#define catarSphereMirror_h

#include "Mirror.h"

namespace catar
{
/// A spherical mirror, given in the camera frame: the description of type "sphere" (numbers:
/// center x, y, z, radius).
struct SphereMirror
{
  Vec3 center = Vec3(0.0, 0.0, 0.2);
  double radius = 0.05;

  /// As a mirror description, e.g. for CameraModel::mirror.
  operator MirrorDescription() const;
  /// The sphere a description gives; false when it is not a sphere's.
  static bool From(const MirrorDescription& description, SphereMirror& sphere);
};

/// The sphere's entry in the catalogue of mirror types (MirrorTypes.cxx).
MirrorType SphereMirrorType();

/// Reflection point only (camera at the origin, sphere centre/radius in the camera frame).
/// Returns Valid (and sets mirrorPoint) when a reflection exists; otherwise InsideMirror,
/// HiddenByMirror, NoReflection or InvalidInput. Never produces NaN.
ProjectionStatus SphereReflectionPoint(
  const Vec3& centre, double radius, const Vec3& point, SolverType solver, Vec3& mirrorPoint);

namespace detail
{
/// The sphere as a Mirror, in the planar problem's units (centre at the origin, unit radius),
/// precomputed once per camera: the reflection point of a camera-frame point without inverse
/// trigonometric functions (the bracket is kept in u = tan(t/2), where angles compare as their
/// tangents).
class SphereSurface final : public Mirror
{
public:
  SphereSurface(const Vec3& centre, double radius);
  const MirrorDescription& Describe() const override { return this->Description; }
  /// As SphereReflectionPoint (InvalidInput for every point when the mirror is invalid).
  /// guess (optional): a point near the answer, e.g. a neighbour's reflection point; Newton then
  /// starts there (in place of the solver's start) and needs one or two steps.
  ProjectionStatus Reflect(const Vec3& point, SolverType solver, Vec3& mirrorPoint,
    const Vec3* guess = nullptr) const override;

  /// Points solved side by side in ReflectNear.
  static constexpr int kLanes = 8;
  static_assert(kLanes <= kMaxBatchSize, "a batch fits the projector's");
  int BatchSize() const override { return kLanes; }
  /// The start of Reflect(points[i], Iterative, mirrorPoints[i], &guesses[i]) for n <= kLanes
  /// points side by side (each step of the plain Newton from the guess is taken for all of them
  /// before the next, so that their arithmetic overlaps): settled[i] = 1 where that Newton settles
  /// on the arc both ends see (mirrorPoints[i] is then Reflect's answer); 0 elsewhere, where
  /// Reflect goes on (the point touches or is inside the mirror, the guess is far, the point is on
  /// the axis, ...).
  void ReflectNear(int n, const Vec3* points, const Vec3* guesses, Vec3* mirrorPoints,
    unsigned char* settled) const override;

  bool Intersect(const Vec3& direction, Vec3& point, Vec3& normal) const override;
  void Intersect(
    int n, const Vec3* directions, Vec3* points, Vec3* normals, unsigned char* hits) const override;
  Vec3 Viewpoint() const override { return this->Centre; }

private:
  MirrorDescription Description;
  Vec3 Centre;
  double Radius;
  double InvRadius = 0.0;
  double A = 0.0;             // camera distance from the centre, in radii
  Vec3 E1 = Vec3::Zero();     // unit vector from the centre towards the camera
  double TanHalfAlphaA = 0.0; // tan(acos(1 / A) / 2): the edge of the arc the camera sees
  bool Valid = false;
};
} // namespace detail

namespace detail
{
/// The planar problem's closed-form step: the root of the reflection quartic inside [lo, hi]
/// (camera at (a,0), point at (bx,by), unit circle), before any Newton polish. False if none.
bool QuarticReflectionAngle(double a, double bx, double by, double lo, double hi, double& theta);
} // namespace detail
} // namespace catar

#endif
