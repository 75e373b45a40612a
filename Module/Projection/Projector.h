// CatadioptricAR Core: forward and back projection through the camera's mirror, camera side: the
// reflection point from the mirror (Mirror.h), then the pixel (lens model), the world frame and
// the reflected ray of a pixel.
#ifndef catarProjector_h
#define catarProjector_h

#include "CameraModel.h"
#include "Mirror.h"
#include "Types.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>

namespace catar
{
/// Forward and back projection for one camera model, with per-camera constants precomputed.
/// Thread-safe after construction (all methods const).
class Projector
{
public:
  explicit Projector(const CameraModel& model);

  /// True when the model passed CameraModel::Validate(); otherwise every result is InvalidInput.
  bool IsValid() const { return this->Valid; }
  const std::string& GetError() const { return this->Error; }
  const CameraModel& GetModel() const { return this->Model; }
  /// The model's pose taken apart once (world <-> camera for many points).
  const PoseFrames& GetPose() const { return this->Pose; }
  /// The camera's mirror (nullptr when the model is not valid).
  const Mirror* GetMirror() const { return this->MirrorModel.get(); }
  /// How many points ProjectWorldNear solves side by side: batches of this size (or a multiple)
  /// use it best. At most Mirror::kMaxBatchSize.
  int GetBatchSize() const { return this->BatchSize; }

  /// Forward projection of a point given in the camera frame / world frame.
  ProjectedPoint ProjectCamera(
    const Vec3& pCamera, SolverType solver = SolverType::Automatic) const;
  ProjectedPoint ProjectWorld(const Vec3& pWorld, SolverType solver = SolverType::Automatic) const;
  /// Forward projection of a world point whose reflection point is known to be near mirrorGuess
  /// (camera frame; e.g. the mean of the reflection points of a triangle's vertices, for its
  /// centroid): the same answer as either solver (the same safeguarded Newton, to the same
  /// tolerance) in fewer steps. A guess far off costs steps, never accuracy.
  ProjectedPoint ProjectWorldNear(const Vec3& pWorld, const Vec3& mirrorGuess) const;
  /// The pixel's derivative with respect to the point p of the camera frame, whose projection
  /// `at` is (ProjectCamera(p)): central differences of 1e-6 |p| (1e-6 at least) along each
  /// axis, each step's projection started from at.mirrorPoint; one-sided where a step loses the
  /// image (near the mirror's rim). False when neither step of some axis has an image (that
  /// column left zero).
  bool PixelDerivative(
    const Vec3& p, const ProjectedPoint& at, Eigen::Matrix<double, 2, 3>& d) const;
  /// ProjectWorldNear for n points: out[i] = ProjectWorldNear(pWorld[i], mirrorGuess[i]), the same
  /// results, solved GetBatchSize() points side by side (for the sphere, about twice as fast per
  /// point as one call each). A guess that is not finite starts that point from the iterative
  /// solver's own guess. With pixels false the pixel may be left at zero and Valid may stand for
  /// OutsideImage (for callers that need reflection points and path lengths only, e.g. the
  /// painter's depths of centroids); mirror points, path lengths and HasProjection(status) are the
  /// same.
  void ProjectWorldNear(std::size_t n, const Vec3* pWorld, const Vec3* mirrorGuess,
    ProjectedPoint* out, bool pixels = true) const;

