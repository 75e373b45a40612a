// RayScene in a build without Embree (CATAR_WITH_EMBREE off, or Embree not found): no scene can
// be built, and each Build says why; queries find nothing. Shadows, shared occluders and the exact
// reference renderer report that sentence where they build their scenes.
#include "RayScene.h"

namespace catar
{
namespace
{
const char* const kWithoutEmbree =
  "this build of CatadioptricAR has no ray queries: it was built without Embree (install "
  "libembree-dev and build again), so shadows, shared occluders and the exact reference renderer "
  "are off";
} // namespace

struct RayScene::Internals
{
};

RayScene::RayScene() = default;
RayScene::~RayScene() = default;

bool RayScene::Build(const std::vector<float>&, const std::vector<std::uint32_t>&)
{
  this->Error = kWithoutEmbree;
  return false;
}

bool RayScene::Build(const std::vector<MeshView>&)
{
  this->Error = kWithoutEmbree;
  return false;
}

bool RayScene::UpdatePoints(std::size_t, const float*)
{
  this->Error = kWithoutEmbree;
  return false;
}

bool RayScene::Commit()
{
  this->Error = kWithoutEmbree;
  return false;
}

bool RayScene::Occluded(const Vec3&, const Vec3&, double) const
{
  return false;
}

RayScene::Hit RayScene::Intersect(const Vec3&, const Vec3&, double, double) const
{
  return Hit();
}

void RayScene::Intersect(std::size_t n, const Ray*, Hit* hits, bool) const
{
  for (std::size_t i = 0; i < n; ++i)
  {
    hits[i] = Hit();
  }
}
} // namespace catar
