// The mirror from its outline (Module/Vision/MirrorOutline.h) on frames the project did not
// render: POV-Ray's anti-aliased images of a physical mirror sphere (reflectance 0.7) in a room,
// before a bright (0.9) or a dark (0.1) backdrop, which the mirror reflects at its rim as a real
// one does: the rim's contrast is only the backdrop's times 0.3, weaker than the reflection's own
// edges inside it. Clean, and with a real lens's blur (1 px) and noise (sigma 6). The truth is the
// centre POV-Ray was given. What must hold: the centre within 0.1 % of its distance on every
// frame, and an image with no mirror in it refused. Skipped where povray is not installed.
#include "MarkerFrameScenes.h"
#include "MirrorOutline.h"
#include "PovRayOutlineFrames.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace catar_independent;

namespace
{
std::string Folder()
{
  char folder[] = "/tmp/catar-outline-XXXXXX";
  return mkdtemp(folder);
}

// The centre found in the frame, or false with the detection's or the fit's sentence.
bool CentreOf(const OutlineScene& scene, const cv::Mat& bgr, catar::Vec3& centre,
  catar::SphereOutlineReport& report, std::string& error)
{
  catar::CameraModel camera;
  camera.intrinsics = scene.intrinsics;
  const std::vector<std::uint8_t> rgba = RgbaPixels(bgr);
  std::vector<catar::Vec2> outline;
  return catar::DetectMirrorOutline(camera, bgr.cols, bgr.rows, rgba.data(), outline, error) &&
    catar::SphereFromOutline(camera, scene.radius, outline, centre, report, error);
}
// The scene rendered by POV-Ray into dir/NAME.png, read back (BGR); empty, with a failure, when
// POV-Ray failed.
cv::Mat Rendered(const std::string& dir, const std::string& name, const OutlineScene& scene)
{
  std::string png, error;
  if (!RenderOutlineFrame(dir, name, scene, png, error))
  {
    ADD_FAILURE() << error;
    return cv::Mat();
  }
  return cv::imread(png, cv::IMREAD_COLOR);
}
} // namespace

TEST(MirrorOutlinePovRay, BrightAndDarkBackdrops)
{
  if (!HavePovRay())
  {
    GTEST_SKIP() << "povray is not installed";
  }
  const std::string dir = Folder();
  struct Case
  {
    std::string name;
    OutlineScene scene;
  };
  std::vector<Case> cases;
  OutlineScene onAxis;
  OutlineScene offAxis;
  offAxis.centre = catar::Vec3(0.03, -0.02, 0.18);
  for (const double backdrop : { 0.9, 0.1 })
  {
    onAxis.backdrop = offAxis.backdrop = backdrop;
    const std::string tone = backdrop > 0.5 ? "bright" : "dark";
    cases.push_back({ tone + "-demo", onAxis });
    cases.push_back({ tone + "-off-axis", offAxis });
  }
  for (const Case& c : cases)
  {
    const cv::Mat clean = Rendered(dir, c.name, c.scene);
    ASSERT_FALSE(clean.empty());
    std::string error;
    for (const bool noisy : { false, true })
    {
      SCOPED_TRACE(c.name + (noisy ? " noisy" : " clean"));
      const cv::Mat frame = noisy ? LensBlurAndNoise(clean, 1.0, 6.0, 11) : clean;
      catar::Vec3 centre;
      catar::SphereOutlineReport report;
      ASSERT_TRUE(CentreOf(c.scene, frame, centre, report, error)) << error;
      const double distance = c.scene.centre.norm();
      const double percent = 100.0 * (centre - c.scene.centre).norm() / distance;
      std::cout << "[ outline  ] " << c.name << (noisy ? " noisy" : " clean") << ": "
                << report.pointCount << " points, rms " << report.rmsPixels << " px; centre error "
                << 1e3 * (centre - c.scene.centre).norm() << " mm (" << percent << " % of "
                << 1e3 * distance << " mm), sigma " << 100.0 * report.centreSigma / distance << " %"
                << std::endl;
      // Measured: 0.0008 to 0.021 %, fixed to 0.0008-0.043 % at three sigmas; the strong edges
      // alone (a dark backdrop): 7.7 to 41 %.
      EXPECT_LT(percent, 0.1);
      EXPECT_LT(report.rmsPixels, 0.5);
      EXPECT_LT(300.0 * report.centreSigma / distance, 0.1) << "a good fit refused";
    }
  }
}

