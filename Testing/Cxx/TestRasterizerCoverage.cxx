// CPU triangle rasteriser: coverage against an exact brute-force reference (top-left rule on the
// 1/256 grid), watertightness of shared edges and vertices, statuses, the guard band, strides
// and clipping (RasterizerTestSupport.h holds the reference).
#include "RasterizerTestSupport.h"

using namespace raster_test;

namespace
{
// ---------------------------------------------------------------------------------------------
// Coverage.

TEST(Rasterizer, RandomGridTrianglesMatchBruteForce)
{
  std::mt19937 rng(12345);
  const int w = 48, h = 40;
  Image img(w, h);
  int totalBad = 0, drawn = 0, degenerate = 0, empty = 0;
  std::string firstBad;
  for (int n = 0; n < 6000; ++n)
  {
    GridPt t[3];
    RandomTriangle(rng, w, h, t);
    img.fill(0);
    const RasterResult res = rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2]));
    std::string bad;
    const auto cmp = CompareCoverage(img, t, &bad);
    if (cmp.first && firstBad.empty())
    {
      firstBad = bad;
    }
    totalBad += cmp.first;
    if (Orient(t[0], t[1], t[2]) == 0)
    {
      EXPECT_EQ(res, RasterResult::Degenerate);
      ++degenerate;
    }
    else if (cmp.second == 0)
    {
      EXPECT_EQ(res, RasterResult::Empty);
      ++empty;
    }
    else
    {
      EXPECT_EQ(res, RasterResult::Drawn);
      ++drawn;
    }
  }
  EXPECT_EQ(totalBad, 0) << firstBad;
  // The sample must actually exercise all the outcomes.
  EXPECT_GT(drawn, 3000);
  EXPECT_GT(empty, 50);
  EXPECT_GT(degenerate, 5);
}

TEST(Rasterizer, RandomOffGridTrianglesMatchBruteForceAfterSnapping)
{
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> ux(-10, 50), uy(-10, 40);
  const int w = 40, h = 30;
  Image img(w, h);
  int totalBad = 0;
  std::string firstBad;
  for (int n = 0; n < 2000; ++n)
  {
    RasterVertex v[3];
    GridPt t[3];
    for (int i = 0; i < 3; ++i)
    {
      v[i] = Vtx(ux(rng), uy(rng));
      t[i] = SnapRef(v[i].x, v[i].y);
    }
    img.fill(0);
    rasterizeTriangle(img.view(), v[0], v[1], v[2]);
    std::string bad;
    const int b = CompareCoverage(img, t, &bad).first;
    if (b && firstBad.empty())
    {
      firstBad = bad;
    }
    totalBad += b;
  }
  EXPECT_EQ(totalBad, 0) << firstBad;
}

// Known triangles with pixel centres on their edges, in all 6 vertex orders.
TEST(Rasterizer, TopLeftRuleOnKnownTriangles)
{
  const int w = 8, h = 8;
  Image img(w, h);
  // Legs on x = 1 (left edge) and y = 1 (top edge), hypotenuse x + y = 6 (a right edge).
  const RasterVertex a[3] = { Vtx(1, 1), Vtx(5, 1), Vtx(1, 5) };
  // Legs on x = 5 (right edge) and y = 5 (bottom edge), hypotenuse x + y = 6 (a left edge).
  const RasterVertex b[3] = { Vtx(5, 1), Vtx(5, 5), Vtx(1, 5) };
  const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
    { 2, 1, 0 } };
  for (const auto& p : perms)
  {
    img.fill(0);
    EXPECT_EQ(rasterizeTriangle(img.view(), a[p[0]], a[p[1]], a[p[2]]), RasterResult::Drawn);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool expected = x >= 1 && y >= 1 && x + y < 6;
        EXPECT_EQ(img.at(x, y)[3] != 0, expected) << "A, pixel " << x << "," << y;
      }
    }
    EXPECT_NE(img.at(1, 1)[3], 0) << "vertex where a top and a left edge meet";
    EXPECT_NE(img.at(3, 1)[3], 0) << "centre on a top edge";
    EXPECT_NE(img.at(1, 3)[3], 0) << "centre on a left edge";
    EXPECT_EQ(img.at(3, 3)[3], 0) << "centre on a right edge";
    EXPECT_EQ(CountNonZeroAlpha(img), 10);

    img.fill(0);
    EXPECT_EQ(rasterizeTriangle(img.view(), b[p[0]], b[p[1]], b[p[2]]), RasterResult::Drawn);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool expected = x < 5 && y < 5 && x + y >= 6;
        EXPECT_EQ(img.at(x, y)[3] != 0, expected) << "B, pixel " << x << "," << y;
      }
    }
    EXPECT_EQ(img.at(5, 3)[3], 0) << "centre on a right edge";
    EXPECT_EQ(img.at(3, 5)[3], 0) << "centre on a bottom edge";
    EXPECT_NE(img.at(3, 3)[3], 0) << "centre on a left (sloped) edge";
    EXPECT_EQ(CountNonZeroAlpha(img), 6);
  }
}

