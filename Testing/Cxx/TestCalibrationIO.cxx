// Calibration files: round trips in YAML and JSON, accepted spellings, clear errors, and the lens
// model against OpenCV's own projectPoints.
#include "CalibrationIO.h"
#include "Projector.h"
#include "SphereMirror.h"
#include "TestCameras.h"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>

using namespace catar;
using catar_test::Sphere;

namespace
{
CameraModel Sample()
{
  CameraModel m;
  m.intrinsics = Intrinsics{ 1100.5, 1050.25, 640.2, 470.8, 0.7, 1280, 960 };
  m.distortion = Distortion{ -0.21, 0.08, 0.0012, -0.0007, -0.01 };
  m.mirror = SphereMirror{ Vec3(0.01, -0.02, 0.2), 0.06 };
  m.worldToCamera << 0, -1, 0, 0.1, 1, 0, 0, -0.2, 0, 0, 1, 0.5, 0, 0, 0, 1;
  return m;
}

std::string TempPath(const std::string& name)
{
  return ::testing::TempDir() + "/catar_" + name;
}

void ExpectSame(const CameraModel& a, const CameraModel& b)
{
  EXPECT_DOUBLE_EQ(a.intrinsics.fx, b.intrinsics.fx);
  EXPECT_DOUBLE_EQ(a.intrinsics.fy, b.intrinsics.fy);
  EXPECT_DOUBLE_EQ(a.intrinsics.cx, b.intrinsics.cx);
  EXPECT_DOUBLE_EQ(a.intrinsics.cy, b.intrinsics.cy);
  EXPECT_DOUBLE_EQ(a.intrinsics.skew, b.intrinsics.skew);
  EXPECT_EQ(a.intrinsics.width, b.intrinsics.width);
  EXPECT_EQ(a.intrinsics.height, b.intrinsics.height);
  EXPECT_DOUBLE_EQ(a.distortion.k1, b.distortion.k1);
  EXPECT_DOUBLE_EQ(a.distortion.p2, b.distortion.p2);
  EXPECT_DOUBLE_EQ(a.distortion.k3, b.distortion.k3);
  EXPECT_EQ(Sphere(a.mirror).center, Sphere(b.mirror).center);
  EXPECT_DOUBLE_EQ(Sphere(a.mirror).radius, Sphere(b.mirror).radius);
  EXPECT_EQ(a.worldToCamera, b.worldToCamera);
}

bool ParseText(const std::string& text, CameraModel& m, std::string& error)
{
  return ParseCalibration(text, m, error);
}
} // namespace

TEST(CalibrationIO, RoundTripYamlAndJson)
{
  const CameraModel m = Sample();
  for (const std::string ext : { ".yaml", ".yml", ".json" })
  {
    const std::string path = TempPath("roundtrip" + ext);
    std::string error;
    ASSERT_TRUE(SaveCalibration(path, m, error)) << error;
    CameraModel back;
    ASSERT_TRUE(LoadCalibration(path, back, error)) << error;
    ExpectSame(m, back);
    std::remove(path.c_str());
  }
  // And through text.
  CameraModel back;
  std::string error;
  ASSERT_TRUE(ParseText(CalibrationToString(m, true), back, error)) << error;
  ExpectSame(m, back);
}

// A written YAML calibration starts with the standard directive "%YAML 1.1" (OpenCV's own
// "%YAML:1.0" is refused by standard YAML parsers), and OpenCV's FileStorage still reads it.
TEST(CalibrationIO, WrittenYamlIsStandardAndOpenCVReadsIt)
{
  const CameraModel m = Sample();
  const std::string text = CalibrationToString(m);
  ASSERT_EQ(text.rfind("%YAML 1.1\n", 0), 0u) << text.substr(0, 40);
  EXPECT_EQ(text.find("%YAML:"), std::string::npos);
  cv::FileStorage in(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(in.isOpened());
  EXPECT_EQ(static_cast<int>(in["image_width"]), m.intrinsics.width);
  EXPECT_EQ(static_cast<int>(in["image_height"]), m.intrinsics.height);
  cv::Mat k;
  in["camera_matrix"] >> k;
  ASSERT_EQ(k.rows, 3);
  ASSERT_EQ(k.cols, 3);
  EXPECT_DOUBLE_EQ(k.at<double>(0, 0), m.intrinsics.fx);
  EXPECT_DOUBLE_EQ(k.at<double>(1, 2), m.intrinsics.cy);
}

TEST(CalibrationIO, PlainSequencesAndOptionalKeys)
{
  const std::string text = R"({
    "image_width": 640, "image_height": 480,
    "camera_matrix": [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1],
    "mirror": { "type": "sphere", "center": [0, 0, 0.3], "radius": 0.1 }
  })";
  CameraModel m;
  std::string error;
  ASSERT_TRUE(ParseText(text, m, error)) << error;
  EXPECT_EQ(m.intrinsics.width, 640);
  EXPECT_DOUBLE_EQ(m.intrinsics.cy, 239.5);
  EXPECT_TRUE(m.distortion.IsZero());
  EXPECT_EQ(m.worldToCamera, Mat4::Identity());
  EXPECT_DOUBLE_EQ(Sphere(m.mirror).center.z(), 0.3);
}

