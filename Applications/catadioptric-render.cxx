// catadioptric-render: renders a scene file (or the built-in demo) to a PNG, or a sequence to
// numbered PNGs or a video, and prints the time of each stage.
//
//   catadioptric-render [SCENE] [-o OUT] [--frames A:B] [--fps F] [--markers BOARD] [--repeat N]
//                       [--adaptive P] [--antialias] [--antialias-samples S]
//                       [--target-area A | --pixel-tolerance P] [--print-demo-scene] [--version]
// (--help lists them; CLI11 parses them: --option value or --option=value.)
#include "vtkCallbackCommand.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"

#include "CommandLine.h"
#include "FileOutput.h"
#include "Json.h"
#include "MarkerPoses.h"
#include "ProgramOutput.h"
#include "RunMain.h"
#include "SceneDescription.h"
#include "Trajectory.h"
#include "VideoIO.h"
#include "vtkPointData.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
const char* const kProgram = "catadioptric-render";

// --quiet: errors and warnings only; --json: the summary as one JSON object on standard output.
bool Quiet = false;
bool Json = false;

// The signal that asked a sequence to stop (SIGINT, SIGTERM), 0 while none has. A second one
// ends the program at once (the handler restores the default action).
volatile std::sig_atomic_t StopSignal = 0;

extern "C" void OnStopSignal(int signal)
{
  StopSignal = signal;
  std::signal(signal, SIG_DFL);
}

// The files the render reads (the scene's, `markers`), a background frame pattern expanded to
// the frames that exist.
catar::FileIdentities InputIdentities(
  vtkCatadioptricSceneRenderer* renderer, const std::string& sceneFile, const std::string& markers)
{
  catar::FileIdentities inputs;
  std::vector<std::string> files;
  files.reserve(static_cast<std::size_t>(renderer->GetNumberOfInputFiles()) + 2);
  for (int i = 0; i < renderer->GetNumberOfInputFiles(); ++i)
  {
    files.emplace_back(renderer->GetInputFile(i));
  }
  files.push_back(sceneFile);
  files.push_back(markers);
  for (const std::string& f : files)
  {
    if (catar::IsFramePattern(f))
    {
      // Frames 0 (or 1) on while they exist, as the background reads them.
      for (long long k = 0; k < 100000000; ++k)
      {
        const std::string name = catar::FrameFileName(f, k);
        if (::access(name.c_str(), F_OK) != 0 && k > 0)
        {
          break;
        }
        inputs.Add(name);
      }
    }
    else
    {
      inputs.Add(f);
    }
  }
  return inputs;
}

// Whether an output (one file, or a pattern's frames [first, end)) is one of the inputs; names
// it in `which`.
bool IsAnInput(const catar::FileIdentities& inputs, const std::string& output, long long first,
  long long end, std::string& which)
{
  if (output.empty())
  {
    return false;
  }
  if (!catar::IsFramePattern(output))
  {
    which = output;
    return inputs.Contains(output);
  }
  for (long long k = first; k < end; ++k)
  {
    which = catar::FrameFileName(output, k);
    if (inputs.Contains(which))
    {
      return true;
    }
  }
  return false;
}

// A JSON string; a JSON number (finite; else null) to 6 digits.
std::string Quoted(const std::string& text)
{
  return catar::JsonString(text);
}

std::string JsonNumber(double v)
{
  return catar::JsonNumber(v, 6);
}

bool IsNpy(const std::string& name)
{
  return name.size() >= 4 && name.compare(name.size() - 4, 4, ".npy") == 0;
}

// --depth from the output's PathLength array (VTK row order: turned top first).
bool WriteDepth(vtkImageData* image, const std::string& depthName)
{
  if (depthName.empty())
  {
    return true;
  }
  auto* depth = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("PathLength"));
  int dims[3];
  image->GetDimensions(dims);
  const long long w = dims[0], h = dims[1];
  if (!depth || depth->GetNumberOfValues() != w * h)
  {
    std::fprintf(stderr, "%s: no path lengths in the output\n", kProgram);
    return false;
  }
  std::vector<float> top(static_cast<std::size_t>(w * h));
  for (long long y = 0; y < h; ++y)
  {
    const float* row = depth->GetPointer((h - 1 - y) * w);
    std::copy(row, row + w, top.begin() + y * w);
  }
  std::string error;
  if (!catar::WriteFloatImageFile(
        depthName, static_cast<int>(w), static_cast<int>(h), top.data(), error))
  {
    std::fprintf(stderr, "%s: --depth %s\n", kProgram, error.c_str());
    return false;
  }
  if (!Quiet && !Json)
  {
    std::printf("wrote %s\n", depthName.c_str());
  }
  return true;
}