// A square split along either diagonal, in both windings: drawing both halves with a = 0.5 on a
// transparent image gives alpha 128 where drawn once and 192 where drawn twice.
TEST(Rasterizer, SquareSplitAlongDiagonalDrawsEachPixelOnce)
{
  const int w = 16, h = 16;
  Image img(w, h);
  // Corners on pixel centres: the diagonal passes through pixel centres.
  const RasterVertex c[4] = { Vtx(2, 2, 1, 1, 1, 0.5f), Vtx(12, 2, 1, 1, 1, 0.5f),
    Vtx(12, 12, 1, 1, 1, 0.5f), Vtx(2, 12, 1, 1, 1, 0.5f) };
  for (int diag = 0; diag < 2; ++diag)
  {
    for (int flip = 0; flip < 2; ++flip)
    {
      img.fill(0);
      const int i0 = diag, i1 = diag + 1, i2 = diag + 2, i3 = (diag + 3) % 4;
      if (flip)
      {
        rasterizeTriangle(img.view(), c[i0], c[i2], c[i1]);
        rasterizeTriangle(img.view(), c[i0], c[i2], c[i3]);
      }
      else
      {
        rasterizeTriangle(img.view(), c[i0], c[i1], c[i2]);
        rasterizeTriangle(img.view(), c[i2], c[i3], c[i0]);
      }
      for (int y = 0; y < h; ++y)
      {
        for (int x = 0; x < w; ++x)
        {
          // The square's top and left sides are drawn, its bottom and right sides are not.
          const bool inside = x >= 2 && x < 12 && y >= 2 && y < 12;
          EXPECT_EQ(static_cast<int>(img.at(x, y)[3]), inside ? 128 : 0)
            << "diag " << diag << " flip " << flip << " pixel " << x << "," << y;
        }
      }
    }
  }
}

