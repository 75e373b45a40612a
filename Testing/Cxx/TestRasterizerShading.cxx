// CPU triangle rasteriser: Gouraud interpolation, alpha compositing and the depth test (order
// independence, the crossing line of interpenetrating slanted triangles, read-only buffers).
#include "RasterizerTestSupport.h"

using namespace raster_test;

namespace
{
// ---------------------------------------------------------------------------------------------
// Shading and compositing.

TEST(Rasterizer, GouraudColourIsTheBarycentricInterpolation)
{
  const int w = 40, h = 32;
  Image img(w, h);
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> uc(-0.3f, 1.3f), ua(0.0f, 1.0f);
  PixelChecks checks;
  for (int n = 0; n < 300; ++n)
  {
    GridPt t[3];
    RandomTriangle(rng, w, h, t);
    if (Orient(t[0], t[1], t[2]) == 0)
    {
      continue;
    }
    float col[3][4];
    RasterVertex v[3];
    for (int i = 0; i < 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        col[i][c] = uc(rng);
      }
      col[i][3] = (n % 2 == 0) ? 1.0f : ua(rng);
      v[i] = Vtx(t[i], col[i][0], col[i][1], col[i][2], col[i][3]);
    }
    // On a transparent black target: out.rgb = 255 c a, out.a = 255 a.
    img.fill(0);
    rasterizeTriangle(img.view(), v[0], v[1], v[2]);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        if (!RefCovered(t, x, y))
        {
          continue;
        }
        long double l[3];
        RefBarycentric(t, x, y, l);
        long double value[4] = { 0, 0, 0, 0 };
        for (int c = 0; c < 4; ++c)
        {
          for (int i = 0; i < 3; ++i)
          {
            value[c] += l[i] * std::min(1.0L, std::max(0.0L, static_cast<long double>(col[i][c])));
          }
        }
        checks.Premultiplied(img, n, x, y, value);
      }
    }
  }
  EXPECT_GT(checks.checked, 10000);
  EXPECT_EQ(checks.bad, 0) << checks.firstBad;
}

TEST(Rasterizer, AlphaBlendingFormula)
{
  const int w = 24, h = 20;
  Image img(w, h);
  img.pattern(10);
  const Image before = img;
  const float src[4] = { 0.2f, 0.7f, 0.9f, 0.35f };
  // Covers the whole image.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(-50, -50, src[0], src[1], src[2], src[3]),
      Vtx(200, -50, src[0], src[1], src[2], src[3]), Vtx(-50, 200, src[0], src[1], src[2], src[3])),
    RasterResult::Drawn);
  const long double a = src[3];
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 4; ++c)
      {
        const long double s = c < 3 ? static_cast<long double>(src[c]) : 1.0L;
        const long double d = before.at(x, y)[c];
        const long double exact = 255.0L * s * a + d * (1.0L - a);
        EXPECT_TRUE(ByteMatches(exact, img.at(x, y)[c]))
          << "pixel " << x << "," << y << " channel " << c << " exact "
          << static_cast<double>(exact) << " got " << static_cast<int>(img.at(x, y)[c]);
      }
    }
  }

  // Gouraud alpha over an opaque background: out.a stays 255, rgb is the formula.
  Image bg(w, h, 255);
  bg.pattern(11);
  for (std::size_t i = 3; i < bg.buf.size(); i += 4)
  {
    bg.buf[i] = 255;
  }
  const Image bgBefore = bg;
  const GridPt t[3] = { SnapRef(0, 0), SnapRef(23, 2), SnapRef(5, 19) };
  const float al[3] = { 0.1f, 0.5f, 0.95f };
  rasterizeTriangle(bg.view(), Vtx(t[0], 1, 0, 0.5f, al[0]), Vtx(t[1], 1, 0, 0.5f, al[1]),
    Vtx(t[2], 1, 0, 0.5f, al[2]));
  int covered = 0;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      if (!RefCovered(t, x, y))
      {
        EXPECT_TRUE(std::equal(bg.at(x, y), bg.at(x, y) + 4, bgBefore.at(x, y)));
        continue;
      }
      ++covered;
      long double l[3];
      RefBarycentric(t, x, y, l);
      const long double alpha = l[0] * al[0] + l[1] * al[1] + l[2] * al[2];
      const long double s[3] = { 1.0L, 0.0L, 0.5L };
      for (int c = 0; c < 3; ++c)
      {
        const long double exact = 255 * s[c] * alpha + bgBefore.at(x, y)[c] * (1 - alpha);
        EXPECT_LE(std::fabs(exact - bg.at(x, y)[c]), 1.0L) << x << "," << y << " c" << c;
      }
      EXPECT_EQ(bg.at(x, y)[3], 255);
    }
  }
  EXPECT_GT(covered, 100);
}

