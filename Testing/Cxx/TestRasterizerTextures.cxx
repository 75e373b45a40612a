// CPU triangle rasteriser: texture mapping (bilinear sampling against a reference sampler and
// hand-computed values, addressing, row order, modulation, strides, invalid textures, and
// clipping / depth of the textured path).
#include "RasterizerTestSupport.h"

using namespace raster_test;

namespace
{
// ---------------------------------------------------------------------------------------------
// Textures.
//
// The reference sampler below follows the definition in Rasterizer.h, written the textbook way:
// s = u * width - 0.5 (texel i's centre at s = i), the two texels floor(s) and floor(s) + 1 with
// their indices wrapped (repeat) or clamped to [0, width - 1] (clamp to edge), weight of the
// second s - floor(s); likewise along v with rows counted from the bottom; long double throughout.

TEST(Rasterizer, SampleTextureAtTexelCentresIsExact)
{
  // Power-of-two sizes: the texel centres (i + 0.5) / n are exact floats, so the result must be
  // the texel exactly (byte / 255 as a float); other sizes are within float rounding.
  const int sizes[5][2] = { { 4, 2 }, { 8, 4 }, { 1, 1 }, { 2, 8 }, { 5, 3 } };
  for (const int ch : { 1, 3, 4 })
  {
    for (const auto& size : sizes)
    {
      const Texels t(size[0], size[1], ch, 100u + static_cast<unsigned>(ch));
      const bool exact = (size[0] & (size[0] - 1)) == 0 && (size[1] & (size[1] - 1)) == 0;
      for (int repeat = 0; repeat < 2; ++repeat)
      {
        const TextureView view = t.view(repeat != 0);
        for (int j = 0; j < t.h; ++j)
        {
          for (int i = 0; i < t.w; ++i)
          {
            float got[4];
            sampleTexture(
              view, static_cast<float>((i + 0.5) / t.w), static_cast<float>((j + 0.5) / t.h), got);
            const std::uint8_t* p = t.texel(i, j);
            const float expected[4] = { (ch == 1 ? p[0] : p[0]) / 255.0f,
              (ch == 1 ? p[0] : p[1]) / 255.0f, (ch == 1 ? p[0] : p[2]) / 255.0f,
              ch == 4 ? p[3] / 255.0f : 1.0f };
            for (int c = 0; c < 4; ++c)
            {
              if (exact)
              {
                EXPECT_EQ(got[c], expected[c]) << "ch " << ch << " size " << t.w << "x" << t.h
                                               << " texel " << i << "," << j << " c" << c;
              }
              else
              {
                EXPECT_NEAR(got[c], expected[c], 1e-6)
                  << "ch " << ch << " texel " << i << "," << j << " c" << c;
              }
            }
          }
        }
      }
    }
  }
}

TEST(Rasterizer, SampleTextureBetweenTexelCentresIsTheBilinearAverage)
{
  const Texels t(4, 4, 4, 7);
  const TextureView view = t.view();
  for (int j = 0; j + 1 < t.h; ++j)
  {
    for (int i = 0; i + 1 < t.w; ++i)
    {
      const std::uint8_t* a = t.texel(i, j);
      const std::uint8_t* b = t.texel(i + 1, j);
      const std::uint8_t* c = t.texel(i, j + 1);
      const std::uint8_t* d = t.texel(i + 1, j + 1);
      float horizontal[4], vertical[4], centre[4], quarter[4];
      // All these coordinates are exact binary fractions.
      sampleTexture(view, (i + 1) / 4.0f, (j + 0.5f) / 4.0f, horizontal);
      sampleTexture(view, (i + 0.5f) / 4.0f, (j + 1) / 4.0f, vertical);
      sampleTexture(view, (i + 1) / 4.0f, (j + 1) / 4.0f, centre);
      // s = 4u - 0.5 = i + 0.25: a quarter of the way from texel i to i + 1.
      sampleTexture(view, (i + 0.75f) / 4.0f, (j + 0.5f) / 4.0f, quarter);
      for (int k = 0; k < 4; ++k)
      {
        EXPECT_FLOAT_EQ(horizontal[k], (a[k] + b[k]) / 510.0f) << i << "," << j << " c" << k;
        EXPECT_FLOAT_EQ(vertical[k], (a[k] + c[k]) / 510.0f) << i << "," << j << " c" << k;
        EXPECT_FLOAT_EQ(centre[k], (a[k] + b[k] + c[k] + d[k]) / 1020.0f)
          << i << "," << j << " c" << k;
        EXPECT_FLOAT_EQ(quarter[k], (0.75f * a[k] + 0.25f * b[k]) / 255.0f)
          << i << "," << j << " c" << k;
      }
    }
  }
}

TEST(Rasterizer, SampleTextureClampAndRepeatAtAndBeyondTheEdges)
{
  const Texels t(4, 2, 4, 8);
  const TextureView clamp = t.view(false), wrap = t.view(true);
  const float vRow0 = 0.25f; // centre of the bottom row
  float got[4];
  for (int k = 0; k < 4; ++k)
  {
    const std::uint8_t first = t.texel(0, 0)[k], last = t.texel(3, 0)[k];
    // Clamp: at the edge and anywhere beyond it, the edge texel.
    for (const float u : { 0.0f, 0.1f, -0.01f, -5.3f, -1e30f })
    {
      sampleTexture(clamp, u, vRow0, got);
      EXPECT_EQ(got[k], first / 255.0f) << "u " << u;
    }
    for (const float u : { 1.0f, 0.9f, 1.01f, 7.2f, 1e30f })
    {
      sampleTexture(clamp, u, vRow0, got);
      EXPECT_EQ(got[k], last / 255.0f) << "u " << u;
    }
    // Repeat: at u = 0 (or any integer) the first and last columns meet half-way.
    for (const float u : { 0.0f, 1.0f, -1.0f, 3.0f })
    {
      sampleTexture(wrap, u, vRow0, got);
      EXPECT_FLOAT_EQ(got[k], (first + last) / 510.0f) << "u " << u;
    }
    // Rows: clamp below / above, wrap between the top and bottom rows.
    const std::uint8_t bottom = t.texel(1, 0)[k], top = t.texel(1, 1)[k];
    sampleTexture(clamp, 0.375f, -2.0f, got);
    EXPECT_EQ(got[k], bottom / 255.0f);
    sampleTexture(clamp, 0.375f, 3.5f, got);
    EXPECT_EQ(got[k], top / 255.0f);
    sampleTexture(wrap, 0.375f, 0.0f, got);
    EXPECT_FLOAT_EQ(got[k], (bottom + top) / 510.0f);
    sampleTexture(wrap, 0.375f, 5.25f, got); // = v 0.25: the bottom row's centre
    EXPECT_EQ(got[k], bottom / 255.0f);
  }
  // Repeat is periodic: u and u + n sample the same.
  float a[4], b[4];
  sampleTexture(wrap, 0.3f, 0.6f, a);
  for (const float du : { 1.0f, -1.0f, 4.0f, -17.0f })
  {
    sampleTexture(wrap, 0.3f + du, 0.6f + du, b);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_NEAR(a[k], b[k], 1e-5) << "shift " << du;
    }
  }