// Fans of triangles around a shared vertex: every pixel centre strictly inside the fan's polygon
// is drawn exactly once (the shared vertex included), none is drawn twice, none outside.
TEST(Rasterizer, FanAroundSharedVertexDrawsEachPixelOnce)
{
  const int w = 48, h = 40;
  Image img(w, h);
  std::mt19937 rng(99);
  struct Fan
  {
    GridPt centre;
    std::vector<GridPt> ring; // convex, in angular order
  };
  std::vector<Fan> fans;
  const double pi = std::acos(-1.0);
  // Circles of points, centre on a pixel centre or not.
  for (int k = 0; k < 6; ++k)
  {
    Fan f;
    const double cx = (k % 2 == 0) ? 20.0 : 20.0 + 93.0 / 256.0;
    const double cy = (k % 2 == 0) ? 17.0 : 17.0 + 200.0 / 256.0;
    f.centre = SnapRef(cx, cy);
    const int n = 5 + 3 * k;
    const double phase = 0.37 * k;
    for (int i = 0; i < n; ++i)
    {
      const double ang = phase + 2 * pi * i / n;
      f.ring.push_back(SnapRef(cx + 14 * std::cos(ang), cy + 14 * std::sin(ang)));
    }
    fans.push_back(f);
  }
  // Spokes along the axes and diagonals, through many pixel centres.
  {
    Fan f;
    f.centre = SnapRef(20, 17);
    const int d[8][2] = { { 1, 0 }, { 1, 1 }, { 0, 1 }, { -1, 1 }, { -1, 0 }, { -1, -1 }, { 0, -1 },
      { 1, -1 } };
    for (const auto& o : d)
    {
      f.ring.push_back(SnapRef(20 + 10 * o[0], 17 + 10 * o[1]));
    }
    fans.push_back(f);
  }

  for (std::size_t fi = 0; fi < fans.size(); ++fi)
  {
    const Fan& f = fans[fi];
    std::vector<int> count(static_cast<std::size_t>(w * h), 0);
    const std::size_t n = f.ring.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      GridPt t[3] = { f.centre, f.ring[i], f.ring[(i + 1) % n] };
      if (rng() & 1)
      {
        std::swap(t[1], t[2]); // random winding
      }
      img.fill(0);
      EXPECT_EQ(
        rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2])), RasterResult::Drawn);
      for (int y = 0; y < h; ++y)
      {
        for (int x = 0; x < w; ++x)
        {
          count[static_cast<std::size_t>(y * w + x)] += img.at(x, y)[3] != 0 ? 1 : 0;
        }
      }
    }
    const std::int64_t sign = Orient(f.ring[0], f.ring[1], f.ring[2]) > 0 ? 1 : -1;
    int interior = 0;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const GridPt p{ 256 * static_cast<std::int64_t>(x), 256 * static_cast<std::int64_t>(y) };
        bool strictlyInside = true, outside = false;
        for (std::size_t i = 0; i < n; ++i)
        {
          const std::int64_t o = Orient(f.ring[i], f.ring[(i + 1) % n], p) * sign;
          strictlyInside = strictlyInside && o > 0;
          outside = outside || o < 0;
        }
        const int c = count[static_cast<std::size_t>(y * w + x)];
        if (strictlyInside)
        {
          ++interior;
          EXPECT_EQ(c, 1) << "fan " << fi << " pixel " << x << "," << y;
        }
        else if (outside)
        {
          EXPECT_EQ(c, 0) << "fan " << fi << " pixel " << x << "," << y;
        }
        else
        {
          EXPECT_LE(c, 1) << "fan " << fi << " pixel " << x << "," << y;
        }
      }
    }
    EXPECT_GT(interior, 100);
  }
}

// A jittered triangle mesh that covers more than the image: every pixel drawn exactly once.
TEST(Rasterizer, JitteredMeshCoversImageExactlyOnce)
{
  const int w = 50, h = 40;
  const int nx = 10, ny = 8; // nodes at -6 + 7 i (i < nx) and -6 + 7 j (j < ny)
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 4; ++trial)
  {
    std::vector<GridPt> node(static_cast<std::size_t>(nx * ny));
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        // Jitter up to 1.25 px in each direction (keeps every cell convex); a quarter of the
        // nodes stay on pixel centres so that many edges pass through pixel centres.
        const int jitter = (rng() % 4 == 0) ? 0 : 320;
        std::uniform_int_distribution<int> u(-jitter, jitter);
        node[static_cast<std::size_t>(j * nx + i)] =
          GridPt{ (-6 + 7 * i) * 256 + u(rng), (-6 + 7 * j) * 256 + u(rng) };
      }
    }
    std::vector<int> count(static_cast<std::size_t>(w * h), 0);
    Image img(w, h);
    for (int j = 0; j + 1 < ny; ++j)
    {
      for (int i = 0; i + 1 < nx; ++i)
      {
        const GridPt& p00 = node[static_cast<std::size_t>(j * nx + i)];
        const GridPt& p10 = node[static_cast<std::size_t>(j * nx + i + 1)];
        const GridPt& p01 = node[static_cast<std::size_t>((j + 1) * nx + i)];
        const GridPt& p11 = node[static_cast<std::size_t>((j + 1) * nx + i + 1)];
        GridPt tris[2][3];
        if (rng() & 1)
        {
          tris[0][0] = p00, tris[0][1] = p10, tris[0][2] = p11;
          tris[1][0] = p00, tris[1][1] = p11, tris[1][2] = p01;
        }
        else
        {
          tris[0][0] = p00, tris[0][1] = p10, tris[0][2] = p01;
          tris[1][0] = p10, tris[1][1] = p11, tris[1][2] = p01;
        }
        for (auto& t : tris)
        {
          if (rng() & 1)
          {
            std::swap(t[0], t[2]);
          }
          img.fill(0);
          rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2]));
          for (int y = 0; y < h; ++y)
          {
            for (int x = 0; x < w; ++x)
            {
              count[static_cast<std::size_t>(y * w + x)] += img.at(x, y)[3] != 0 ? 1 : 0;
            }
          }
        }
      }
    }
    int wrong = 0;
    for (int c : count)
    {
      wrong += c != 1 ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0) << "trial " << trial;
  }
}