// A frame with no mirror (the backdrop and the room, noisy): refused, not fitted to noise.
TEST(MirrorOutlinePovRay, NoMirrorIsRefused)
{
  if (!HavePovRay())
  {
    GTEST_SKIP() << "povray is not installed";
  }
  OutlineScene scene;
  scene.centre = catar::Vec3(0.0, 0.0, -5.0); // behind the camera, out of view
  scene.backdropBehind = 5.4;
  std::string png, error;
  ASSERT_TRUE(RenderOutlineFrame(Folder(), "no-mirror", scene, png, error)) << error;
  const cv::Mat frame = LensBlurAndNoise(cv::imread(png, cv::IMREAD_COLOR), 1.0, 6.0, 5);
  catar::Vec3 centre;
  catar::SphereOutlineReport report;
  const bool found = CentreOf(scene, frame, centre, report, error);
  EXPECT_TRUE(!found || report.rmsPixels > 3.0)
    << "a mirror found where there is none: " << report.pointCount << " points, rms "
    << report.rmsPixels << " px";
  std::cout << "[ outline  ] no mirror: "
            << (found ? "fitted, rms " + std::to_string(report.rmsPixels) + " px" : error)
            << std::endl;
}

// A dome: the sphere cut by a plane 0.3 R from its centre, turned up and towards the camera, on a
// post: the upper part of the outline is the sphere's limb, the lower the cut's circle seen
// aslant (no right circular cone from the camera: the outline's fit leaves it out). The centre
// comes from the limb, within 0.1 % of its distance clean and with eight draws of the noise on
// the bright backdrop, 0.15 % on the dark one.
TEST(MirrorOutlinePovRay, DomeMirror)
{
  if (!HavePovRay())
  {
    GTEST_SKIP() << "povray is not installed";
  }
  const std::string dir = Folder();
  OutlineScene scene;
  scene.domeAxis = catar::Vec3(0.0, -1.0, -0.5).normalized();
  scene.domeCut = 0.3;
  for (const double backdrop : { 0.9, 0.1 })
  {
    scene.backdrop = backdrop;
    const std::string name = backdrop > 0.5 ? "dome-bright" : "dome-dark";
    const cv::Mat clean = Rendered(dir, name, scene);
    ASSERT_FALSE(clean.empty());
    std::string error;
    for (int seed = 12; seed < 21; ++seed)
    {
      const bool noisy = seed > 12;
      SCOPED_TRACE(name + (noisy ? " noisy" : " clean"));
      const cv::Mat frame = noisy ? LensBlurAndNoise(clean, 1.0, 6.0, seed) : clean;
      catar::Vec3 centre;
      catar::SphereOutlineReport report;
      EXPECT_TRUE(CentreOf(scene, frame, centre, report, error)) << error;
      const double distance = scene.centre.norm();
      const double percent = 100.0 * (centre - scene.centre).norm() / distance;
      std::cout << "[ outline  ] " << name << (noisy ? " noisy" : " clean") << ": "
                << report.pointCount << " points, rms " << report.rmsPixels << " px; centre error "
                << 1e3 * (centre - scene.centre).norm() << " mm (" << percent << " %), sigma "
                << 100.0 * report.centreSigma / distance << " %" << std::endl;
      // Measured: 0.0007 to 0.010 % (bright), 0.014 to 0.137 % (dark, noisy; the strong edges'
      // ellipse alone, before the rim's search and the cones: 40 to 59 %). Within 0.1 %, or
      // refused: catadioptric-mirror-outline refuses a centre fixed only to more than 0.1 % of
      // its distance at three sigmas (--max-uncertainty), which six of the eight dark, noisy
      // draws are (three sigmas 0.11-0.15 %), the one 0.137 % off among them.
      const double uncertainty = 300.0 * report.centreSigma / distance;
      EXPECT_TRUE(percent < 0.1 || uncertainty > 0.1)
        << percent << " % off, yet fixed to " << uncertainty << " % at three sigmas";
      if (backdrop > 0.5 || !noisy)
      {
        EXPECT_LT(percent, 0.1);
        EXPECT_LT(uncertainty, 0.1) << "a good fit refused";
      }
    }
  }
}

