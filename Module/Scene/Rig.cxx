#include "Rig.h"

#include "Mirror.h"
#include "Parallel.h"
#include "Projector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

namespace catar
{
namespace
{
// Bisection steps along a grid edge: 2^-40 of a cell.
constexpr int kBisections = 40;
// Coarse search for the part of the image that shows the mirror: at least this many samples along
// the image's longer side (and four per fine cell), at most kMaxCoarse.
constexpr int kMinCoarse = 256;
constexpr int kMaxCoarse = 2048;

// A pixel's view of the mirror: the point the camera sees there and the normal (camera frame).
struct Sample
{
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  bool hit = false;
};

class MirrorSampler
{
public:
  MirrorSampler(const CameraModel& model, const Mirror& mirror)
    : Model(model)
    , TheMirror(mirror)
  {
  }

  Sample At(const Vec2& pixel) const
  {
    Sample s;
    Vec3 d;
    if (!pixel.allFinite() || !this->Model.PixelToDirection(pixel, d))
    {
      return s;
    }
    s.hit = this->TheMirror.Intersect(d, s.point, s.normal) && s.point.allFinite() &&
      s.normal.allFinite();
    return s;
  }

  /// The last point on the segment from a pixel that sees the mirror (`in`) to one that does not
  /// (`out`) that still sees it, by bisection; `at` is its pixel, `sample` its view.
  void Boundary(Vec2 in, Vec2 out, const Sample& inSample, Vec2& at, Sample& sample) const
  {
    sample = inSample;
    for (int k = 0; k < kBisections; ++k)
    {
      const Vec2 mid = 0.5 * (in + out);
      const Sample s = this->At(mid);
      if (s.hit)
      {
        in = mid;
        sample = s;
      }
      else
      {
        out = mid;
      }
    }
    at = in;
  }

private:
  const CameraModel& Model;
  const Mirror& TheMirror;
};

// A grid of pixels over [x0, x1] x [y0, y1]: nx x ny cells.
struct Grid
{
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int nx = 1, ny = 1;
  Vec2 Pixel(int i, int j) const
  {
    // The last line lands on x1 / y1 exactly.
    const double x = i == nx ? x1 : x0 + (x1 - x0) * i / nx;
    const double y = j == ny ? y1 : y0 + (y1 - y0) * j / ny;
    return Vec2(x, y);
  }
  int Vertex(int i, int j) const { return j * (nx + 1) + i; }
  int Vertices() const { return (nx + 1) * (ny + 1); }
};

// Samples every vertex of a grid (rows in parallel).
std::vector<Sample> SampleGrid(const MirrorSampler& sampler, const Grid& grid, int threads)
{
  std::vector<Sample> samples(static_cast<std::size_t>(grid.Vertices()));
  parallel::For(0, grid.ny + 1, 1, threads, [&](std::int64_t j0, std::int64_t j1) {
    for (std::int64_t j = j0; j < j1; ++j)
    {
      for (int i = 0; i <= grid.nx; ++i)
      {
        samples[grid.Vertex(i, static_cast<int>(j))] =
          sampler.At(grid.Pixel(i, static_cast<int>(j)));
      }
    }
  });
  return samples;
}

// The camera-frame point of a pixel at depth z through the lens alone; false beyond the
// distortion model's range.
bool LensPoint(const CameraModel& model, const Vec2& pixel, double z, Vec3& point)
{
  Vec2 xy;
  if (!model.PixelToNormalized(pixel, xy))
  {
    return false;
  }
  point = Vec3(xy.x() * z, xy.y() * z, z);
  return point.allFinite();
}

// The mirror as the camera sees it, camera frame (rig.mirror* and rig.outlines).
void SampleMirror(
  const CameraModel& model, const Mirror& mirror, const RigOptions& options, RigGeometry& rig)
{
  const MirrorSampler sampler(model, mirror);
  const double w = model.intrinsics.width;
  const double h = model.intrinsics.height;
  const double longer = std::max(w, h);

  // 1. Where in the image the mirror is: a coarse grid over the whole image.
  // (No finer than a pixel but in images smaller than kMinCoarse pixels.)
  const int imageCells = static_cast<int>(std::max<double>(kMinCoarse, longer));
  const int coarseCells =
    std::min({ kMaxCoarse, imageCells, std::max(kMinCoarse, 4 * options.mirrorResolution) });
  const double coarseStep = longer / coarseCells;
  Grid coarse;
  coarse.x0 = -0.5;
  coarse.y0 = -0.5;
  coarse.x1 = w - 0.5;
  coarse.y1 = h - 0.5;
  coarse.nx = std::max(1, static_cast<int>(std::ceil(w / coarseStep - 1e-9)));
  coarse.ny = std::max(1, static_cast<int>(std::ceil(h / coarseStep - 1e-9)));
  const std::vector<Sample> coarseSamples = SampleGrid(sampler, coarse, options.threads);
  int imin = coarse.nx + 1, imax = -1, jmin = coarse.ny + 1, jmax = -1;
  for (int j = 0; j <= coarse.ny; ++j)
  {
    for (int i = 0; i <= coarse.nx; ++i)
    {
      if (coarseSamples[coarse.Vertex(i, j)].hit)
      {
        imin = std::min(imin, i);
        imax = std::max(imax, i);
        jmin = std::min(jmin, j);
        jmax = std::max(jmax, j);
      }
    }
  }
  if (imax < 0)
  {
    return; // the camera does not see the mirror
  }
  // One coarse cell of margin: the mirror's image ends somewhere in it.
  Grid grid;
  const Vec2 low = coarse.Pixel(std::max(0, imin - 1), std::max(0, jmin - 1));
  const Vec2 high = coarse.Pixel(std::min(coarse.nx, imax + 1), std::min(coarse.ny, jmax + 1));
  grid.x0 = low.x();
  grid.y0 = low.y();
  grid.x1 = high.x();
  grid.y1 = high.y();
  const double lx = grid.x1 - grid.x0;
  const double ly = grid.y1 - grid.y0;
  const double cell = std::max(lx, ly) / options.mirrorResolution;
  grid.nx = std::max(1, static_cast<int>(std::ceil(lx / cell - 1e-9)));
  grid.ny = std::max(1, static_cast<int>(std::ceil(ly / cell - 1e-9)));

  // 2. The fine grid.
  const std::vector<Sample> samples = SampleGrid(sampler, grid, options.threads);
  std::vector<int> vertexId(samples.size(), -1);
  for (std::size_t v = 0; v < samples.size(); ++v)
  {
    if (samples[v].hit)
    {
      vertexId[v] = static_cast<int>(rig.mirrorPoints.size());
      rig.mirrorPoints.push_back(samples[v].point);
      rig.mirrorNormals.push_back(samples[v].normal);
      const int i = static_cast<int>(v) % (grid.nx + 1);
      const int j = static_cast<int>(v) / (grid.nx + 1);
      rig.mirrorPixels.push_back(grid.Pixel(i, j));
    }
  }

  // 3. The boundary points on the grid's edges whose ends disagree. Edges: horizontal (i, j) ->
  // (i + 1, j) numbered j * nx + i, then vertical (i, j) -> (i, j + 1) after them.
  const int horizontal = grid.nx * (grid.ny + 1);
  const int edgeCount = horizontal + (grid.nx + 1) * grid.ny;
  auto edgeEnds = [&](int e, int& a, int& b) {
    if (e < horizontal)
    {
      const int i = e % grid.nx, j = e / grid.nx;
      a = grid.Vertex(i, j);
      b = grid.Vertex(i + 1, j);
    }
    else
    {
      const int k = e - horizontal;
      const int i = k % (grid.nx + 1), j = k / (grid.nx + 1);
      a = grid.Vertex(i, j);
      b = grid.Vertex(i, j + 1);
    }
  };
  auto vertexPixel = [&](int v) { return grid.Pixel(v % (grid.nx + 1), v / (grid.nx + 1)); };
  std::vector<int> crossed;
  for (int e = 0; e < edgeCount; ++e)
  {
    int a, b;
    edgeEnds(e, a, b);
    if (samples[a].hit != samples[b].hit)
    {
      crossed.push_back(e);
    }
  }
  std::vector<Vec2> crossingPixel(crossed.size());
  std::vector<Sample> crossingSample(crossed.size());
  parallel::For(0, static_cast<std::int64_t>(crossed.size()), 16, options.threads,
    [&](std::int64_t k0, std::int64_t k1) {
      for (std::int64_t k = k0; k < k1; ++k)
      {
        int a, b;
        edgeEnds(crossed[k], a, b);
        if (!samples[a].hit)
        {
          std::swap(a, b);
        }
        sampler.Boundary(
          vertexPixel(a), vertexPixel(b), samples[a], crossingPixel[k], crossingSample[k]);
      }
    });
  std::vector<int> edgeId(static_cast<std::size_t>(edgeCount), -1);
  for (std::size_t k = 0; k < crossed.size(); ++k)
  {
    edgeId[crossed[k]] = static_cast<int>(rig.mirrorPoints.size());
    rig.mirrorPoints.push_back(crossingSample[k].point);
    rig.mirrorNormals.push_back(crossingSample[k].normal);
    rig.mirrorPixels.push_back(crossingPixel[k]);
  }

  // 4. The cells, marching-squares style. Each cell's perimeter is walked against the pixel
  // order (x right, y down): top-left, down the left edge, bottom-left, along the bottom, ...;
  // seen from the camera that winds the triangles so that their normals face it. The points met
  // all lie on the cell's perimeter, in order, so the polygon they make is convex.
  auto hEdge = [&](int i, int j) { return j * grid.nx + i; };
  auto vEdge = [&](int i, int j) { return horizontal + j * (grid.nx + 1) + i; };
  for (int j = 0; j < grid.ny; ++j)
  {
    for (int i = 0; i < grid.nx; ++i)
    {
      const int corner[4] = { grid.Vertex(i, j), grid.Vertex(i, j + 1), grid.Vertex(i + 1, j + 1),
        grid.Vertex(i + 1, j) };
      const int edge[4] = { vEdge(i, j), hEdge(i, j + 1), vEdge(i + 1, j), hEdge(i, j) };
      int polygon[8];
      bool isCorner[8];
      int m = 0, hits = 0;
      for (int c = 0; c < 4; ++c)
      {
        if (samples[corner[c]].hit)
        {
          polygon[m] = vertexId[corner[c]];
          isCorner[m++] = true;
          ++hits;
        }
        if (edgeId[edge[c]] >= 0)
        {
          polygon[m] = edgeId[edge[c]];
          isCorner[m++] = false;
        }
      }
      if (hits == 0 || m < 3)
      {
        continue;
      }
      const bool saddle = hits == 2 && samples[corner[0]].hit == samples[corner[2]].hit;
      if (saddle &&
        !sampler.At(grid.Pixel(i, j) + 0.5 * (grid.Pixel(i + 1, j + 1) - grid.Pixel(i, j))).hit)
      {
        // Two diagonal corners see the mirror, the cell's centre does not: two separate corners.
        for (int p = 0; p < m; ++p)
        {
          if (isCorner[p])
          {
            rig.mirrorTriangles.push_back(
              { { polygon[(p + m - 1) % m], polygon[p], polygon[(p + 1) % m] } });
          }
        }
        continue;
      }
      // A fan from a corner: no two of its neighbours share a side of the cell with it.
      int start = 0;
      while (!isCorner[start])
      {
        ++start;
      }
      for (int k = 1; k + 1 < m; ++k)
      {
        rig.mirrorTriangles.push_back(
          { { polygon[start], polygon[(start + k) % m], polygon[(start + k + 1) % m] } });
      }
    }
  }

  // 5. The outline: the edges that one triangle alone has, chained head to tail (the triangles
  // wind the same way, so each loop follows its edges' direction).
  const std::uint64_t n = rig.mirrorPoints.size();
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(rig.mirrorTriangles.size() * 3);
  auto key = [n](int a, int b) {
    return static_cast<std::uint64_t>(std::min(a, b)) * n +
      static_cast<std::uint64_t>(std::max(a, b));
  };
  for (const auto& t : rig.mirrorTriangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++uses[key(t[k], t[(k + 1) % 3])];
    }
  }
  std::unordered_multimap<int, int> next;
  for (const auto& t : rig.mirrorTriangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (uses[key(t[k], t[(k + 1) % 3])] == 1)
      {
        next.emplace(t[k], t[(k + 1) % 3]);
      }
    }
  }
  while (!next.empty())
  {
    auto it = next.begin();
    const int first = it->first;
    std::vector<int> loop{ first };
    int at = it->second;
    next.erase(it);
    while (at != first)
    {
      loop.push_back(at);
      auto step = next.find(at);
      if (step == next.end())
      {
        break; // an open chain (not expected): kept as it is
      }
      at = step->second;
      next.erase(step);
    }
    if (loop.size() >= 2)
    {
      rig.outlines.push_back(std::move(loop));
    }
  }
}
} // namespace