TEST(Rasterizer, OpaqueOverwritesAndTransparentKeeps)
{
  const int w = 10, h = 10;
  Image img(w, h);
  img.pattern(12);
  const Image before = img;
  const float c[3] = { 0.2f, 0.4f, 0.6f };
  // Opaque flat colour: round(255 c) and alpha 255, whatever was there.
  rasterizeTriangle(img.view(), Vtx(-20, -20, c[0], c[1], c[2], 1),
    Vtx(40, -20, c[0], c[1], c[2], 1), Vtx(-20, 40, c[0], c[1], c[2], 1));
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(img.at(x, y)[k],
          static_cast<int>(std::floor(255.0L * static_cast<long double>(c[k]) + 0.5L)));
      }
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // Gouraud opaque: a colour gradient whose values at pixel centres are exact multiples of 1/255.
  img.pattern(13);
  // r = x / 255: red 0 on the left edge x = 0 (drawn: a left edge), 1 at x = 255.
  rasterizeTriangle(
    img.view(), Vtx(0, -20, 0, 0, 1, 1), Vtx(255, -20, 1, 0, 1, 1), Vtx(0, 40, 0, 0, 1, 1));
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], x) << x << "," << y;
      EXPECT_EQ(img.at(x, y)[1], 0);
      EXPECT_EQ(img.at(x, y)[2], 255);
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // Alpha 0 leaves the target unchanged.
  img = before;
  rasterizeTriangle(
    img.view(), Vtx(-20, -20, 1, 1, 1, 0), Vtx(40, -20, 1, 1, 1, 0), Vtx(-20, 40, 1, 1, 1, 0));
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, ColoursAreClamped)
{
  Image img(8, 8);
  img.pattern(14);
  // Flat: (1.5, -0.5, 0.25, 3.0) -> (1, 0, 0.25, 1) -> (255, 0, 64, 255).
  rasterizeTriangle(img.view(), Vtx(-20, -20, 1.5f, -0.5f, 0.25f, 3.0f),
    Vtx(40, -20, 1.5f, -0.5f, 0.25f, 3.0f), Vtx(-20, 40, 1.5f, -0.5f, 0.25f, 3.0f));
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 8; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], 255);
      EXPECT_EQ(img.at(x, y)[1], 0);
      EXPECT_EQ(img.at(x, y)[2], 64);
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // Gouraud: vertex colours are clamped before interpolation (red 2 -> 1 at every vertex, alpha
  // -1 -> 0 at every vertex: nothing changes).
  img.pattern(15);
  const Image before = img;
  rasterizeTriangle(
    img.view(), Vtx(-20, -20, 2, 0, 0, -1), Vtx(40, -20, 5, 1, 0, -2), Vtx(-20, 40, 3, 0, 1, -1));
  EXPECT_EQ(img.buf, before.buf);
  rasterizeTriangle(
    img.view(), Vtx(-20, -20, 2, 0, 0, 1), Vtx(40, -20, 5, 0, 0, 1), Vtx(-20, 40, 3, 0, 0, 1));
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 8; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], 255);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Depth.

