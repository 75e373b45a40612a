#include "RayTracer.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace catar
{

namespace
{
bool Finite(const Vec3& p)
{
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

/// Slab test: does origin + t d, t > 0, meet the box [lo, hi]?
bool RayMeetsBox(const Vec3& origin, const Vec3& direction, const Vec3& lo, const Vec3& hi)
{
  double t0 = 0.0;
  double t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    if (direction[k] == 0.0)
    {
      if (origin[k] < lo[k] || origin[k] > hi[k])
      {
        return false;
      }
      continue;
    }
    const double inv = 1.0 / direction[k];
    double a = (lo[k] - origin[k]) * inv;
    double b = (hi[k] - origin[k]) * inv;
    if (a > b)
    {
      std::swap(a, b);
    }
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1)
    {
      return false;
    }
  }
  return true;
}
} // namespace

bool RayTracer::SetScene(const std::vector<TraceMesh>& meshes,
  const std::vector<TextureView>& textures, const std::vector<LightSource>& lights,
  const Vec3& globalAmbient, bool shadows)
{
  this->HasScene = false;
  this->Error.clear();
  this->Meshes.clear();
  this->Triangles.clear();
  std::vector<float> points;
  std::vector<std::uint32_t> indices;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const TraceMesh& mesh = meshes[m];
    const std::string which = "mesh " + std::to_string(m) + ": ";
    const std::size_t n = mesh.points.size();
    const std::size_t nt = mesh.triangles.size();
    if (n > std::numeric_limits<std::uint32_t>::max() / 2 ||
      points.size() / 3 + n > std::numeric_limits<std::uint32_t>::max() / 2)
    {
      this->Error = which + "too many points";
      return false;
    }
    for (const Vec3& p : mesh.points)
    {
      if (!Finite(p))
      {
        this->Error = which + "a point has a NaN or infinite coordinate";
        return false;
      }
    }
    for (const auto& t : mesh.triangles)
    {
      if (t[0] >= n || t[1] >= n || t[2] >= n)
      {
        this->Error = which + "a triangle refers to a point that does not exist";
        return false;
      }
    }
    if (!mesh.triangleIds.empty() && mesh.triangleIds.size() != nt)
    {
      this->Error = which + "triangleIds must have one value per triangle";
      return false;
    }
    const std::size_t colorCount = mesh.colorSource == TraceMesh::ColorSource::Point ? n
      : mesh.colorSource == TraceMesh::ColorSource::Cell                             ? nt
                                                                                     : 0;
    if (mesh.colorSource != TraceMesh::ColorSource::Solid && mesh.colors.size() != 4 * colorCount)
    {
      this->Error = which + "colors must have 4 values per " +
        (mesh.colorSource == TraceMesh::ColorSource::Point ? "point" : "triangle");
      return false;
    }
    if (!mesh.normals.empty() && mesh.normals.size() != n)
    {
      this->Error = which + "normals must have one value per point";
      return false;
    }
    if (!mesh.tcoords.empty() && mesh.tcoords.size() != 2 * n)
    {
      this->Error = which + "tcoords must have 2 values per point";
      return false;
    }
    if (mesh.texture >= static_cast<int>(textures.size()))
    {
      this->Error = which + "texture " + std::to_string(mesh.texture) + " does not exist (" +
        std::to_string(textures.size()) + " textures)";
      return false;
    }
    const std::uint32_t base = static_cast<std::uint32_t>(points.size() / 3);
    for (const Vec3& p : mesh.points)
    {
      points.push_back(static_cast<float>(p.x()));
      points.push_back(static_cast<float>(p.y()));
      points.push_back(static_cast<float>(p.z()));
    }
    for (std::size_t t = 0; t < nt; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        indices.push_back(base + mesh.triangles[t][k]);
        lo = lo.cwiseMin(mesh.points[mesh.triangles[t][k]]);
        hi = hi.cwiseMax(mesh.points[mesh.triangles[t][k]]);
      }
      this->Triangles.push_back({ static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(t) });
    }
  }
  if (!this->Scene.Build(points, indices))
  {
    this->Error = "building the ray scene failed: " + this->Scene.GetError();
    this->Triangles.clear();
    return false;
  }
  this->Meshes = meshes;
  this->Textures = textures;
  this->Lights = lights;
  this->GlobalAmbient = globalAmbient;
  this->Shadows = shadows;
  // Grow the box a little: Embree's single precision must not lose grazing hits.
  const Vec3 pad = Vec3::Constant(1e-6 * std::max(1.0, (hi - lo).norm()));
  this->BoundsMin = this->Triangles.empty() ? Vec3::Zero() : Vec3(lo - pad);
  this->BoundsMax = this->Triangles.empty() ? Vec3::Zero() : Vec3(hi + pad);
  this->HasScene = true;
  return true;
}

