// catadioptric-mirror-outline: a spherical mirror's centre (camera frame) from its outline in a
// camera frame, or a quadric mirror's mounting from its rim (Module/Vision/MirrorOutline.h).
//
//   catadioptric-mirror-outline CALIBRATION IMAGE (--radius R | --rim [--keep-axis])
//                               [-o OUT.yaml] [--overlay OUT.png] [--max-rms PX]
//                               [--max-uncertainty PERCENT]
//
// The calibration gives the camera's intrinsics and distortion; with --radius its mirror is
// replaced by the sphere found, with --rim its quadric mirror's mirror_to_camera is the first
// guess and is replaced. Exit status: 0 success, 1 bad input, no outline or a fit refused, 2 usage
// error.
#include "CalibrationIO.h"
#include "MirrorOutline.h"

#include "CommandLine.h"
#include "FileOutput.h"
#include "ImageFile.h"
#include "RunMain.h"

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

namespace
{
const char* const kProgram = "catadioptric-mirror-outline";

int Error(const std::string& message, int code = 1)
{
  std::fprintf(stderr, "%s: %s\n", kProgram, message.c_str());
  return code;
}

// The image with the outline fitted (red, anti-aliased; `fitted`, pixels) and the detected outline
// points (green pixels) over it.
bool WriteOverlay(const std::string& path, const cv::Mat& bgr,
  const std::vector<catar::Vec2>& points, const std::vector<catar::Vec2>& fitted,
  std::string& error)
{
  cv::Mat drawn = bgr.clone();
  constexpr int kShift = 4; // sub-pixel drawing: coordinates in 1/16 pixel
  const auto at = [](const catar::Vec2& p) {
    // Pixel centres are integers in the image convention and in OpenCV's drawing.
    return cv::Point(static_cast<int>(std::lround(p.x() * (1 << kShift))),
      static_cast<int>(std::lround(p.y() * (1 << kShift))));
  };
  std::vector<cv::Point> curve;
  for (const catar::Vec2& p : fitted)
  {
    if (p.allFinite() && std::abs(p.x()) < 1e6 && std::abs(p.y()) < 1e6)
    {
      curve.push_back(at(p));
    }
  }
  if (!curve.empty())
  {
    cv::polylines(drawn, curve, true, cv::Scalar(0, 0, 255), 1, cv::LINE_AA, kShift);
  }
  // Each point as the pixel it lies in, over the curve.
  for (const catar::Vec2& p : points)
  {
    const int x = static_cast<int>(std::lround(p.x())), y = static_cast<int>(std::lround(p.y()));
    if (x >= 0 && y >= 0 && x < drawn.cols && y < drawn.rows)
    {
      drawn.at<cv::Vec3b>(y, x) = cv::Vec3b(0, 255, 0);
    }
  }
  // Encoded in memory (the format by the name's extension), then written whole or not at all.
  const std::size_t dot = path.find_last_of('.');
  const std::string extension = dot == std::string::npos ? std::string() : path.substr(dot);
  std::vector<unsigned char> encoded;
  try
  {
    if (extension.empty() || !cv::imencode(extension, drawn, encoded))
    {
      error = "cannot write '" + path + "': name an image format by its extension (.png, .jpg)";
      return false;
    }
  }
  catch (const cv::Exception&)
  {
    error = "cannot write '" + path + "': no image format has the extension '" + extension +
      "' (.png, .jpg)";
    return false;
  }
  return catar::WriteWholeFile(path, std::string(encoded.begin(), encoded.end()), error);
}
} // namespace

