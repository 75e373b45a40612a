// CatadioptricAR Core: mirrors that are a part of a quadric surface (the paper's section 3.1,
// equation 1): X^T Omega X = 0 with X = (x, y, z, 1) in the mirror frame, placed in the camera
// frame by the rigid H_OC (x_camera = H_OC x_mirror), the physical mirror being the part with
// zmin <= z <= zmax (mirror frame).
//
// Types (MirrorTypes.cxx): "quadric" (Omega given), and named shapes that make Omega from a few
// numbers, each with the same mirror_to_camera and z_range (mirror frame, axis z):
//  - hyperboloid a, b:    (x^2 + y^2) / b^2 - z^2 / a^2 + 1 = 0 (two sheets, vertices z = +-a,
//                         foci z = +-sqrt(a^2 + b^2));
//  - paraboloid focal f:  x^2 + y^2 - 4 f (z + f) = 0 (focus at the origin, vertex z = -f);
//  - ellipsoid semi_axes (ax, ay, az): x^2 / ax^2 + y^2 / ay^2 + z^2 / az^2 - 1 = 0;
//  - cone half_angle t (degrees): x^2 + y^2 - tan(t)^2 z^2 = 0 (apex at the origin);
//  - sphere radius r: x^2 + y^2 + z^2 - r^2 = 0, cut by z_range (a variant of the closed-form
//    sphere type, told apart by its keys).
// Each is written so that it is negative inside (the bowl's side of a sheet, the solid of an
// ellipsoid); a given Omega must follow the same sign (Documentation/mirrors.md).
//
// Forward projection: the reflection point r is where the optical path |r| + |P - r| is
// stationary on the surface (Fermat), found by Newton on the Lagrange system
//   r / |r| + (r - P) / |r - P| = lambda grad F(r),   F(r) = 0,
// started from a neighbour's answer (plain Newton, several points side by side: ReflectNear; then
// the safeguarded one, whose steps lower the residual), or from a table of the mirror's
// back-projected rays (the ray whose direction seen from the mirror's effective viewpoint is
// nearest P's), or, should that fail, from each of the table's rays nearest P in turn. A found
// point counts when it lies on the mirror part, reflects (both rays on the side of the normal that
// faces them), is the first point the camera ray meets, and the reflected segment to P meets no
// mirror on the way.
#ifndef catarQuadricMirror_h
#define catarQuadricMirror_h

#include "Mirror.h"

#include <vector>

namespace catar
{
/// A quadric mirror in the camera frame, as the solvers use it.
struct QuadricGeometry
{
  Mat4 omega = Mat4::Zero(); ///< mirror frame, negative inside
  Mat4 mirrorToCamera = Mat4::Identity();
  double zmin = 0.0;
  double zmax = 0.0;

  /// Empty when usable; otherwise a sentence naming the key at fault.
  std::string Validate() const;
};

/// The geometry of a description of one of the quadric types ("quadric", "hyperboloid",
/// "paraboloid", "ellipsoid", "cone", the cut "sphere"); false for another type or a wrong count.
/// Shape numbers out of range (a negative axis, ...) leave omega zero and, when shapeError is
/// given, a sentence there.
bool QuadricFromDescription(const MirrorDescription& description, QuadricGeometry& geometry,
  std::string* shapeError = nullptr);

/// The catalogue entries of the quadric types (MirrorTypes.cxx).
std::vector<MirrorType> QuadricMirrorTypes();

namespace detail
{
/// A quadric mirror as a Mirror (see the file comment).
class QuadricSurface final : public Mirror
{
public:
  QuadricSurface(const MirrorDescription& description, const QuadricGeometry& geometry);
  const MirrorDescription& Describe() const override { return this->Description; }
  ProjectionStatus Reflect(const Vec3& point, SolverType solver, Vec3& mirrorPoint,
    const Vec3* guess = nullptr) const override;
  bool Intersect(const Vec3& direction, Vec3& point, Vec3& normal) const override;
  /// Points solved side by side in ReflectNear (QuadricReflectNear.cxx).
  static constexpr int kLanes = 8;
  static_assert(kLanes <= kMaxBatchSize, "a batch fits the projector's");
  int BatchSize() const override { return kLanes; }
  void ReflectNear(int n, const Vec3* points, const Vec3* guesses, Vec3* mirrorPoints,
    unsigned char* settled) const override;
  Vec3 Viewpoint() const override { return this->EffectiveViewpoint; }