  // Against the reference, anywhere in [-3, 3]^2, for each channel count, odd sizes and both
  // addressing modes.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> uc(-3, 3);
  const int sizes[3][2] = { { 5, 3 }, { 4, 4 }, { 1, 3 } };
  for (const int ch : { 1, 3, 4 })
  {
    for (const auto& size : sizes)
    {
      const Texels tex(size[0], size[1], ch, 11u + static_cast<unsigned>(ch));
      for (int repeat = 0; repeat < 2; ++repeat)
      {
        for (int n = 0; n < 500; ++n)
        {
          const float u = uc(rng), v = uc(rng);
          long double ref[4];
          RefSample(tex, u, v, repeat != 0, ref);
          sampleTexture(tex.view(repeat != 0), u, v, got);
          for (int k = 0; k < 4; ++k)
          {
            EXPECT_NEAR(got[k], static_cast<double>(ref[k]), 1e-5)
              << "ch " << ch << " size " << size[0] << "x" << size[1] << " repeat " << repeat
              << " uv " << u << "," << v << " c" << k;
          }
        }
      }
    }
  }
  // Huge coordinates stay in range.
  for (int repeat = 0; repeat < 2; ++repeat)
  {
    sampleTexture(t.view(repeat != 0), 3e38f, -3e38f, got);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_TRUE(got[k] >= 0.0f && got[k] <= 1.0f);
    }
  }
}