// ---------------------------------------------------------------------------------------------
// Statuses.

TEST(Rasterizer, DegenerateTrianglesDrawNothing)
{
  Image img(16, 16);
  img.pattern(1);
  const Image before = img;
  // Collinear.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(5, 5), Vtx(10, 10)), RasterResult::Degenerate);
  // Collinear along a row of pixel centres.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(1, 3), Vtx(9, 3), Vtx(4, 3)), RasterResult::Degenerate);
  // Repeated vertex.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(2, 2), Vtx(2, 2), Vtx(10, 4)), RasterResult::Degenerate);
  // Non-degenerate in doubles, but two vertices snap to the same 1/256 grid point.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(5, 5), Vtx(10, 10), Vtx(5.001, 5)), RasterResult::Degenerate);
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, EmptyTrianglesDrawNothing)
{
  Image img(16, 16);
  img.pattern(2);
  const Image before = img;
  // Between pixel centres.
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(3.1, 3.1), Vtx(3.9, 3.1), Vtx(3.1, 3.9)),
    RasterResult::Empty);
  // Only touches a centre with its right edge: (4, 4) lies on x + y = 8, a right edge.
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(3.5, 3.5), Vtx(4.5, 3.5), Vtx(3.5, 4.5)),
    RasterResult::Empty);
  // Entirely outside the image.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(-20, -5), Vtx(-10, -5), Vtx(-15, 30)), RasterResult::Empty);
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(20, 20), Vtx(40, 20), Vtx(30, 40)), RasterResult::Empty);
  // Inside the image but outside the clip rectangle.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(6, 0), Vtx(0, 6), PixelRect{ 8, 8, 16, 16 }),
    RasterResult::Empty);
  // Empty clip rectangle.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(16, 0), Vtx(0, 16), PixelRect{ 4, 4, 4, 9 }),
    RasterResult::Empty);
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, NonFiniteInputIsRejected)
{
  Image img(16, 16);
  img.pattern(3);
  const Image before = img;
  Depth depth(16, 16);
  const std::vector<float> depthBefore = depth.buf;
  const double values[3] = { std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  for (double bad : values)
  {
    for (int vi = 0; vi < 3; ++vi)
    {
      for (int field = 0; field < 7; ++field)
      {
        RasterVertex v[3] = { Vtx(0, 0), Vtx(15, 0), Vtx(0, 15) };
        RasterVertex& t = v[vi];
        switch (field)
        {
          case 0:
            t.x = bad;
            break;
          case 1:
            t.y = bad;
            break;
          case 2:
            t.r = static_cast<float>(bad);
            break;
          case 3:
            t.g = static_cast<float>(bad);
            break;
          case 4:
            t.b = static_cast<float>(bad);
            break;
          case 5:
            t.a = static_cast<float>(bad);
            break;
          default:
            t.depth = static_cast<float>(bad);
            break;
        }
        const DepthView dv = depth.view();
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2]), RasterResult::InvalidInput)
          << "vertex " << vi << " field " << field;
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2], &dv), RasterResult::InvalidInput)
          << "vertex " << vi << " field " << field;
      }
    }
  }
  // Invalid buffers.
  ImageView none;
  EXPECT_EQ(rasterizeTriangle(none, Vtx(0, 0), Vtx(15, 0), Vtx(0, 15)), RasterResult::InvalidInput);
  Depth small(8, 16);
  const DepthView sv = small.view();
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(15, 0), Vtx(0, 15), &sv),
    RasterResult::InvalidInput);
  EXPECT_EQ(img.buf, before.buf);
  EXPECT_EQ(depth.buf, depthBefore);
}