TEST(Rasterizer, DepthTestKeepsTheNearerTriangleInAnyOrder)
{
  const int w = 40, h = 30;
  // A: constant depth 0.3, red; B: constant 0.6, blue.
  const GridPt ta[3] = { SnapRef(2, 3), SnapRef(30, 5), SnapRef(8, 27) };
  const GridPt tb[3] = { SnapRef(12.5, 1.25), SnapRef(38, 20), SnapRef(10, 29) };
  const RasterVertex a[3] = { Vtx(ta[0], 1, 0, 0, 1, 0.3f), Vtx(ta[1], 1, 0, 0, 1, 0.3f),
    Vtx(ta[2], 1, 0, 0, 1, 0.3f) };
  const RasterVertex b[3] = { Vtx(tb[0], 0, 0, 1, 1, 0.6f), Vtx(tb[1], 0, 0, 1, 1, 0.6f),
    Vtx(tb[2], 0, 0, 1, 1, 0.6f) };
  Image ab(w, h), ba(w, h);
  Depth dab(w, h), dba(w, h);
  const DepthView vab = dab.view(), vba = dba.view();
  rasterizeTriangle(ab.view(), a[0], a[1], a[2], &vab);
  rasterizeTriangle(ab.view(), b[0], b[1], b[2], &vab);
  rasterizeTriangle(ba.view(), b[0], b[1], b[2], &vba);
  rasterizeTriangle(ba.view(), a[0], a[1], a[2], &vba);
  EXPECT_EQ(ab.buf, ba.buf);
  EXPECT_EQ(dab.buf, dba.buf);
  int overlap = 0;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool inA = RefCovered(ta, x, y), inB = RefCovered(tb, x, y);
      overlap += inA && inB ? 1 : 0;
      const std::uint8_t* p = ab.at(x, y);
      if (inA)
      {
        EXPECT_TRUE(p[0] == 255 && p[2] == 0) << x << "," << y;
        EXPECT_FLOAT_EQ(dab.at(x, y), 0.3f);
      }
      else if (inB)
      {
        EXPECT_TRUE(p[0] == 0 && p[2] == 255) << x << "," << y;
        EXPECT_FLOAT_EQ(dab.at(x, y), 0.6f);
      }
      else
      {
        EXPECT_EQ(p[3], 0);
        EXPECT_EQ(dab.at(x, y), std::numeric_limits<float>::infinity());
      }
    }
  }
  EXPECT_GT(overlap, 50);
}

TEST(Rasterizer, DepthIsInterpolatedTestedStrictlyAndWritten)
{
  const int w = 40, h = 30;
  // A slopes from depth 0 (left) to 1 (right); B is flat at 0.5: they intersect near x = 20.
  const GridPt ta[3] = { SnapRef(-5, -5), SnapRef(45, -5), SnapRef(-5, 35) };
  const float za[3] = { 0.0f, 1.0f, 0.0f };
  const GridPt tb[3] = { SnapRef(-5, -5), SnapRef(45, 35), SnapRef(-5, 35) };
  for (int order = 0; order < 2; ++order)
  {
    Image img(w, h);
    Depth depth(w, h);
    const DepthView dv = depth.view();
    for (int k = 0; k < 2; ++k)
    {
      if ((k == 0) == (order == 0))
      {
        rasterizeTriangle(img.view(), Vtx(ta[0], 1, 0, 0, 1, za[0]), Vtx(ta[1], 1, 0, 0, 1, za[1]),
          Vtx(ta[2], 1, 0, 0, 1, za[2]), &dv);
      }
      else
      {
        rasterizeTriangle(img.view(), Vtx(tb[0], 0, 0, 1, 1, 0.5f), Vtx(tb[1], 0, 0, 1, 1, 0.5f),
          Vtx(tb[2], 0, 0, 1, 1, 0.5f), &dv);
      }
    }
    int nearA = 0, nearB = 0;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool inA = RefCovered(ta, x, y), inB = RefCovered(tb, x, y);
        long double l[3];
        RefBarycentric(ta, x, y, l);
        const long double zA = l[0] * za[0] + l[1] * za[1] + l[2] * za[2];
        const std::uint8_t* p = img.at(x, y);
        bool expectA = inA;
        if (inA && inB)
        {
          if (std::fabs(zA - 0.5L) < 1e-4L)
          {
            continue; // too close to call in float
          }
          expectA = zA < 0.5L;
        }
        if (expectA)
        {
          ++nearA;
          EXPECT_EQ(p[0], 255) << "order " << order << " pixel " << x << "," << y;
          EXPECT_NEAR(depth.at(x, y), static_cast<double>(zA), 1e-5);
        }
        else if (inB)
        {
          ++nearB;
          EXPECT_EQ(p[2], 255) << "order " << order << " pixel " << x << "," << y;
          EXPECT_FLOAT_EQ(depth.at(x, y), 0.5f);
        }
      }
    }
    EXPECT_GT(nearA, 100);
    EXPECT_GT(nearB, 100);
  }

  // Strictly less: the same triangle drawn twice with a = 0.5 blends once with the depth test
  // (alpha 128) and twice without it (alpha 192).
  const RasterVertex t[3] = { Vtx(1, 1, 1, 1, 1, 0.5f, 0.25f), Vtx(9, 2, 1, 1, 1, 0.5f, 0.75f),
    Vtx(3, 8, 1, 1, 1, 0.5f, 0.5f) };
  Image once(12, 12), twice(12, 12);
  Depth depth(12, 12);
  const DepthView dv = depth.view();
  for (int k = 0; k < 2; ++k)
  {
    rasterizeTriangle(once.view(), t[0], t[1], t[2], &dv);
    rasterizeTriangle(twice.view(), t[0], t[1], t[2]);
  }
  EXPECT_GT(ExpectBlendedOnceAndTwice(once, twice), 15);
}