TEST(Rasterizer, TextureRowsCountFromTheBottom)
{
  // 2x2 RGB: the bottom row (texel row 0, stored first) is red, the top row blue.
  const std::uint8_t bottomUp[12] = { 255, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0, 255 };
  // The same image stored top row first, addressed with a negative stride.
  const std::uint8_t topDown[12] = { 0, 0, 255, 0, 0, 255, 255, 0, 0, 255, 0, 0 };
  const TextureView views[2] = { TextureView{ bottomUp, 2, 2, 3, 6, false },
    TextureView{ topDown + 6, 2, 2, 3, -6, false } };
  for (const TextureView& view : views)
  {
    float got[4];
    sampleTexture(view, 0.5f, 0.05f, got); // v near 0: bottom
    EXPECT_EQ(got[0], 1.0f);
    EXPECT_EQ(got[2], 0.0f);
    sampleTexture(view, 0.3f, 0.25f, got);
    EXPECT_EQ(got[0], 1.0f);
    EXPECT_EQ(got[2], 0.0f);
    sampleTexture(view, 0.7f, 0.95f, got); // v near 1: top
    EXPECT_EQ(got[0], 0.0f);
    EXPECT_EQ(got[2], 1.0f);
    sampleTexture(view, 0.5f, 0.5f, got); // half-way
    EXPECT_FLOAT_EQ(got[0], 0.5f);
    EXPECT_FLOAT_EQ(got[2], 0.5f);
    EXPECT_EQ(got[1], 0.0f);
    EXPECT_EQ(got[3], 1.0f);

    // Drawn on a square whose bottom image edge has v = 0 and top edge v = 1: the image is
    // upright (red at the bottom rows, blue at the top rows: image y points down, v up).
    const int n = 16;
    Image img(n, n);
    const RasterVertex tl = UV(Vtx(-0.5, -0.5), 0, 1), tr = UV(Vtx(n - 0.5, -0.5), 1, 1),
                       br = UV(Vtx(n - 0.5, n - 0.5), 1, 0), bl = UV(Vtx(-0.5, n - 0.5), 0, 0);
    EXPECT_EQ(rasterizeTriangle(img.view(), tl, tr, br, nullptr, &view), RasterResult::Drawn);
    EXPECT_EQ(rasterizeTriangle(img.view(), tl, br, bl, nullptr, &view), RasterResult::Drawn);
    for (int x = 0; x < n; ++x)
    {
      for (int y : { 0, 1, 2, 3 })
      {
        EXPECT_EQ(img.at(x, y)[0], 0) << x << "," << y;
        EXPECT_EQ(img.at(x, y)[2], 255) << x << "," << y;
      }
      for (int y : { 12, 13, 14, 15 })
      {
        EXPECT_EQ(img.at(x, y)[0], 255) << x << "," << y;
        EXPECT_EQ(img.at(x, y)[2], 0) << x << "," << y;
      }
      EXPECT_EQ(img.at(x, 8)[3], 255);
    }
  }
}

// A textured triangle with white vertices shows the bilinear sample of the interpolated (u, v),
// checked at pixels whose values are worked out by hand.
TEST(Rasterizer, TexturedTriangleShowsTheBilinearTexelAtHandPickedPixels)
{
  // 2x2 RGBA, bottom row first: (0,0) red, (1,0) green, (0,1) blue, (1,1) white.
  const std::uint8_t texels[16] = { 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255,
    255 };
  const TextureView tex{ texels, 2, 2, 4, 8, false };
  // Vertices on pixel centres: u = x / 64 and v = 1 - y / 64 at pixel (x, y), so the texel
  // coordinates are s = 2u - 0.5 = x / 32 - 0.5 and t = 2v - 0.5 = 1.5 - y / 32.
  const RasterVertex a = UV(Vtx(0, 0), 0, 1), b = UV(Vtx(64, 0), 1, 1), c = UV(Vtx(0, 64), 0, 0);
  struct Expect
  {
    int x, y;
    double rgb[3]; // exact value on the 0..255 scale
  };
  const Expect expected[] = {
    // s = 0, t = 1: texel (0, 1), blue.
    { 16, 16, { 0, 0, 255 } },
    // s = 0.5, t = 1: half blue, half white.
    { 32, 16, { 127.5, 127.5, 255 } },
    // s = -0.25, t = 1.25: clamped to texel (0, 1).
    { 8, 8, { 0, 0, 255 } },
    // s = 0.25, t = 0.75: weights red 0.75*0.25, green 0.25*0.25, blue 0.75*0.75, white
    // 0.25*0.75 -> r = 255 (0.1875 + 0.1875), g = 255 (0.0625 + 0.1875), b = 255 (0.5625 + 0.1875).
    { 24, 24, { 95.625, 63.75, 191.25 } },
    // s = 0.125, t = 0.375: red 0.875*0.625, green 0.125*0.625, blue 0.875*0.375, white
    // 0.125*0.375 -> r = 255 * 0.59375, g = 255 * 0.125, b = 255 * 0.375.
    { 20, 36, { 151.40625, 31.875, 95.625 } },
    // s = -0.5 (clamped to 0), t = -0.4375 (clamped to 0): texel (0, 0), red.
    { 0, 62, { 255, 0, 0 } },
    // s = 1.3125 (clamped to 1), t = 1.5 (clamped to 1): texel (1, 1), white.
    { 58, 0, { 255, 255, 255 } },
  };
  for (int order = 0; order < 2; ++order)
  {
    Image img(64, 64);
    img.pattern(21); // opaque texels overwrite whatever is there
    if (order == 0)
    {
      EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, nullptr, &tex), RasterResult::Drawn);
    }
    else
    {
      EXPECT_EQ(rasterizeTriangle(img.view(), c, b, a, nullptr, &tex), RasterResult::Drawn);
    }
    for (const Expect& e : expected)
    {
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_TRUE(ByteMatches(e.rgb[k], img.at(e.x, e.y)[k]))
          << "pixel " << e.x << "," << e.y << " c" << k << " expected " << e.rgb[k] << " got "
          << static_cast<int>(img.at(e.x, e.y)[k]);
      }
      EXPECT_EQ(img.at(e.x, e.y)[3], 255);
    }
  }
}

