// Environments (Core): the equirectangular panorama's mapping and bilinear lookup, the room
// rendered into a panorama, camera frames of a panorama seen in the mirror, and the scene keys of
// the panorama background.
#include "Environment.h"
#include "Projector.h"
#include "SceneDescription.h"
#include "SphereMirror.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <vector>

using namespace catar;

namespace
{
constexpr double kPi = 3.14159265358979323846;

// A panorama whose every pixel has its own colour (no two neighbours alike).
EquirectangularPanorama PatternPanorama(int width, int height, int channels)
{
  EquirectangularPanorama p;
  p.width = width;
  p.height = height;
  p.channels = channels;
  p.pixels.resize(static_cast<std::size_t>(width) * height * channels);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      std::uint8_t* t = p.texel(i, j);
      t[0] = static_cast<std::uint8_t>((37 * i + 11 * j) % 256);
      t[1] = static_cast<std::uint8_t>((59 * j + 5 * i + 80) % 256);
      t[2] = static_cast<std::uint8_t>(((i ^ j) * 23 + 7) % 256);
      if (channels == 4)
      {
        t[3] = static_cast<std::uint8_t>(i % 2 ? 0 : 255); // alpha: kept, not used
      }
    }
  }
  return p;
}

Vec3 TexelColor(const EquirectangularPanorama& p, int i, int j)
{
  const std::uint8_t* t = p.texel(i, j);
  return Vec3(t[0], t[1], t[2]) / 255.0;
}

Vec3 FromLonLat(double lon, double lat)
{
  return Vec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
}

// A camera of the demo's layout at a small size: world z up, the camera looks along world +y at
// a mirror 20 cm away (its image, a disc of about 50 pixels radius, sits in the middle).
CameraModel SmallCamera()
{
  CameraModel m;
  m.intrinsics.width = 160;
  m.intrinsics.height = 120;
  m.intrinsics.fx = m.intrinsics.fy = 200.0;
  m.intrinsics.cx = 79.5;
  m.intrinsics.cy = 59.5;
  m.mirror = SphereMirror{ Vec3(0.0, 0.0, 0.2), 0.05 };
  m.worldToCamera << 1, 0, 0, 0, //
    0, 0, -1, 1.0,               // camera y (down) = -world z; camera at world (0, -0.2, 1)
    0, 1, 0, 0.2,                //
    0, 0, 0, 1;
  return m;
}

std::uint8_t Byte(double v)
{
  return static_cast<std::uint8_t>(std::lround(255.0 * std::min(1.0, std::max(0.0, v))));
}
} // namespace

TEST(EnvironmentPanorama, MappingConvention)
{
  const int w = 16, h = 8;
  // +x: longitude 0, the middle of the image (between columns 7 and 8), on the equator.
  Vec2 p = PanoramaPixel(w, h, Vec3(1, 0, 0));
  EXPECT_NEAR(p.x(), 7.5, 1e-12);
  EXPECT_NEAR(p.y(), 3.5, 1e-12);
  // +y: longitude +90 degrees, a quarter of the width to the LEFT of the middle.
  p = PanoramaPixel(w, h, Vec3(0, 2, 0));
  EXPECT_NEAR(p.x(), 3.5, 1e-12);
  // -y: a quarter to the right.
  p = PanoramaPixel(w, h, Vec3(0, -1, 0));
  EXPECT_NEAR(p.x(), 11.5, 1e-12);
  // -x: the seam (left edge of column 0 = right edge of the last column).
  p = PanoramaPixel(w, h, Vec3(-1, 0, 0));
  EXPECT_NEAR(p.x(), -0.5, 1e-12);
  p = PanoramaPixel(w, h, Vec3(-1, -0.0, 0));
  EXPECT_NEAR(p.x(), -0.5, 1e-12);
  // Zenith at the top edge of row 0, nadir at the bottom edge of the last row.
  EXPECT_NEAR(PanoramaPixel(w, h, Vec3(0, 0, 3)).y(), -0.5, 1e-12);
  EXPECT_NEAR(PanoramaPixel(w, h, Vec3(0, 0, -1)).y(), h - 0.5, 1e-12);
  // A degenerate direction gives the image centre, never NaN.
  p = PanoramaPixel(w, h, Vec3(0, 0, 0));
  EXPECT_NEAR(p.x(), 7.5, 1e-12);
  EXPECT_NEAR(p.y(), 3.5, 1e-12);
  p = PanoramaPixel(w, h, Vec3(std::nan(""), 0, 0));
  EXPECT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y()));
  // PanoramaDirection inverts PanoramaPixel.
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const Vec3 d = PanoramaDirection(w, h, i, j);
      EXPECT_NEAR(d.norm(), 1.0, 1e-12);
      const Vec2 back = PanoramaPixel(w, h, d);
      EXPECT_NEAR(back.x(), i, 1e-9);
      EXPECT_NEAR(back.y(), j, 1e-9);
    }
  }
}