// --mask and --ids from the output's VisibleTriangle array (VTK row order: turned top first).
bool WriteMaskAndIds(vtkImageData* image, const std::string& maskName, const std::string& idsName)
{
  if (maskName.empty() && idsName.empty())
  {
    return true;
  }
  auto* ids = vtkTypeInt64Array::SafeDownCast(image->GetPointData()->GetArray("VisibleTriangle"));
  int dims[3];
  image->GetDimensions(dims);
  const long long w = dims[0], h = dims[1];
  if (!ids || ids->GetNumberOfValues() != w * h)
  {
    std::fprintf(stderr, "%s: no visible-triangle ids in the output\n", kProgram);
    return false;
  }
  std::vector<long long> top(static_cast<std::size_t>(w * h));
  for (long long y = 0; y < h; ++y)
  {
    std::copy(
      ids->GetPointer((h - 1 - y) * w), ids->GetPointer((h - 1 - y) * w) + w, top.begin() + y * w);
  }
  std::string error;
  if (!maskName.empty())
  {
    // One 8-bit channel: 255 where a triangle is seen, 0 elsewhere.
    std::vector<std::uint8_t> mask(top.size());
    for (std::size_t i = 0; i < top.size(); ++i)
    {
      mask[i] = top[i] >= 0 ? 255 : 0;
    }
    if (!catar::WriteMaskFile(
          maskName, static_cast<int>(w), static_cast<int>(h), mask.data(), error))
    {
      std::fprintf(stderr, "%s: --mask %s\n", kProgram, error.c_str());
      return false;
    }
    if (!Quiet && !Json)
    {
      std::printf("wrote %s\n", maskName.c_str());
    }
  }
  if (!idsName.empty())
  {
    // An image: 16-bit R = mesh + 1 (0: none), G and B = the cell's low and high 16 bits.
    std::vector<std::uint16_t> rgb;
    if (!IsNpy(idsName))
    {
      rgb.resize(3 * top.size(), 0);
      for (std::size_t i = 0; i < top.size(); ++i)
      {
        if (top[i] >= 0)
        {
          rgb[3 * i] = static_cast<std::uint16_t>((top[i] >> 32) + 1);
          rgb[3 * i + 1] = static_cast<std::uint16_t>(top[i] & 0xFFFF);
          rgb[3 * i + 2] = static_cast<std::uint16_t>((top[i] >> 16) & 0xFFFF);
        }
      }
    }
    if (IsNpy(idsName) ? !catar::WriteNpyInt64(idsName, h, w, top.data(), error)
                       : !catar::WriteImage16File(
                           idsName, static_cast<int>(w), static_cast<int>(h), 3, rgb.data(), error))
    {
      std::fprintf(stderr, "%s: --ids %s\n", kProgram, error.c_str());
      return false;
    }
    if (!Quiet && !Json)
    {
      std::printf("wrote %s\n", idsName.c_str());
    }
  }
  return true;
}

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

// "A:B", "A:", ":B" or "A" (frames A to B-1; A alone is that frame); false when malformed.
bool ParseRange(const std::string& text, long long& first, long long& end)
{
  const std::size_t colon = text.find(':');
  auto number = [](const std::string& s, long long& v) {
    if (s.empty())
    {
      return true;
    }
    // Digits only, at most 10^12 (no sequence is longer; a larger number would overflow).
    if (s.size() > 13 || s.find_first_not_of("0123456789") != std::string::npos)
    {
      return false;
    }
    v = std::stoll(s);
    return v <= 1000000000000LL;
  };
  if (colon == std::string::npos)
  {
    if (text.empty() || !number(text, first))
    {
      return false;
    }
    end = first + 1;
    return true;
  }
  return number(text.substr(0, colon), first) && number(text.substr(colon + 1), end);
}

