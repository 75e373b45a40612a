// catadioptric-pose: the camera's world-to-camera pose from pixels of known world points
// (Module/Vision/PoseEstimation.h).
//
//   catadioptric-pose CALIBRATION POINTS.csv [-o OUT.yaml] [--threshold PX] [--seed N]
//
// Each CSV row is u,v,X,Y,Z: a pixel (pixel (0,0) is the centre of the top-left pixel) and the
// world point seen there. Exit status: 0 success, 1 bad input or no pose, 2 usage error.
#include "CalibrationIO.h"
#include "FileInput.h"
#include "PoseEstimation.h"

#include "CommandLine.h"
#include "RunMain.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const kProgram = "catadioptric-pose";

int Error(const std::string& message, int code = 1)
{
  std::fprintf(stderr, "%s: %s\n", kProgram, message.c_str());
  return code;
}

std::string Trim(const std::string& s)
{
  const std::size_t first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
  {
    return std::string();
  }
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

std::vector<std::string> SplitFields(const std::string& line)
{
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string field;
  while (std::getline(in, field, ','))
  {
    fields.push_back(Trim(field));
  }
  if (!line.empty() && line.back() == ',')
  {
    fields.emplace_back(); // a trailing comma: an empty last field
  }
  return fields;
}

// A whole field as a finite number.
bool ParseNumber(const std::string& field, double& value)
{
  if (field.empty())
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtod(field.c_str(), &end);
  return errno == 0 && *end == '\0' && std::isfinite(value);
}

bool ParseRow(const std::vector<std::string>& fields, catar::PoseObservation& o)
{
  double v[5];
  if (fields.size() != 5)
  {
    return false;
  }
  for (int k = 0; k < 5; ++k)
  {
    if (!ParseNumber(fields[k], v[k]))
    {
      return false;
    }
  }
  o.pixel = catar::Vec2(v[0], v[1]);
  o.world = catar::Vec3(v[2], v[3], v[4]);
  return true;
}

// A header: the first row, when none of its fields is a number ("u,v,X,Y,Z").
bool IsHeader(const std::vector<std::string>& fields)
{
  double value = 0.0;
  for (const std::string& f : fields)
  {
    if (ParseNumber(f, value))
    {
      return false;
    }
  }
  return true;
}

// Reads the rows u,v,X,Y,Z; skips blank lines, '#' comments (to the end of the line) and a
// header. Returns an empty string, or the sentence that names the bad line.
std::string ReadPoints(const std::string& path, std::vector<catar::PoseObservation>& points)
{
  // A regular file of at most 256 MiB: /dev/zero or a FIFO is refused, not read without end.
  std::string error;
  if (!catar::CheckInputFile(path, std::uint64_t(1) << 28, error))
  {
    return error;
  }
  std::ifstream in(path);
  if (!in)
  {
    return "cannot open '" + path + "'";
  }
  std::string line;
  bool first = true;
  for (int number = 1; std::getline(in, line); ++number)
  {
    const std::string content = Trim(line.substr(0, line.find('#')));
    if (content.empty())
    {
      continue;
    }
    const std::vector<std::string> fields = SplitFields(content);
    catar::PoseObservation o;
    const bool row = ParseRow(fields, o);
    const bool header = !row && first && IsHeader(fields);
    first = false;
    if (header)
    {
      continue;
    }
    if (!row)
    {
      return path + " line " + std::to_string(number) +
        ": expected five finite numbers u,v,X,Y,Z, got \"" + content + "\"";
    }
    points.push_back(o);
  }
  if (in.bad())
  {
    return "cannot read '" + path + "'";
  }
  return std::string();
}

void PrintPose(const catar::PoseResult& r, std::size_t total)
{
  for (int i = 0; i < 4; ++i)
  {
    std::printf("%.9g %.9g %.9g %.9g\n", r.worldToCamera(i, 0), r.worldToCamera(i, 1),
      r.worldToCamera(i, 2), r.worldToCamera(i, 3));
  }
  std::printf("inliers: %d of %zu\n", r.inlierCount, total);
  std::printf("rms: %.6g px\n", r.rmsPixels);
}
} // namespace

namespace
{
int Run(int argc, char* argv[])
{
  CLI::App app(
    "Finds the camera's world-to-camera pose M (p_camera = M p_world) from pixels of\n"
    "known world points seen through its mirror. Prints M, one row per line, then\n"
    "'inliers: N of TOTAL' and 'rms: X px' (the inliers' reprojection error through the\n"
    "mirror). POINTS.csv holds one row u,v,X,Y,Z per point; pixel (0,0) is the centre\n"
    "of the top-left pixel. A header line, blank lines and # comments are skipped.",
    kProgram);
  app.footer("Exit status: 0 success, 1 bad input or no pose found, 2 usage error.");
  std::string calibration, pointsPath, output;
  catar::PoseOptions options;
  const CLI::Validator positive(
    [](std::string& text) {
      double value = 0.0;
      return ParseNumber(text, value) && value > 0.0 ? std::string()
                                                     : std::string("must be a positive number");
    },
    "POSITIVE");
  app.add_option("CALIBRATION", calibration, "calibration file (YAML or JSON)")->required();
  app.add_option("POINTS", pointsPath, "CSV file of u,v,X,Y,Z rows")->required();
  app.add_option("-o,--output", output, "write the calibration with the pose found")
    ->type_name("OUT.yaml");
  app
    .add_option("--threshold", options.inlierThreshold,
      "inlier reprojection error through the mirror (default 2)")
    ->type_name("PX")
    ->check(positive);
  app.add_option("--seed", options.seed, "RANSAC seed (default 0)")->type_name("N");
  const int parsed = catar::ParseCommandLine(app, kProgram, argc, argv);
  if (parsed >= 0)
  {
    return parsed;
  }

  catar::CameraModel camera;
  std::string error;
  if (!catar::LoadCalibration(calibration, camera, error))
  {
    return Error(error);
  }
  std::vector<catar::PoseObservation> points;
  error = ReadPoints(pointsPath, points);
  if (!error.empty())
  {
    return Error(error);
  }
  const catar::PoseResult result = catar::EstimatePose(camera, points, options);
  if (!result.ok)
  {
    return Error(result.error);
  }
  PrintPose(result, points.size());
  if (!output.empty())
  {
    catar::CameraModel posed = camera;
    posed.worldToCamera = result.worldToCamera;
    if (!catar::SaveCalibration(output, posed, error))
    {
      return Error(error);
    }
  }
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  return catar::RunMain("catadioptric-pose", Run, argc, argv);
}
