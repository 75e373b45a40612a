// catadioptric-calibrate: the rig's mirror (and with --free mirror,lens its lens) from images of a
// marker board seen in the mirror (Module/Vision/RigCalibration.h).
//
//   catadioptric-calibrate INIT.yaml BOARD.yaml IMAGE_OR_VIDEO... -o RIG.yaml
//                          [--free mirror|mirror,lens] [--json] [--every N] [--max-rms PX]
//
// INIT.yaml: a calibration file whose lens is known and whose mirror gives the type and a starting
// guess. BOARD.yaml: a marker board file (Markers.h). Each input is an image, a numbered image
// pattern or a video (every frame, or every N-th with --every). Exit status: 0 success, 1 bad input
// or no calibration (one sentence says why), 2 usage error.
#include "CalibrationIO.h"
#include "Json.h"
#include "Markers.h"
#include "Mirror.h"
#include "RigCalibration.h"
#include "VideoIO.h"

#include "CommandLine.h"
#include "RunMain.h"

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const kProgram = "catadioptric-calibrate";

int Error(const std::string& message, int code = 1)
{
  std::fprintf(stderr, "%s: %s\n", kProgram, message.c_str());
  return code;
}

struct Loaded
{
  std::vector<catar::Frame> frames;
  std::vector<std::string> names;
};

// Every frame of the inputs (every N-th of a sequence); false with a sentence.
bool ReadInputs(const std::vector<std::string>& inputs, long long every, bool quiet, Loaded& out,
  std::string& error)
{
  for (const std::string& input : inputs)
  {
    catar::FrameReader reader;
    if (!reader.Open(input, error))
    {
      error = input + ": " + error;
      return false;
    }
    const long long count = reader.GetNumberOfFrames();
    for (long long k = 0; k<count; k += count> 1 ? every : 1)
    {
      catar::Frame frame;
      if (!reader.Read(k, frame, error))
      {
        error = input + ": " + error;
        return false;
      }
      out.frames.push_back(std::move(frame));
      out.names.push_back(count > 1 ? input + "#" + std::to_string(k) : input);
    }
    if (!quiet)
    {
      std::fprintf(stderr, "%s: read %s (%lld frame%s)\n", kProgram, input.c_str(),
        count > 1 ? (count + every - 1) / every : 1LL, count > 1 ? "s" : "");
    }
  }
  return true;
}

std::string NumbersJson(const std::vector<catar::CalibratedNumber>& numbers)
{
  std::ostringstream s;
  s << "{";
  for (std::size_t i = 0; i < numbers.size(); ++i)
  {
    const catar::CalibratedNumber& n = numbers[i];
    s << (i ? ", " : "") << catar::JsonString(n.name)
      << ": {\"value\": " << catar::JsonNumber(n.value)
      << ", \"sigma\": " << catar::JsonNumber(n.sigma, 6)
      << ", \"unit\": " << catar::JsonString(n.unit) << "}";
  }
  s << "}";
  return s.str();
}

// The mirror's description by its type's keys.
std::string MirrorJson(const catar::MirrorDescription& mirror)
{
  std::ostringstream s;
  s << "{\"type\": " << catar::JsonString(mirror.type);
  if (const catar::MirrorType* type = catar::FindMirrorType(mirror.type, mirror.parameters.size()))
  {
    std::size_t i = 0;
    for (const catar::MirrorParameter& p : type->parameters)
    {
      s << ", " << catar::JsonString(p.key) << ": ";
      if (p.count == 1)
      {
        s << catar::JsonNumber(mirror.parameters.at(i++));
        continue;
      }
      s << "[";
      for (int k = 0; k < p.count; ++k)
      {
        s << (k ? ", " : "") << catar::JsonNumber(mirror.parameters.at(i++));
      }
      s << "]";
    }
  }
  s << "}";
  return s.str();
}

void PrintSummary(const catar::CalibrationResult& r, const std::vector<std::string>& names)
{
  std::printf("rms: %.4g px over %d images\n", r.rmsPixels, r.imagesUsed);
  for (const catar::CalibratedNumber& n : r.mirror)
  {
    std::printf("mirror %s: %.9g +- %.3g %s\n", n.name.c_str(), n.value, n.sigma, n.unit.c_str());
  }
  for (const catar::CalibratedNumber& n : r.lens)
  {
    std::printf("lens %s: %.9g +- %.3g %s\n", n.name.c_str(), n.value, n.sigma, n.unit.c_str());
  }
  for (std::size_t k = 0; k < r.usedViews.size(); ++k)
  {
    std::printf("  %s: %.3g px\n", names[static_cast<std::size_t>(r.usedViews[k])].c_str(),
      r.viewRmsPixels[k]);
  }
  for (const std::string& s : r.skipped)
  {
    std::printf("  left out: %s\n", s.c_str());
  }
}

