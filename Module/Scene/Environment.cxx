#include "Environment.h"

#include "Projector.h"
#include "SafeCast.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace catar
{
namespace
{
// 1 on a grid line of the given spacing and half width, 0 elsewhere.
inline bool OnGrid(double u, double spacing, double halfWidth)
{
  const double f = u / spacing - std::floor(u / spacing);
  return f * spacing < halfWidth || (1.0 - f) * spacing < halfWidth;
}

inline bool InRect(double u, double v, double u0, double u1, double v0, double v1)
{
  return u >= u0 && u <= u1 && v >= v0 && v <= v1;
}

Vec3 WallColor(int wall, double u, double z, const RoomEnvironment& room)
{
  static const Vec3 base[4] = { Vec3(0.52, 0.62, 0.80), Vec3(0.58, 0.74, 0.58),
    Vec3(0.86, 0.80, 0.64), Vec3(0.80, 0.58, 0.52) };
  if (z < room.minCorner.z() + 0.12)
  {
    return Vec3(0.25, 0.22, 0.2); // skirting board
  }
  if (wall == 2 && InRect(u, z, -0.7, 0.7, 0.9, 2.1))
  {
    // Window with a cross-shaped frame; sky brighter at the top.
    if (std::abs(u) < 0.03 || std::abs(z - 1.5) < 0.03 || !InRect(u, z, -0.65, 0.65, 0.95, 2.05))
    {
      return Vec3(0.95, 0.95, 0.95);
    }
    const double k = (z - 0.9) / 1.2;
    return Vec3(0.55 + 0.3 * k, 0.75 + 0.15 * k, 0.98);
  }
  if (wall == 1 && InRect(u, z, -0.5, 0.3, room.minCorner.z(), 2.0))
  {
    const bool handle = InRect(u, z, 0.15, 0.22, 0.95, 1.02);
    return handle ? Vec3(0.9, 0.8, 0.3) : Vec3(0.42, 0.25, 0.12);
  }
  if (OnGrid(u, room.wallTile, 0.012) || OnGrid(z, room.wallTile, 0.012))
  {
    return base[wall] * 0.55;
  }
  return base[wall];
}
} // namespace

Vec3 RoomColor(const RoomEnvironment& room, const Vec3& origin, const Vec3& d)
{
  // Exit point of the ray from the box (the origin is clamped into the box).
  const Vec3 o = origin.cwiseMax(room.minCorner).cwiseMin(room.maxCorner);
  double tExit = std::numeric_limits<double>::infinity();
  int face = -1; // 0:-x 1:+x 2:-y 3:+y 4:floor 5:ceiling
  for (int k = 0; k < 3; ++k)
  {
    if (d[k] > 0.0)
    {
      const double t = (room.maxCorner[k] - o[k]) / d[k];
      if (t < tExit)
      {
        tExit = t;
        face = 2 * k + 1;
      }
    }
    else if (d[k] < 0.0)
    {
      const double t = (room.minCorner[k] - o[k]) / d[k];
      if (t < tExit)
      {
        tExit = t;
        face = 2 * k;
      }
    }
  }
  if (face < 0 || !std::isfinite(tExit))
  {
    return Vec3(0, 0, 0);
  }
  const Vec3 p = o + tExit * d;
  switch (face)
  {
    case 4: // floor: checker
    {
      const long long i = FloorToInteger(p.x() / room.floorTile);
      const long long j = FloorToInteger(p.y() / room.floorTile);
      if (OnGrid(p.x(), room.floorTile, 0.006) || OnGrid(p.y(), room.floorTile, 0.006))
      {
        return Vec3(0.15, 0.13, 0.12);
      }
      return ((i + j) & 1) ? Vec3(0.78, 0.66, 0.48) : Vec3(0.46, 0.34, 0.24);
    }
    case 5: // ceiling: panels and a lamp
    {
      if (InRect(p.x(), p.y(), -0.4, 0.4, -0.4, 0.4))
      {
        return Vec3(1.0, 0.98, 0.9);
      }
      if (OnGrid(p.x(), 0.6, 0.01) || OnGrid(p.y(), 0.6, 0.01))
      {
        return Vec3(0.6, 0.6, 0.62);
      }
      return Vec3(0.88, 0.88, 0.9);
    }
    case 0:
      return WallColor(1, p.y(), p.z(), room);
    case 1:
      return WallColor(0, p.y(), p.z(), room);
    case 2:
      return WallColor(3, p.x(), p.z(), room);
    default:
      return WallColor(2, p.x(), p.z(), room);
  }
}

namespace
{
constexpr double kPi = 3.14159265358979323846;

inline std::uint8_t ToByte(double v)
{
  return static_cast<std::uint8_t>(std::lround(255.0 * std::min(1.0, std::max(0.0, v))));
}

// The per-pixel loop shared by every environment: back-projects samples x samples sub-pixel
// positions of each pixel of rows [y0, y1), averages color(pixel, ray) over them and writes RGBA8
// (alpha 255).
template<class SampleColor>
void RenderRows(const Projector& projector, int samples, const ImageView& target, int y0, int y1,
  const SampleColor& color)
{
  samples = std::max(1, std::min(8, samples));
  const double inv = 1.0 / (samples * samples);
  // A row's samples are back-projected together (Projector's batches), then shaded in order.
  const std::size_t perPixel = static_cast<std::size_t>(samples) * samples;
  std::vector<Vec2> px(perPixel * static_cast<std::size_t>(std::max(0, target.width)));
  std::vector<BackProjectedRay> rays(px.size());
  for (int y = std::max(0, y0); y < std::min(target.height, y1); ++y)
  {
    std::size_t i = 0;
    for (int x = 0; x < target.width; ++x)
    {
      for (int sy = 0; sy < samples; ++sy)
      {
        for (int sx = 0; sx < samples; ++sx)
        {
          px[i++] = Vec2(x + (sx + 0.5) / samples - 0.5, y + (sy + 0.5) / samples - 0.5);
        }
      }
    }
    projector.BackProjectWorld(px.size(), px.data(), rays.data());
    i = 0;
    for (int x = 0; x < target.width; ++x)
    {
      Vec3 sum = Vec3::Zero();
      for (std::size_t k = 0; k < perPixel; ++k, ++i)
      {
        sum += color(px[i], rays[i]);
      }
      sum *= inv;
      std::uint8_t* out = target.pixel(x, y);
      for (int k = 0; k < 3; ++k)
      {
        out[k] = ToByte(sum[k]);
      }
      out[3] = 255;
    }
  }
}
} // namespace

void RenderEnvironmentRows(const Projector& projector, const RoomEnvironment& room, int samples,
  const ImageView& target, int y0, int y1)
{
  const CameraModel& model = projector.GetModel();
  const Vec3 eye = model.CameraToWorld(Vec3::Zero());
  RenderRows(
    projector, samples, target, y0, y1, [&](const Vec2& px, const BackProjectedRay& ray) -> Vec3 {
      if (HasProjection(ray.status))
      {
        return 0.92 * RoomColor(room, ray.mirrorPoint, ray.direction); // ~92% reflectance
      }
      Vec3 camera;
      if (ray.status == ProjectionStatus::NoReflection && model.PixelToDirection(px, camera))
      {
        return RoomColor(room, eye, model.CameraToWorldDirection(camera));
      }
      return Vec3::Zero();
    });
}

bool EquirectangularPanorama::IsValid() const
{
  return width > 0 && height > 0 && (channels == 3 || channels == 4) &&
    pixels.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels;
}

Vec2 PanoramaPixel(int width, int height, const Vec3& d)
{
  const double n = d.norm();
  double lon = 0.0;
  double lat = 0.0;
  if (n > 0.0 && std::isfinite(n))
  {
    lon = std::atan2(d.y(), d.x());
    if (lon <= -kPi)
    {
      lon = kPi; // keep x in [-0.5, width - 0.5)
    }
    lat = std::asin(std::min(1.0, std::max(-1.0, d.z() / n)));
  }
  return Vec2((0.5 - lon / (2.0 * kPi)) * width - 0.5, (0.5 - lat / kPi) * height - 0.5);
}

Vec3 PanoramaDirection(int width, int height, double x, double y)
{
  const double lon = 2.0 * kPi * (0.5 - (x + 0.5) / width);
  const double lat = std::min(0.5 * kPi, std::max(-0.5 * kPi, kPi * (0.5 - (y + 0.5) / height)));
  const double c = std::cos(lat);
  return Vec3(c * std::cos(lon), c * std::sin(lon), std::sin(lat));
}

Vec3 PanoramaColor(const EquirectangularPanorama& panorama, const Vec3& worldDirection)
{
  if (!panorama.IsValid())
  {
    return Vec3::Zero();
  }
  const int w = panorama.width;
  const int h = panorama.height;
  const Vec2 p = PanoramaPixel(w, h, worldDirection);
  // Longitude wraps: columns i0 and i0 + 1 modulo the width.
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
  {
    return Vec3::Zero();
  }
  const double fx = std::floor(p.x());
  const double tx = p.x() - fx;
  int i0 = static_cast<int>(FloorToInteger(p.x()) % w);
  if (i0 < 0)
  {
    i0 += w;
  }
  const int i1 = (i0 + 1) % w;
  // Latitude clamps: above the first / below the last row centre, that row.
  const double y = std::min(static_cast<double>(h - 1), std::max(0.0, p.y()));
  const double fy = std::floor(y);
  const double ty = y - fy;
  const int j0 = static_cast<int>(fy);
  const int j1 = std::min(j0 + 1, h - 1);
  const std::uint8_t* c00 = panorama.texel(i0, j0);
  const std::uint8_t* c10 = panorama.texel(i1, j0);
  const std::uint8_t* c01 = panorama.texel(i0, j1);
  const std::uint8_t* c11 = panorama.texel(i1, j1);
  Vec3 c;
  for (int k = 0; k < 3; ++k)
  {
    const double top = (1.0 - tx) * c00[k] + tx * c10[k];
    const double bottom = (1.0 - tx) * c01[k] + tx * c11[k];
    c[k] = ((1.0 - ty) * top + ty * bottom) / 255.0;
  }
  return c;
}

EquirectangularPanorama MakeRoomPanorama(
  const RoomEnvironment& room, const Vec3& viewpoint, int width)
{
  EquirectangularPanorama panorama;
  panorama.width = std::max(2, width + (width & 1));
  panorama.height = panorama.width / 2;
  panorama.channels = 3;
  panorama.pixels.resize(
    static_cast<std::size_t>(panorama.width) * panorama.height * panorama.channels);
  RenderRoomPanoramaRows(room, viewpoint, panorama, 0, panorama.height);
  return panorama;
}

void RenderRoomPanoramaRows(const RoomEnvironment& room, const Vec3& viewpoint,
  EquirectangularPanorama& panorama, int j0, int j1)
{
  if (!panorama.IsValid())
  {
    return;
  }
  for (int j = std::max(0, j0); j < std::min(panorama.height, j1); ++j)
  {
    for (int i = 0; i < panorama.width; ++i)
    {
      const Vec3 c =
        RoomColor(room, viewpoint, PanoramaDirection(panorama.width, panorama.height, i, j));
      std::uint8_t* out = panorama.texel(i, j);
      for (int k = 0; k < 3; ++k)
      {
        out[k] = ToByte(c[k]);
      }
      if (panorama.channels == 4)
      {
        out[3] = 255;
      }
    }
  }
}

Vec3 PlacedPanoramaColor(
  const EquirectangularPanorama& panorama, const PanoramaPlacement& placement, const Vec3& d)
{
  if (placement.rotation == 0.0)
  {
    return PanoramaColor(panorama, d);
  }
  // World longitude L shows the panorama's longitude L - rotation.
  const double a = placement.rotation * kPi / 180.0;
  const double c = std::cos(a);
  const double s = std::sin(a);
  return PanoramaColor(panorama, Vec3(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z()));
}

void RenderPanoramaRows(const Projector& projector, const EquirectangularPanorama& panorama,
  const PanoramaPlacement& placement, int samples, const ImageView& target, int y0, int y1)
{
  RenderRows(
    projector, samples, target, y0, y1, [&](const Vec2&, const BackProjectedRay& ray) -> Vec3 {
      return HasProjection(ray.status) ? PlacedPanoramaColor(panorama, placement, ray.direction)
                                       : placement.backdrop;
    });
}
} // namespace catar
