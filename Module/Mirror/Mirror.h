// CatadioptricAR Core: the mirror, whatever its shape.
//
// A mirror is described by data (MirrorDescription: a type name and that type's numbers, in the
// camera frame) and modelled by a Mirror: the few operations every consumer needs (is it usable,
// the reflection point of a point, several at once from nearby answers, the first point a camera
// ray meets and the normal there). The camera side (pixels, world frame, reflected rays) is
// Projector.h's; the shapes are the Mirror implementations listed in MirrorTypes.cxx, each in
// its own files.
#ifndef catarMirror_h
#define catarMirror_h

#include "MirrorDescription.h"
#include "Types.h"

#include <memory>
#include <string>
#include <vector>

namespace catar
{
/// The shape-neutral operations of a mirror placed in the camera frame, the camera centre at the
/// origin. Implementations are immutable once built and thread-safe (all methods const).
class Mirror
{
public:
  virtual ~Mirror() = default;

  /// The description it was built from.
  virtual const MirrorDescription& Describe() const = 0;

  /// The reflection point of a camera-frame point: Valid (and mirrorPoint set) when the camera
  /// sees the point in the mirror; otherwise InsideMirror, HiddenByMirror, NoReflection or
  /// InvalidInput, and mirrorPoint zero. Never NaN. guess (optional): a point on the mirror near
  /// the answer (e.g. a neighbour's reflection point), where the search may start; a poor guess
  /// costs time, never accuracy.
  virtual ProjectionStatus Reflect(
    const Vec3& point, SolverType solver, Vec3& mirrorPoint, const Vec3* guess = nullptr) const = 0;

  /// The solver `solver` stands for: itself, or for Automatic the faster one that gives the same
  /// answer on this mirror (Iterative unless an implementation says otherwise).
  virtual SolverType Resolve(SolverType solver) const
  {
    return solver == SolverType::Automatic ? SolverType::Iterative : solver;
  }

  /// How many points ReflectNear solves side by side (at most kMaxBatchSize).
  virtual int BatchSize() const { return 1; }
  static constexpr int kMaxBatchSize = 64;

  /// The fast start of Reflect(points[i], Iterative, mirrorPoints[i], &guesses[i]) for
  /// n <= BatchSize() points: settled[i] = 1 where it found Reflect's answer (set in
  /// mirrorPoints[i]), 0 where Reflect must go on. This default settles none.
  virtual void ReflectNear(int n, const Vec3* points, const Vec3* guesses, Vec3* mirrorPoints,
    unsigned char* settled) const;

  /// The first point of the mirror on the ray from the camera centre along the unit vector
  /// direction, and the unit normal there facing the camera. False when the ray misses it.
  virtual bool Intersect(const Vec3& direction, Vec3& point, Vec3& normal) const = 0;
  /// Intersect for n rays at once: hits[i] = Intersect(directions[i], points[i], normals[i])
  /// (a loop the compiler can overlap; this default calls Intersect one by one).
  virtual void Intersect(
    int n, const Vec3* directions, Vec3* points, Vec3* normals, unsigned char* hits) const;

  /// A point from which the world around the mirror is seen as the mirror shows it (the centre of
  /// a sphere): where an environment panorama is taken.
  virtual Vec3 Viewpoint() const = 0;
};

/// One group of a mirror type's numbers: its key (in calibration files and for the VTK camera),
/// how many numbers it holds, and what they mean.
struct MirrorParameter
{
  std::string key;
  int count = 1;
  std::string help;
};

/// A kind of mirror: its name, its parameters (in order) and their default values, and how to
/// check and build one.
struct MirrorType
{
  std::string name;
  std::string help;
  std::vector<MirrorParameter> parameters;
  std::vector<double> defaults;
  /// Empty when the description (of this type, with exactly its count of finite numbers) is a
  /// usable mirror for a camera at the origin; otherwise a sentence that says what is wrong.
  std::string (*validate)(const MirrorDescription& description) = nullptr;
  /// The model of a valid description.
  std::shared_ptr<const Mirror> (*make)(const MirrorDescription& description) = nullptr;
  /// The surface of a description of this type (its whole surface, the cut aside) as the quadric
  /// F(r) = r^T A r + 2 B^T r + C = 0 of the camera frame, negative inside; false when it cannot
  /// say (numbers out of range). Cheap: no model is built (the calibration differentiates it).
  bool (*quadric)(const MirrorDescription& description, Mat3& A, Vec3& B, double& C) = nullptr;

  /// The total count of numbers of this type.
  int ParameterCount() const;
  /// The offset of a parameter's first number, or -1 when the type has no such key.
  int ParameterOffset(const std::string& key) const;
  const MirrorParameter* FindParameter(const std::string& key) const;
};

/// Every mirror type, the default first (MirrorTypes.cxx lists them).
const std::vector<MirrorType>& MirrorTypes();
/// The type of that name, or nullptr. A name may have variants that differ in their keys (the
/// closed-form sphere takes center and radius, the sphere cut by z_range radius,
/// mirror_to_camera and z_range): the first, or the one with that many numbers.
const MirrorType* FindMirrorType(const std::string& name);
const MirrorType* FindMirrorType(const std::string& name, std::size_t count);
/// "sphere, ..." : the names, for messages.
std::string MirrorTypeNames();

/// Empty when the description names a known type with the right count of finite numbers that
/// describe a usable mirror; otherwise a sentence that says what is wrong.
std::string ValidateMirror(const MirrorDescription& description);

/// The description's surface as a quadric of the camera frame (MirrorType::quadric); false for an
/// unknown type or a wrong count, or when the type cannot say.
bool MirrorQuadric(const MirrorDescription& description, Mat3& A, Vec3& B, double& C);

/// The model of a description, or nullptr (and error set) when ValidateMirror fails.
std::shared_ptr<const Mirror> MakeMirror(const MirrorDescription& description, std::string& error);
} // namespace catar

#endif