// A hyperbolic mirror (a = 3 cm, b = 4 cm, its sheet from the vertex to z = 7 cm, tilted 4 degrees,
// as Data/scenes/hyperbolic-tilted.yaml) seen through a wider lens (f = 500 px): the outline is
// its rim, a circle seen aslant. QuadricFromRim from a first guess 3 mm and 4 mm off: with the
// axis kept (the rig's true one), the rim's centre within 0.1 % of its distance; with the axis
// fitted, never silently wrong: the true axis within the range of tilts reported to fit alike
// (and four sigmas).
TEST(MirrorOutlinePovRay, HyperboloidRim)
{
  if (!HavePovRay())
  {
    GTEST_SKIP() << "povray is not installed";
  }
  const std::string dir = Folder();
  const double tilt = 4.0 * 3.14159265358979323846 / 180.0;
  OutlineScene scene;
  scene.intrinsics = catar::Intrinsics{ 500.0, 500.0, 663.5, 523.5, 0.0, 1328, 1048 };
  scene.hyperboloid = true;
  scene.mirrorToCamera << 1, 0, 0, 0, 0, std::cos(tilt), -std::sin(tilt), 0, 0, std::sin(tilt),
    std::cos(tilt), 0.05, 0, 0, 0, 1;
  const catar::Vec3 rimCentre =
    scene.mirrorToCamera.topLeftCorner<3, 3>() * catar::Vec3(0, 0, scene.zmax) +
    scene.mirrorToCamera.topRightCorner<3, 1>();
  const catar::Vec3 axis = scene.mirrorToCamera.topLeftCorner<3, 3>().col(2);
  scene.centre = rimCentre;
  catar::CameraModel camera;
  camera.intrinsics = scene.intrinsics;
  std::vector<double> parameters = { scene.a, scene.b };
  for (int row = 0; row < 4; ++row)
  {
    for (int col = 0; col < 4; ++col)
    {
      parameters.push_back(scene.mirrorToCamera(row, col));
    }
  }
  parameters.push_back(scene.zmin);
  parameters.push_back(scene.zmax);
  const catar::MirrorDescription truth("hyperboloid", parameters);
  for (const double backdrop : { 0.9, 0.1 })
  {
    scene.backdrop = backdrop;
    const std::string name = backdrop > 0.5 ? "rim-bright" : "rim-dark";
    const cv::Mat clean = Rendered(dir, name, scene);
    ASSERT_FALSE(clean.empty());
    std::string error;
    for (const bool noisy : { false, true })
    {
      SCOPED_TRACE(name + (noisy ? " noisy" : " clean"));
      const cv::Mat frame = noisy ? LensBlurAndNoise(clean, 1.0, 6.0, 17) : clean;
      const std::vector<std::uint8_t> rgba = RgbaPixels(frame);
      catar::MirrorOutlineOptions detection;
      detection.limb = false;
      std::vector<catar::Vec2> outline;
      ASSERT_TRUE(catar::DetectMirrorOutline(
        camera, frame.cols, frame.rows, rgba.data(), detection, outline, error))
        << error;
      for (const bool fitAxis : { false, true })
      {
        catar::MirrorDescription mirror = truth;
        mirror.parameters[2 + 3] += 0.003;
        mirror.parameters[2 + 11] += 0.004;
        catar::RimFitOptions options;
        options.fitAxis = fitAxis;
        catar::RimOutlineReport report;
        ASSERT_TRUE(catar::QuadricFromRim(camera, outline, options, mirror, report, error))
          << error;
        const double percent = 100.0 * (report.rimCentre - rimCentre).norm() / rimCentre.norm();
        const double degrees = std::atan2(axis.cross(report.axis).norm(), axis.dot(report.axis)) *
          180.0 / 3.14159265358979323846;
        std::cout << "[ rim      ] " << name << (noisy ? " noisy" : " clean")
                  << (fitAxis ? ", axis fitted: " : ", axis kept: ") << outline.size()
                  << " points, rms " << report.rmsPixels << " px; rim centre "
                  << 1e3 * (report.rimCentre - rimCentre).norm() << " mm (" << percent
                  << " %), axis " << degrees << " deg off"
                  << (report.ambiguousTilt > 0.0 ? ", two tilts fit" : "") << std::endl;
        // Measured: axis kept 0.0014 to 0.0065 %; axis fitted, the two tilts flagged every time
        // (the one nearer the guess 0.04 to 0.16 degrees off).
        EXPECT_LT(report.rmsPixels, 0.5);
        if (!fitAxis)
        {
          EXPECT_LT(percent, 0.1);
        }
        else
        {
          const double sigma = report.axisSigma * 180.0 / 3.14159265358979323846;
          EXPECT_LT(degrees, report.ambiguousTilt * 180.0 / 3.14159265358979323846 + 4.0 * sigma);
        }
      }
    }
  }
}
