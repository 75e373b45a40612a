// catadioptric-compare: accuracy metrics between two renderings of the same scene (e.g. the
// rasterised frame against the ray-traced reference), see Documentation/accuracy-metrics.md.
//
//   catadioptric-compare A.png B.png [--background R,G,B[,A]] [--background-image BG.png]
//                        [--tolerance T] [--silhouette-psnr] [--csv FILE] [--diff FILE]
//                        [--threads N] [--version]
//
// Exit status: 0 on success, 2 on a usage error, 1 when an image cannot be read or the two images
// cannot be compared (different sizes).
#include "CommandLine.h"
#include "Csv.h"
#include "FileOutput.h"
#include "ImageFile.h"
#include "ImageMetrics.h"
#include "RunMain.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr const char* kProgram = "catadioptric-compare";

// Reads an 8- or 16-bit grey, BGR or BGRA image and converts it to RGBA8.
bool ReadRgba(const std::string& path, cv::Mat& rgba, std::string& error)
{
  // A regular file, whole, of a size the project handles: checked before decoding.
  std::vector<unsigned char> bytes;
  catar::ImageHeader header;
  if (!catar::ReadImageFileBytes(path, bytes, header, error))
  {
    return false;
  }
  cv::Mat image;
  try
  {
    image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  }
  catch (const cv::Exception& e)
  {
    error = "cannot read image '" + path + "': " + e.what();
    return false;
  }
  if (image.empty())
  {
    error = "cannot read image '" + path + "' (missing or not an image)";
    return false;
  }
  if (image.depth() == CV_16U)
  {
    image.convertTo(image, CV_8U, 1.0 / 257.0);
  }
  else if (image.depth() != CV_8U)
  {
    error = "image '" + path + "' has an unsupported depth (8- or 16-bit expected)";
    return false;
  }
  switch (image.channels())
  {
    case 1:
      cv::cvtColor(image, rgba, cv::COLOR_GRAY2RGBA);
      break;
    case 3:
      cv::cvtColor(image, rgba, cv::COLOR_BGR2RGBA);
      break;
    case 4:
      cv::cvtColor(image, rgba, cv::COLOR_BGRA2RGBA);
      break;
    default:
      error = "image '" + path + "' has " + std::to_string(image.channels()) +
        " channels (1, 3 or 4 expected)";
      return false;
  }
  return true;
}

catar::ConstImageView View(const cv::Mat& rgba)
{
  return catar::ConstImageView{ rgba.ptr<std::uint8_t>(0), rgba.cols, rgba.rows,
    static_cast<std::ptrdiff_t>(rgba.step[0]) };
}

// Parses "R,G,B" or "R,G,B,A" (each 0..255).
bool ParseColour(const std::string& text, std::array<std::uint8_t, 4>& colour)
{
  std::vector<long> values;
  const char* p = text.c_str();
  for (;;)
  {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(p, &end, 10);
    if (end == p || errno != 0 || v < 0 || v > 255)
    {
      return false;
    }
    values.push_back(v);
    if (*end == '\0')
    {
      break;
    }
    if (*end != ',')
    {
      return false;
    }
    p = end + 1;
  }
  if (values.size() != 3 && values.size() != 4)
  {
    return false;
  }
  for (std::size_t i = 0; i < 4; ++i)
  {
    colour[i] = static_cast<std::uint8_t>(i < values.size() ? values[i] : 255);
  }
  return true;
}

std::string Number(double v)
{
  if (std::isinf(v))
  {
    return v > 0 ? "inf" : "-inf";
  }
  if (std::isnan(v))
  {
    return "nan";
  }
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", v);
  return buffer;
}
} // namespace

