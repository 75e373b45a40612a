#include "RayTracer.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace catar
{

namespace
{
constexpr double kPi = 3.14159265358979323846;

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

namespace
{
// Runs body over [0, n) with `parallel`, or on this thread without one.
void Run(const RayTracer::ParallelFor& parallel, std::size_t n,
  const std::function<void(std::size_t, std::size_t)>& body)
{
  if (n == 0)
  {
    return;
  }
  if (parallel)
  {
    parallel(n, body);
  }
  else
  {
    body(0, n);
  }
}
} // namespace

bool RayTracer::SetScene(const std::vector<TraceMesh>& meshes,
  const std::vector<TextureView>& textures, const std::vector<LightSource>& lights,
  const Vec3& globalAmbient, bool shadows)
{
  std::vector<std::shared_ptr<const TraceMesh>> copies;
  copies.reserve(meshes.size());
  for (const TraceMesh& mesh : meshes)
  {
    copies.push_back(std::make_shared<const TraceMesh>(mesh));
  }
  return this->SetScene(copies, textures, lights, globalAmbient, shadows);
}

bool RayTracer::SetScene(const std::vector<std::shared_ptr<const TraceMesh>>& meshes,
  const std::vector<TextureView>& textures, const std::vector<LightSource>& lights,
  const Vec3& globalAmbient, bool shadows, int buildThreads)
{
  const bool hadScene = this->HasScene;
  this->HasScene = false;
  this->Error.clear();
  // Meshes given again (same object, same place) keep their geometry, checked when it came.
  bool keep = hadScene && meshes.size() == this->Meshes.size();
  std::vector<bool> known(meshes.size(), false);
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    known[m] = hadScene && m < this->Meshes.size() && meshes[m] == this->Meshes[m];
    keep = keep && known[m];
  }
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const std::string which = "mesh " + std::to_string(m) + ": ";
    if (!meshes[m])
    {
      this->Error = which + "missing";
      this->Meshes.clear();
      return false;
    }
    const TraceMesh& mesh = *meshes[m];
    const std::size_t n = mesh.points.size();
    const std::size_t nt = mesh.triangles.size();
    if (!known[m])
    {
      if (n > std::numeric_limits<std::uint32_t>::max() / 2)
      {
        this->Error = which + "too many points";
        this->Meshes.clear();
        return false;
      }
      for (const Vec3& p : mesh.points)
      {
        if (!Finite(p))
        {
          this->Error = which + "a point has a NaN or infinite coordinate";
          this->Meshes.clear();
          return false;
        }
      }
      for (const auto& t : mesh.triangles)
      {
        if (t[0] >= n || t[1] >= n || t[2] >= n)
        {
          this->Error = which + "a triangle refers to a point that does not exist";
          this->Meshes.clear();
          return false;
        }
      }
    }
    if (!mesh.triangleIds.empty() && mesh.triangleIds.size() != nt)
    {
      this->Error = which + "triangleIds must have one value per triangle";
      this->Meshes.clear();
      return false;
    }
    const std::size_t colorCount = mesh.colorSource == TraceMesh::ColorSource::Point ? n
      : mesh.colorSource == TraceMesh::ColorSource::Cell                             ? nt
                                                                                     : 0;
    if (mesh.colorSource != TraceMesh::ColorSource::Solid && mesh.colors.size() != 4 * colorCount)
    {
      this->Error = which + "colors must have 4 values per " +
        (mesh.colorSource == TraceMesh::ColorSource::Point ? "point" : "triangle");
      this->Meshes.clear();
      return false;
    }
    if (!mesh.normals.empty() && mesh.normals.size() != n)
    {
      this->Error = which + "normals must have one value per point";
      this->Meshes.clear();
      return false;
    }
    if (!mesh.tcoords.empty() && mesh.tcoords.size() != 2 * n)
    {
      this->Error = which + "tcoords must have 2 values per point";
      this->Meshes.clear();
      return false;
    }
    if (mesh.texture >= static_cast<int>(textures.size()))
    {
      this->Error = which + "texture " + std::to_string(mesh.texture) + " does not exist (" +
        std::to_string(textures.size()) + " textures)";
      this->Meshes.clear();
      return false;
    }
  }
  if (!keep)
  {
    // Meshes given anew with the triangles and the number of points of the ones they replace:
    // their structures refitted to the new points; else the acceleration structure built again,
    // one Embree geometry per mesh.
    bool refit = hadScene && meshes.size() == this->Meshes.size() && this->Scene.GetDynamic();
    for (std::size_t m = 0; refit && m < meshes.size(); ++m)
    {
      refit = known[m] ||
        (meshes[m]->points.size() == this->Meshes[m]->points.size() &&
          meshes[m]->triangles == this->Meshes[m]->triangles);
    }
    std::vector<std::vector<float>> points(meshes.size());
    std::vector<RayScene::MeshView> views(meshes.size());
    // Mesh m's points in single precision, and the view of them the ray scene builds from.
    const auto convert = [&](std::size_t m) {
      const TraceMesh& mesh = *meshes[m];
      points[m].resize(3 * mesh.points.size());
      for (std::size_t i = 0; i < mesh.points.size(); ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          points[m][3 * i + k] = static_cast<float>(mesh.points[i][k]);
        }
      }
      views[m].points = points[m].data();
      views[m].pointCount = mesh.points.size();
      views[m].triangles = mesh.triangles.empty() ? nullptr : mesh.triangles.front().data();
      views[m].triangleCount = mesh.triangles.size();
    };
    for (std::size_t m = 0; m < meshes.size(); ++m)
    {
      if (!(refit && known[m]))
      {
        convert(m);
      }
    }
    if (refit)
    {
      for (std::size_t m = 0; refit && m < meshes.size(); ++m)
      {
        refit = known[m] || this->Scene.UpdatePoints(m, points[m].data());
      }
      refit = refit && this->Scene.Commit();
      if (refit)
      {
        ++this->Refits;
      }
    }
    if (!refit)
    {
      for (std::size_t m = 0; m < meshes.size(); ++m)
      {
        if (views[m].points == nullptr && !meshes[m]->points.empty())
        {
          convert(m); // skipped above for a refit that failed
        }
      }
      this->Scene.SetBuildThreads(buildThreads);
      this->Scene.SetDynamic(true);
      if (!this->Scene.Build(views))
      {
        this->Error = "building the ray scene failed: " + this->Scene.GetError();
        this->Meshes.clear();
        return false;
      }
      ++this->Builds;
    }
    // The bounds of the triangles.
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    bool any = false;
    for (const auto& m : meshes)
    {
      for (const auto& t : m->triangles)
      {
        for (int k = 0; k < 3; ++k)
        {
          lo = lo.cwiseMin(m->points[t[k]]);
          hi = hi.cwiseMax(m->points[t[k]]);
        }
      }
      any = any || !m->triangles.empty();
    }
    // Grow the box a little: Embree's single precision must not lose grazing hits.
    const Vec3 pad = Vec3::Constant(1e-6 * std::max(1.0, (hi - lo).norm()));
    this->BoundsMin = any ? Vec3(lo - pad) : Vec3::Zero();
    this->BoundsMax = any ? Vec3(hi + pad) : Vec3::Zero();
    this->SphereCentre = 0.5 * (this->BoundsMin + this->BoundsMax);
    this->SphereRadius = 0.5 * (this->BoundsMax - this->BoundsMin).norm();
  }
  this->Meshes = meshes;
  this->Textures = textures;
  this->Lights = lights;
  this->GlobalAmbient = globalAmbient;
  this->Shadows = shadows;
  this->HasScene = true;
  return true;
}