// Random triangles, textures, (u, v), colours and alpha against the reference: the drawn colour
// is the barycentric colour times the bilinear texel of the barycentric (u, v).
TEST(Rasterizer, TexturedColourIsTheModulatedBilinearSample)
{
  const int w = 40, h = 32;
  Image img(w, h);
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> uc(-0.2f, 1.2f), ua(0.0f, 1.0f), ut(-1.5f, 2.5f);
  PixelChecks checks;
  for (int n = 0; n < 300; ++n)
  {
    GridPt t[3];
    RandomTriangle(rng, w, h, t);
    if (Orient(t[0], t[1], t[2]) == 0)
    {
      continue;
    }
    const int ch = n % 3 == 0 ? 1 : (n % 3 == 1 ? 3 : 4);
    const Texels tex(2 + n % 4, 1 + n % 5, ch, static_cast<unsigned>(n));
    const bool repeat = (n / 3) % 2 == 0;
    const TextureView view = tex.view(repeat);
    float col[3][4], uv[3][2];
    RasterVertex v[3];
    for (int i = 0; i < 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        col[i][c] = (n % 5 == 0) ? 1.0f : uc(rng); // some white
      }
      col[i][3] = (n % 2 == 0) ? 1.0f : ua(rng);
      uv[i][0] = ut(rng);
      uv[i][1] = ut(rng);
      v[i] = UV(Vtx(t[i], col[i][0], col[i][1], col[i][2], col[i][3]), uv[i][0], uv[i][1]);
    }
    // On a transparent black target: out.rgb = 255 c a, out.a = 255 a.
    img.fill(0);
    rasterizeTriangle(img.view(), v[0], v[1], v[2], nullptr, &view);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        if (!RefCovered(t, x, y))
        {
          EXPECT_EQ(img.at(x, y)[3], 0);
          continue;
        }
        long double l[3];
        RefBarycentric(t, x, y, l);
        long double value[4] = { 0, 0, 0, 0 }, u = 0, tv = 0;
        for (int i = 0; i < 3; ++i)
        {
          for (int c = 0; c < 4; ++c)
          {
            value[c] += l[i] * std::min(1.0L, std::max(0.0L, static_cast<long double>(col[i][c])));
          }
          u += l[i] * uv[i][0];
          tv += l[i] * uv[i][1];
        }
        long double texel[4];
        RefSample(tex, u, tv, repeat, texel);
        for (int c = 0; c < 4; ++c)
        {
          value[c] *= texel[c];
        }
        checks.Premultiplied(img, n, x, y, value);
      }
    }
  }
  EXPECT_GT(checks.checked, 10000);
  EXPECT_EQ(checks.bad, 0) << checks.firstBad;
}