TEST(Rasterizer, GuardBand)
{
  const double g = 1 << 20;
  const int w = 64, h = 48;
  Image img(w, h);
  img.pattern(4);
  const Image before = img;
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(g + 1, 0), Vtx(0, 10)),
    RasterResult::OutsideGuardBand);
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(10, 0), Vtx(0, -g - 0.5)),
    RasterResult::OutsideGuardBand);
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(-g - 1e-3, 0), Vtx(10, 0), Vtx(0, 10)),
    RasterResult::OutsideGuardBand);
  EXPECT_EQ(img.buf, before.buf);

  // Vertices exactly on the guard band are accepted and are exact: a huge triangle that covers
  // the image, and long thin slivers crossing it.
  const GridPt tris[4][3] = {
    { SnapRef(-g, -g), SnapRef(g, -g), SnapRef(0, g) },
    { SnapRef(-g, 10.3), SnapRef(g, 12.7), SnapRef(-g, 20.1) },
    { SnapRef(-g, 21), SnapRef(g, 25), SnapRef(g, 27) },
    { SnapRef(17, -g), SnapRef(37.5, g), SnapRef(16.25, g) },
  };
  for (const auto& t : tris)
  {
    img.fill(0);
    EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2])), RasterResult::Drawn);
    std::string bad;
    const auto cmp = CompareCoverage(img, t, &bad);
    EXPECT_EQ(cmp.first, 0) << bad;
    EXPECT_GT(cmp.second, 0);
  }
  img.fill(0);
  rasterizeTriangle(img.view(), Vtx(tris[0][0]), Vtx(tris[0][1]), Vtx(tris[0][2]));
  EXPECT_EQ(CountNonZeroAlpha(img), w * h);
}

// ---------------------------------------------------------------------------------------------
// Addressing and clipping.

TEST(Rasterizer, NegativeRowStrideDrawsTheSamePictureFlipped)
{
  const int w = 37, h = 29;
  const auto scene = RandomScene(5, w, h, 300);
  for (int useDepth = 0; useDepth < 2; ++useDepth)
  {
    Image top(w, h), bottom(w, h);
    top.pattern(6);
    // bottom holds the same logical picture stored bottom-up.
    for (int y = 0; y < h; ++y)
    {
      std::copy_n(top.buf.begin() + 4 * w * y, 4 * w, bottom.buf.begin() + 4 * w * (h - 1 - y));
    }
    Depth dTop(w, h, 0.7f), dBottom(w, h, 0.7f);
    const DepthView dvTop = dTop.view(), dvBottom = dBottom.flippedView();
    int drawn = 0;
    for (const auto& t : scene)
    {
      const RasterResult a =
        rasterizeTriangle(top.view(), t.v[0], t.v[1], t.v[2], useDepth ? &dvTop : nullptr);
      const RasterResult b = rasterizeTriangle(
        bottom.flippedView(), t.v[0], t.v[1], t.v[2], useDepth ? &dvBottom : nullptr);
      EXPECT_EQ(a, b);
      drawn += a == RasterResult::Drawn ? 1 : 0;
    }
    EXPECT_GT(drawn, 200);
    for (int y = 0; y < h; ++y)
    {
      EXPECT_TRUE(std::equal(top.buf.begin() + 4 * w * y, top.buf.begin() + 4 * w * (y + 1),
        bottom.buf.begin() + 4 * w * (h - 1 - y)))
        << "row " << y;
      EXPECT_TRUE(std::equal(dTop.buf.begin() + w * y, dTop.buf.begin() + w * (y + 1),
        dBottom.buf.begin() + w * (h - 1 - y)))
        << "depth row " << y;
    }
  }
  // And the flipped view really is bottom-up: pixel (0, 0) is in the last memory row.
  Image img(4, 3);
  rasterizeTriangle(img.flippedView(), Vtx(-0.5, -0.5), Vtx(1, -0.5), Vtx(-0.5, 1));
  EXPECT_EQ(img.buf[4 * 4 * 2 + 3], 255);
  EXPECT_EQ(CountNonZeroAlpha(img), 1);
}