bool RayTracer::PrepareRays(const Projector& projector, int samples, const ParallelFor& parallel)
{
  this->Error.clear();
  if (!projector.IsValid())
  {
    this->Error = "invalid camera: " + projector.GetError();
    this->Rays.clear();
    this->RayValid.clear();
    this->Tiles.clear();
    this->Width = this->Height = 0;
    return false;
  }
  samples = std::max(1, std::min(8, samples));
  const CameraModel& model = projector.GetModel();
  const int w = model.intrinsics.width;
  const int h = model.intrinsics.height;
  // The pose: moves the rays into the world at render time.
  this->WorldToCamera = model.worldToCamera.topLeftCorner<3, 3>();
  this->Translation = model.worldToCamera.topRightCorner<3, 1>();
  this->CameraToWorld = this->WorldToCamera.transpose();
  this->CameraCentre = -this->CameraToWorld * this->Translation;
  if (this->Width == w && this->Height == h && this->Samples == samples && w > 0 &&
    this->RaysLens.SameLens(model) && this->RaysLens.mirror == model.mirror)
  {
    return true; // the same rays in the camera frame
  }
  const std::size_t count = static_cast<std::size_t>(w) * h * samples * samples;
  this->Rays.assign(count, Ray{ { 0, 0, 0 }, { 0, 0, 0 } });
  this->RayValid.assign(count, 0);
  this->Width = w;
  this->Height = h;
  this->Samples = samples;
  this->TilesX = (w + kTile - 1) / kTile;
  this->TilesY = (h + kTile - 1) / kTile;
  this->Tiles.assign(static_cast<std::size_t>(this->TilesX) * this->TilesY, Tile());
  Run(parallel, static_cast<std::size_t>(this->TilesY), [&](std::size_t b, std::size_t e) {
    this->BackProjectTileRows(projector, static_cast<int>(b), static_cast<int>(e));
  });
  this->RaysLens = model;
  ++this->RayPreparations;
  return true;
}