TEST(Rasterizer, TexturedModulationByColourAndAlpha)
{
  const int w = 12, h = 10;
  Image img(w, h);
  img.pattern(31);
  const Image before = img;
  // One RGBA texel: the sample is that texel everywhere.
  const std::uint8_t texel[4] = { 200, 100, 50, 128 };
  const TextureView tex{ texel, 1, 1, 4, 4, true };
  const float col[4] = { 0.5f, 1.0f, 0.25f, 0.8f };
  const RasterVertex v[3] = { UV(Vtx(-20, -20, col[0], col[1], col[2], col[3]), 0.3f, 0.1f),
    UV(Vtx(60, -20, col[0], col[1], col[2], col[3]), 5.0f, -2.0f),
    UV(Vtx(-20, 60, col[0], col[1], col[2], col[3]), -3.0f, 0.7f) };
  EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2], nullptr, &tex), RasterResult::Drawn);
  // src = colour * texel / 255, alpha = 0.8 * 128 / 255, then source-over.
  const long double alpha = 0.8L * 128.0L / 255.0L;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 4; ++c)
      {
        const long double src = c < 3 ? static_cast<long double>(col[c]) * texel[c] / 255.0L : 1;
        const long double exact = 255 * src * alpha + before.at(x, y)[c] * (1 - alpha);
        EXPECT_LE(std::fabs(exact - img.at(x, y)[c]), 1.0L)
          << x << "," << y << " c" << c << " exact " << static_cast<double>(exact) << " got "
          << static_cast<int>(img.at(x, y)[c]);
      }
    }
  }

  // Grey texture: r = g = b = L, alpha 1; with opaque vertices it overwrites:
  // out = round(255 * colour * L / 255) = round(colour * L), alpha 255.
  const std::uint8_t grey = 90;
  const TextureView greyTex{ &grey, 1, 1, 1, 1, false };
  const float c2[3] = { 1.0f, 0.5f, 0.2f };
  img = before;
  rasterizeTriangle(img.view(), Vtx(-20, -20, c2[0], c2[1], c2[2], 1),
    Vtx(60, -20, c2[0], c2[1], c2[2], 1), Vtx(-20, 60, c2[0], c2[1], c2[2], 1), nullptr, &greyTex);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], 90);
      EXPECT_EQ(img.at(x, y)[1], 45);
      EXPECT_EQ(img.at(x, y)[2], 18);
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // A transparent texel leaves the target unchanged; a transparent vertex colour too.
  const std::uint8_t clear[4] = { 255, 255, 255, 0 };
  const TextureView clearTex{ clear, 1, 1, 4, 4, false };
  img = before;
  rasterizeTriangle(img.view(), Vtx(-20, -20), Vtx(60, -20), Vtx(-20, 60), nullptr, &clearTex);
  EXPECT_EQ(img.buf, before.buf);
  rasterizeTriangle(img.view(), Vtx(-20, -20, 1, 1, 1, 0), Vtx(60, -20, 1, 1, 1, 0),
    Vtx(-20, 60, 1, 1, 1, 0), nullptr, &greyTex);
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, TexturedNegativeRowStrideMatchesTheFlippedTexture)
{
  const int w = 37, h = 29;
  auto scene = RandomScene(51, w, h, 200);
  std::mt19937 rng(52);
  std::uniform_real_distribution<float> ut(-1.2f, 2.2f);
  for (auto& t : scene)
  {
    for (auto& v : t.v)
    {
      v.u = ut(rng);
      v.v = ut(rng);
    }
  }
  for (const int ch : { 1, 3, 4 })
  {
    for (int repeat = 0; repeat < 2; ++repeat)
    {
      const int tw = 5, th = 4, pad = 3; // rows padded: stride != width * channels
      const std::ptrdiff_t stride = tw * ch + pad;
      std::vector<std::uint8_t> up(static_cast<std::size_t>(stride * th), 0xAB);
      std::vector<std::uint8_t> down(up.size(), 0xCD);
      std::mt19937 trng(53u + static_cast<unsigned>(ch));
      for (int j = 0; j < th; ++j)
      {
        for (int k = 0; k < tw * ch; ++k)
        {
          const std::uint8_t b = static_cast<std::uint8_t>(trng() & 0xFF);
          up[static_cast<std::size_t>(j * stride + k)] = b;              // row j from the start
          down[static_cast<std::size_t>((th - 1 - j) * stride + k)] = b; // row j from the end
        }
      }
      const TextureView tUp{ up.data(), tw, th, ch, stride, repeat != 0 };
      const TextureView tDown{ down.data() + (th - 1) * stride, tw, th, ch, -stride, repeat != 0 };
      Image a(w, h), b(w, h);
      a.pattern(54);
      b.buf = a.buf;
      Depth da(w, h), db(w, h);
      const DepthView dva = da.view(), dvb = db.view();
      int drawn = 0;
      for (const auto& t : scene)
      {
        const RasterResult ra = rasterizeTriangle(a.view(), t.v[0], t.v[1], t.v[2], &dva, &tUp);
        const RasterResult rb = rasterizeTriangle(b.view(), t.v[0], t.v[1], t.v[2], &dvb, &tDown);
        EXPECT_EQ(ra, rb);
        drawn += ra == RasterResult::Drawn ? 1 : 0;
      }
      EXPECT_GT(drawn, 100);
      EXPECT_EQ(a.buf, b.buf) << "channels " << ch << " repeat " << repeat;
      EXPECT_EQ(da.buf, db.buf);
      // And the texture really is sampled: the picture differs from an untextured drawing.
      Image plain(w, h);
      plain.pattern(54);
      for (const auto& t : scene)
      {
        rasterizeTriangle(plain.view(), t.v[0], t.v[1], t.v[2]);
      }
      EXPECT_NE(plain.buf, a.buf);
    }
  }
}