TEST(CalibrationIO, ErrorsNameTheProblem)
{
  struct Case
  {
    std::string text;
    std::string expected;
  };
  const std::string good = R"("image_width": 640, "image_height": 480,
    "camera_matrix": [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1])";
  const std::vector<Case> cases = {
    { "{" + good + "}", "mirror" },
    { R"({"image_width": 640, "camera_matrix": [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1],
         "mirror": {"center": [0,0,1], "radius": 0.1}})",
      "image_height" },
    { "{" + good + R"(, "mirror": {"center": [0,0,1]}})", "radius" },
    { "{" + good + R"(, "mirror": {"center": [0,0], "radius": 0.1}})", "mirror.center" },
    { "{" + good + R"(, "mirror": {"type": "cone", "center": [0,0,1], "radius": 0.1}})", "cone" },
    { "{" + good + R"(, "mirror": {"center": [0,0,0.05], "radius": 0.1}})", "inside" },
    { "{" + good + R"(, "mirror": {"center": [0,0,1], "radius": -0.1}})", "radius" },
    { "{" + good + R"(, "mirror": {"center": [0,0,1], "radius": 0.1},
         "distortion_coefficients": [1, 2, 3]})",
      "distortion" },
    { "{" + good + R"(, "mirror": {"center": [0,0,1], "radius": 0.1},
         "world_to_camera": [2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})",
      "rotation" },
    { R"({"image_width": 640, "image_height": 480, "camera_matrix": [-5, 0, 1, 0, 5, 1, 0, 0, 1],
         "mirror": {"center": [0,0,1], "radius": 0.1}})",
      "focal" },
  };
  for (const Case& c : cases)
  {
    CameraModel m;
    const CameraModel before = m;
    std::string error;
    EXPECT_FALSE(ParseText(c.text, m, error)) << c.text;
    EXPECT_NE(error.find(c.expected), std::string::npos)
      << "error '" << error << "' lacks '" << c.expected << "'";
    ExpectSame(before, m); // untouched on failure
  }
  CameraModel m;
  std::string error;
  EXPECT_FALSE(LoadCalibration("/nonexistent/calibration.yaml", m, error));
  EXPECT_NE(error.find("/nonexistent/calibration.yaml"), std::string::npos);
  const std::string garbage = TempPath("garbage.yaml");
  std::ofstream(garbage) << "%YAML:1.0\n---\nimage_width: [1, 2\n";
  EXPECT_FALSE(LoadCalibration(garbage, m, error));
  EXPECT_FALSE(error.empty());
  std::remove(garbage.c_str());
}