bool RayTracer::PrepareRays(const Projector& projector, int samples)
{
  this->Error.clear();
  this->Rays.clear();
  this->RayValid.clear();
  this->Width = this->Height = 0;
  if (!projector.IsValid())
  {
    this->Error = "invalid camera: " + projector.GetError();
    return false;
  }
  samples = std::max(1, std::min(8, samples));
  const CameraModel& model = projector.GetModel();
  const int w = model.intrinsics.width;
  const int h = model.intrinsics.height;
  const std::size_t count = static_cast<std::size_t>(w) * h * samples * samples;
  this->Rays.resize(count);
  this->RayValid.assign(count, 0);
  // A row's samples are back-projected together (Projector's batches).
  const std::size_t perRow = static_cast<std::size_t>(w) * samples * samples;
  std::vector<Vec2> pixels(perRow);
  std::vector<BackProjectedRay> rays(perRow);
  std::size_t i = 0;
  for (int y = 0; y < h; ++y)
  {
    std::size_t j = 0;
    for (int x = 0; x < w; ++x)
    {
      for (int sy = 0; sy < samples; ++sy)
      {
        for (int sx = 0; sx < samples; ++sx)
        {
          pixels[j++] = Vec2(x + (sx + 0.5) / samples - 0.5, y + (sy + 0.5) / samples - 0.5);
        }
      }
    }
    projector.BackProjectWorld(perRow, pixels.data(), rays.data());
    for (j = 0; j < perRow; ++j, ++i)
    {
      const BackProjectedRay& ray = rays[j];
      if (!HasProjection(ray.status))
      {
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        this->Rays[i].origin[k] = static_cast<float>(ray.mirrorPoint[k]);
        this->Rays[i].direction[k] = static_cast<float>(ray.direction[k]);
      }
      this->RayValid[i] = 1;
    }
  }
  this->Width = w;
  this->Height = h;
  this->Samples = samples;
  return true;
}

void RayTracer::ShadeHit(const Vec3& origin, const Vec3& direction, const RayScene::Hit& hit,
  float rgba[4], RayTraceStatistics& statistics) const
{
  const GlobalTriangle g = this->Triangles[hit.triangle];
  const TraceMesh& mesh = this->Meshes[g.mesh];
  const auto& t = mesh.triangles[g.local];
  const double w1 = hit.u, w2 = hit.v, w0 = 1.0 - hit.u - hit.v;
  const Vec3& a = mesh.points[t[0]];
  const Vec3& b = mesh.points[t[1]];
  const Vec3& c = mesh.points[t[2]];
  // The hit point on the exact (double) triangle: Embree found where, this says exactly.
  const Vec3 p = w0 * a + w1 * b + w2 * c;

  // Base colour.
  float base[4] = { static_cast<float>(mesh.color.x()), static_cast<float>(mesh.color.y()),
    static_cast<float>(mesh.color.z()), 1.0f };
  if (mesh.colorSource == TraceMesh::ColorSource::Point)
  {
    for (int k = 0; k < 4; ++k)
    {
      base[k] = static_cast<float>(w0 * mesh.colors[4 * t[0] + k] + w1 * mesh.colors[4 * t[1] + k] +
        w2 * mesh.colors[4 * t[2] + k]);
    }
  }
  else if (mesh.colorSource == TraceMesh::ColorSource::Cell)
  {
    std::copy_n(&mesh.colors[4 * static_cast<std::size_t>(g.local)], 4, base);
  }

  Vec3 colour(base[0], base[1], base[2]);
  if (mesh.shading != TraceMesh::Shading::None)
  {
    Vec3 n = (b - a).cross(c - a);
    if (mesh.shading == TraceMesh::Shading::Smooth && !mesh.normals.empty())
    {
      const Vec3 interpolated =
        w0 * mesh.normals[t[0]] + w1 * mesh.normals[t[1]] + w2 * mesh.normals[t[2]];
      if (interpolated.squaredNorm() > 0.0)
      {
        n = interpolated;
      }
    }
    const double norm = n.norm();
    n = norm > 0.0 ? Vec3(n / norm) : Vec3(-direction.normalized());
    // The viewer is this ray's own mirror point.
    if (mesh.twoSided && n.dot(origin - p) < 0.0)
    {
      n = -n;
    }
    Material material = mesh.material;
    if (mesh.colorSource != TraceMesh::ColorSource::Solid)
    {
      material.ambient = mesh.ambientFactor * colour;
      material.diffuse = mesh.diffuseFactor * colour;
    }
    std::vector<unsigned char> lit;
    if (this->Shadows && !this->Lights.empty())
    {
      lit.resize(this->Lights.size());
      statistics.shadowRays += TraceShadows(this->Scene, p, n, this->Lights, lit.data());
    }
    colour = Shade(p, n, origin, this->Lights, material, this->GlobalAmbient,
      lit.empty() ? nullptr : lit.data(), false);
  }
  float out[4] = { static_cast<float>(colour.x()), static_cast<float>(colour.y()),
    static_cast<float>(colour.z()), static_cast<float>(base[3] * mesh.opacity) };
  if (mesh.texture >= 0 && !mesh.tcoords.empty())
  {
    const float u = static_cast<float>(
      w0 * mesh.tcoords[2 * t[0]] + w1 * mesh.tcoords[2 * t[1]] + w2 * mesh.tcoords[2 * t[2]]);
    const float v = static_cast<float>(w0 * mesh.tcoords[2 * t[0] + 1] +
      w1 * mesh.tcoords[2 * t[1] + 1] + w2 * mesh.tcoords[2 * t[2] + 1]);
    float texel[4];
    sampleTexture(this->Textures[mesh.texture], u, v, texel);
    for (int k = 0; k < 4; ++k)
    {
      out[k] *= texel[k];
    }
  }
  for (int k = 0; k < 4; ++k)
  {
    rgba[k] = std::min(1.0f, std::max(0.0f, out[k]));
  }
}