TEST(Rasterizer, InvalidTexturesAreRejected)
{
  Image img(16, 16);
  img.pattern(61);
  const Image before = img;
  Depth depth(16, 16);
  const std::vector<float> depthBefore = depth.buf;
  const DepthView dv = depth.view();
  const std::uint8_t texels[16] = {};
  const TextureView good{ texels, 2, 2, 4, 8, false };
  TextureView bad[8] = { good, good, good, good, good, good, good, good };
  bad[0].data = nullptr;
  bad[1].width = 0;
  bad[2].height = 0;
  bad[3].width = -2;
  bad[4].height = -1;
  bad[5].channels = 0;
  bad[6].channels = 2;
  bad[7].channels = 5;
  const RasterVertex a = Vtx(0, 0), b = Vtx(15, 0), c = Vtx(0, 15);
  for (int k = 0; k < 8; ++k)
  {
    EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, nullptr, &bad[k]), RasterResult::InvalidInput)
      << k;
    EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, &dv, &bad[k]), RasterResult::InvalidInput)
      << k;
    EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, PixelRect{ 0, 0, 8, 8 }, nullptr, &bad[k]),
      RasterResult::InvalidInput)
      << k;
    // InvalidInput comes before the other outcomes.
    EXPECT_EQ(rasterizeTriangle(img.view(), a, a, a, nullptr, &bad[k]), RasterResult::InvalidInput);
    EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(1e7, 0), c, nullptr, &bad[k]),
      RasterResult::InvalidInput);
    float rgba[4] = { 0.5f, 0.5f, 0.5f, 0.5f };
    sampleTexture(bad[k], 0.5f, 0.5f, rgba);
    for (float x : rgba)
    {
      EXPECT_EQ(x, 0.0f) << k;
    }
  }
  // Non-finite texture coordinates, with or without a texture (every vertex field must be
  // finite, as for the depth).
  const float values[3] = { std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity() };
  for (float value : values)
  {
    for (int vi = 0; vi < 3; ++vi)
    {
      for (int field = 0; field < 2; ++field)
      {
        RasterVertex v[3] = { a, b, c };
        (field == 0 ? v[vi].u : v[vi].v) = value;
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2], nullptr, &good),
          RasterResult::InvalidInput);
        EXPECT_EQ(
          rasterizeTriangle(img.view(), v[0], v[1], v[2], &dv, &good), RasterResult::InvalidInput);
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2]), RasterResult::InvalidInput);
      }
    }
    float rgba[4] = { 0.5f, 0.5f, 0.5f, 0.5f };
    sampleTexture(good, value, 0.5f, rgba);
    EXPECT_EQ(rgba[0], 0.0f);
    EXPECT_EQ(rgba[3], 0.0f);
    sampleTexture(good, 0.5f, value, rgba);
    EXPECT_EQ(rgba[1], 0.0f);
  }
  EXPECT_EQ(img.buf, before.buf);
  EXPECT_EQ(depth.buf, depthBefore);
  // A null texture is the untextured drawing.
  Image x(16, 16), y(16, 16);
  rasterizeTriangle(x.view(), Vtx(1, 1, 0.2f, 0.4f, 0.6f, 0.7f), Vtx(14, 3, 0.9f, 0.1f, 0, 1),
    Vtx(4, 13, 0, 1, 0.5f, 0.3f), nullptr, nullptr);
  rasterizeTriangle(y.view(), Vtx(1, 1, 0.2f, 0.4f, 0.6f, 0.7f), Vtx(14, 3, 0.9f, 0.1f, 0, 1),
    Vtx(4, 13, 0, 1, 0.5f, 0.3f));
  EXPECT_EQ(x.buf, y.buf);
  EXPECT_GT(CountNonZeroAlpha(x), 20);
}

