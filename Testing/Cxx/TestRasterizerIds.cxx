// CPU triangle rasteriser: triangle-id buffers, snapping to the 1/256 grid, and the covered
// pixel bounds.
#include "RasterizerTestSupport.h"

using namespace raster_test;

namespace
{
// ---------------------------------------------------------------------------------------------
// Triangle ids.

namespace
{
struct Ids
{
  int w = 0;
  int h = 0;
  std::vector<RasterId> buf;

  Ids(int width, int height)
    : w(width)
    , h(height)
    , buf(static_cast<std::size_t>(width * height), -1)
  {
  }

  IdView view() { return IdView{ buf.data(), w, h, w }; }

  IdView flippedView()
  {
    return IdView{ buf.data() + static_cast<std::ptrdiff_t>(w) * (h - 1), w, h, -w };
  }

  RasterId at(int x, int y) const { return buf[static_cast<std::size_t>(y) * w + x]; }
};
} // namespace

TEST(Rasterizer, IdBufferHoldsTheLastTriangleDrawnInEachPixel)
{
  // Random triangles drawn in sequence, with ids: each pixel's id is that of the last triangle
  // (in draw order) that covers it per the reference coverage, -1 where none does; the image
  // drawn with ids is the image drawn without them. Gouraud, flat, transparent and textured
  // triangles, with and without a depth buffer.
  const int w = 48, h = 36;
  std::mt19937 rng(4711);
  Texels tex(5, 4, 4, 99);
  const TextureView tv = tex.view();
  for (int round = 0; round < 40; ++round)
  {
    const bool useDepth = round % 2 == 1;
    Image plain(w, h), withIds(w, h);
    Depth dPlain(w, h), dIds(w, h);
    const DepthView dvPlain = dPlain.view(), dvIds = dIds.view();
    Ids ids(w, h);
    const IdView iv = round % 4 < 2 ? ids.view() : ids.flippedView();
    std::vector<std::array<GridPt, 3>> tris;
    std::vector<float> depths;
    for (int k = 0; k < 6; ++k)
    {
      std::array<GridPt, 3> t;
      RandomTriangle(rng, w, h, t.data());
      const int kind = std::uniform_int_distribution<int>(0, 3)(rng);
      const float z = std::uniform_real_distribution<float>(0.1f, 1.0f)(rng);
      RasterVertex v[3];
      for (int i = 0; i < 3; ++i)
      {
        const float c = kind == 1 ? 0.5f : 0.2f * static_cast<float>(i + 1);
        v[i] = Vtx(t[i], c, 1 - c, 0.3f, kind == 2 ? 0.4f : 1.0f, z);
        v[i].u = 0.3f * static_cast<float>(i);
        v[i].v = 0.5f;
      }
      const TextureView* texture = kind == 3 ? &tv : nullptr;
      const RasterResult r1 =
        rasterizeTriangle(plain.view(), v[0], v[1], v[2], useDepth ? &dvPlain : nullptr, texture);
      const RasterResult r2 = rasterizeTriangle(
        withIds.view(), v[0], v[1], v[2], useDepth ? &dvIds : nullptr, texture, &iv, 1000 + k);
      EXPECT_EQ(r1, r2);
      tris.push_back(t);
      depths.push_back(z);
    }
    ASSERT_EQ(plain.buf, withIds.buf) << "round " << round;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        // Expected: the last covering triangle (painter), or the nearest one, the first drawn
        // among equal depths (strict depth test).
        RasterId expected = -1;
        float best = std::numeric_limits<float>::infinity();
        for (int k = 0; k < static_cast<int>(tris.size()); ++k)
        {
          if (!RefCovered(tris[k].data(), x, y))
          {
            continue;
          }
          if (!useDepth)
          {
            expected = 1000 + k;
          }
          else if (depths[k] < best)
          {
            best = depths[k];
            expected = 1000 + k;
          }
        }
        const int row = round % 4 < 2 ? y : h - 1 - y;
        ASSERT_EQ(ids.at(x, row), expected) << "round " << round << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(Rasterizer, InvalidIdBuffersAreRejected)
{
  Image img(10, 10);
  Ids small(9, 10);
  const IdView sv = small.view();
  IdView none = sv;
  none.data = nullptr;
  const RasterVertex a = Vtx(0, 0), b = Vtx(9, 0), c = Vtx(0, 9);
  EXPECT_EQ(
    rasterizeTriangle(img.view(), a, b, c, nullptr, nullptr, &sv, 1), RasterResult::InvalidInput);
  EXPECT_EQ(
    rasterizeTriangle(img.view(), a, b, c, nullptr, nullptr, &none, 1), RasterResult::InvalidInput);
  EXPECT_EQ(CountNonZeroAlpha(img), 0);
  for (RasterId v : small.buf)
  {
    EXPECT_EQ(v, -1);
  }
}

// ---------------------------------------------------------------------------------------------
// Batches: snapToGrid, rasterizeSnappedTriangle, coveredPixelBounds.

TEST(Rasterizer, SnapToGridIsTheDocumentedRounding)
{
  EXPECT_EQ(snapToGrid(0.0), 0);
  EXPECT_EQ(snapToGrid(1.0), 256);
  EXPECT_EQ(snapToGrid(-1.0), -256);
  EXPECT_EQ(snapToGrid(0.5 / 256), 1);   // exact half: up
  EXPECT_EQ(snapToGrid(-0.5 / 256), 0);  // exact half: up, towards +inf
  EXPECT_EQ(snapToGrid(-1.5 / 256), -1); // likewise
  EXPECT_EQ(snapToGrid(kRasterGuardBand), 1 << 28);
  EXPECT_EQ(snapToGrid(-kRasterGuardBand), -(1 << 28));
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-kRasterGuardBand, kRasterGuardBand), small(-3, 3);
  for (int i = 0; i < 100000; ++i)
  {
    const double c = i % 2 ? u(rng) : small(rng);
    ASSERT_EQ(snapToGrid(c), SnapRef(c, 0).x) << c;
  }
}

TEST(Rasterizer, SnappedTrianglesDrawExactlyAsRasterizeTriangle)
{
  // Random scenes drawn twice, once with rasterizeTriangle and once with the vertices snapped
  // first (snapToGrid) and rasterizeSnappedTriangle: same pixels, depths, ids and results, with
  // and without depth (written or read-only), ids and textures of each channel count, over the
  // whole image and tile by tile (uneven tiles and 32-row bands), with either row order.
  const int w = 61, h = 83;
  const std::vector<Texels> textures{ Texels(7, 5, 1, 1), Texels(6, 9, 3, 2), Texels(8, 8, 4, 3) };
  for (int round = 0; round < 48; ++round)
  {
    const bool useDepth = round % 2 == 1;
    const bool readOnly = round % 4 == 3;
    const bool useIds = round % 3 == 0;
    const int texture = round % 8 < 4 ? -1 : round % 3;
    const bool flipped = round % 5 == 0;
    const int tiling = round % 3; // whole image, uneven tiles, 32-row bands
    auto scene = RandomScene(100 + round, w, h, 150);
    std::mt19937 rng(round);
    std::uniform_real_distribution<float> ut(-0.3f, 1.3f);
    for (auto& t : scene)
    {
      for (auto& v : t.v)
      {
        v.u = ut(rng);
        v.v = ut(rng);
      }
    }
    const TextureView tv = texture >= 0 ? textures[texture].view(round % 2 == 0) : TextureView{};
    Image a(w, h), b(w, h);
    a.pattern(round);
    b.buf = a.buf;
    Depth da(w, h, 0.9f), db(w, h, 0.9f);
    DepthView dva = flipped ? da.flippedView() : da.view();
    DepthView dvb = flipped ? db.flippedView() : db.view();
    dva.write = dvb.write = !readOnly;
    Ids ia(w, h), ib(w, h);
    const IdView iva = ia.view(), ivb = ib.view();
    std::vector<PixelRect> tiles;
    if (tiling == 0)
    {
      tiles.push_back(PixelRect{ 0, 0, w, h });
    }
    for (int ty = 0; tiling != 0 && ty < h; ty += tiling == 1 ? 13 : 32)
    {
      for (int tx = 0; tx < w; tx += tiling == 1 ? 17 : w)
      {
        tiles.push_back(PixelRect{ tx, ty, std::min(w, tx + (tiling == 1 ? 17 : w)),
          std::min(h, ty + (tiling == 1 ? 13 : 32)) });
      }
    }
    for (std::size_t k = 0; k < scene.size(); ++k)
    {
      const RasterVertex* v = scene[k].v;
      SnappedTriangle s;
      for (int i = 0; i < 3; ++i)
      {
        s.x[i] = snapToGrid(v[i].x);
        s.y[i] = snapToGrid(v[i].y);
        s.rgba[i][0] = v[i].r;
        s.rgba[i][1] = v[i].g;
        s.rgba[i][2] = v[i].b;
        s.rgba[i][3] = v[i].a;
        s.depth[i] = v[i].depth;
        s.u[i] = v[i].u;
        s.v[i] = v[i].v;
      }
      for (const PixelRect& tile : tiles)
      {
        const RasterResult ra = rasterizeTriangle(flipped ? a.flippedView() : a.view(), v[0], v[1],
          v[2], tile, useDepth ? &dva : nullptr, texture >= 0 ? &tv : nullptr,
          useIds ? &iva : nullptr, static_cast<RasterId>(k));
        const RasterResult rb = rasterizeSnappedTriangle(flipped ? b.flippedView() : b.view(), s,
          tile, useDepth ? &dvb : nullptr, texture >= 0 ? &tv : nullptr, useIds ? &ivb : nullptr,
          static_cast<RasterId>(k));
        ASSERT_EQ(ra, rb) << "round " << round << " triangle " << k;
      }
    }
    ASSERT_EQ(a.buf, b.buf) << "round " << round;
    ASSERT_EQ(da.buf, db.buf) << "round " << round;
    ASSERT_EQ(ia.buf, ib.buf) << "round " << round;
  }
}

TEST(Rasterizer, CoveredPixelBoundsHoldEveryCoveredPixel)
{
  // Against the reference coverage: the bounds hold every covered centre of the clip rectangle;
  // they are exactly the covered centres' bounding box (empty when none) whenever the centres of
  // the clip rectangle inside the triangle's bounding box span at most 2 x 2 pixels, and empty
  // for a degenerate triangle. Tiny triangles (most of a detailed mesh seen in the mirror),
  // large ones, clip rectangles cutting them, either winding.
  const int w = 40, h = 30;
  std::mt19937 rng(2024);
  int exact = 0, exactEmpty = 0, coarse = 0;
  for (int n = 0; n < 30000; ++n)
  {
    GridPt t[3];
    if (n % 3 == 0)
    {
      RandomTriangle(rng, w, h, t);
    }
    else
    {
      // Within about a pixel of a random point, often on centres or half pixels.
      const double cx = std::uniform_real_distribution<double>(-2, w + 2)(rng);
      const double cy = std::uniform_real_distribution<double>(-2, h + 2)(rng);
      const double r = n % 3 == 1 ? 0.7 : 1.6;
      for (auto& p : t)
      {
        p.x = RandomCoord(rng, cx - r, cx + r);
        p.y = RandomCoord(rng, cy - r, cy + r);
      }
      if (n % 17 == 0)
      {
        t[2] = t[1]; // degenerate
      }
    }
    PixelRect clip{ 0, 0, w, h };
    if (n % 4 == 3)
    {
      clip = PixelRect{ std::uniform_int_distribution<int>(-3, w / 2)(rng),
        std::uniform_int_distribution<int>(-3, h / 2)(rng),
        std::uniform_int_distribution<int>(w / 2, w + 3)(rng),
        std::uniform_int_distribution<int>(h / 2, h + 3)(rng) };
    }
    const std::int32_t x[3] = { static_cast<std::int32_t>(t[0].x),
      static_cast<std::int32_t>(t[1].x), static_cast<std::int32_t>(t[2].x) };
    const std::int32_t y[3] = { static_cast<std::int32_t>(t[0].y),
      static_cast<std::int32_t>(t[1].y), static_cast<std::int32_t>(t[2].y) };
    const PixelRect got = coveredPixelBounds(x, y, clip);
    // The centres inside the triangle's bounding box and the clip rectangle.
    const auto floorDiv = [](std::int64_t a) {
      return static_cast<int>(std::floor(static_cast<double>(a) / 256.0));
    };
    const auto ceilDiv = [](std::int64_t a) {
      return static_cast<int>(std::ceil(static_cast<double>(a) / 256.0));
    };
    const int bx0 = std::max(clip.x0, ceilDiv(std::min({ t[0].x, t[1].x, t[2].x })));
    const int by0 = std::max(clip.y0, ceilDiv(std::min({ t[0].y, t[1].y, t[2].y })));
    const int bx1 = std::min(clip.x1 - 1, floorDiv(std::max({ t[0].x, t[1].x, t[2].x })));
    const int by1 = std::min(clip.y1 - 1, floorDiv(std::max({ t[0].y, t[1].y, t[2].y })));
    PixelRect ref{ bx1 + 1, by1 + 1, bx0, by0 }; // bounding box of the covered centres
    int covered = 0;
    for (int py = by0; py <= by1; ++py)
    {
      for (int px = bx0; px <= bx1; ++px)
      {
        if (RefCovered(t, px, py))
        {
          ++covered;
          ref.x0 = std::min(ref.x0, px);
          ref.y0 = std::min(ref.y0, py);
          ref.x1 = std::max(ref.x1, px + 1);
          ref.y1 = std::max(ref.y1, py + 1);
        }
      }
    }
    const bool none = covered == 0;
    const bool gotEmpty = got.x0 >= got.x1 || got.y0 >= got.y1;
    const bool small = bx1 - bx0 <= 1 && by1 - by0 <= 1;
    const bool degenerate = Orient(t[0], t[1], t[2]) == 0;
    std::ostringstream what;
    what << "triangle (" << t[0].x << "," << t[0].y << ") (" << t[1].x << "," << t[1].y << ") ("
         << t[2].x << "," << t[2].y << ") clip " << clip.x0 << "," << clip.y0 << " " << clip.x1
         << "," << clip.y1 << " got " << got.x0 << "," << got.y0 << " " << got.x1 << "," << got.y1;
    if (degenerate || (small && none))
    {
      ASSERT_TRUE(gotEmpty) << what.str();
      exactEmpty += none && !degenerate ? 1 : 0;
    }
    else if (small)
    {
      ASSERT_EQ(got.x0, ref.x0) << what.str();
      ASSERT_EQ(got.y0, ref.y0) << what.str();
      ASSERT_EQ(got.x1, ref.x1) << what.str();
      ASSERT_EQ(got.y1, ref.y1) << what.str();
      ++exact;
    }
    else if (!none)
    {
      ASSERT_FALSE(gotEmpty) << what.str();
      ASSERT_LE(got.x0, ref.x0) << what.str();
      ASSERT_LE(got.y0, ref.y0) << what.str();
      ASSERT_GE(got.x1, ref.x1) << what.str();
      ASSERT_GE(got.y1, ref.y1) << what.str();
      ++coarse;
    }
  }
  // The sample must exercise every case.
  EXPECT_GT(exact, 1000);
  EXPECT_GT(exactEmpty, 1000);
  EXPECT_GT(coarse, 1000);
}

} // namespace