// Files written by OpenCV's own FileStorage (YAML with its %YAML:1.0 header and !!opencv-matrix,
// and JSON with "type_id") load unchanged: the writer is OpenCV's, not the project's.
TEST(CalibrationIO, ReadsWhatOpenCVWrites)
{
  const CameraModel m = Sample();
  for (const std::string ext : { ".yaml", ".json" })
  {
    cv::FileStorage out(ext, cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    ASSERT_TRUE(out.isOpened());
    out << "image_width" << m.intrinsics.width << "image_height" << m.intrinsics.height;
    cv::Mat K = (cv::Mat_<double>(3, 3) << m.intrinsics.fx, m.intrinsics.skew, m.intrinsics.cx, 0,
      m.intrinsics.fy, m.intrinsics.cy, 0, 0, 1);
    out << "camera_matrix" << K;
    const Distortion& d = m.distortion;
    out << "distortion_coefficients" << (cv::Mat_<double>(5, 1) << d.k1, d.k2, d.p1, d.p2, d.k3);
    out << "mirror"
        << "{"
        << "type"
        << "sphere"
        << "center" << std::vector<double>{ 0.01, -0.02, 0.2 } << "radius" << 0.06 << "}";
    cv::Mat P(4, 4, CV_32F); // single precision: the reader converts any element type
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        P.at<float>(r, c) = static_cast<float>(m.worldToCamera(r, c));
      }
    }
    out << "world_to_camera" << P;
    const std::string text = out.releaseAndGetString();
    ASSERT_NE(text.find(ext == ".yaml" ? "!!opencv-matrix" : "opencv-matrix"), std::string::npos);
    CameraModel back;
    std::string error;
    ASSERT_TRUE(ParseText(text, back, error)) << error << "\n" << text;
    EXPECT_DOUBLE_EQ(back.intrinsics.fx, m.intrinsics.fx);
    EXPECT_DOUBLE_EQ(back.intrinsics.skew, m.intrinsics.skew);
    EXPECT_DOUBLE_EQ(back.distortion.k3, m.distortion.k3);
    EXPECT_DOUBLE_EQ(Sphere(back.mirror).radius, 0.06);
    EXPECT_NEAR(back.worldToCamera(1, 3), m.worldToCamera(1, 3), 1e-7); // as OpenCV prints floats
  }
}

// YAML as people write it: no header, block sequences, comments, booleans are not numbers,
// quoted numbers are strings, a key given twice is an error, syntax errors give line and column.
TEST(CalibrationIO, PlainYamlAndItsErrors)
{
  const std::string body = R"(# a camera
image_width: 640
image_height: 480
camera_matrix:
  - 500
  - 0
  - 319.5
  - 0
  - 500
  - 239.5
  - 0
  - 0
  - 1
mirror:
  type: sphere
  center: [0, 0, +0.3]
  radius: .1
)";
  CameraModel m;
  std::string error;
  ASSERT_TRUE(ParseText(body, m, error)) << error;
  EXPECT_DOUBLE_EQ(m.intrinsics.cx, 319.5);
  EXPECT_DOUBLE_EQ(Sphere(m.mirror).radius, 0.1);
  EXPECT_DOUBLE_EQ(Sphere(m.mirror).center.z(), 0.3);

  struct Case
  {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
    { body + "image_width: 320\n", "line 18: key 'image_width' is given twice" },
    { "image_width: \"640\"\n" + body.substr(body.find("image_height")), "'image_width'" },
    { body + "world_to_camera: true\n", "'world_to_camera' must be a number" },
    { body + "world_to_camera: [1, 0, 0, 0,\n  0, 1, 0]]\n", "line 19, column" },
    { body + "  radius: 0x10\n", "" }, // any error: a duplicate or a non-number
    { "<?xml version=\"1.0\"?>\n<opencv_storage></opencv_storage>\n", "calibration" },
    { std::string("image_width: 640\0\n", 18), "NUL" },
    { "a: &a [0, 0, 0, 0, 0, 0, 0, 0]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a]\n"
      "c: &c [*b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c]\n"
      "e: &e [*d, *d, *d, *d, *d, *d, *d, *d]\nf: &f [*e, *e, *e, *e, *e, *e, *e, *e]\n"
      "g: &g [*f, *f, *f, *f, *f, *f, *f, *f]\nh: &h [*g, *g, *g, *g, *g, *g, *g, *g]\n",
      "aliases are expanded" },
  };
  for (const Case& c : cases)
  {
    CameraModel before;
    CameraModel after = before;
    EXPECT_FALSE(ParseText(c.text, after, error)) << c.text;
    EXPECT_NE(error.find(c.expected), std::string::npos)
      << "error '" << error << "' lacks '" << c.expected << "'";
    ExpectSame(before, after);
  }
}