TEST(Rasterizer, InterpenetratingTrianglesCrossAtTheExpectedColumn)
{
  // Two large triangles covering the whole image, both slanted in depth:
  //   A (red):  zA(x, y) = 0.2 + 0.02 x + 0.0045 y   (the vertex depths are this plane's values)
  //   B (blue): zB(x, y) = 1.0 - 0.01 x
  // They cross where 0.8 - 0.0045 y = 0.03 x, i.e. at x_c(y) = 26.667 - 0.15 y (23.82 on row 19):
  // A is nearer left of the line, B right of it. Whatever the order, each row must show A up to
  // the column before ceil(x_c) and B from there (+-1 for float depths).
  const int w = 60, h = 20;
  auto zA = [](double x, double y) { return static_cast<float>(0.2 + 0.02 * x + 0.0045 * y); };
  auto zB = [](double x, double) { return static_cast<float>(1.0 - 0.01 * x); };
  const double pa[3][2] = { { -10, -10 }, { 150, -10 }, { -10, 100 } };
  const double pb[3][2] = { { -15, -12 }, { 160, -5 }, { -15, 90 } };
  RasterVertex a[3], b[3];
  for (int i = 0; i < 3; ++i)
  {
    a[i] = Vtx(pa[i][0], pa[i][1], 1, 0, 0, 1, zA(pa[i][0], pa[i][1]));
    b[i] = Vtx(pb[i][0], pb[i][1], 0, 0, 1, 1, zB(pb[i][0], pb[i][1]));
  }
  Image ab(w, h), ba(w, h);
  Depth dab(w, h), dba(w, h);
  const DepthView vab = dab.view(), vba = dba.view();
  ASSERT_EQ(rasterizeTriangle(ab.view(), a[0], a[1], a[2], &vab), RasterResult::Drawn);
  ASSERT_EQ(rasterizeTriangle(ab.view(), b[0], b[1], b[2], &vab), RasterResult::Drawn);
  ASSERT_EQ(rasterizeTriangle(ba.view(), b[0], b[1], b[2], &vba), RasterResult::Drawn);
  ASSERT_EQ(rasterizeTriangle(ba.view(), a[0], a[1], a[2], &vba), RasterResult::Drawn);
  EXPECT_EQ(ab.buf, ba.buf);
  EXPECT_EQ(dab.buf, dba.buf);
  int exact = 0;
  for (int y = 0; y < h; ++y)
  {
    const double xc = (0.8 - 0.0045 * y) / 0.03;
    const int expectedFirstB = static_cast<int>(std::ceil(xc));
    // The row is A ... A B ... B: find where it switches and check nothing else appears.
    int firstB = w;
    for (int x = 0; x < w; ++x)
    {
      const std::uint8_t* p = ab.at(x, y);
      ASSERT_EQ(p[3], 255) << "uncovered pixel " << x << "," << y;
      const bool isB = p[2] == 255 && p[0] == 0;
      const bool isA = p[0] == 255 && p[2] == 0;
      ASSERT_TRUE(isA || isB) << x << "," << y;
      if (isB && firstB == w)
      {
        firstB = x;
      }
      if (firstB < w)
      {
        EXPECT_TRUE(isB) << "A right of the crossing at " << x << "," << y;
      }
      // The stored depth is the nearer surface's.
      const double zNear = std::min(zA(x, y), zB(x, y));
      EXPECT_NEAR(dab.at(x, y), zNear, 1e-5) << x << "," << y;
    }
    EXPECT_NEAR(firstB, expectedFirstB, 1) << "row " << y << " crossing at x = " << xc;
    exact += firstB == expectedFirstB ? 1 : 0;
  }
  // The crossing comes no nearer than 0.016 px to a pixel centre (row 11: 25.017), a depth
  // difference of 5e-4, far above float resolution: the float depths decide exactly.
  EXPECT_EQ(exact, h);
}