void RayTracer::BackProjectTileRows(const Projector& projector, int r0, int r1)
{
  const int w = this->Width;
  const int samples = this->Samples;
  const int perPixel = samples * samples;
  // A row's samples are back-projected together (Projector's batches).
  const std::size_t perRow = static_cast<std::size_t>(w) * perPixel;
  std::vector<Vec2> pixels(perRow);
  std::vector<BackProjectedRay> rays(perRow);
  for (int y = r0 * kTile; y < std::min(this->Height, r1 * kTile); ++y)
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
    projector.BackProjectCamera(perRow, pixels.data(), rays.data());
    std::size_t i = static_cast<std::size_t>(y) * perRow;
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
  // The tiles' balls of origins and cones of directions, from the single-precision rays.
  for (int ty = r0; ty < r1; ++ty)
  {
    const int y0 = ty * kTile, y1 = std::min(this->Height, y0 + kTile);
    for (int tx = 0; tx < this->TilesX; ++tx)
    {
      const int x0 = tx * kTile, x1 = std::min(w, x0 + kTile);
      Vec3 centre = Vec3::Zero(), axis = Vec3::Zero();
      std::uint32_t n = 0;
      auto forEach = [&](auto&& f) {
        for (int y = y0; y < y1; ++y)
        {
          for (std::size_t i = (static_cast<std::size_t>(y) * w + x0) * perPixel,
                           end = (static_cast<std::size_t>(y) * w + x1) * perPixel;
               i < end; ++i)
          {
            if (this->RayValid[i])
            {
              const Ray& r = this->Rays[i];
              f(Vec3(r.origin[0], r.origin[1], r.origin[2]),
                Vec3(r.direction[0], r.direction[1], r.direction[2]));
            }
          }
        }
      };
      forEach([&](const Vec3& o, const Vec3& d) {
        centre += o;
        axis += d.normalized();
        ++n;
      });
      Tile& tile = this->Tiles[static_cast<std::size_t>(ty) * this->TilesX + tx];
      tile.rays = n;
      if (n == 0)
      {
        continue;
      }
      centre /= n;
      const double axisNorm = axis.norm();
      axis = axisNorm > 0 ? Vec3(axis / axisNorm) : Vec3(0, 0, 1);
      double radius = 0.0, angle = axisNorm > 0 ? 0.0 : kPi;
      forEach([&](const Vec3& o, const Vec3& d) {
        radius = std::max(radius, (o - centre).norm());
        angle = std::max(angle, std::acos(std::max(-1.0, std::min(1.0, d.normalized().dot(axis)))));
      });
      for (int k = 0; k < 3; ++k)
      {
        tile.centre[k] = static_cast<float>(centre[k]);
        tile.axis[k] = static_cast<float>(axis[k]);
      }
      // Rounded up: the bounds must hold every ray (the tests below pad them again).
      tile.radius = static_cast<float>(radius * (1.0 + 1e-6) + 1e-9 * centre.norm());
      angle = std::min(kPi, angle + 1e-6);
      tile.cosAngle = std::cos(angle);
      tile.sinAngle = std::sin(angle);
    }
  }
}