// ROS camera_info, as ROS's camera_calibration writes it, with the mirror beside it: the lens as
// the same calibration written with plain lists.
TEST(CalibrationIO, ReadsRosCameraInfoForTheLens)
{
  const std::string mirror = "mirror: { center: [0, 0, 0.14], radius: 0.05 }\n";
  const std::string ros = "image_width: 640\nimage_height: 480\ncamera_name: narrow_stereo\n"
                          "camera_matrix:\n  rows: 3\n  cols: 3\n"
                          "  data: [480.5, 0.0, 319.25, 0.0, 481.0, 239.75, 0.0, 0.0, 1.0]\n"
                          "distortion_model: plumb_bob\n"
                          "distortion_coefficients:\n  rows: 1\n  cols: 5\n"
                          "  data: [-0.1, 0.02, 0.001, -0.002, 0.0005]\n"
                          "rectification_matrix:\n  rows: 3\n  cols: 3\n"
                          "  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n"
                          "projection_matrix:\n  rows: 3\n  cols: 4\n"
                          "  data: [480.5, 0, 319.25, 0, 0, 481.0, 239.75, 0, 0, 0, 1, 0]\n" +
    mirror;
  const std::string plain =
    "image_width: 640\nimage_height: 480\n"
    "camera_matrix: [480.5, 0.0, 319.25, 0.0, 481.0, 239.75, 0.0, 0.0, 1.0]\n"
    "distortion_coefficients: [-0.1, 0.02, 0.001, -0.002, 0.0005]\n" +
    mirror;
  CameraModel a, b;
  std::string error;
  ASSERT_TRUE(ParseCalibration(ros, a, error)) << error;
  ASSERT_TRUE(ParseCalibration(plain, b, error)) << error;
  EXPECT_EQ(a.intrinsics.fx, 480.5);
  EXPECT_EQ(a.intrinsics.cy, 239.75);
  EXPECT_EQ(a.distortion.k1, -0.1);
  EXPECT_EQ(a.distortion.k3, 0.0005);
  EXPECT_EQ(a.intrinsics.fx, b.intrinsics.fx);
  EXPECT_EQ(a.intrinsics.fy, b.intrinsics.fy);
  EXPECT_EQ(a.distortion.p2, b.distortion.p2);
  // Other models, and matrices whose size does not match, are refused by name.
  std::string other = ros;
  other.replace(other.find("plumb_bob"), 9, "fov");
  EXPECT_FALSE(ParseCalibration(other, a, error));
  EXPECT_NE(error.find("distortion_model"), std::string::npos) << error;
  std::string wrong = ros;
  wrong.replace(wrong.find("rows: 1"), 7, "rows: 2");
  EXPECT_FALSE(ParseCalibration(wrong, a, error));
  EXPECT_NE(error.find("distortion_coefficients"), std::string::npos) << error;
}