TEST(Rasterizer, ReadOnlyDepthBufferTestsWithoutWriting)
{
  // An opaque red square at depth 0.5 writes depth; a half-transparent blue triangle behind it
  // (0.7) drawn with write = false shows only outside the square and leaves the buffer as it was;
  // a half-transparent green one in front (0.3) blends over the square, again without writing.
  const int w = 24, h = 16;
  Image img(w, h);
  Depth depth(w, h);
  const DepthView dv = depth.view();
  DepthView ro = dv;
  ro.write = false;
  const RasterVertex red[4] = { Vtx(3.5, 3.5, 1, 0, 0, 1, 0.5f), Vtx(11.5, 3.5, 1, 0, 0, 1, 0.5f),
    Vtx(11.5, 11.5, 1, 0, 0, 1, 0.5f), Vtx(3.5, 11.5, 1, 0, 0, 1, 0.5f) };
  rasterizeTriangle(img.view(), red[0], red[1], red[2], &dv);
  rasterizeTriangle(img.view(), red[0], red[2], red[3], &dv);
  const std::vector<float> afterOpaque = depth.buf;
  ASSERT_EQ(rasterizeTriangle(img.view(), Vtx(-5, -5, 0, 0, 1, 0.5f, 0.7f),
              Vtx(40, -5, 0, 0, 1, 0.5f, 0.7f), Vtx(-5, 40, 0, 0, 1, 0.5f, 0.7f), &ro),
    RasterResult::Drawn);
  EXPECT_EQ(depth.buf, afterOpaque);
  ASSERT_EQ(rasterizeTriangle(img.view(), Vtx(5.5, 5.5, 0, 1, 0, 0.5f, 0.3f),
              Vtx(9.5, 5.5, 0, 1, 0, 0.5f, 0.3f), Vtx(5.5, 9.5, 0, 1, 0, 0.5f, 0.3f), &ro),
    RasterResult::Drawn);
  EXPECT_EQ(depth.buf, afterOpaque);
  const GridPt blue[3] = { SnapRef(-5, -5), SnapRef(40, -5), SnapRef(-5, 40) };
  const GridPt green[3] = { SnapRef(5.5, 5.5), SnapRef(9.5, 5.5), SnapRef(5.5, 9.5) };
  int blended = 0, behind = 0, front = 0;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool inRed = x >= 4 && x <= 11 && y >= 4 && y <= 11;
      const std::uint8_t* p = img.at(x, y);
      if (inRed && RefCovered(green, x, y))
      {
        ++front; // green over red: (128, 128, 0)
        EXPECT_EQ(p[0], 128) << x << "," << y;
        EXPECT_EQ(p[1], 128) << x << "," << y;
        EXPECT_EQ(p[2], 0) << x << "," << y;
      }
      else if (inRed)
      {
        ++behind; // the blue triangle behind is rejected
        EXPECT_EQ(p[0], 255) << x << "," << y;
        EXPECT_EQ(p[2], 0) << x << "," << y;
      }
      else if (RefCovered(blue, x, y))
      {
        ++blended; // blue over nothing
        EXPECT_EQ(p[2], 128) << x << "," << y;
        EXPECT_EQ(p[3], 128) << x << "," << y;
        EXPECT_EQ(depth.at(x, y), std::numeric_limits<float>::infinity());
      }
    }
  }
  EXPECT_GT(front, 5);
  EXPECT_GT(behind, 30);
  EXPECT_GT(blended, 100);
}

} // namespace