bool RayTracer::TileMeetsSphere(const Tile& tile, const Vec3& c, double r)
{
  // A ray from a point within tile.radius of the centre meets the sphere only if the ray from
  // the centre with the same direction meets the sphere grown by that radius: its direction is
  // then within b = asin(R / distance) of the sphere's centre, and within a + b of the axis (a:
  // the tile's angle). With cosines: a + b >= pi (everything passes) when cos a <= -cos b, else
  // the test is cos(angle to the centre) >= cos(a + b) = cos a cos b - sin a sin b.
  const Vec3 o(tile.centre[0], tile.centre[1], tile.centre[2]);
  const Vec3 v = c - o;
  const double distance = v.norm();
  // Padded for the single-precision rays and the moves between frames (relative 1e-6).
  const double grown = (r + tile.radius) * (1.0 + 1e-6) + 1e-6 * distance;
  if (!(distance > grown))
  {
    return true;
  }
  const double sinB = grown / distance;
  const double cosB = std::sqrt(1.0 - sinB * sinB);
  // The padding of the angle: b grown by about 1e-6.
  const double cosA = tile.cosAngle, sinA = tile.sinAngle;
  const double cosPadded = cosB * (1.0 - 5e-13) - sinB * 1e-6, sinPadded = sinB + cosB * 1e-6;
  if (cosA <= -cosPadded)
  {
    return true;
  }
  const Vec3 axis(tile.axis[0], tile.axis[1], tile.axis[2]);
  return v.dot(axis) >= distance * axis.norm() * (cosA * cosPadded - sinA * sinPadded);
}