namespace
{
// A fit refused: the overlay still drawn (to show why), the reason printed; exit status 1.
int Refuse(const std::string& why, const std::string& imagePath, const std::string& overlay,
  const cv::Mat& bgr, const std::vector<catar::Vec2>& points,
  const std::vector<catar::Vec2>& fitted)
{
  std::string error;
  if (!overlay.empty())
  {
    WriteOverlay(overlay, bgr, points, fitted, error);
  }
  return Error(imagePath + ": " + why);
}

// What a fit must meet: --max-rms (pixels) and --max-uncertainty (the centre's three sigmas, per
// cent of its distance).
struct FitLimits
{
  double maxRms = 3.0;
  double maxUncertainty = 0.1;
};

// The sphere of that radius from the outline points: printed, written, drawn.
int SphereFromItsOutline(catar::CameraModel camera, const cv::Mat& bgr,
  const std::vector<catar::Vec2>& points, double radius, const FitLimits& limits,
  const std::string& imagePath, const std::string& output, const std::string& overlay)
{
  std::string error;
  catar::Vec3 centre;
  catar::SphereOutlineReport report;
  if (!catar::SphereFromOutline(camera, radius, points, centre, report, error))
  {
    return Error(imagePath + ": " + error);
  }
  const std::vector<catar::Vec2> fitted = catar::SphereOutline(camera, centre, radius, 720);
  const double maxRms = limits.maxRms;
  const double uncertainty = 300.0 * report.centreSigma / report.distance; // 3 sigmas, per cent
  const auto refuse = [&](const std::string& why) {
    return Refuse(why, imagePath, overlay, bgr, points, fitted);
  };
  if (!(report.rmsPixels <= maxRms))
  {
    char text[256];
    std::snprintf(text, sizeof text,
      "the outline found does not fit a sphere's: its %d points lie %.3g px (RMS) from the best "
      "sphere's outline, more than --max-rms %.3g px (a wrong lens calibration, or an edge that "
      "is not the mirror's rim%s)",
      report.pointCount, report.rmsPixels, maxRms, overlay.empty() ? "" : ": see the overlay");
    return refuse(text);
  }
  if (!(uncertainty <= limits.maxUncertainty))
  {
    char text[512];
    std::snprintf(text, sizeof text,
      "the outline fixes the sphere's centre only to %.3g %% of its distance (three sigmas: "
      "%.3g; its %d points lie %.3g px RMS from the sphere's outline), more than "
      "--max-uncertainty %.3g %% (a rim of little contrast against the backdrop: put a bright, "
      "plain one behind the mirror; or a short arc of it, as a lens calibration that is not "
      "right leaves%s)",
      uncertainty, 3.0 * report.centreSigma, report.pointCount, report.rmsPixels,
      limits.maxUncertainty, overlay.empty() ? "" : "; see the overlay");
    return refuse(text);
  }
  std::printf("centre: %.9g %.9g %.9g\n", centre.x(), centre.y(), centre.z());
  std::printf("distance: %.9g\n", report.distance);
  std::printf("centre sigma: %.3g (%.3g %% of the distance)\n", report.centreSigma,
    100.0 * report.centreSigma / report.distance);
  std::printf("outline points: %d\n", report.pointCount);
  std::printf("rms: %.4g px\n", report.rmsPixels);

  camera.mirror = catar::MirrorOfOutline(centre, radius);
  if (!output.empty() && !catar::SaveCalibration(output, camera, error))
  {
    return Error(error);
  }
  if (!overlay.empty() && !WriteOverlay(overlay, bgr, points, fitted, error))
  {
    return Error(error);
  }
  return 0;
}

// The calibration's quadric mirror placed from its rim: printed, written, drawn; refused when
// the rim fits two tilts (unless the axis is kept) or fits poorly.
int PlaceFromRim(catar::CameraModel camera, const cv::Mat& bgr,
  const std::vector<catar::Vec2>& points, bool keepAxis, double maxRms,
  const std::string& imagePath, const std::string& output, const std::string& overlay)
{
  std::string error;
  catar::RimFitOptions options;
  options.fitAxis = !keepAxis;
  catar::RimOutlineReport report;
  catar::MirrorDescription mirror = camera.mirror;
  if (!catar::QuadricFromRim(camera, points, options, mirror, report, error))
  {
    return Error(imagePath + ": " + error);
  }
  const std::vector<catar::Vec2> fitted = catar::RimOutline(camera, report, 720);
  const auto refuse = [&](const std::string& why) {
    return Refuse(why, imagePath, overlay, bgr, points, fitted);
  };
  constexpr double kDegrees = 180.0 / 3.14159265358979323846;
  char text[512];
  if (!(report.rmsPixels <= maxRms))
  {
    std::snprintf(text, sizeof text,
      "the outline found does not fit the mirror's rim: its %d points lie %.3g px (RMS) from the "
      "best rim's image, more than --max-rms %.3g px (a wrong mirror shape or z_range, a wrong "
      "lens calibration, or an edge that is not the rim)",
      report.pointCount, report.rmsPixels, maxRms);
    return refuse(text);
  }
  if (report.ambiguousTilt > 0.0)
  {
    const catar::Vec3& a = report.axis;
    const catar::Vec3& b = report.otherAxis;
    std::snprintf(text, sizeof text,
      "the rim fits two tilts of the mirror %.3g degrees apart equally well (axis %.6f %.6f %.6f "
      "or %.6f %.6f %.6f): a rim seen nearly head-on fixes its distance, not its tilt. With "
      "--keep-axis the first guess's axis is kept and the rim's centre fitted",
      report.ambiguousTilt * kDegrees, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
    return refuse(text);
  }
  std::printf("rim centre: %.9g %.9g %.9g\n", report.rimCentre.x(), report.rimCentre.y(),
    report.rimCentre.z());
  std::printf("axis: %.9g %.9g %.9g%s\n", report.axis.x(), report.axis.y(), report.axis.z(),
    keepAxis ? " (kept)" : "");
  std::printf("rim radius: %.9g (z = %.9g in the mirror frame)\n", report.rimRadius, report.rimZ);
  std::printf(
    "one sigma: centre %.3g, axis %.3g degrees\n", report.centreSigma, report.axisSigma * kDegrees);
  std::printf("moved from the first guess: %.3g, turned %.3g degrees\n", report.shift,
    report.axisTurn * kDegrees);
  std::printf("outline points: %d\n", report.pointCount);
  std::printf("rms: %.4g px\n", report.rmsPixels);
  camera.mirror = mirror;
  if (!output.empty() && !catar::SaveCalibration(output, camera, error))
  {
    return Error(error);
  }
  if (!overlay.empty() && !WriteOverlay(overlay, bgr, points, fitted, error))
  {
    return Error(error);
  }
  return 0;
}

int Run(int argc, char* argv[])
{
  CLI::App app("Finds a spherical mirror's centre (camera frame) from its outline in a camera "
               "frame: detects the outline, fits the sphere of the given radius and prints its "
               "centre, the number of outline points used and their RMS distance (pixels) from "
               "the outline of the sphere found. With --rim, places the calibration's quadric "
               "mirror of revolution (its mirror_to_camera the first guess) from its rim instead. "
               "The calibration gives the camera's intrinsics and distortion. Exit status: 0 "
               "success, 1 bad input, no outline or a fit refused, 2 usage error.",
    kProgram);
  std::string calibration, imagePath, output, overlay;
  double radius = 0.0;
  app.add_option("CALIBRATION", calibration, "calibration file (YAML or JSON)")->required();
  app.add_option("IMAGE", imagePath, "camera frame that shows the whole mirror")->required();
  bool rim = false, keepAxis = false;
  auto* radiusOption =
    app.add_option("--radius", radius, "the sphere's radius, in the calibration's length unit");
  auto* rimOption = app.add_flag("--rim", rim,
    "place the calibration's quadric mirror of revolution (hyperboloid, paraboloid, ...) from "
    "its rim, the circle at the widest end of its z_range; its mirror_to_camera is the first "
    "guess");
  rimOption->excludes(radiusOption);
  app
    .add_flag("--keep-axis", keepAxis,
      "with --rim: keep the first guess's axis and fit the rim's centre only (a rim seen nearly "
      "head-on fixes its distance, not its tilt)")
    ->needs(rimOption);
  app.add_option(
    "-o,--output", output, "write the calibration with the mirror {type: sphere, center, radius}");
  app.add_option("--overlay", overlay,
    "write the image with the detected outline points (green) and the sphere's outline (red), "
    "also when the fit is refused");
  FitLimits limits;
  double& maxRms = limits.maxRms;
  app.add_option("--max-rms", maxRms,
    "refuse a fit whose points lie further than this RMS (pixels) from the sphere's outline: "
    "not a whole sphere's outline (a dome's cut, a wrong lens calibration, a wrong edge); "
    "default 3");
  app.add_option("--max-uncertainty", limits.maxUncertainty,
    "with --radius: refuse a fit that fixes the sphere's centre only to more than this per cent "
    "of its distance at three sigmas (from the fit's residuals and their correlation along the "
    "outline); default 0.1");
  const int parsed = catar::ParseCommandLine(app, kProgram, argc, argv);
  if (parsed >= 0)
  {
    return parsed;
  }

  if (!rim && (!(radius > 0.0) || !std::isfinite(radius)))
  {
    return Error("--radius must be a positive number (got " + std::to_string(radius) +
        "; run with --help for usage)",
      2);
  }

  catar::CameraModel camera;
  std::string error;
  // For a sphere the lens is what is needed: a calibration of the bare camera (no mirror) is read
  // too. For a rim, the mirror is the first guess.
  if (!(rim ? catar::LoadCalibration(calibration, camera, error)
            : catar::LoadLensCalibration(calibration, camera, error)))
  {
    return Error(error);
  }
  // A regular file, whole, of a size the project handles: checked before decoding.
  std::vector<unsigned char> bytes;
  catar::ImageHeader header;
  if (!catar::ReadImageFileBytes(imagePath, bytes, header, error))
  {
    return Error(error);
  }
  // Failures are reported here, in one sentence, not by OpenCV's log.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  cv::Mat bgr;
  try
  {
    bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  }
  catch (const cv::Exception& e)
  {
    return Error("cannot read the image '" + imagePath + "': " + e.what());
  }
  if (bgr.empty())
  {
    return Error("cannot read the image '" + imagePath + "' (missing, or not an image)");
  }
  if (bgr.cols != camera.intrinsics.width || bgr.rows != camera.intrinsics.height)
  {
    return Error("the image '" + imagePath + "' is " + std::to_string(bgr.cols) + " x " +
      std::to_string(bgr.rows) + " pixels but the calibration is for " +
      std::to_string(camera.intrinsics.width) + " x " + std::to_string(camera.intrinsics.height));
  }
  cv::Mat rgba;
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  if (!rgba.isContinuous())
  {
    rgba = rgba.clone();
  }

  std::vector<catar::Vec2> points;
  catar::MirrorOutlineOptions options;
  options.limb = !rim; // a rim seen aslant is any ellipse
  if (!catar::DetectMirrorOutline(
        camera, rgba.cols, rgba.rows, rgba.ptr<std::uint8_t>(0), options, points, error))
  {
    return Error(imagePath + ": " + error);
  }
  return rim
    ? PlaceFromRim(camera, bgr, points, keepAxis, maxRms, imagePath, output, overlay)
    : SphereFromItsOutline(camera, bgr, points, radius, limits, imagePath, output, overlay);
}
} // namespace

int main(int argc, char* argv[])
{
  return catar::RunMain("catadioptric-mirror-outline", Run, argc, argv);
}