TEST(EnvironmentPanorama, PixelCentresGiveTheirColours)
{
  for (int channels : { 3, 4 })
  {
    const EquirectangularPanorama p = PatternPanorama(24, 12, channels);
    ASSERT_TRUE(p.IsValid());
    for (int j = 0; j < p.height; ++j)
    {
      for (int i = 0; i < p.width; ++i)
      {
        const Vec3 c = PanoramaColor(p, 5.0 * PanoramaDirection(p.width, p.height, i, j));
        EXPECT_LT((c - TexelColor(p, i, j)).cwiseAbs().maxCoeff(), 1e-9)
          << "pixel " << i << ", " << j << ", " << channels << " channels";
      }
    }
    // Half way between two pixel centres: their mean (bilinear).
    const Vec3 mid = PanoramaColor(p, PanoramaDirection(p.width, p.height, 4.5, 6.0));
    EXPECT_LT((mid - 0.5 * (TexelColor(p, 4, 6) + TexelColor(p, 5, 6))).norm(), 1e-9);
    const Vec3 quad = PanoramaColor(p, PanoramaDirection(p.width, p.height, 4.5, 6.5));
    const Vec3 mean = 0.25 *
      (TexelColor(p, 4, 6) + TexelColor(p, 5, 6) + TexelColor(p, 4, 7) + TexelColor(p, 5, 7));
    EXPECT_LT((quad - mean).norm(), 1e-9);
  }
  // An invalid panorama gives black.
  EquirectangularPanorama bad;
  EXPECT_FALSE(bad.IsValid());
  EXPECT_EQ(PanoramaColor(bad, Vec3(1, 0, 0)), Vec3::Zero());
}