// "1:05" (minutes and seconds) or "1:02:05".
std::string HoursMinutes(double seconds)
{
  const long long s = static_cast<long long>(std::max(0.0, seconds) + 0.5);
  char b[32];
  if (s >= 3600)
  {
    std::snprintf(b, sizeof b, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  }
  else
  {
    std::snprintf(b, sizeof b, "%lld:%02lld", s / 60, s % 60);
  }
  return b;
}

// The progress line: a bar on a terminal (rewritten in place), a line every tenth otherwise.
// Long work's progress (remeshing, a reference render): after a second (the environment's
// CATAR_PROGRESS_AFTER seconds), a bar with the time left on a terminal, else a line at every
// tenth; nothing with --quiet or --json.
struct WorkProgress
{
  std::string text;
  Clock::time_point start;
  int tenths = -1;
  bool shown = false;
};

void OnProgress(vtkObject* caller, unsigned long, void* clientData, void* callData)
{
  auto* p = static_cast<WorkProgress*>(clientData);
  auto* renderer = static_cast<vtkCatadioptricSceneRenderer*>(caller);
  if (StopSignal != 0)
  {
    renderer->AbortExecuteOn(); // long work (remeshing) stops at its next step
  }
  const double fraction = callData ? *static_cast<double*>(callData) : 0.0;
  const std::string text = renderer->GetProgressText();
  const auto now = Clock::now();
  if (text != p->text || fraction <= 0.0)
  {
    p->text = text;
    p->start = now;
    p->tenths = -1;
    p->shown = false;
  }
  const double elapsed = Seconds(p->start, now);
  static const double after =
    std::getenv("CATAR_PROGRESS_AFTER") ? std::atof(std::getenv("CATAR_PROGRESS_AFTER")) : 1.0;
  if (Quiet || Json || (elapsed < after && !p->shown))
  {
    return;
  }
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (isatty(fileno(stderr)))
  {
    const int width = 30, filled = static_cast<int>(width * std::min(1.0, fraction));
    std::fprintf(stderr, "\r%s [%s%s] %3.0f%%, %s left ", text.c_str(),
      std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), 100.0 * fraction,
      HoursMinutes(left).c_str());
    if (fraction >= 1.0)
    {
      std::fputc('\n', stderr);
    }
  }
  else if (static_cast<int>(10 * fraction) != p->tenths)
  {
    p->tenths = static_cast<int>(10 * fraction);
    std::fprintf(
      stderr, "%s: %3.0f%%, %s left\n", text.c_str(), 100.0 * fraction, HoursMinutes(left).c_str());
  }
  p->shown = true;
  std::fflush(stderr);
}

void Progress(long long done, long long total, double elapsed, bool terminal)
{
  if (Quiet)
  {
    return;
  }
  const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
  const double left = rate > 0.0 ? (total - done) / rate : 0.0;
  if (terminal)
  {
    const int width = 30;
    const int filled = static_cast<int>(width * done / std::max(1LL, total));
    std::fprintf(stderr, "\r[%s%s] %lld/%lld frames, %.1f fps, %s left ",
      std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), done, total, rate,
      HoursMinutes(left).c_str());
    if (done == total)
    {
      std::fputc('\n', stderr);
    }
  }
  else if (done == total || (done * 10 / total) != ((done - 1) * 10 / total))
  {
    std::fprintf(stderr, "%lld/%lld frames, %.1f fps, %s left\n", done, total, rate,
      HoursMinutes(left).c_str());
  }
  std::fflush(stderr);
}

