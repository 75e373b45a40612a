// CatadioptricAR Core: forward and back projection through a spherical mirror, camera side: the
// reflection point from SphereMirror.h, then the pixel (lens model), the world frame and the
// reflected ray of a pixel.
#ifndef catarSphereProjection_h
#define catarSphereProjection_h

#include "CameraModel.h"
#include "Polynomials.h" // the solvers the sphere's reflection reduces to
#include "Projection.h"
#include "SphereMirror.h"

#include <cstddef>
#include <string>

namespace catar
{
/// Forward and back projection for one camera model, with per-camera constants precomputed.
/// Thread-safe after construction (all methods const).
class SphereProjector
{
public:
  explicit SphereProjector(const CameraModel& model);

  /// True when the model passed CameraModel::Validate(); otherwise every result is InvalidInput.
  bool IsValid() const { return this->Valid; }
  const std::string& GetError() const { return this->Error; }
  const CameraModel& GetModel() const { return this->Model; }

  /// Forward projection of a point given in the camera frame / world frame.
  ProjectedPoint ProjectCamera(const Vec3& pCamera, SolverType solver = SolverType::Quartic) const;
  ProjectedPoint ProjectWorld(const Vec3& pWorld, SolverType solver = SolverType::Quartic) const;
  /// Forward projection of a world point whose reflection point is known to be near mirrorGuess
  /// (camera frame; e.g. the mean of the reflection points of a triangle's vertices, for its
  /// centroid): the same answer as either solver (the same safeguarded Newton, to the same
  /// tolerance) in fewer steps. A guess far off costs steps, never accuracy.
  ProjectedPoint ProjectWorldNear(const Vec3& pWorld, const Vec3& mirrorGuess) const;
  /// ProjectWorldNear for n points: out[i] = ProjectWorldNear(pWorld[i], mirrorGuess[i]), the same
  /// results, solved several points side by side (about twice as fast per point as one call
  /// each). A guess that is not finite starts that point from the iterative solver's own guess.
  /// With pixels false the pixel may be left at zero and Valid may stand for OutsideImage (for
  /// callers that need reflection points and path lengths only, e.g. the painter's depths of
  /// centroids); mirror points, path lengths and HasProjection(status) are the same.
  void ProjectWorldNear(std::size_t n, const Vec3* pWorld, const Vec3* mirrorGuess,
    ProjectedPoint* out, bool pixels = true) const;

  /// Back projection of a pixel: the reflected ray in the camera frame / world frame.
  /// Pixels whose ray misses the mirror give NoReflection; pixels outside the image are still
  /// back-projected and flagged OutsideImage.
  BackProjectedRay BackProjectCamera(const Vec2& pixel) const;
  BackProjectedRay BackProjectWorld(const Vec2& pixel) const;

private:
  ProjectedPoint ProjectCameraFrom(const Vec3& p, SolverType solver, const Vec3* mirrorGuess) const;
  // The camera-side end of a projection: r is p's reflection point (both camera frame).
  ProjectedPoint Finish(const Vec3& p, const Vec3& r, bool pixel = true) const;

  CameraModel Model;
  bool Valid = false;
  std::string Error;
  detail::MirrorFrame Frame;
  Mat3 R; // world-to-camera rotation
  Vec3 T; // world-to-camera translation
};
} // namespace catar

#endif