bool BuildRig(
  const Projector& projector, const RigOptions& options, RigGeometry& rig, std::string& error)
{
  rig = RigGeometry();
  if (!projector.IsValid() || !projector.GetMirror())
  {
    error = "invalid camera: " + projector.GetError();
    return false;
  }
  if (options.mirrorResolution < 2)
  {
    error =
      "the mirror resolution must be 2 or more, not " + std::to_string(options.mirrorResolution);
    return false;
  }
  if (!std::isfinite(options.frustumLength))
  {
    error = "the frustum length must be a finite number";
    return false;
  }
  const CameraModel& model = projector.GetModel();
  const PoseFrames& pose = projector.GetPose();
  rig.centre = pose.centre;

  SampleMirror(model, *projector.GetMirror(), options, rig);

  // The frustum's depth: given, or a quarter beyond the farthest mirror point seen.
  double length = options.frustumLength;
  if (!(length > 0.0))
  {
    length = 0.0;
    for (const Vec3& p : rig.mirrorPoints)
    {
      length = std::max(length, p.z());
    }
    if (!(length > 0.0))
    {
      length = projector.GetMirror()->Viewpoint().z();
    }
    length = length > 0.0 && std::isfinite(length) ? 1.25 * length : 1.0;
  }
  rig.frustumLength = length;

  // The far border, image order.
  const double w = model.intrinsics.width;
  const double h = model.intrinsics.height;
  const Vec2 corner[4] = { Vec2(-0.5, -0.5), Vec2(w - 0.5, -0.5), Vec2(w - 0.5, h - 0.5),
    Vec2(-0.5, h - 0.5) };
  const int perSide = model.distortion.IsZero() ? 1 : std::max(1, options.borderSamples);
  for (int s = 0; s < 4; ++s)
  {
    for (int k = 0; k < perSide; ++k)
    {
      const Vec2 pixel =
        k == 0 ? corner[s] : corner[s] + (corner[(s + 1) % 4] - corner[s]) * k / perSide;
      Vec3 p;
      if (LensPoint(model, pixel, length, p))
      {
        if (k == 0)
        {
          rig.corners[s] = static_cast<int>(rig.border.size());
        }
        rig.border.push_back(pose.ToWorld(p));
        rig.borderPixels.push_back(pixel);
      }
    }
  }

  // The mirror to world coordinates.
  for (std::size_t k = 0; k < rig.mirrorPoints.size(); ++k)
  {
    rig.mirrorPoints[k] = pose.ToWorld(rig.mirrorPoints[k]);
    rig.mirrorNormals[k] = (pose.rotationT * rig.mirrorNormals[k]).normalized();
  }
  return true;
}
} // namespace catar