// The textured path covers, clips and depth-tests exactly like the untextured one.
TEST(Rasterizer, TexturedCoverageClipAndDepthMatchTheUntexturedRules)
{
  // Coverage against the brute-force reference: an opaque RGB texture on a transparent image
  // sets alpha 255 exactly on the covered pixels.
  {
    std::mt19937 rng(71);
    std::uniform_real_distribution<float> ut(-2, 3);
    const int w = 48, h = 40;
    Image img(w, h);
    const Texels tex(3, 3, 3, 72);
    int totalBad = 0, drawn = 0;
    std::string firstBad;
    for (int n = 0; n < 2000; ++n)
    {
      GridPt t[3];
      RandomTriangle(rng, w, h, t);
      img.fill(0);
      const TextureView view = tex.view(n % 2 == 0);
      const RasterResult res = rasterizeTriangle(img.view(), UV(Vtx(t[0]), ut(rng), ut(rng)),
        UV(Vtx(t[1]), ut(rng), ut(rng)), UV(Vtx(t[2]), ut(rng), ut(rng)), nullptr, &view);
      std::string bad;
      const auto cmp = CompareCoverage(img, t, &bad);
      if (cmp.first && firstBad.empty())
      {
        firstBad = bad;
      }
      totalBad += cmp.first;
      const RasterResult expected = Orient(t[0], t[1], t[2]) == 0
        ? RasterResult::Degenerate
        : (cmp.second == 0 ? RasterResult::Empty : RasterResult::Drawn);
      EXPECT_EQ(res, expected) << "triangle " << n;
      drawn += res == RasterResult::Drawn ? 1 : 0;
    }
    EXPECT_EQ(totalBad, 0) << firstBad;
    EXPECT_GT(drawn, 1000);
  }

  // Clip tiles give the same picture and depth as the whole image.
  const int w = 61, h = 47;
  auto scene = RandomScene(73, w, h, 400);
  std::mt19937 rng(74);
  std::uniform_real_distribution<float> ut(-1, 2);
  for (auto& t : scene)
  {
    for (auto& v : t.v)
    {
      v.u = ut(rng);
      v.v = ut(rng);
    }
  }
  const Texels tex(7, 5, 4, 75);
  const TextureView view = tex.view(true);
  Image whole(w, h), tiled(w, h);
  whole.pattern(76);
  tiled.buf = whole.buf;
  Depth dWhole(w, h, 0.8f), dTiled(w, h, 0.8f);
  const DepthView dvWhole = dWhole.view(), dvTiled = dTiled.view();
  for (const auto& t : scene)
  {
    rasterizeTriangle(whole.view(), t.v[0], t.v[1], t.v[2], &dvWhole, &view);
  }
  const int tw = 16, th = 12;
  for (int ty = 0; ty < h; ty += th)
  {
    for (int tx = 0; tx < w; tx += tw)
    {
      const PixelRect clip{ tx, ty, std::min(tx + tw, w), std::min(ty + th, h) };
      for (const auto& t : scene)
      {
        rasterizeTriangle(tiled.view(), t.v[0], t.v[1], t.v[2], clip, &dvTiled, &view);
      }
    }
  }
  EXPECT_EQ(whole.buf, tiled.buf);
  EXPECT_EQ(dWhole.buf, dTiled.buf);
  // Pixels outside a clip rectangle are untouched.
  {
    Image part(w, h);
    part.pattern(77);
    const Image background = part;
    const PixelRect clip{ 13, 9, 40, 31 };
    const RasterVertex a = UV(Vtx(-3.3, 2.2, 0.9f, 0.2f, 0.1f, 0.6f), 0, 0);
    const RasterVertex b = UV(Vtx(70.1, 10.4, 0.1f, 0.8f, 0.3f, 1.0f), 2, 0);
    const RasterVertex c = UV(Vtx(20.7, 52.9, 0.4f, 0.4f, 0.9f, 0.8f), 0, 2);
    Image ref = background;
    rasterizeTriangle(ref.view(), a, b, c, nullptr, &view);
    EXPECT_EQ(rasterizeTriangle(part.view(), a, b, c, clip, nullptr, &view), RasterResult::Drawn);
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

  // The depth test and the depth written are those of the untextured drawing.
  Image plain(w, h);
  Depth dPlain(w, h, 0.8f);
  const DepthView dvPlain = dPlain.view();
  for (const auto& t : scene)
  {
    rasterizeTriangle(plain.view(), t.v[0], t.v[1], t.v[2], &dvPlain);
  }
  EXPECT_EQ(dPlain.buf, dWhole.buf);

  // Two textured triangles with depth against the reference: A (red texture) slopes from depth
  // 0 to 1, B (blue texture) is flat at 0.5; in both drawing orders the nearer one is shown.
  const GridPt ta[3] = { SnapRef(-5, -5), SnapRef(45, -5), SnapRef(-5, 35) };
  const float za[3] = { 0.0f, 1.0f, 0.0f };
  const GridPt tb[3] = { SnapRef(-5, -5), SnapRef(45, 35), SnapRef(-5, 35) };
  const std::uint8_t red[3] = { 255, 0, 0 }, blue[3] = { 0, 0, 255 };
  const TextureView redTex{ red, 1, 1, 3, 3, false }, blueTex{ blue, 1, 1, 3, 3, true };
  for (int order = 0; order < 2; ++order)
  {
    Image img(40, 30);
    Depth depth(40, 30);
    const DepthView dv = depth.view();
    for (int k = 0; k < 2; ++k)
    {
      if ((k == 0) == (order == 0))
      {
        rasterizeTriangle(img.view(), UV(Vtx(ta[0], 1, 1, 1, 1, za[0]), 0, 0),
          UV(Vtx(ta[1], 1, 1, 1, 1, za[1]), 1, 0), UV(Vtx(ta[2], 1, 1, 1, 1, za[2]), 0, 1), &dv,
          &redTex);
      }
      else
      {
        rasterizeTriangle(img.view(), UV(Vtx(tb[0], 1, 1, 1, 1, 0.5f), 3, 0),
          UV(Vtx(tb[1], 1, 1, 1, 1, 0.5f), 0, 4), UV(Vtx(tb[2], 1, 1, 1, 1, 0.5f), 1, 1), &dv,
          &blueTex);
      }
    }
    int nearA = 0, nearB = 0;
    for (int y = 0; y < 30; ++y)
    {
      for (int x = 0; x < 40; ++x)
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
          EXPECT_TRUE(p[0] == 255 && p[2] == 0) << "order " << order << " pixel " << x << "," << y;
          EXPECT_NEAR(depth.at(x, y), static_cast<double>(zA), 1e-5);
        }
        else if (inB)
        {
          ++nearB;
          EXPECT_TRUE(p[0] == 0 && p[2] == 255) << "order " << order << " pixel " << x << "," << y;
          EXPECT_FLOAT_EQ(depth.at(x, y), 0.5f);
        }
        else
        {
          EXPECT_EQ(p[3], 0);
        }
      }
    }
    EXPECT_GT(nearA, 100);
    EXPECT_GT(nearB, 100);
  }

  // Strictly less: the same half-transparent textured triangle drawn twice blends once with the
  // depth test (alpha 128) and twice without it (alpha 192).
  const std::uint8_t half[4] = { 255, 255, 255, 255 };
  const TextureView halfTex{ half, 1, 1, 4, 4, false };
  const RasterVertex t3[3] = { Vtx(1, 1, 1, 1, 1, 0.5f, 0.25f), Vtx(9, 2, 1, 1, 1, 0.5f, 0.75f),
    Vtx(3, 8, 1, 1, 1, 0.5f, 0.5f) };
  Image once(12, 12), twice(12, 12);
  Depth depth(12, 12);
  const DepthView dv = depth.view();
  for (int k = 0; k < 2; ++k)
  {
    rasterizeTriangle(once.view(), t3[0], t3[1], t3[2], &dv, &halfTex);
    rasterizeTriangle(twice.view(), t3[0], t3[1], t3[2], nullptr, &halfTex);
  }
  EXPECT_GT(ExpectBlendedOnceAndTwice(once, twice), 15);
}
} // namespace
