// catadioptric-render's command line (CLI11): --version, --option=value as well as --option
// value, -h, usage errors printed once with exit status 2, no colour codes.
#include "TestPrograms.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace
{
catar_test::ProgramRun Render(const std::string& arguments)
{
  return catar_test::RunProgram(CATAR_RENDER_PROGRAM, arguments);
}

int Lines(const std::string& text)
{
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}
} // namespace

TEST(RenderProgram, VersionAndHelp)
{
  const auto version = Render("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output, std::string("catadioptric-render ") + CATAR_VERSION + "\n");
  const auto help = Render("-h");
  EXPECT_EQ(help.status, 0);
  for (const char* option : { "--output", "--frames", "--fps", "--adaptive", "--antialias",
         "--antialias-samples", "--repeat", "--target-area", "--pixel-tolerance", "--version" })
  {
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
  }
  EXPECT_EQ(help.output.find('\x1b'), std::string::npos) << "colour codes in the help";
}

TEST(RenderProgram, OptionsTakeTheirValueEitherWay)
{
  const std::string dir = ::testing::TempDir();
  for (const std::string form : { "--output=", "--output " })
  {
    const std::string out = dir + "/catar_cli_" + (form.back() == '=' ? "eq" : "sp") + ".png";
    std::remove(out.c_str());
    const auto run =
      Render(form + "'" + out + "' --repeat=1 --antialias --antialias-samples 2 --adaptive=4");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_TRUE(std::ifstream(out).good()) << form;
    EXPECT_NE(run.output.find("wrote " + out), std::string::npos) << run.output;
  }
}

TEST(RenderProgram, UsageErrorsOnceWithStatusTwo)
{
  for (const char* bad : { "--bogus", "--antialias-samples 5", "--repeat 0", "--fps=-1",
         "--target-area 1e-4 --pixel-tolerance 1", "--frames 3:1", "--adaptive", "a.yaml b.yaml",
         // An option where a file name belongs, and a frame number past 64 bits.
         "-o --quiet", "--mask --json", "--frames 99999999999999999999",
         "--frames 0:99999999999999999999" })
  {
    const auto run = Render(bad);
    EXPECT_EQ(run.status, 2) << bad << ": " << run.output;
    EXPECT_EQ(Lines(run.output), 1) << bad << ": " << run.output;
    EXPECT_EQ(run.output.rfind("catadioptric-render: ", 0), 0u) << run.output;
    EXPECT_NE(run.output.find("--help"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find('\x1b'), std::string::npos) << run.output;
  }
}

// An error inside the VTK pipeline is printed once, as one plain line: no VTK log decoration
// (colours, file and line, the object's address), no executive dump, not again by the program.
TEST(RenderProgram, ErrorsOnceAsPlainLines)
{
  for (const char* name : { "remesh-runaway-pixel-tolerance", "huge-coordinates-shadows" })
  {
    const std::string scene = std::string(CATAR_SOURCE_DIR) + "/Testing/Corpus/" + name + ".yaml";
    const auto run = Render("'" + scene + "' -o '" + ::testing::TempDir() + "/catar_error.png'");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_EQ(run.output.find('\x1b'), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("ERROR: In"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("(0x"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("returned failure"), std::string::npos) << run.output;
    // Every line is the program's, and no line comes twice.
    std::istringstream lines(run.output);
    std::set<std::string> seen;
    for (std::string line; std::getline(lines, line);)
    {
      EXPECT_EQ(line.rfind("catadioptric-render: ", 0), 0u) << line;
      EXPECT_TRUE(seen.insert(line).second) << "printed twice: " << line;
    }
  }
}

// The image's format follows the extension; an unknown one is a usage error before any work.
TEST(RenderProgram, ImageFormatByExtension)
{
  const std::string dir = ::testing::TempDir();
  const std::pair<const char*, std::string> formats[] = { { "png", "\x89PNG" },
    { "jpg", "\xFF\xD8\xFF" }, { "tif", "II*" }, { "bmp", "BM" } };
  for (const auto& f : formats)
  {
    const std::string out = dir + "/catar_format." + f.first;
    std::remove(out.c_str());
    const auto run = Render("--antialias -o '" + out + "'");
    EXPECT_EQ(run.status, 0) << f.first << ": " << run.output;
    std::ifstream in(out, std::ios::binary);
    std::string head(f.second.size(), '\0');
    in.read(&head[0], static_cast<std::streamsize>(head.size()));
    EXPECT_EQ(head, f.second) << f.first;
  }
  const auto bad = Render("-o '" + dir + "/catar_format.xyz'");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_EQ(Lines(bad.output), 1) << bad.output;
  EXPECT_NE(bad.output.find("unknown image format '.xyz'"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find(".jpg"), std::string::npos) << bad.output;
}

// --alpha, --mask and --ids, read back by numpy: the alpha is 255 exactly where a triangle is
// seen (opaque objects), the mask is the ids' silhouette.
TEST(RenderProgram, AlphaMaskAndIds)
{
  const auto numpy = catar_test::RunProgram(CATAR_SYSTEM_PYTHON, "-c 'import numpy, PIL'");
  if (numpy.status != 0)
  {
    GTEST_SKIP() << "no numpy and PIL in " << CATAR_SYSTEM_PYTHON;
  }
  const std::string dir = ::testing::TempDir();
  const std::string image = dir + "/catar_alpha.png", mask = dir + "/catar_mask.png",
                    ids = dir + "/catar_ids.npy";
  const auto run = Render("--alpha -o '" + image + "' --mask '" + mask + "' --ids '" + ids + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string check = "-c 'import numpy, PIL.Image as I\n"
                            "a = numpy.asarray(I.open(\"" +
    image + "\"))\nm = numpy.asarray(I.open(\"" + mask + "\").convert(\"L\"))\nt = numpy.load(\"" +
    ids +
    "\")\n"
    "assert t.dtype == numpy.int64 and t.shape == a.shape[:2] == m.shape, (t.shape, a.shape)\n"
    "seen = t >= 0\n"
    "assert 1000 < seen.sum() < seen.size // 2, seen.sum()\n"
    "assert (t[~seen] == -1).all()\n"
    "assert ((m == 255) == seen).all() and ((m == 0) == ~seen).all()\n"
    "assert I.open(\"" +
    mask + "\").mode == \"L\", I.open(\"" + mask +
    "\").mode\n"
    "assert ((a[..., 3] == 255) == seen).all() and (a[..., 3][~seen] == 0).all()\n"
    "print(\"seen\", seen.sum(), \"meshes\", sorted(set((t[seen] >> 32).tolist())))'";
  const auto read = catar_test::RunProgram(CATAR_SYSTEM_PYTHON, check);
  EXPECT_EQ(read.status, 0) << read.output;
  std::cout << "[ cli      ] " << read.output;
  // Sequences and the other extensions are refused.
  EXPECT_EQ(Render("--ids '" + dir + "/x.txt'").status, 2);
  EXPECT_EQ(Render("--mask '" + dir + "/x.xyz'").status, 2);
}

// --depth (32-bit float .tif and .exr: the same values, NaN exactly where no triangle is seen)
// and --ids as a 16-bit RGB image (the same ids as the .npy array, decoded as the help says).
TEST(RenderProgram, DepthAndIdImages)
{
  const std::string dir = ::testing::TempDir();
  const std::string tif = dir + "/catar_depth.tif", exr = dir + "/catar_depth.exr",
                    png = dir + "/catar_ids.png", npy = dir + "/catar_ids16.npy";
  const auto run =
    Render("-o '" + dir + "/catar_depth_frame.png' --depth '" + tif + "' --ids '" + png + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto second =
    Render("-o '" + dir + "/catar_depth_frame.png' --depth '" + exr + "' --ids '" + npy + "'");
  ASSERT_EQ(second.status, 0) << second.output;
  const cv::Mat a = cv::imread(tif, cv::IMREAD_UNCHANGED);
  const cv::Mat b = cv::imread(exr, cv::IMREAD_UNCHANGED);
  const cv::Mat ids = cv::imread(png, cv::IMREAD_UNCHANGED); // B, G, R
  ASSERT_EQ(a.type(), CV_32FC1);
  ASSERT_EQ(ids.type(), CV_16UC3);
  // The .npy: a header, then int64 values, rows top first.
  std::ifstream in(npy, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t data = bytes.find('\n') + 1;
  ASSERT_EQ(bytes.size() - data, 8u * a.total());
  const auto* npyIds = reinterpret_cast<const long long*>(bytes.data() + data);
  long seen = 0, bad = 0;
  for (int y = 0; y < a.rows; ++y)
  {
    for (int x = 0; x < a.cols; ++x)
    {
      const long long id = npyIds[static_cast<std::size_t>(y) * a.cols + x];
      const cv::Vec3w rgb = ids.at<cv::Vec3w>(y, x);
      const long long fromPng = rgb[2] == 0 ? -1
                                            : (static_cast<long long>(rgb[2] - 1) << 32) + rgb[1] +
          (static_cast<long long>(rgb[0]) << 16);
      const float d = a.at<float>(y, x);
      bad += fromPng != id || std::isnan(d) != (id < 0) || !(std::isnan(d) || d > 0);
      if (!b.empty())
      {
        const float e = b.at<float>(y, x);
        bad += !(e == d || (std::isnan(e) && std::isnan(d)));
      }
      seen += id >= 0;
    }
  }
  EXPECT_GT(seen, 1000);
  EXPECT_EQ(bad, 0);
  std::cout << "[ cli      ] " << seen << " pixels with a path length and an id"
            << (b.empty() ? " (no EXR reader: .exr not compared)" : "") << "\n";
  // Other extensions are usage errors.
  EXPECT_EQ(Render("--depth '" + dir + "/x.png'").status, 2);
  EXPECT_EQ(Render("--ids '" + dir + "/x.jpg'").status, 2);
}

// --json: one JSON object (read by Python's json), for one image and for a sequence; --quiet:
// nothing printed on success; neither: a summary with the stage times.
TEST(RenderProgram, JsonSummaryAndQuiet)
{
  const std::string dir = ::testing::TempDir();
  const auto one = Render("--json -o '" + dir + "/catar_json.png'");
  ASSERT_EQ(one.status, 0) << one.output;
  const auto read = catar_test::RunProgram(CATAR_SYSTEM_PYTHON,
    "-c 'import json, sys\nd = json.loads(sys.argv[1])\n"
    "assert d[\"width\"] == 1328 and d[\"height\"] == 1048 and d[\"triangles\"] > 0, d\n"
    "assert d[\"scene\"] is None and d[\"ids\"] is None, d\n"
    "assert set(d[\"stages_ms\"]) >= {\"projection\", \"sort\", \"composite\"}, d\n"
    "assert d[\"frame_ms\"] > 0, d' '" +
      one.output + "'");
  EXPECT_EQ(read.status, 0) << read.output << one.output;
  const std::string scene = std::string(CATAR_SOURCE_DIR) + "/Data/scenes/moving-camera.yaml";
  const auto sequence =
    Render("'" + scene + "' --json --quiet --frames 0:2 -o '" + dir + "/catar_json_%02d.png'");
  ASSERT_EQ(sequence.status, 0) << sequence.output;
  const auto readSequence = catar_test::RunProgram(CATAR_SYSTEM_PYTHON,
    "-c 'import json, sys\nd = json.loads(sys.argv[1])\n"
    "assert d[\"frames\"] == 2 and d[\"first\"] == 0 and d[\"last\"] == 1, d\n"
    "assert d[\"stages_ms\"][\"composite\"][\"mean\"] > 0, d' '" +
      sequence.output + "'");
  EXPECT_EQ(readSequence.status, 0) << readSequence.output << sequence.output;
  const auto quiet = Render("--quiet -o '" + dir + "/catar_quiet.png'");
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.output, "");
  // Without either: the image, its triangles and the time of each stage, as the help says.
  const auto plain = Render("-o '" + dir + "/catar_plain.png'");
  EXPECT_EQ(plain.status, 0);
  for (const char* line :
    { "image: 1328 x 1048, ", "  projection ", "  composite ", "  per frame ", "wrote " })
  {
    EXPECT_NE(plain.output.find(line), std::string::npos) << line << " in\n" << plain.output;
  }
}

// --reference renders with the exact ray tracer: the same silhouette as the fast path (the demo's
// triangles are small), other pixels here and there; --samples needs it.
TEST(RenderProgram, ReferenceRenderer)
{
  if (catar_test::RunProgram(CATAR_SYSTEM_PYTHON, "-c 'import numpy, PIL'").status != 0)
  {
    GTEST_SKIP() << "no numpy and PIL in " << CATAR_SYSTEM_PYTHON;
  }
  const std::string dir = ::testing::TempDir();
  const std::string fast = dir + "/catar_fast_ids.npy", exact = dir + "/catar_exact_ids.npy";
  const auto a = Render("--quiet -o '" + dir + "/catar_fast.png' --ids '" + fast + "'");
  ASSERT_EQ(a.status, 0) << a.output;
  const auto b = Render("--quiet --reference --samples 2 -o '" + dir + "/catar_exact.png' --ids '" +
    exact + "' --json");
  ASSERT_EQ(b.status, 0) << b.output;
  const auto compare = catar_test::RunProgram(CATAR_SYSTEM_PYTHON,
    "-c 'import numpy, PIL.Image as I\n"
    "f = numpy.load(\"" +
      fast + "\") >= 0\ne = numpy.load(\"" + exact +
      "\") >= 0\n"
      "iou = (f & e).sum() / (f | e).sum()\n"
      "a = numpy.asarray(I.open(\"" +
      dir +
      "/catar_fast.png\")).astype(int)\n"
      "b = numpy.asarray(I.open(\"" +
      dir +
      "/catar_exact.png\")).astype(int)\n"
      "print(\"IoU\", iou, \"differing pixels\", (abs(a - b).max(axis=2) > 8).sum())\n"
      "assert iou > 0.97, iou\nassert (a != b).any()'");
  EXPECT_EQ(compare.status, 0) << compare.output;
  std::cout << "[ cli      ] fast against --reference: " << compare.output;
  EXPECT_EQ(Render("--samples 2").status, 2);

  // --alpha with --reference: the objects opaque (alpha 255) exactly where a ray meets them (one
  // ray a pixel), the rest transparent; the same alpha as the fast path's nearly everywhere.
  const std::string fastAlpha = dir + "/catar_fast_alpha.png",
                    exactAlpha = dir + "/catar_exact_alpha.png";
  ASSERT_EQ(Render("--quiet --alpha -o '" + fastAlpha + "'").status, 0);
  const auto c = Render(
    "--quiet --reference --alpha -o '" + exactAlpha + "' --ids '" + dir + "/catar_alpha_ids.npy'");
  ASSERT_EQ(c.status, 0) << c.output;
  const auto alpha = catar_test::RunProgram(CATAR_SYSTEM_PYTHON,
    "-c 'import numpy, PIL.Image as I\n"
    "e = numpy.asarray(I.open(\"" +
      exactAlpha + "\"))[..., 3]\nf = numpy.asarray(I.open(\"" + fastAlpha +
      "\"))[..., 3]\nseen = numpy.load(\"" + dir +
      "/catar_alpha_ids.npy\") >= 0\n"
      "assert 1000 < seen.sum() < seen.size // 2, seen.sum()\n"
      "assert (e[seen] == 255).all() and (e[~seen] == 0).all(), (e[seen].min(), e[~seen].max())\n"
      "agree = (e == f).mean()\nprint(\"alpha agrees on\", agree)\nassert agree > 0.995, agree'");
  EXPECT_EQ(alpha.status, 0) << alpha.output;
}

// Long work shows its progress (here from the start: CATAR_PROGRESS_AFTER=0), a line at every
// tenth when standard error is not a terminal; --quiet shows none.
TEST(RenderProgram, ProgressOfLongWork)
{
  const std::string dir = ::testing::TempDir();
  const auto shown = catar_test::RunProgram("/usr/bin/env",
    "CATAR_PROGRESS_AFTER=0 '" + std::string(CATAR_RENDER_PROGRAM) + "' --reference -o '" + dir +
      "/catar_progress.png' --pixel-tolerance 4");
  ASSERT_EQ(shown.status, 0) << shown.output;
  EXPECT_NE(shown.output.find("reference render: 100%"), std::string::npos) << shown.output;
  EXPECT_NE(shown.output.find("remeshing "), std::string::npos) << shown.output;
  EXPECT_EQ(shown.output.find('\r'), std::string::npos) << "a bar where no terminal is";
  const auto quiet = catar_test::RunProgram("/usr/bin/env",
    "CATAR_PROGRESS_AFTER=0 '" + std::string(CATAR_RENDER_PROGRAM) + "' --reference --quiet -o '" +
      dir + "/catar_progress.png'");
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.output, "");
}