namespace
{
int Run(int argc, char* argv[])
{
  CLI::App app("Compares two renderings of the same scene and prints one metric per line (name "
               "value): silhouette IoU, mean and max (Hausdorff) boundary distance in pixels, PSNR "
               "of RGB in dB and SSIM of the luminance (Documentation/accuracy-metrics.md). A "
               "pixel is part of the object when it differs from the background (--background, "
               "or the pixel of --background-image) by more than T levels in some channel of "
               "RGBA.",
    kProgram);
  app.footer("Exit status: 0 success, 1 unreadable or incomparable images, 2 usage error.");
  std::vector<std::string> inputs;
  catar::CompareOptions options;
  std::string backgroundImageName;
  std::string csvName;
  std::string diffName;
  std::string backgroundText;
  inputs.resize(2);
  app.add_option("A", inputs[0], "an image (8- or 16-bit grey, RGB or RGBA)")->required();
  app.add_option("B", inputs[1], "the image to compare with A, of the same size")->required();
  app.add_option("--background", backgroundText, "the background colour (default 0,0,0,255)")
    ->type_name("R,G,B[,A]")
    ->check(CLI::Validator(
      [](std::string& text) {
        std::array<std::uint8_t, 4> colour{};
        return ParseColour(text, colour) ? std::string()
                                         : std::string("needs R,G,B or R,G,B,A (0..255)");
      },
      ""));
  app.add_option("--background-image", backgroundImageName,
    "the background, pixel by pixel (an image of the same size)");
  app
    .add_option("--tolerance", options.colorTolerance,
      "levels a channel may differ from the background and stay background (default 0)")
    ->type_name("T")
    ->check(CLI::Range(0, 255));
  app.add_flag("--silhouette-psnr", options.psnrOverSilhouette,
    "the PSNR over the union of the silhouettes only");
  app.add_option("--csv", csvName, "also write a header and one row of the metrics");
  app.add_option("--diff", diffName, "also write |A - B| x 4 as an image (PNG, ...)");
  const int parsed = catar::ParseCommandLine(app, kProgram, argc, argv);
  if (parsed >= 0)
  {
    return parsed;
  }
  if (!backgroundText.empty())
  {
    ParseColour(backgroundText, options.background);
  }

  cv::Mat a, b, background;
  std::string error;
  if (!ReadRgba(inputs[0], a, error) || !ReadRgba(inputs[1], b, error) ||
    (!backgroundImageName.empty() && !ReadRgba(backgroundImageName, background, error)))
  {
    std::fprintf(stderr, "%s: %s\n", kProgram, error.c_str());
    return 1;
  }
  if (!background.empty())
  {
    options.backgroundImage = View(background);
  }
  catar::ImageInput inputA;
  inputA.color = View(a);
  catar::ImageInput inputB;
  inputB.color = View(b);
  const catar::ImageComparison r = catar::CompareImages(inputA, inputB, options);
  if (!r.ok())
  {
    std::fprintf(stderr, "%s: %s\n", kProgram, r.error.c_str());
    return 1;
  }

  const std::vector<std::pair<std::string, std::string>> rows = {
    { "pixels", std::to_string(r.pixels) },
    { "silhouette_pixels_a", std::to_string(r.silhouettePixelsA) },
    { "silhouette_pixels_b", std::to_string(r.silhouettePixelsB) },
    { "iou", Number(r.silhouetteIoU) },
    { "mean_boundary_distance", Number(r.meanBoundaryDistance) },
    { "max_boundary_distance", Number(r.maxBoundaryDistance) },
    { "psnr", Number(r.psnr) },
    { "psnr_pixels", std::to_string(r.psnrPixels) },
    { "ssim", Number(r.ssim) },
  };
  for (const auto& row : rows)
  {
    std::printf("%s %s\n", row.first.c_str(), row.second.c_str());
  }

  if (!csvName.empty())
  {
    std::ostringstream csv;
    csv << "a,b";
    for (const auto& row : rows)
    {
      csv << ',' << row.first;
    }
    csv << '\n' << catar::CsvField(inputs[0]) << ',' << catar::CsvField(inputs[1]);
    for (const auto& row : rows)
    {
      csv << ',' << row.second;
    }
    csv << '\n';
    std::string error;
    if (!catar::WriteWholeFile(csvName, csv.str(), error))
    {
      std::fprintf(stderr, "%s: cannot write the CSV: %s\n", kProgram, error.c_str());
      return 1;
    }
  }

  if (!diffName.empty())
  {
    cv::Mat diff(a.rows, a.cols, CV_8UC4);
    const std::string diffError = catar::DifferenceImage(View(a), View(b),
      catar::ImageView{ diff.ptr<std::uint8_t>(0), diff.cols, diff.rows,
        static_cast<std::ptrdiff_t>(diff.step[0]) });
    bool written = diffError.empty();
    std::vector<uchar> bytes;
    if (written)
    {
      cv::cvtColor(diff, diff, cv::COLOR_RGBA2BGRA);
      // Encoded in memory (the format follows the extension), then written with every error
      // checked.
      const size_t dot = diffName.find_last_of('.');
      try
      {
        written = dot != std::string::npos && cv::imencode(diffName.substr(dot), diff, bytes);
      }
      catch (const cv::Exception&)
      {
        written = false;
      }
    }
    std::string error = "cannot encode the image (is the extension an image format?)";
    if (!written ||
      !catar::WriteWholeFile(diffName, std::string(bytes.begin(), bytes.end()), error))
    {
      std::fprintf(
        stderr, "catadioptric-compare: cannot write '%s': %s\n", diffName.c_str(), error.c_str());
      return 1;
    }
  }
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  return catar::RunMain("catadioptric-compare", Run, argc, argv);
}