// Every key is checked: a misspelt one is an error that names it and the nearest known key (a
// misspelt optional key would otherwise be a silently used default). The other keys of the files
// ROS and OpenCV's calibration samples write are read past.
TEST(CalibrationIO, UnknownKeysAreErrorsWithSuggestions)
{
  const std::string lens = "image_width: 640\nimage_height: 480\n"
                           "camera_matrix: [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1]\n";
  const std::string mirror = "mirror: { center: [0, 0, 0.3], radius: 0.1 }\n";
  struct Case
  {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
    { lens + mirror + "distortion_coeficients: [0.1, 0, 0, 0, 0]\n",
      "unknown key 'distortion_coeficients' (did you mean 'distortion_coefficients'?)" },
    { lens + mirror + "world_to_camer: [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]\n",
      "(did you mean 'world_to_camera'?)" },
    { lens + "mirror: { center: [0, 0, 0.3], radius: 0.1, radus: 0.2 }\n",
      "mirror type 'sphere': unknown key 'radus' (did you mean 'radius'?)" },
    { lens +
        "mirror: { type: hyperboloid, a: 0.02, b: 0.03, radius: 0.1,\n"
        "  mirror_to_camera: [1,0,0,0, 0,1,0,0, 0,0,1,0.2, 0,0,0,1] }\n",
      "mirror type 'hyperboloid': unknown key 'radius'" },
    { lens + mirror + "fisheye_model: 1\ndistortion_coefficients: [0.1, 0, 0, 0, 0]\n",
      "a fisheye lens must have 4 numbers" },
  };
  for (const Case& c : cases)
  {
    CameraModel m;
    std::string error;
    EXPECT_FALSE(ParseCalibration(c.text, m, error)) << c.text;
    EXPECT_NE(error.find(c.expected), std::string::npos)
      << "error '" << error << "' lacks '" << c.expected << "'";
  }

  // As OpenCV's camera_calibration sample writes its output, with the mirror added.
  cv::FileStorage out(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  out << "calibration_time"
      << "Tue 24 Nov 2026"
      << "nr_of_frames" << 25 << "image_width" << 640 << "image_height" << 480;
  out << "board_width" << 9 << "board_height" << 6 << "square_size" << 0.025;
  out << "fix_aspect_ratio" << 1.0 << "flags" << 2 << "fisheye_model" << 0;
  out << "camera_matrix" << (cv::Mat_<double>(3, 3) << 500, 0, 319.5, 0, 500, 239.5, 0, 0, 1);
  out << "distortion_coefficients" << (cv::Mat_<double>(5, 1) << -0.2, 0.05, 0, 0, 0);
  out << "avg_reprojection_error" << 0.31;
  out << "per_view_reprojection_errors" << cv::Mat(cv::Mat_<float>(25, 1, 0.3f));
  out << "extrinsic_parameters" << cv::Mat(cv::Mat_<double>(25, 6, 0.1));
  const std::string text =
    out.releaseAndGetString() + "mirror: { type: sphere, center: [0, 0, 0.3], radius: 0.1 }\n";
  CameraModel m;
  std::string error;
  ASSERT_TRUE(ParseCalibration(text, m, error)) << error << "\n" << text;
  EXPECT_DOUBLE_EQ(m.distortion.k1, -0.2);
  EXPECT_DOUBLE_EQ(Sphere(m.mirror).radius, 0.1);
}

TEST(CalibrationIO, SavesOnlyFormatsItReads)
{
  std::string error;
  EXPECT_FALSE(SaveCalibration(TempPath("camera.xml"), Sample(), error));
  EXPECT_NE(error.find(".yaml, .yml or .json"), std::string::npos) << error;
  const std::string upper = TempPath("CAMERA.YAML");
  ASSERT_TRUE(SaveCalibration(upper, Sample(), error)) << error;
  CameraModel back;
  ASSERT_TRUE(LoadCalibration(upper, back, error)) << error;
  ExpectSame(Sample(), back);
  std::remove(upper.c_str());
}

TEST(CameraModel, LensMatchesOpenCVProjectPoints)
{
  CameraModel m = Sample();
  m.intrinsics.skew = 0.0; // cv::projectPoints has no skew
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::vector<cv::Point3d> pts;
  for (int i = 0; i < 2000; ++i)
  {
    pts.emplace_back(u(rng), u(rng), 1.0 + 0.5 * u(rng));
  }
  cv::Mat K = (cv::Mat_<double>(3, 3) << m.intrinsics.fx, 0, m.intrinsics.cx, 0, m.intrinsics.fy,
    m.intrinsics.cy, 0, 0, 1);
  cv::Mat D = (cv::Mat_<double>(1, 5) << m.distortion.k1, m.distortion.k2, m.distortion.p1,
    m.distortion.p2, m.distortion.k3);
  std::vector<cv::Point2d> px;
  cv::projectPoints(pts, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, px);
  for (size_t i = 0; i < pts.size(); ++i)
  {
    const Vec2 mine = m.DirectionToPixel(Vec3(pts[i].x, pts[i].y, pts[i].z));
    EXPECT_NEAR(mine.x(), px[i].x, 1e-9);
    EXPECT_NEAR(mine.y(), px[i].y, 1e-9);
    // And the inverse recovers the normalised coordinates.
    Vec2 xy;
    ASSERT_TRUE(m.PixelToNormalized(mine, xy));
    EXPECT_NEAR(xy.x(), pts[i].x / pts[i].z, 1e-12);
    EXPECT_NEAR(xy.y(), pts[i].y / pts[i].z, 1e-12);
  }
}

TEST(CameraModel, ResizedKeepsRaysOnTheSameRelativePositions)
{
  const CameraModel m = Sample();
  const CameraModel half = m.Resized(m.intrinsics.width / 2, m.intrinsics.height / 2);
  const Vec3 d(0.1, -0.05, 1.0);
  const Vec2 a = m.DirectionToPixel(d);
  const Vec2 b = half.DirectionToPixel(d);
  EXPECT_NEAR((b.x() + 0.5) * 2.0, a.x() + 0.5, 1e-9);
  EXPECT_NEAR((b.y() + 0.5) * 2.0, a.y() + 0.5, 1e-9);
}