// Renders frames [first, end) of the sequence to a pattern or a video; prints a summary.
int RenderSequence(vtkCatadioptricSceneRenderer* renderer, const std::string& outName,
  long long first, long long end, double fps, catar_render::MarkerPoses& poses)
{
  vtkCatadioptricCamera* cam = renderer->GetCamera();
  catar::FrameWriter writer;
  std::string error;
  if (!writer.Open(outName, cam->GetImageWidth(), cam->GetImageHeight(), fps, error))
  {
    std::fprintf(stderr, "catadioptric-render: %s\n", error.c_str());
    return 1;
  }
  const int stages = renderer->GetNumberOfStages();
  const int perFrame = renderer->GetFirstPerFrameStage();
  std::vector<double> sum(stages, 0.0), worst(stages, 0.0);
  double encode = 0.0, encodeWorst = 0.0, pose = 0.0, poseWorst = 0.0;
  const bool terminal = isatty(fileno(stderr)) != 0;
  const auto start = Clock::now();
  // An error or a signal leaves no output that looks complete: the video is given up (kept under
  // a name that says it is partial, or removed) and the program says which.
  const auto giveUp = [&writer](const std::string& why, int status) {
    std::string what;
    writer.Abandon(what);
    std::fprintf(stderr, "\ncatadioptric-render: %s%s%s\n", why.c_str(), what.empty() ? "" : "; ",
      what.c_str());
    return status;
  };
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
  for (long long k = first; k < end; ++k)
  {
    if (StopSignal != 0)
    {
      const int signal = StopSignal;
      return giveUp(std::string("stopped by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
          " before frame " + std::to_string(k),
        128 + signal);
    }
    if (!renderer->RenderFrame(static_cast<int>(k)))
    {
      // The renderer's error has been printed already when it came through VTK's output.
      const std::string error = catar::ProgramOutputWindow::Message(renderer->GetLastError());
      return giveUp("frame " + std::to_string(k) +
          (error == catar::ProgramOutputWindow::LastError() ? std::string(" failed")
                                                            : ": " + error),
        1);
    }
    for (int s = perFrame; s < stages; ++s) // the background (decoding) and the frame's
    {
      sum[s] += renderer->GetStageTime(s);
      worst[s] = std::max(worst[s], renderer->GetStageTime(s));
    }
    pose += renderer->GetPoseTime();
    poseWorst = std::max(poseWorst, renderer->GetPoseTime());
    poses.Add(renderer, k);
    const auto e0 = Clock::now();
    if (!writer.Write(k, vtkCatadioptricImageSupport::ToFrame(renderer->GetOutput()), error))
    {
      return giveUp(error, 1);
    }
    const double e = Seconds(e0, Clock::now());
    encode += e;
    encodeWorst = std::max(encodeWorst, e);
    Progress(k - first + 1, end - first, Seconds(start, Clock::now()), terminal);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!writer.Finish(error))
  {
    std::fprintf(stderr, "catadioptric-render: %s\n", error.c_str());
    return 1;
  }
  if (!poses.Write(Quiet || Json))
  {
    return 1;
  }
  const int status = poses.Status();
  if (!writer.GetNote().empty())
  {
    std::fprintf(stderr, "catadioptric-render: warning: %s\n", writer.GetNote().c_str());
  }
  const double total = Seconds(start, Clock::now());
  const long long n = end - first;
  if (Json)
  {
    std::string stagesJson;
    for (int s = perFrame; s < stages; ++s)
    {
      stagesJson += std::string(stagesJson.empty() ? "" : ", ") +
        Quoted(renderer->GetStageName(s)) + ": {\"mean\": " + JsonNumber(1e3 * sum[s] / n) +
        ", \"max\": " + JsonNumber(1e3 * worst[s]) + "}";
    }
    stagesJson += ", \"encode\": {\"mean\": " + JsonNumber(1e3 * encode / n) +
      ", \"max\": " + JsonNumber(1e3 * encodeWorst) + "}";
    if (*renderer->GetPoseReport())
    {
      stagesJson += ", \"pose\": {\"mean\": " + JsonNumber(1e3 * pose / n) +
        ", \"max\": " + JsonNumber(1e3 * poseWorst) + "}";
    }
    std::printf("{\"output\": %s, \"frames\": %lld, \"first\": %lld, \"last\": %lld, "
                "\"seconds\": %s, \"frames_per_second\": %s, \"pose_failures\": %d, "
                "\"stages_ms\": {%s}}\n",
      Quoted(outName).c_str(), n, first, end - 1, JsonNumber(total).c_str(),
      JsonNumber(n / total).c_str(), renderer->GetNumberOfPoseFailures(), stagesJson.c_str());
    return status;
  }
  if (Quiet)
  {
    return status;
  }
  std::printf("frames: %lld (%lld to %lld) in %.2f s: %.1f frames a second with decoding and "
              "encoding\n",
    n, first, end - 1, total, n / total);
  std::printf("  %-11s %9s %9s\n", "stage", "mean ms", "max ms");
  for (int s = perFrame; s < stages; ++s)
  {
    std::printf(
      "  %-11s %9.2f %9.2f\n", renderer->GetStageName(s), 1e3 * sum[s] / n, 1e3 * worst[s]);
  }
  if (*renderer->GetPoseReport())
  {
    std::printf("  %-11s %9.2f %9.2f   (markers; %d frames without a pose)\n", "pose",
      1e3 * pose / n, 1e3 * poseWorst, renderer->GetNumberOfPoseFailures());
  }
  std::printf("  %-11s %9.2f %9.2f\n", "encode", 1e3 * encode / n, 1e3 * encodeWorst);
  std::printf("wrote %s\n", outName.c_str());
  return status;
}
} // namespace