int Run(int argc, char* argv[])
{
  CLI::App app(
    "Calibrates a catadioptric rig from images of a marker board seen in its mirror:\n"
    "the mirror (sphere: center and radius; hyperboloid, paraboloid, ellipsoid, cone:\n"
    "mirror_to_camera and the shape's numbers) and, with --free mirror,lens, the lens's\n"
    "focal lengths, principal point and distortion, by minimising the corners'\n"
    "reprojection error through the exact projection. INIT.yaml gives the lens and the\n"
    "mirror's type and starting guess; BOARD.yaml the markers' layout. RIG.yaml gets the\n"
    "calibrated lens and mirror and a 'calibration' map (rms_px, images_used, each\n"
    "estimated number's value and standard deviation).",
    kProgram);
  app.footer("Exit status: 0 success, 1 bad input or no calibration (the reason is printed), "
             "2 usage error.");
  std::string initPath, boardPath, output, free = "mirror";
  std::vector<std::string> inputs;
  bool json = false;
  bool quiet = false;
  long long every = 1;
  catar::CalibrationOptions options;
  app.add_option("INIT", initPath, "starting calibration (YAML or JSON): lens and mirror guess")
    ->required();
  app.add_option("BOARD", boardPath, "marker board file (YAML or JSON)")->required();
  app.add_option("IMAGES", inputs, "images, numbered image patterns or videos of the board")
    ->required();
  app.add_option("-o,--output", output, "the calibrated rig (.yaml, .yml or .json)")
    ->type_name("RIG.yaml")
    ->required();
  app.add_option("--free", free, "what is estimated: mirror (default) or mirror,lens")
    ->type_name("WHAT")
    ->check(CLI::IsMember({ "mirror", "mirror,lens" }));
  app.add_flag("--json", json, "print one JSON object (rms_px, images_used, mirror, ...)");
  app.add_option("--every", every, "take every N-th frame of a video or sequence (default 1)")
    ->type_name("N")
    ->check(CLI::Range(1LL, 1000000LL));
  app
    .add_option("--max-rms", options.maxRmsPixels,
      "refuse a calibration whose corners' RMS exceeds this (default 2)")
    ->type_name("PX")
    ->check(CLI::Range(1e-3, 1e3));
  app.add_flag("-q,--quiet", quiet, "no progress on standard error");
  const int parsed = catar::ParseCommandLine(app, kProgram, argc, argv);
  if (parsed >= 0)
  {
    return parsed;
  }
  options.freeLens = free == "mirror,lens";

  catar::CameraModel initial;
  std::string error;
  if (!catar::LoadCalibration(initPath, initial, error))
  {
    return Error(error);
  }
  catar::MarkerBoard board;
  if (!catar::LoadMarkerBoard(boardPath, board, error))
  {
    return Error(error);
  }
  Loaded loaded;
  if (!ReadInputs(inputs, every, quiet || json, loaded, error))
  {
    return Error(error);
  }
  std::vector<catar::CalibrationImage> images;
  for (std::size_t i = 0; i < loaded.frames.size(); ++i)
  {
    const catar::Frame& f = loaded.frames[i];
    images.push_back({ loaded.names[i], f.width, f.height, f.rgba.data() });
  }
  int pass = 0;
  int last = -1;
  options.progress = [&](int iteration, double rms) {
    if (iteration <= last)
    {
      ++pass;
    }
    last = iteration;
    if (!quiet && !json)
    {
      std::fprintf(stderr, "%s: %s, iteration %d: rms %.4g px\n", kProgram,
        pass == 0 ? "OpenCV's corners" : "corners on the edges", iteration, rms);
    }
  };
  const catar::CalibrationResult result =
    catar::CalibrateRigFromImages(initial, board, images, options);
  if (!result.ok)
  {
    return Error("cannot calibrate: " + result.error);
  }
  const catar::CalibrationRecord record = catar::RecordOf(result, loaded.names);
  catar::CameraModel rig = result.camera;
  rig.worldToCamera = initial.worldToCamera;
  if (!catar::SaveCalibration(output, rig, error, &record))
  {
    return Error(error);
  }
  if (json)
  {
    std::ostringstream s;
    s << "{\"rms_px\": " << catar::JsonNumber(result.rmsPixels, 6)
      << ", \"images_used\": " << result.imagesUsed << ", \"mirror\": " << MirrorJson(rig.mirror)
      << ", \"estimated\": " << NumbersJson(result.mirror)
      << ", \"lens\": " << NumbersJson(result.lens) << ", \"images\": [";
    for (std::size_t i = 0; i < record.images.size(); ++i)
    {
      s << (i ? ", " : "") << catar::JsonString(record.images[i]);
    }
    s << "], \"left_out\": [";
    for (std::size_t i = 0; i < result.skipped.size(); ++i)
    {
      s << (i ? ", " : "") << catar::JsonString(result.skipped[i]);
    }
    s << "], \"output\": " << catar::JsonString(output) << "}";
    std::printf("%s\n", s.str().c_str());
    return 0;
  }
  PrintSummary(result, loaded.names);
  if (!quiet)
  {
    std::printf("wrote %s\n", output.c_str());
  }
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  return catar::RunMain(kProgram, Run, argc, argv);
}