TEST(Rasterizer, ClipTilesEqualTheWholeImage)
{
  const int w = 61, h = 47;
  const auto scene = RandomScene(7, w, h, 400);
  Image whole(w, h), tiled(w, h);
  whole.pattern(8);
  tiled.buf = whole.buf;
  Depth dWhole(w, h, 0.8f), dTiled(w, h, 0.8f);
  const DepthView dvWhole = dWhole.view(), dvTiled = dTiled.view();
  std::vector<RasterResult> wholeResult;
  for (const auto& t : scene)
  {
    wholeResult.push_back(rasterizeTriangle(whole.view(), t.v[0], t.v[1], t.v[2], &dvWhole));
  }
  const int tw = 16, th = 12; // uneven last tiles
  std::vector<bool> anyDrawn(scene.size(), false);
  for (int ty = 0; ty < h; ty += th)
  {
    for (int tx = 0; tx < w; tx += tw)
    {
      const PixelRect clip{ tx, ty, std::min(tx + tw, w), std::min(ty + th, h) };
      for (std::size_t i = 0; i < scene.size(); ++i)
      {
        const auto& t = scene[i];
        const RasterResult r =
          rasterizeTriangle(tiled.view(), t.v[0], t.v[1], t.v[2], clip, &dvTiled);
        anyDrawn[i] = anyDrawn[i] || r == RasterResult::Drawn;
      }
    }
  }
  EXPECT_EQ(whole.buf, tiled.buf);
  EXPECT_EQ(dWhole.buf, dTiled.buf);
  for (std::size_t i = 0; i < scene.size(); ++i)
  {
    EXPECT_EQ(wholeResult[i] == RasterResult::Drawn, anyDrawn[i]) << "triangle " << i;
  }

  // A clip rectangle larger than the image is the whole image; pixels outside a clip rectangle
  // are untouched and pixels inside equal the unclipped drawing.
  const RasterVertex a = Vtx(-3.3, 2.2, 0.9f, 0.2f, 0.1f, 0.6f);
  const RasterVertex b = Vtx(70.1, 10.4, 0.1f, 0.8f, 0.3f, 1.0f);
  const RasterVertex c = Vtx(20.7, 52.9, 0.4f, 0.4f, 0.9f, 0.8f);
  Image ref(w, h), big(w, h), part(w, h);
  ref.pattern(9);
  big.buf = ref.buf;
  part.buf = ref.buf;
  const Image background = ref;
  rasterizeTriangle(ref.view(), a, b, c);
  EXPECT_EQ(rasterizeTriangle(big.view(), a, b, c, PixelRect{ -100, -50, 1000, 2000 }),
    RasterResult::Drawn);
  EXPECT_EQ(big.buf, ref.buf);
  const PixelRect clip{ 13, 9, 40, 31 };
  EXPECT_EQ(rasterizeTriangle(part.view(), a, b, c, clip), RasterResult::Drawn);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool in = x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1;
      const Image& expected = in ? ref : background;
      EXPECT_TRUE(std::equal(part.at(x, y), part.at(x, y) + 4, expected.at(x, y)))
        << "pixel " << x << "," << y;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Edge samples (anti-aliasing).

// Coverage of the samples of every pixel: exactly the pixel centres a triangle covers on an image
// S times larger, the vertices moved to that image's coordinates (S (c + 0.5) - 0.5).
TEST(Rasterizer, EdgeSamplesAreTheCentresOfALargerImage)
{
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> px(-3.0, 27.0), py(-3.0, 23.0);
  const int w = 24, h = 20;
  long mismatches = 0, covered = 0;
  for (int samples = 2; samples <= kMaxEdgeSamples; ++samples)
  {
    for (int n = 0; n < 150; ++n)
    {
      SnappedTriangle t;
      for (int k = 0; k < 3; ++k)
      {
        t.x[k] = snapToGrid(px(rng));
        t.y[k] = snapToGrid(py(rng));
        std::fill(t.rgba[k], t.rgba[k] + 4, 1.0f);
      }
      // The larger image, drawn from vertices given in its own pixel coordinates.
      Image big(samples * w, samples * h);
      RasterVertex v[3];
      for (int k = 0; k < 3; ++k)
      {
        v[k].x = samples * (t.x[k] / 256.0 + 0.5) - 0.5;
        v[k].y = samples * (t.y[k] / 256.0 + 0.5) - 0.5;
      }
      rasterizeTriangle(big.view(), v[0], v[1], v[2]);
      for (int y = 0; y < h; ++y)
      {
        for (int x = 0; x < w; ++x)
        {
          Image block(samples, samples);
          RasterResult result;
          ASSERT_TRUE(rasterizeSamples(block.view(), t, x, y, samples, nullptr, nullptr, result));
          bool reachable = false;
          const std::uint32_t mask = sampleCoverage(t, x, y, samples, reachable);
          ASSERT_TRUE(reachable);
          for (int j = 0; j < samples; ++j)
          {
            for (int i = 0; i < samples; ++i)
            {
              const bool a = block.at(i, j)[3] != 0;
              const bool b = big.at(samples * x + i, samples * y + j)[3] != 0;
              const bool m = (mask >> (i + samples * j)) & 1u;
              mismatches += (a != b) + (m != b);
              covered += a;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(covered, 10000);
  EXPECT_EQ(mismatches, 0);
}

// A straight edge through a pixel: the samples right of it, counted by hand.
TEST(Rasterizer, EdgeSamplesRightOfAnEdge)
{
  for (int samples = 2; samples <= kMaxEdgeSamples; ++samples)
  {
    for (const double e : { -0.45, -0.2, 0.05, 0.3, 0.45 })
    {
      // A large triangle covering x >= 10 + e over pixel (10, 5)'s rows.
      SnappedTriangle t;
      const double xs[3] = { 10 + e, 10 + e, 60 }, ys[3] = { -40, 50, 5 };
      for (int k = 0; k < 3; ++k)
      {
        t.x[k] = snapToGrid(xs[k]);
        t.y[k] = snapToGrid(ys[k]);
        std::fill(t.rgba[k], t.rgba[k] + 4, 1.0f);
      }
      Image block(samples, samples);
      RasterResult result;
      ASSERT_TRUE(rasterizeSamples(block.view(), t, 10, 5, samples, nullptr, nullptr, result));
      int expected = 0, got = 0;
      for (int i = 0; i < samples; ++i)
      {
        expected += (i + 0.5) / samples - 0.5 > e ? samples : 0;
        for (int j = 0; j < samples; ++j)
        {
          got += block.at(i, j)[3] != 0;
        }
      }
      EXPECT_EQ(got, expected) << samples << " samples, edge at +" << e;
    }
  }
  // A vertex too far for the sample grid's fixed point: nothing drawn, false.
  SnappedTriangle far;
  const double xs[3] = { 0, 300000, 0 }, ys[3] = { 0, 0, 10 };
  for (int k = 0; k < 3; ++k)
  {
    far.x[k] = snapToGrid(xs[k]);
    far.y[k] = snapToGrid(ys[k]);
  }
  Image block(4, 4);
  RasterResult result;
  EXPECT_FALSE(rasterizeSamples(block.view(), far, 1, 1, 4, nullptr, nullptr, result));
  EXPECT_EQ(block.at(0, 0)[3], 0);
  bool reachable = true;
  EXPECT_EQ(sampleCoverage(far, 1, 1, 4, reachable), 0u);
  EXPECT_FALSE(reachable);
}

} // namespace
