#include "PolygonProjection.h"

#include "Parallel.h"
#include "Polygons.h"

#include <algorithm>
#include <cmath>

namespace catar
{
namespace
{
// Polygons per parallel task: waking the pool's threads costs more than projecting a few hundred
// polygons; smaller meshes are projected inline.
constexpr std::int64_t kGrain = 512;
// How many polygons ahead the loop asks for its vertices' records.
constexpr std::int64_t kPrefetchCells = 8;
} // namespace

// Polygons whose centroid is still to be projected.
struct PolygonProjection::Batch
{
  static constexpr int W = Mirror::kMaxBatchSize;
  explicit Batch(int size)
    : size(size)
  {
  }
  int size; // the projector's batch size
  int n = 0;
  std::int64_t out[W];
  Vec3 centroid[W], guess[W], normal[W];
  double bounds[W][4];
  ProjectedPoint q[W];
  bool Full() const { return this->n == this->size; }
  void Add(std::int64_t o, const Vec3& c, const Vec3& g, const Vec3& nrm, double xmin, double xmax,
    double ymin, double ymax)
  {
    this->out[this->n] = o;
    this->centroid[this->n] = c;
    this->guess[this->n] = g;
    this->normal[this->n] = nrm;
    this->bounds[this->n][0] = xmin;
    this->bounds[this->n][1] = xmax;
    this->bounds[this->n][2] = ymin;
    this->bounds[this->n][3] = ymax;
    ++this->n;
  }
};

PolygonProjection::PolygonProjection(const Projector& projector, bool cullBackFaces)
  : TheProjector(&projector)
  , Width(projector.GetModel().intrinsics.width)
  , Height(projector.GetModel().intrinsics.height)
  , CullBackFaces(cullBackFaces)
  , CameraToWorldRotation(projector.GetPose().rotationT)
  , CameraCentre(projector.GetPose().centre)
{
}

template<typename Index>
void PolygonProjection::ProjectRange(const PolygonsView<Index>& polygons,
  const PolygonOutputs& output, std::int64_t begin, std::int64_t end,
  std::atomic<bool>* needsFateCheckFlag) const
{
  const Index* off = polygons.offsets;
  const Index* conn = polygons.connectivity;
  const VertexRecord* vertices = polygons.vertices;
  Batch batch(this->TheProjector->GetBatchSize());
  bool needsFateCheck = false;
  for (std::int64_t c = begin; c < end; ++c)
  {
    if (c + kPrefetchCells < end)
    {
      // The vertices of a cell a few ahead: their cache misses overlap this cell's work.
      for (Index k = off[c + kPrefetchCells]; k < off[c + kPrefetchCells + 1]; ++k)
      {
        parallel::Prefetch(vertices + conn[k]);
      }
    }
    const Index* ids = conn + off[c];
    const std::int64_t n = static_cast<std::int64_t>(off[c + 1] - off[c]);
    const std::int64_t out = output.cellOffset + c;
    output.depth[out] = 0.0;
    output.visible[out] = 0;
    std::fill(output.centroidMirror + 3 * out, output.centroidMirror + 3 * out + 3, 0.0);
    if (n < 3)
    {
      continue;
    }
    Vec3 centroid = Vec3::Zero();
    Vec3 guess = Vec3::Zero();
    const double* lp = vertices[ids[n - 1]].point;
    NewellNormal newell(Vec3(lp[0], lp[1], lp[2])); // |normal| = 2 area
    bool all = true;
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (std::int64_t k = 0; k < n; ++k)
    {
      const VertexRecord& v = vertices[ids[k]];
      if (!v.visible)
      {
        all = false;
        break;
      }
      const Vec3 p(v.point[0], v.point[1], v.point[2]);
      centroid += p;
      if (this->CullBackFaces)
      {
        newell.Add(p);
      }
      guess += Vec3(v.mirror[0], v.mirror[1], v.mirror[2]);
      xmin = std::min(xmin, v.pixel[0]);
      xmax = std::max(xmax, v.pixel[0]);
      ymin = std::min(ymin, v.pixel[1]);
      ymax = std::max(ymax, v.pixel[1]);
    }
    if (needsFateCheckFlag && n == 3 && !needsFateCheck)
    {
      const double* const px[3] = { vertices[ids[0]].pixel, vertices[ids[1]].pixel,
        vertices[ids[2]].pixel };
      needsFateCheck = catar::NeedsFateCheck(all, px, this->Tessellation);
    }
    if (!all)
    {
      continue;
    }
    centroid /= static_cast<double>(n);
    guess /= static_cast<double>(n);
    const Vec3& normal = newell.Sum();
    if (this->CullBackFaces)
    {
      // Facing away from the viewer (the reflection point) by more than a sliver: dropped
      // before its exact projection. The mean of the vertices' reflection points stands in
      // for the centroid's; cells within 1e-3 of edge-on wait for the exact one below.
      const Vec3 toViewer = this->CameraToWorldRotation * guess + this->CameraCentre - centroid;
      if (normal.dot(toViewer) < -1e-3 * normal.norm() * toViewer.norm())
      {
        continue;
      }
    }
    batch.Add(out, centroid, guess, normal, xmin, xmax, ymin, ymax);
    if (batch.Full())
    {
      this->Finish(batch, output);
    }
  }
  this->Finish(batch, output);
  if (needsFateCheck)
  {
    needsFateCheckFlag->store(true, std::memory_order_relaxed);
  }
}

void PolygonProjection::Finish(Batch& batch, const PolygonOutputs& output) const
{
  this->TheProjector->ProjectWorldNear(batch.n, batch.centroid, batch.guess, batch.q, false);
  for (int k = 0; k < batch.n; ++k)
  {
    const ProjectedPoint& q = batch.q[k];
    const std::int64_t out = batch.out[k];
    if (!HasProjection(q.status))
    {
      continue;
    }
    output.depth[out] = q.pathLength;
    std::copy(q.mirrorPoint.data(), q.mirrorPoint.data() + 3, output.centroidMirror + 3 * out);
    if (this->CullBackFaces &&
      batch.normal[k].dot(this->CameraToWorldRotation * q.mirrorPoint + this->CameraCentre -
        batch.centroid[k]) <= 0.0)
    {
      continue;
    }
    const double* b = batch.bounds[k];
    const bool overlapsImage =
      b[1] >= -0.5 && b[3] >= -0.5 && b[0] < this->Width - 0.5 && b[2] < this->Height - 0.5;
    output.visible[out] = overlapsImage ? 1 : 0;
  }
  batch.n = 0;
}

template<typename Index>
void PolygonProjection::Project(const PolygonsView<Index>& polygons, const PolygonOutputs& out,
  int threads, std::atomic<bool>* needsFateCheck) const
{
  parallel::For(0, polygons.numberOfPolygons, kGrain, threads, [&](std::int64_t b, std::int64_t e) {
    this->ProjectRange(polygons, out, b, e, needsFateCheck);
  });
}

template<typename Index>
void PolygonProjection::ProjectPieces(const PolygonsView<Index>& polygons, std::int64_t nCells,
  const std::int64_t* sources, const PolygonOutputs& from, const PolygonOutputs& out,
  int threads) const
{
  parallel::For(0, nCells, kGrain, threads, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t c = b; c < e; ++c)
    {
      const std::int64_t s = sources[c];
      out.depth[c] = s >= 0 ? from.depth[s] : 0.0;
      for (int k = 0; k < 3; ++k)
      {
        out.centroidMirror[3 * c + k] = s >= 0 ? from.centroidMirror[3 * s + k] : 0.0;
      }
      out.visible[c] = s >= 0 ? from.visible[s] : 0;
    }
  });
  // The pieces: runs of polygons, in the caller's thread.
  const std::int64_t first = out.cellOffset;
  const std::int64_t nPolys = polygons.numberOfPolygons;
  for (std::int64_t p = 0; p < nPolys;)
  {
    if (sources[first + p] >= 0)
    {
      ++p;
      continue;
    }
    std::int64_t e = p + 1;
    while (e < nPolys && sources[first + e] < 0)
    {
      ++e;
    }
    this->ProjectRange(polygons, out, p, e, nullptr);
    p = e;
  }
}

#define CATAR_POLYGONS_INSTANTIATE(Index)                                                          \
  template void PolygonProjection::Project<Index>(                                                 \
    const PolygonsView<Index>&, const PolygonOutputs&, int, std::atomic<bool>*) const;             \
  template void PolygonProjection::ProjectPieces<Index>(const PolygonsView<Index>&, std::int64_t,  \
    const std::int64_t*, const PolygonOutputs&, const PolygonOutputs&, int) const;
CATAR_POLYGONS_INSTANTIATE(int)
CATAR_POLYGONS_INSTANTIATE(long)
CATAR_POLYGONS_INSTANTIATE(long long)
#undef CATAR_POLYGONS_INSTANTIATE
} // namespace catar