namespace
{
int Run(int argc, char* argv[])
{
  // VTK's errors and warnings: once each, as plain lines.
  catar::ProgramOutputWindow::Install(kProgram);
  std::string scene;
  std::string outName = "catadioptric-render.png";
  int repeat = 1;
  double targetArea = 0.0;
  double pixelTolerance = 0.0;
  long long first = 0, end = -1; // --frames (end -1: the sequence's last)
  std::string frameRange;
  double fps = 0.0;
  std::string markers;
  catar_render::MarkerPoses poses;
  double adaptive = 0.0;
  int antialiasSamples = 0;
  bool antialias = false, printDemo = false, alpha = false, reference = false;
  int referenceSamples = 1;
  std::string maskName, idsName, depthName;

  CLI::App app(
    "Renders SCENE (YAML or JSON, Documentation/file-formats.md) to OUT and prints the time "
    "of each stage. Without SCENE it renders the built-in demo scene.",
    kProgram);
  app.footer(
    "Sequences (a scene with a trajectory, a video background, keyframes or 'sequence'): OUT as "
    "a pattern (out/frame_%05d.png) writes every frame as a numbered image, OUT ending in .mp4 "
    "or .avi writes a video; OUT a plain image name writes the first frame of the range. A "
    "progress line on standard error and a per-stage summary follow.\n\nFiles: a relative name "
    "in a scene is looked for in the scene's folder, then in each folder of CATAR_DATA_PATH "
    "(':' between them), then in the installed data (" +
    catar::InstalledDataDir() +
    ": calibration/, scenes/, meshes/); SCENE itself, when it is not found where named, too."
    "\n\nExit status: 0 "
    "success, 1 the scene or an output failed, 2 usage error.");
  app.add_option("SCENE", scene, "scene file (YAML or JSON); without it, the built-in demo");
  app.add_option("-o,--output", outName,
    "image (.png, .jpg, .tif, .bmp, .webp; the format by the extension), numbered images (a "
    "%05d pattern) or video (.mp4, .avi); default catadioptric-render.png");
  app
    .add_option("--frames", frameRange,
      "frames A to B-1 of a sequence (0-based; A: and :B leave an end open; A alone: that frame)")
    ->type_name("A:B");
  app.add_option("--fps", fps, "the video's frame rate (default: the sequence's)")
    ->check(CLI::Range(1e-6, 1000.0));
  app.add_option("--markers", markers,
    "estimate each frame's camera pose from this board's markers seen in the background "
    "(Documentation/markers.md)");
  app.add_option("--poses-out", poses.path,
    "write each frame's camera pose found from its markers: FILE.tum or FILE.txt, the reliable "
    "poses as a TUM trajectory (time tx ty tz qx qy qz qw, the camera in the world); FILE.csv or "
    "FILE.json, every frame with its verdict (reliable, unreliable, missing), one-sigma "
    "uncertainty and why (Documentation/markers.md)");
  app.add_flag("--allow-missing-poses", poses.allowMissing,
    "with markers, exit 0 even when frames had no reliable pose (they keep the previous frame's "
    "pose; the frames before the first keep the scene's); without it such a run writes its "
    "outputs and exits with status 3");
  app
    .add_option("--adaptive", adaptive,
      "split, every frame, the triangles whose edges bend more than P pixels "
      "(Documentation/edges-and-rasterisation.md; "
      "overrides the scene's)")
    ->type_name("P")
    ->check(CLI::Range(1e-9, 1e6));
  app.add_flag("--antialias", antialias,
    "redraw the edge pixels from 4 x 4 samples each (Documentation/edges-and-rasterisation.md; "
    "overrides the "
    "scene's)");
  app
    .add_option("--antialias-samples", antialiasSamples,
      "anti-aliasing with S x S samples per edge pixel (2, 3 or 4)")
    ->type_name("S")
    ->check(CLI::Range(2, 4));
  app
    .add_option("--repeat", repeat,
      "render the frame N times, the camera marked modified before each so that every per-frame "
      "stage runs again, and report the median of each stage and of the whole frame over frames "
      "2 to N")
    ->type_name("N")
    ->check(CLI::PositiveNumber);
  auto* area = app
                 .add_option("--target-area", targetArea,
                   "remesh every object to triangles of about A square metres")
                 ->type_name("A")
                 ->check(CLI::PositiveNumber);
  app
    .add_option("--pixel-tolerance", pixelTolerance,
      "remesh every object so that no visible edge bends more than P pixels")
    ->type_name("P")
    ->check(CLI::PositiveNumber)
    ->excludes(area);
  app.add_flag("--alpha", alpha,
    "the objects alone over a transparent background (PNG, TIFF and WebP keep the alpha)");
  app.add_option("--mask", maskName,
    "also write the objects' mask: 255 where a triangle is seen, 0 elsewhere (an image)");
  app.add_option("--ids", idsName,
    "also write the visible triangle per pixel: a NumPy .npy array of int64, rows top first, "
    "mesh * 2^32 + cell, -1 for none; or a 16-bit RGB .png/.tif, R = mesh + 1 (0: none), "
    "G + 65536 B = cell");
  app.add_option("--depth", depthName,
    "also write the path length per pixel (from the mirror to the surface seen, scene units; "
    "NaN where none) as a 32-bit float .exr or .tif");
  auto* referenceFlag = app.add_flag("--reference", reference,
    "render with the exact reference ray tracer instead of the fast path (Documentation/"
    "reference-ray-tracer.md; overrides the scene's 'renderer')");
  app.add_option("--samples", referenceSamples, "the reference's rays per pixel side (1 to 8)")
    ->type_name("N")
    ->check(CLI::Range(1, 8))
    ->needs(referenceFlag);
  app.add_flag("--quiet", Quiet, "print errors and warnings only (no progress, no summary)");
  app.add_flag(
    "--json", Json, "print the summary (sizes, counts, the time of each stage) as one JSON object");
  app.add_flag("--print-demo-scene", printDemo, "write the demo scene's YAML to standard output");
  int threads = 0;
  const int parsed = catar::ParseCommandLine(app, kProgram, argc, argv, &threads);
  if (parsed >= 0)
  {
    return parsed;
  }
  if (printDemo)
  {
    std::fputs(vtkCatadioptricSceneRenderer::GetDemoSceneText(), stdout);
    return 0;
  }
  if (!frameRange.empty() && (!ParseRange(frameRange, first, end) || (end >= 0 && end <= first)))
  {
    std::fprintf(stderr,
      "%s: --frames needs A:B with 0 <= A < B (frames A to B-1), A:, :B or A (run with --help "
      "for usage)\n",
      kProgram);
    return 2;
  }
  // `-o --quiet` takes "--quiet" as the file name: an output name that starts with '-' is almost
  // always a forgotten value (a file named so can be given as ./-name).
  for (const auto& output : { std::make_pair("-o", outName), std::make_pair("--mask", maskName),
         std::make_pair("--ids", idsName), std::make_pair("--depth", depthName) })
  {
    if (output.second.size() > 1 && output.second[0] == '-')
    {
      std::fprintf(stderr,
        "%s: %s needs a file name, not '%s' (a file whose name starts with '-' is given as "
        "./%s; run with --help for usage)\n",
        kProgram, output.first, output.second.c_str(), output.second.c_str());
      return 2;
    }
  }
  const int antialiasing = antialiasSamples > 0 ? antialiasSamples : antialias ? 4 : 0;
  // One image: its format by the extension, checked before any work (and the mask's, the ids').
  std::string formatError;
  if (!catar::IsFramePattern(outName) && !catar::FrameWriter::IsVideo(outName) &&
    !catar::IsImageFileName(outName, &formatError))
  {
    std::fprintf(stderr, "%s: -o %s (run with --help for usage)\n", kProgram, formatError.c_str());
    return 2;
  }
  if (!maskName.empty() && !catar::IsImageFileName(maskName, &formatError))
  {
    std::fprintf(
      stderr, "%s: --mask %s (run with --help for usage)\n", kProgram, formatError.c_str());
    return 2;
  }
  const auto extensionIn = [](const std::string& name, std::initializer_list<const char*> list) {
    for (const char* e : list)
    {
      const std::size_t n = std::strlen(e);
      if (name.size() > n && name.compare(name.size() - n, n, e) == 0)
      {
        return true;
      }
    }
    return false;
  };
  if (!idsName.empty() && !extensionIn(idsName, { ".npy", ".png", ".tif", ".tiff" }))
  {
    std::fprintf(stderr,
      "%s: --ids writes a NumPy .npy file or a 16-bit .png or .tif (run with --help for usage)\n",
      kProgram);
    return 2;
  }
  if (!depthName.empty() && !extensionIn(depthName, { ".exr", ".tif", ".tiff" }))
  {
    std::fprintf(stderr,
      "%s: --depth writes a 32-bit float .exr or .tif (run with --help for usage)\n", kProgram);
    return 2;
  }
  // Parallel loops: STDThread unless the environment chose a backend (--threads chooses it too).
  if (threads > 0 || !std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkCatadioptricParallel::EnableThreads(threads);
  }

  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  WorkProgress workProgress;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetCallback(OnProgress);
  onProgress->SetClientData(&workProgress);
  renderer->AddObserver(vtkCommand::ProgressEvent, onProgress);
  // A scene that is not where it was named is looked for on the data search path
  // (CATAR_DATA_PATH, then the installed data) by LoadScene: `catadioptric-render
  // scenes/two-objects.yaml`; the name found is its first input file.
  renderer->SetSceneFileName(scene.empty() ? nullptr : scene.c_str());
  renderer->SetRemeshTargetArea(targetArea);
  renderer->SetRemeshPixelTolerance(pixelTolerance);
  renderer->SetMarkerBoardFileName(markers.empty() ? nullptr : markers.c_str());
  renderer->SetAdaptiveTolerance(adaptive);
  renderer->SetAntialias(antialiasing);
  renderer->SetTransparentBackground(alpha);
  renderer->SetReferenceSamples(reference ? referenceSamples : 0);
  renderer->SetOutputVisibleTriangle(!maskName.empty() || !idsName.empty());
  renderer->SetOutputPathLength(!depthName.empty());
  // SIGINT or SIGTERM while the scene loads (remeshing can take minutes) stops it at the next
  // progress step; a second one ends the program at once.
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
  const bool loaded = renderer->LoadScene();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (StopSignal != 0)
  {
    const int signal = StopSignal;
    std::fprintf(stderr, "\n%s: stopped by %s while reading the scene; nothing was written\n",
      kProgram, signal == SIGINT ? "SIGINT" : "SIGTERM");
    return 128 + signal;
  }
  if (!loaded)
  {
    catar::PrintError(kProgram, renderer->GetLastError());
    return 1;
  }
  if (!scene.empty() && renderer->GetNumberOfInputFiles() > 0)
  {
    scene = renderer->GetInputFile(0); // where it was found
  }

  if (!poses.path.empty())
  {
    const std::string problem = poses.CheckPath();
    if (!problem.empty())
    {
      std::fprintf(stderr, "%s: %s\n", kProgram, problem.c_str());
      return 2;
    }
    if (!renderer->GetUsesMarkers())
    {
      std::fprintf(stderr,
        "%s: --poses-out needs poses from markers: give --markers BOARD or the scene's "
        "'markers'\n",
        kProgram);
      return 2;
    }
  }
  const long long frames = renderer->GetNumberOfFrames();
  if (*renderer->GetSequenceNote() && !Quiet)
  {
    std::fprintf(stderr, "catadioptric-render: note: %s\n", renderer->GetSequenceNote());
  }
  end = end < 0 ? frames : end;
  if (first >= frames || end > frames)
  {
    std::fprintf(stderr,
      "catadioptric-render: --frames %lld:%lld is outside the sequence (frames 0 to %lld)\n", first,
      end, frames - 1);
    return 2;
  }
  // No output may be an input (compared as files, not names): writing it would destroy what is
  // being read. Checked before anything is written.
  {
    const catar::FileIdentities inputs = InputIdentities(renderer, scene, markers);
    std::string which;
    for (const auto& output : { std::make_pair("-o", outName), std::make_pair("--mask", maskName),
           std::make_pair("--ids", idsName), std::make_pair("--depth", depthName),
           std::make_pair("--poses-out", poses.path) })
    {
      if (IsAnInput(inputs, output.second, first, end, which))
      {
        std::fprintf(stderr,
          "catadioptric-render: %s %s: '%s' is one of the scene's inputs; refusing to write "
          "over it (choose another output name)\n",
          output.first, output.second.c_str(), which.c_str());
        return 2;
      }
    }
  }
  std::string patternError;
  const bool sequence =
    catar::IsFramePattern(outName, &patternError) || catar::FrameWriter::IsVideo(outName);
  if (!patternError.empty())
  {
    std::fprintf(stderr, "catadioptric-render: -o %s\n", patternError.c_str());
    return 2;
  }
  if (sequence && (!maskName.empty() || !idsName.empty() || !depthName.empty()))
  {
    std::fprintf(stderr,
      "%s: --mask, --ids and --depth go with one image, not a sequence (run with --help for "
      "usage)\n",
      kProgram);
    return 2;
  }
  if (sequence)
  {
    return RenderSequence(
      renderer, outName, first, end, fps > 0.0 ? fps : renderer->GetFrameRate(), poses);
  }
  if (frames > 1 && end - first > 1 && !Quiet)
  {
    std::fprintf(stderr,
      "catadioptric-render: note: the scene has %lld frames; writing frame %lld (give -o "
      "out/frame_%%05d.png or out.mp4 for all)\n",
      frames, first);
  }
  // --repeat N: N frames, the camera marked modified before each after the first, so that every
  // per-frame stage runs again as when the camera moves (what depends only on inputs that did not
  // change -- the synthesised background, the colours averaged at the vertices -- is kept, as it
  // would be). Every frame's stages are kept: with N > 1 the summary gives their medians over
  // frames 2 to N (the first frame also makes what the others reuse) and the first frame apart.
  const int stages = renderer->GetNumberOfStages();
  const int perFrame = renderer->GetFirstPerFrameStage();
  std::vector<std::vector<double>> stageTimes(stages);
  std::vector<double> poseTimes, frameTimes;
  for (int f = 0; f < repeat; ++f)
  {
    if (f > 0)
    {
      renderer->GetCamera()->Modified();
    }
    if (!renderer->RenderFrame(static_cast<int>(first)))
    {
      catar::PrintError(kProgram, renderer->GetLastError());
      return 1;
    }
    for (int s = perFrame; s < stages; ++s)
    {
      stageTimes[s].push_back(renderer->GetStageTime(s));
    }
    poseTimes.push_back(renderer->GetFramePoseTime());
    frameTimes.push_back(renderer->GetFrameTime());
  }
  poses.Add(renderer, first);
  // A stage's time: the load's own, or the median of the frames timed (all but the first).
  const std::size_t timedFrom = repeat > 1 ? 1 : 0;
  const auto median = [timedFrom](const std::vector<double>& all) {
    std::vector<double> v(all.begin() + static_cast<std::ptrdiff_t>(timedFrom), all.end());
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const auto stageTime = [&](int s) {
    return s < perFrame ? renderer->GetStageTime(s) : median(stageTimes[s]);
  };
  const bool markerPose = *renderer->GetPoseReport() != '\0';
  const double frameTime = median(frameTimes);
  if (renderer->GetNumberOfTriangles() == 0)
  {
    std::fprintf(stderr,
      "catadioptric-render: warning: nothing to draw: the scene has no objects with triangles "
      "(is 'objects' spelt right?); the image is the background alone\n");
  }
  if (!renderer->WriteImage(outName.c_str()))
  {
    catar::PrintError(kProgram, renderer->GetLastError());
    return 1;
  }
  if (!WriteMaskAndIds(renderer->GetOutput(), maskName, idsName) ||
    !WriteDepth(renderer->GetOutput(), depthName) || !poses.Write(Quiet || Json))
  {
    return 1;
  }
  const int status = poses.Status();
  vtkCatadioptricCamera* cam = renderer->GetCamera();
  if (Json)
  {
    std::string stagesJson;
    for (int s = 0; s < stages; ++s)
    {
      stagesJson += std::string(s ? ", " : "") + Quoted(renderer->GetStageName(s)) + ": " +
        JsonNumber(1e3 * stageTime(s));
    }
    if (markerPose)
    {
      stagesJson += ", \"pose\": " + JsonNumber(1e3 * median(poseTimes));
    }
    std::printf("{\"scene\": %s, \"output\": %s, \"mask\": %s, \"ids\": %s, \"depth\": %s, "
                "\"width\": %d, "
                "\"height\": %d, \"triangles\": %lld, \"backend\": %s, \"threads\": %d, "
                "\"repeat\": %d, \"stages_ms\": {%s}, \"frame_ms\": %s, \"first_frame_ms\": %s}\n",
      scene.empty() ? "null" : Quoted(scene).c_str(), Quoted(outName).c_str(),
      maskName.empty() ? "null" : Quoted(maskName).c_str(),
      idsName.empty() ? "null" : Quoted(idsName).c_str(),
      depthName.empty() ? "null" : Quoted(depthName).c_str(), cam->GetImageWidth(),
      cam->GetImageHeight(), static_cast<long long>(renderer->GetNumberOfTriangles()),
      Quoted(vtkSMPTools::GetBackend()).c_str(), vtkSMPTools::GetEstimatedNumberOfThreads(), repeat,
      stagesJson.c_str(), JsonNumber(1e3 * frameTime).c_str(),
      JsonNumber(1e3 * frameTimes.front()).c_str());
    return status;
  }
  if (Quiet)
  {
    return status;
  }
  std::printf("scene: %s\n", scene.empty() ? "(built-in demo)" : scene.c_str());
  std::printf("image: %d x %d, %lld triangles, SMP backend %s (%d threads)\n", cam->GetImageWidth(),
    cam->GetImageHeight(), static_cast<long long>(renderer->GetNumberOfTriangles()),
    vtkSMPTools::GetBackend(), vtkSMPTools::GetEstimatedNumberOfThreads());
  if (*renderer->GetPoseReport())
  {
    std::printf("pose from markers: %s (%.2f ms)\n", renderer->GetPoseReport(),
      1e3 * renderer->GetPoseTime());
  }
  if (*renderer->GetMeshReport())
  {
    std::printf("remeshed:\n%s", renderer->GetMeshReport());
  }
  for (int s = 0; s < stages; ++s)
  {
    if (s == perFrame && repeat > 1)
    {
      std::printf("per frame, median of frames 2 to %d:\n", repeat);
    }
    std::printf("  %-11s %9.2f ms\n", renderer->GetStageName(s), 1e3 * stageTime(s));
  }
  if (markerPose)
  {
    std::printf("  %-11s %9.2f ms\n", "pose", 1e3 * median(poseTimes));
  }
  std::string sum;
  for (int s = perFrame; s < stages; ++s)
  {
    sum += std::string(sum.empty() ? "" : " + ") + renderer->GetStageName(s);
  }
  sum += markerPose ? " + pose" : "";
  if (repeat > 1)
  {
    std::printf("  per frame   %9.2f ms (%s; the first frame %.2f ms)\n", 1e3 * frameTime,
      sum.c_str(), 1e3 * frameTimes.front());
  }
  else
  {
    std::printf("  per frame   %9.2f ms (%s)\n", 1e3 * frameTime, sum.c_str());
  }
  std::printf("wrote %s\n", outName.c_str());
  return status;
}
} // namespace

int main(int argc, char* argv[])
{
  return catar::RunMain("catadioptric-render", Run, argc, argv);
}