void RayTracer::RenderRows(const ImageView& target, RasterId* ids, std::ptrdiff_t idRowStride,
  int y0, int y1, RayTraceStatistics* statistics, float* pathLengths) const
{
  if (!this->HasScene || this->Width <= 0 || target.data == nullptr ||
    target.width != this->Width || target.height != this->Height)
  {
    return;
  }
  RayTraceStatistics local;
  const int s = this->Samples;
  const int perPixel = s * s;
  const int centre = (s / 2) * s + s / 2; // the centre-most sample
  const double inv = 1.0 / perPixel;
  const double tfar = std::numeric_limits<double>::infinity();
  for (int y = std::max(0, y0); y < std::min(this->Height, y1); ++y)
  {
    for (int x = 0; x < this->Width; ++x)
    {
      const std::size_t first =
        (static_cast<std::size_t>(y) * this->Width + static_cast<std::size_t>(x)) * perPixel;
      std::uint8_t* px = target.pixel(x, y);
      const double frame[3] = { px[0] / 255.0, px[1] / 255.0, px[2] / 255.0 };
      double sum[3] = { 0.0, 0.0, 0.0 };
      RasterId id = -1;
      float pathLength = std::numeric_limits<float>::quiet_NaN();
      bool any = false;
      for (int k = 0; k < perPixel; ++k)
      {
        double sample[3] = { frame[0], frame[1], frame[2] };
        if (this->RayValid[first + k])
        {
          ++local.mirrorRays;
          const Ray& r = this->Rays[first + k];
          const Vec3 origin(r.origin[0], r.origin[1], r.origin[2]);
          const Vec3 direction(r.direction[0], r.direction[1], r.direction[2]);
          if (!this->Triangles.empty() &&
            RayMeetsBox(origin, direction, this->BoundsMin, this->BoundsMax))
          {
            ++local.tracedRays;
            const RayScene::Hit hit = this->Scene.Intersect(origin, direction, 0.0, tfar);
            if (hit.hit)
            {
              ++local.hits;
              any = true;
              float rgba[4];
              this->ShadeHit(origin, direction, hit, rgba, local);
              for (int c = 0; c < 3; ++c)
              {
                sample[c] = rgba[3] * rgba[c] + (1.0 - rgba[3]) * frame[c];
              }
              if (k == centre)
              {
                const GlobalTriangle g = this->Triangles[hit.triangle];
                const TraceMesh& mesh = this->Meshes[g.mesh];
                const RasterId local_id =
                  mesh.triangleIds.empty() ? g.local : mesh.triangleIds[g.local];
                id = (static_cast<RasterId>(g.mesh) << 32) + local_id;
                // The rays' directions are unit vectors: t is the distance.
                pathLength = static_cast<float>(hit.t * direction.norm());
              }
            }
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += sample[c];
        }
      }
      if (any)
      {
        for (int c = 0; c < 3; ++c)
        {
          px[c] = static_cast<std::uint8_t>(std::lround(255.0 * std::min(1.0, sum[c] * inv)));
        }
      }
      if (ids)
      {
        ids[y * idRowStride + x] = id;
      }
      if (pathLengths)
      {
        pathLengths[y * idRowStride + x] = pathLength;
      }
    }
  }
  if (statistics)
  {
    statistics->mirrorRays += local.mirrorRays;
    statistics->tracedRays += local.tracedRays;
    statistics->hits += local.hits;
    statistics->shadowRays += local.shadowRays;
  }
}

} // namespace catar