TEST(EnvironmentPanorama, WrapsInLongitudeAndClampsInLatitude)
{
  const EquirectangularPanorama p = PatternPanorama(24, 12, 3);
  const int w = p.width;
  // On the seam (-x): the mean of the first and last columns.
  const double lat = PanoramaDirection(w, p.height, 0, 5).z();
  const Vec3 seam = PanoramaColor(p, Vec3(-std::sqrt(1 - lat * lat), 0.0, lat));
  EXPECT_LT((seam - 0.5 * (TexelColor(p, 0, 5) + TexelColor(p, w - 1, 5))).norm(), 1e-9);
  // Continuous across the seam and everywhere else: a sweep in small steps changes the colour by
  // at most (step in pixels) x (largest difference of neighbours = 1).
  for (double latitude : { -1.2, -0.3, 0.0, 0.4, 1.5 })
  {
    const int n = 20000;
    const double step = 2.0 * kPi / n;
    Vec3 previous = PanoramaColor(p, FromLonLat(kPi - 100 * step, latitude));
    double largest = 0.0;
    for (int k = 1; k <= n; ++k)
    {
      const Vec3 c = PanoramaColor(p, FromLonLat(kPi - 100 * step + k * step, latitude));
      largest = std::max(largest, (c - previous).cwiseAbs().maxCoeff());
      previous = c;
    }
    EXPECT_LT(largest, step * w / (2 * kPi) + 1e-9) << "latitude " << latitude;
  }
  // Just either side of the seam: nearly the same colour.
  const Vec3 left = PanoramaColor(p, FromLonLat(kPi - 1e-7, 0.1));
  const Vec3 right = PanoramaColor(p, FromLonLat(-kPi + 1e-7, 0.1));
  EXPECT_LT((left - right).cwiseAbs().maxCoeff(), 1e-5);
  // Above the first row's centres: that row (interpolated along it only); the same at the bottom.
  const double top = kPi * (0.5 - 0.5 / p.height); // latitude of row 0's centres
  const double lon3 = 2.0 * kPi * (0.5 - 3.5 / w); // longitude of column 3's centres
  for (double latitude : { top + 1e-3, 0.5 * (top + 0.5 * kPi), 0.5 * kPi - 1e-9 })
  {
    const Vec3 c = PanoramaColor(p, FromLonLat(lon3, latitude));
    EXPECT_LT((c - TexelColor(p, 3, 0)).norm(), 1e-9) << latitude;
    const Vec3 b = PanoramaColor(p, FromLonLat(lon3, -latitude));
    EXPECT_LT((b - TexelColor(p, 3, p.height - 1)).norm(), 1e-9) << -latitude;
  }
  // The poles themselves look up longitude 0: between the two middle columns.
  const Vec3 zenith = PanoramaColor(p, Vec3(0, 0, 1));
  EXPECT_LT((zenith - 0.5 * (TexelColor(p, w / 2 - 1, 0) + TexelColor(p, w / 2, 0))).norm(), 1e-9);
  const Vec3 nadir = PanoramaColor(p, Vec3(0, 0, -1));
  EXPECT_LT(
    (nadir - 0.5 * (TexelColor(p, w / 2 - 1, p.height - 1) + TexelColor(p, w / 2, p.height - 1)))
      .norm(),
    1e-9);
}

TEST(EnvironmentPanorama, RotationTurnsAboutZ)
{
  const EquirectangularPanorama p = PatternPanorama(36, 18, 3);
  PanoramaPlacement placement;
  placement.rotation = 30.0;
  // The panorama's +x (longitude 0) now shows at world longitude +30 degrees.
  for (double lat : { -0.7, 0.0, 0.3 })
  {
    for (double lon : { -2.5, 0.0, 1.0, 3.0 })
    {
      const Vec3 world = FromLonLat(lon + 30.0 * kPi / 180.0, lat);
      EXPECT_LT(
        (PlacedPanoramaColor(p, placement, world) - PanoramaColor(p, FromLonLat(lon, lat))).norm(),
        1e-9);
    }
  }
}