  /// F(r) in the camera frame (negative inside), its gradient, and z in the mirror frame.
  double Value(const Vec3& r) const { return r.dot(this->A * r) + 2.0 * this->B.dot(r) + this->C; }
  Vec3 Gradient(const Vec3& r) const { return 2.0 * (this->A * r + this->B); }
  double MirrorZ(const Vec3& r) const { return this->W.dot(r) + this->W0; }

  /// Axial placements (a surface of revolution about the mirror frame's z, the camera on that
  /// axis): every reflection of P lies in the plane of the axis and P, where the camera ray's
  /// elevation is the one unknown. AxialReflect finds all roots of the reflection equation along
  /// the elevations that meet the mirror (bracketed, then regula falsi) and keeps the valid one
  /// with the shortest optical path: true with status Valid (mirrorPoint set) or HiddenByMirror;
  /// false when it has no answer (not axial, P on the axis, no reflection). Reflect uses it for
  /// the quartic solver without a guess.
  bool IsAxial() const { return this->Axial; }
  /// Automatic is Quartic for an axial placement (every image found, the shortest path kept),
  /// else Iterative (both run the same Newton there).
  SolverType Resolve(SolverType solver) const override
  {
    return solver != SolverType::Automatic ? solver
      : this->Axial                        ? SolverType::Quartic
                                           : SolverType::Iterative;
  }
  bool AxialReflect(const Vec3& point, Vec3& mirrorPoint, ProjectionStatus& status) const;

private:
  // Newton on the Lagrange system from r; true with the converged point in r.
  bool Newton(const Vec3& point, Vec3& r) const;
  // Whether r (converged for point) is a reflection the camera sees: Valid, HiddenByMirror or
  // NoReflection.
  ProjectionStatus Check(const Vec3& point, const Vec3& r) const;
  // The first hit of the line origin + t d (t > tmin) with the mirror part: t, or -1.
  double FirstHit(const Vec3& origin, const Vec3& d, double tmin) const;
  // In that plane (radial coordinate rho, axial z, mirror frame): the first point of the mirror
  // on the camera ray of elevation theta (from the axis, towards +rho for theta > 0), and the
  // reflection equation's residual there for the point (rhoP, zP); false when the ray misses.
  bool AxialResidual(
    double theta, double rhoP, double zP, double& residual, double& rho, double& z) const;
  bool InPart(const Vec3& r, double tolerance) const;

  MirrorDescription Description;
  Mat3 A = Mat3::Zero(); // F(r) = r^T A r + 2 B^T r + C, camera frame
  Vec3 B = Vec3::Zero();
  double C = 0.0;
  Vec3 W = Vec3::Zero(); // z in the mirror frame = W^T r + W0
  double W0 = 0.0;
  double Zmin = 0.0;
  double Zmax = 0.0;
  double Length = 1.0;
  Vec3 EffectiveViewpoint = Vec3::Zero();
  // Axial placements: the meridian alpha rho^2 + beta z^2 + 2 gamma z + delta = 0, the camera at
  // z = AxialCamera on the axis, the frames, and the elevations that meet the mirror.
  bool Axial = false;
  double Alpha = 0.0, Beta = 0.0, Gamma = 0.0, Delta = 0.0, AxialCamera = 0.0;
  Mat4 CameraToMirror = Mat4::Identity();
  Mat4 MirrorToCameraFrame = Mat4::Identity();
  double ThetaMax = 0.0; // rays of elevation in [0, ThetaMax] may meet the mirror
  // The elevations (signed: negative towards -rho) whose rays meet the mirror: intervals
  // [first, second], their ends on the rim to rounding (independent of the point).
  std::vector<std::pair<double, double>> AxialIntervals;
  // The table of back-projected rays: mirror points and reflected directions, and a map from the
  // direction seen from EffectiveViewpoint (a cube map, kMapSide^2 cells a face) to the table.
  std::vector<Vec3> TablePoints;
  std::vector<Vec3> TableDirections;
  static constexpr int kMapSide = 16;
  std::vector<int> Map; // 6 * kMapSide^2 table indices
  int MapCell(const Vec3& direction) const;
};
} // namespace detail
} // namespace catar

#endif