void RayTracer::ShadeHit(const Vec3& origin, const Vec3& direction, const RayScene::Hit& hit,
  float rgba[4], RayTraceStatistics& statistics) const
{
  const TraceMesh& mesh = *this->Meshes[hit.mesh];
  const std::uint32_t local = hit.triangle;
  const auto& t = mesh.triangles[local];
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
    std::copy_n(&mesh.colors[4 * static_cast<std::size_t>(local)], 4, base);
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
    // Shadows: a flag per light (on the stack for up to 16 lights).
    unsigned char few[16];
    std::vector<unsigned char> many;
    unsigned char* lit = nullptr;
    if (this->Shadows && !this->Lights.empty())
    {
      if (this->Lights.size() > sizeof(few))
      {
        many.resize(this->Lights.size());
      }
      lit = many.empty() ? few : many.data();
      statistics.shadowRays += TraceShadows(this->Scene, p, n, this->Lights, lit);
    }
    colour = Shade(p, n, origin, this->Lights, material, this->GlobalAmbient, lit, false);
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
  y0 = std::max(0, y0);
  y1 = std::min(this->Height, y1);
  RayTraceStatistics local;
  const int perPixel = this->Samples * this->Samples;
  // The scene's bounding sphere in the camera frame, where the tiles' bounds are.
  const Vec3 sphereCentre = this->WorldToCamera * this->SphereCentre + this->Translation;
  const bool anyTriangle = this->Scene.GetNumberOfTriangles() > 0;
  TileBuffers buffers; // made at the first tile traced
  for (int ty = y0 / kTile; ty * kTile < y1; ++ty)
  {
    const int a = std::max(y0, ty * kTile), b = std::min(y1, (ty + 1) * kTile);
    for (int tx = 0; tx < this->TilesX; ++tx)
    {
      const Tile& tile = this->Tiles[static_cast<std::size_t>(ty) * this->TilesX + tx];
      if (anyTriangle && tile.rays > 0 &&
        (!this->TileCulling || TileMeetsSphere(tile, sphereCentre, this->SphereRadius)))
      {
        if (buffers.which.empty())
        {
          const std::size_t most = static_cast<std::size_t>(kTile) * kTile * perPixel;
          buffers.rays.resize(most);
          buffers.which.resize(most);
          buffers.hits.resize(most);
        }
        this->RenderTile(target, ids, idRowStride, tx, a, b, buffers, local, pathLengths);
        continue;
      }
      // Nothing to trace: the frame stays; no triangle, no path length.
      const int x0 = tx * kTile, x1 = std::min(this->Width, x0 + kTile);
      if (b - a == kTile || b - a == this->Height - ty * kTile)
      {
        local.mirrorRays += tile.rays;
      }
      else if (tile.rays > 0)
      {
        for (int y = a; y < b; ++y)
        {
          const std::size_t first = (static_cast<std::size_t>(y) * this->Width + x0) * perPixel;
          const std::size_t last = (static_cast<std::size_t>(y) * this->Width + x1) * perPixel;
          local.mirrorRays += static_cast<std::size_t>(std::count(
            this->RayValid.begin() + first, this->RayValid.begin() + last, std::uint8_t(1)));
        }
      }
      for (int y = a; y < b; ++y)
      {
        if (ids)
        {
          std::fill(ids + y * idRowStride + x0, ids + y * idRowStride + x1, RasterId(-1));
        }
        if (pathLengths)
        {
          std::fill(pathLengths + y * idRowStride + x0, pathLengths + y * idRowStride + x1,
            std::numeric_limits<float>::quiet_NaN());
        }
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

void RayTracer::RenderTile(const ImageView& target, RasterId* ids, std::ptrdiff_t idRowStride,
  int tx, int y0, int y1, TileBuffers& buffers, RayTraceStatistics& local, float* pathLengths) const
{
  const int s = this->Samples;
  const int perPixel = s * s;
  const int centre = (s / 2) * s + s / 2; // the centre-most sample
  const double inv = 1.0 / perPixel;
  const int x0 = tx * kTile, x1 = std::min(this->Width, x0 + kTile);
  const int tileWidth = x1 - x0;
  // The tile's rays, moved into the world, that reach the scene's box: traced together.
  Ray* rays = buffers.rays.data();
  std::int16_t* which = buffers.which.data(); // per sample of the tile: its ray, or -1
  int n = 0;
  const Mat3& rotation = this->CameraToWorld;
  for (int y = y0; y < y1; ++y)
  {
    const std::size_t first = (static_cast<std::size_t>(y) * this->Width + x0) * perPixel;
    const int row = (y - y0) * tileWidth * perPixel;
    for (int j = 0; j < tileWidth * perPixel; ++j)
    {
      which[row + j] = -1;
      if (!this->RayValid[first + j])
      {
        continue;
      }
      ++local.mirrorRays;
      const Ray& c = this->Rays[first + j];
      const Vec3 o = rotation * Vec3(c.origin[0], c.origin[1], c.origin[2]) + this->CameraCentre;
      const Vec3 d = rotation * Vec3(c.direction[0], c.direction[1], c.direction[2]);
      Ray& r = rays[n];
      for (int k = 0; k < 3; ++k)
      {
        r.origin[k] = static_cast<float>(o[k]);
        r.direction[k] = static_cast<float>(d[k]);
      }
      if (RayMeetsBox(Vec3(r.origin[0], r.origin[1], r.origin[2]),
            Vec3(r.direction[0], r.direction[1], r.direction[2]), this->BoundsMin, this->BoundsMax))
      {
        which[row + j] = static_cast<std::int16_t>(n++);
      }
    }
  }
  local.tracedRays += static_cast<std::size_t>(n);
  RayScene::Hit* hits = buffers.hits.data();
  this->Scene.Intersect(static_cast<std::size_t>(n), rays, hits);

  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      const int firstSample = ((y - y0) * tileWidth + (x - x0)) * perPixel;
      std::uint8_t* px = target.pixel(x, y);
      // The frame's alpha too: over a transparent background (alpha 0) a sample's alpha is its
      // surface's, as the compositor composites it (a + frame alpha (1 - a)).
      const double frame[4] = { px[0] / 255.0, px[1] / 255.0, px[2] / 255.0, px[3] / 255.0 };
      double sum[4] = { 0.0, 0.0, 0.0, 0.0 };
      RasterId id = -1;
      float pathLength = std::numeric_limits<float>::quiet_NaN();
      bool any = false;
      for (int k = 0; k < perPixel; ++k)
      {
        double sample[4] = { frame[0], frame[1], frame[2], frame[3] };
        const int i = which[firstSample + k];
        if (i >= 0 && hits[i].hit)
        {
          const RayScene::Hit& hit = hits[i];
          const Ray& r = rays[i];
          const Vec3 origin(r.origin[0], r.origin[1], r.origin[2]);
          const Vec3 direction(r.direction[0], r.direction[1], r.direction[2]);
          ++local.hits;
          any = true;
          float rgba[4];
          this->ShadeHit(origin, direction, hit, rgba, local);
          for (int c = 0; c < 3; ++c)
          {
            sample[c] = rgba[3] * rgba[c] + (1.0 - rgba[3]) * frame[c];
          }
          sample[3] = rgba[3] + (1.0 - rgba[3]) * frame[3];
          if (k == centre)
          {
            const TraceMesh& mesh = *this->Meshes[hit.mesh];
            const RasterId triangle =
              mesh.triangleIds.empty() ? hit.triangle : mesh.triangleIds[hit.triangle];
            id = (static_cast<RasterId>(hit.mesh) << 32) + triangle;
            // The rays' directions are unit vectors: t is the distance.
            pathLength = static_cast<float>(hit.t * direction.norm());
          }
        }
        for (int c = 0; c < 4; ++c)
        {
          sum[c] += sample[c];
        }
      }
      if (any)
      {
        for (int c = 0; c < 4; ++c)
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
}

} // namespace catar