TEST(EnvironmentPanorama, RoomPanoramaAgreesWithRoomColor)
{
  RoomEnvironment room;
  const Vec3 viewpoint(0.3, -0.2, 1.1);
  const EquirectangularPanorama p = MakeRoomPanorama(room, viewpoint, 255);
  EXPECT_EQ(p.width, 256);
  EXPECT_EQ(p.height, 128);
  EXPECT_EQ(p.channels, 3);
  ASSERT_TRUE(p.IsValid());
  // Pixel centres: RoomColor of their direction, to 8 bits.
  for (int j = 0; j < p.height; j += 3)
  {
    for (int i = 0; i < p.width; i += 5)
    {
      const Vec3 d = PanoramaDirection(p.width, p.height, i, j);
      const Vec3 expected = RoomColor(room, viewpoint, d);
      EXPECT_LT((PanoramaColor(p, d) - expected).cwiseAbs().maxCoeff(), 0.5 / 255 + 1e-9)
        << "pixel " << i << ", " << j;
    }
  }
  // Rows rendered in pieces into an RGBA panorama: the same pixels, alpha 255.
  EquirectangularPanorama rgba;
  rgba.width = p.width;
  rgba.height = p.height;
  rgba.channels = 4;
  rgba.pixels.assign(static_cast<std::size_t>(p.width) * p.height * 4, 0);
  RenderRoomPanoramaRows(room, viewpoint, rgba, 0, 50);
  RenderRoomPanoramaRows(room, viewpoint, rgba, 50, 1000);
  for (int j = 0; j < p.height; ++j)
  {
    for (int i = 0; i < p.width; ++i)
    {
      ASSERT_TRUE(std::equal(p.texel(i, j), p.texel(i, j) + 3, rgba.texel(i, j)));
      ASSERT_EQ(rgba.texel(i, j)[3], 255);
    }
  }

  // Random directions: the bilinear lookup lies between the room's colours at the four nearest
  // pixel centres (channel by channel, to 8 bits), and equals RoomColor away from the edges of
  // the room's pattern (grid lines, checker squares).
  const EquirectangularPanorama fine = MakeRoomPanorama(room, viewpoint, 1024);
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  int close = 0;
  const int n = 4000;
  for (int k = 0; k < n; ++k)
  {
    const Vec3 d = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Vec3 c = PanoramaColor(fine, d);
    const Vec2 px = PanoramaPixel(fine.width, fine.height, d);
    Vec3 lo = Vec3::Constant(1.0), hi = Vec3::Zero();
    for (double x : { std::floor(px.x()), std::floor(px.x()) + 1.0 })
    {
      for (double y : { std::floor(px.y()), std::floor(px.y()) + 1.0 })
      {
        const Vec3 corner = RoomColor(room, viewpoint,
          PanoramaDirection(
            fine.width, fine.height, x, std::min(fine.height - 1.0, std::max(0.0, y))));
        lo = lo.cwiseMin(corner);
        hi = hi.cwiseMax(corner);
      }
    }
    EXPECT_TRUE(
      ((c.array() >= lo.array() - 0.5 / 255 - 1e-9) && (c.array() <= hi.array() + 0.5 / 255 + 1e-9))
        .all())
      << "direction " << d.transpose();
    close += (c - RoomColor(room, viewpoint, d)).cwiseAbs().maxCoeff() < 2.0 / 255;
  }
  EXPECT_GT(close, 0.85 * n);
}

TEST(EnvironmentPanorama, FrameReflectsThePanoramaAndShowsTheBackdrop)
{
  const Projector projector(SmallCamera());
  ASSERT_TRUE(projector.IsValid()) << projector.GetError();
  const int w = projector.GetModel().intrinsics.width;
  const int h = projector.GetModel().intrinsics.height;
  const EquirectangularPanorama pano = MakeRoomPanorama(RoomEnvironment(), Vec3(0, 0, 1), 512);
  PanoramaPlacement placement;
  placement.rotation = 30.0;
  placement.backdrop = Vec3(0.2, 0.4, 0.6);
  const double a = -placement.rotation * kPi / 180.0;
  auto expectedColor = [&](const Vec3& d) {
    // Rotated by -30 degrees about z, computed here rather than by PlacedPanoramaColor.
    const Vec3 r(
      std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y(), d.z());
    return PanoramaColor(pano, r);
  };

  for (int samples : { 1, 2 })
  {
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w) * h * 4, 0);
    ImageView view;
    view.data = rgba.data();
    view.width = w;
    view.height = h;
    view.rowStride = 4 * w;
    // In two halves, as threads would.
    RenderPanoramaRows(projector, pano, placement, samples, view, 0, h / 2);
    RenderPanoramaRows(projector, pano, placement, samples, view, h / 2, h);
    int mirror = 0, backdrop = 0, mixed = 0;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        // The sub-samples of this pixel, back-projected here.
        Vec3 sum = Vec3::Zero();
        int hits = 0;
        for (int sy = 0; sy < samples; ++sy)
        {
          for (int sx = 0; sx < samples; ++sx)
          {
            const Vec2 px(x + (sx + 0.5) / samples - 0.5, y + (sy + 0.5) / samples - 0.5);
            const BackProjectedRay ray = projector.BackProjectWorld(px);
            if (HasProjection(ray.status))
            {
              ++hits;
              sum += expectedColor(ray.direction);
            }
            else
            {
              sum += placement.backdrop;
            }
          }
        }
        const std::uint8_t* out = view.pixel(x, y);
        ASSERT_EQ(out[3], 255);
        if (hits == 0)
        {
          ++backdrop;
          ASSERT_EQ(out[0], 51);
          ASSERT_EQ(out[1], 102);
          ASSERT_EQ(out[2], 153);
          continue;
        }
        hits == samples* samples ? ++mirror : ++mixed;
        const Vec3 expected = sum / (samples * samples);
        for (int k = 0; k < 3; ++k)
        {
          ASSERT_LE(std::abs(int(out[k]) - int(Byte(expected[k]))), 1)
            << "pixel " << x << ", " << y << " channel " << k << " samples " << samples;
        }
      }
    }
    // The mirror's image is a disc of about 52 pixels radius in the middle of the image.
    EXPECT_GT(mirror, 7000);
    EXPECT_LT(mirror, 9500);
    EXPECT_GT(backdrop, 8000);
    if (samples == 1)
    {
      EXPECT_EQ(mixed, 0);
    }
    else
    {
      EXPECT_GT(mixed, 100); // the disc's rim averages mirror and backdrop
    }
    // The middle of the disc reflects what is behind the camera (world -y).
    const BackProjectedRay centre = projector.BackProjectWorld(Vec2(79.5, 59.5));
    ASSERT_TRUE(HasProjection(centre.status));
    EXPECT_LT(centre.direction.y(), -0.99);
  }
}