  /// Back projection of a pixel: the reflected ray in the camera frame / world frame.
  /// Pixels whose ray misses the mirror give NoReflection; pixels outside the image are still
  /// back-projected and flagged OutsideImage.
  BackProjectedRay BackProjectCamera(const Vec2& pixel) const;
  BackProjectedRay BackProjectWorld(const Vec2& pixel) const;
  /// The same for n pixels: out[i] = BackProjectCamera(pixels[i]) / BackProjectWorld(pixels[i]),
  /// the same results, the mirror's intersections computed a batch at a time (faster per pixel).
  void BackProjectCamera(std::size_t n, const Vec2* pixels, BackProjectedRay* out) const;
  void BackProjectWorld(std::size_t n, const Vec2* pixels, BackProjectedRay* out) const;

private:
  ProjectedPoint ProjectCameraFrom(const Vec3& p, SolverType solver, const Vec3* mirrorGuess) const;
  // The camera-side end of a projection: r is p's reflection point (both camera frame).
  ProjectedPoint Finish(const Vec3& p, const Vec3& r, bool pixel = true) const;
  // The unit camera ray of a pixel; false with out's status set (InvalidInput, NoReflection)
  // when there is none.
  bool CameraRay(const Vec2& pixel, Vec3& d, BackProjectedRay& out) const;
  // The reflected ray of the camera ray d (unit) that meets the mirror at r, normal nrm.
  BackProjectedRay Reflected(const Vec2& pixel, const Vec3& d, const Vec3& r, const Vec3& n) const;

  CameraModel Model;
  bool Valid = false;
  std::string Error;
  std::shared_ptr<const Mirror> MirrorModel;
  int BatchSize = 1;
  PoseFrames Pose; // the model's pose, taken apart once
};
/// Projects points begin..end-1 of a sequence in which points that follow each other are mostly
/// neighbours (a mesh's points): store(i, point, result) for each, in order, with
/// result = projector.ProjectWorld(pointAt(i), solver) (the same answers to the solver's
/// tolerance). With the iterative solver each point's Newton starts at the reflection point of a
/// point just before it: the first GetBatchSize() points one by one, each from the previous one's;
/// then a batch at a time, solved side by side (ProjectWorldNear), each from the point a batch
/// before it. Points without such a start use the solver's own.
/// pointAt(i) returns a Vec3 (world frame); store(i, const Vec3&, const ProjectedPoint&).
template<typename PointAt, typename Store>
void ProjectRun(const Projector& projector, SolverType solver, std::ptrdiff_t begin,
  std::ptrdiff_t end, PointAt&& pointAt, Store&& store)
{
  if (solver != SolverType::Iterative)
  {
    for (std::ptrdiff_t i = begin; i < end; ++i)
    {
      const Vec3 p = pointAt(i);
      store(i, p, projector.ProjectWorld(p, solver));
    }
    return;
  }
  constexpr int M = Mirror::kMaxBatchSize;
  const std::ptrdiff_t W = projector.GetBatchSize();
  const std::ptrdiff_t serialEnd = std::min(end, begin + W);
  // The reflection points of the last W points (NaN where there is none), by (i - begin) % W.
  Vec3 last[M];
  const Vec3 none = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  bool havePrevious = false;
  Vec3 previous = Vec3::Zero();
  for (std::ptrdiff_t i = begin; i < serialEnd; ++i)
  {
    const Vec3 p = pointAt(i);
    const ProjectedPoint q =
      havePrevious ? projector.ProjectWorldNear(p, previous) : projector.ProjectWorld(p, solver);
    havePrevious = HasProjection(q.status);
    previous = q.mirrorPoint;
    last[i - begin] = havePrevious ? q.mirrorPoint : none; // i - begin < W
    store(i, p, q);
  }
  Vec3 p[M], guess[M];
  ProjectedPoint q[M];
  for (std::ptrdiff_t first = serialEnd; first < end; first += W)
  {
    const std::ptrdiff_t n = std::min(W, end - first);
    for (std::ptrdiff_t l = 0; l < n; ++l)
    {
      p[l] = pointAt(first + l);
      guess[l] = last[l]; // the point W places before: batches start W apart from begin + W
    }
    projector.ProjectWorldNear(static_cast<std::size_t>(n), p, guess, q);
    for (std::ptrdiff_t l = 0; l < n; ++l)
    {
      last[l] = HasProjection(q[l].status) ? q[l].mirrorPoint : none;
      store(first + l, p[l], q[l]);
    }
  }
}
} // namespace catar

#endif