TEST(EnvironmentScene, PanoramaBackgroundKeys)
{
  const std::string camera = R"(camera: { image_width: 320, image_height: 240,
  camera_matrix: [300, 0, 159.5, 0, 300, 119.5, 0, 0, 1],
  mirror: { center: [0, 0, 0.2], radius: 0.05 } }
)";
  SceneDescription s;
  std::string error;
  // The panorama must exist to be found (it is read only when rendering).
  const std::string folder = ::testing::TempDir() + "/catar_panorama_keys";
  ASSERT_EQ(std::system(("mkdir -p '" + folder + "/env'").c_str()), 0);
  std::ofstream(folder + "/env/place.jpg") << "not read here";
  ASSERT_TRUE(ParseScene("%YAML:1.0\n---\n" + camera +
      "background: { type: panorama, file: env/place.jpg, rotation: -45, "
      "backdrop: [0.1, 0.2, 0.3], samples: 3 }\n",
    folder, s, error))
    << error;
  EXPECT_EQ(s.background.type, "panorama");
  EXPECT_EQ(s.background.panorama, folder + "/env/place.jpg");
  EXPECT_DOUBLE_EQ(s.background.rotation, -45.0);
  EXPECT_EQ(s.background.backdrop, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(s.background.samples, 3);

  // Defaults: no file (the generated room panorama), no rotation, mid grey.
  SceneDescription d;
  ASSERT_TRUE(
    ParseScene("%YAML:1.0\n---\n" + camera + "background: { type: panorama }\n", "", d, error))
    << error;
  EXPECT_TRUE(d.background.panorama.empty());
  EXPECT_EQ(d.background.rotation, 0.0);
  EXPECT_EQ(d.background.backdrop, Vec3(0.5, 0.5, 0.5));

  const std::pair<std::string, std::string> cases[] = {
    { "background: { type: panorama, rotation: [1, 2] }", "rotation" },
    { "background: { type: panorama, rotation: .nan }", "rotation" },
    { "background: { type: panorama, backdrop: [2, 0, 0] }", "backdrop" },
    { "background: { type: panorama, backdrop: [0, 0] }", "backdrop" },
    { "background: { type: panorama, file: [1, 2] }", "file" },
    { "background: { type: panoramic }", "panorama" },
  };
  for (const auto& c : cases)
  {
    SceneDescription bad;
    EXPECT_FALSE(ParseScene("%YAML:1.0\n---\n" + camera + c.first + "\n", "", bad, error))
      << c.first;
    EXPECT_NE(error.find(c.second), std::string::npos)
      << "'" << error << "' lacks '" << c.second << "'";
  }
}
