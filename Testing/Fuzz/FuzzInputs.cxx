// FuzzInputs: a bounded mutation fuzzer for what users hand the project: scene and calibration
// files (parsed by catar::ParseScene / ParseCalibration) and mesh files (read, checked, projected
// and composited, as a scene's mesh object is).
//
//   FuzzInputs SEED_DIR... [--iterations N] [--seconds S] [--seed K] [--mutations M]
//
// Every file in the seed folders is mutated N times (byte flips, inserted, deleted and repeated
// ranges, numbers swapped for extreme ones, splices with other seeds) with a fixed random seed, so
// that a run is reproducible; each input gets 1 to M mutations (default 4; 0: the seeds as they
// are, which the valid seeds must pass). Each input must end with a result or an error sentence: a
// crash, an abort or (under the sanitizers) a memory error or undefined behaviour ends the program
// and fails its test. The last input is kept in fuzz-last-input.* in the working folder, so that a
// crash can be replayed.
#include "CalibrationIO.h"
#include "Markers.h"
#include "SceneDescription.h"
#include "Trajectory.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricSceneObjects.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct Seed
{
  std::string name;
  std::string extension; // ".yaml", ".obj", ...
  std::string bytes;
};

std::string ReadFile(const std::filesystem::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One mutation of `data`, drawn from `rng`; `other` is another seed for splices.
void Mutate(std::string& data, const std::string& other, std::mt19937_64& rng)
{
  static const char* const kValues[] = { "nan", ".nan", "inf", "-inf", "1e308", "-1e308", "1e25",
    "0", "-1", "-2147483649", "4294967296", "99999999999999999999", "2.5", "[", "]", "{", "}", "\n",
    ": ", "- ", "\"", "#", "%YAML:1.0\n", "\0" };
  auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  switch (rng() % 7)
  {
    case 0: // flip bits of a few bytes
      for (int k = 0, n = 1 + static_cast<int>(rng() % 4); k < n && !data.empty(); ++k)
      {
        data[pick(data.size())] ^= static_cast<char>(1u << (rng() % 8));
      }
      break;
    case 1: // delete a range
      if (!data.empty())
      {
        const std::size_t at = pick(data.size());
        data.erase(at, 1 + pick(std::min<std::size_t>(64, data.size() - at)));
      }
      break;
    case 2: // repeat a range
      if (!data.empty())
      {
        const std::size_t at = pick(data.size());
        const std::string piece = data.substr(at, 1 + pick(64));
        data.insert(pick(data.size() + 1), piece);
      }
      break;
    case 3: // insert an extreme or structural token
    {
      const char* v = kValues[pick(sizeof(kValues) / sizeof(kValues[0]))];
      data.insert(pick(data.size() + 1), std::string(v, std::max<std::size_t>(1, std::strlen(v))));
      break;
    }
    case 4: // replace a number by an extreme value
    {
      std::vector<std::size_t> starts;
      for (std::size_t i = 0; i < data.size(); ++i)
      {
        if (std::isdigit(static_cast<unsigned char>(data[i])) &&
          (i == 0 || !std::isalnum(static_cast<unsigned char>(data[i - 1]))))
        {
          starts.push_back(i);
        }
      }
      if (!starts.empty())
      {
        const std::size_t at = starts[pick(starts.size())];
        std::size_t end = at;
        while (end < data.size() &&
          (std::isdigit(static_cast<unsigned char>(data[end])) || data[end] == '.'))
        {
          ++end;
        }
        data.replace(at, end - at, kValues[pick(13)]);
      }
      break;
    }
    case 5: // truncate
      data.resize(pick(data.size() + 1));
      break;
    default: // splice with another seed
      if (!other.empty())
      {
        const std::size_t at = pick(other.size());
        data.insert(pick(data.size() + 1), other.substr(at, 1 + pick(256)));
      }
  }
}

class Fuzzer
{
public:
  explicit Fuzzer(const std::string& work)
    : Work(work)
  {
    catar::CameraModel model = catar::DemoScene().camera;
    // A small image: the compositor's cost per input stays low.
    this->Camera->SetModel(model.Resized(166, 131));
  }

  // Runs one input; returns true when it was accepted (false: refused with an error).
  bool Run(const Seed& seed, const std::string& data)
  {
    const std::string file = this->Work + "/fuzz-last-input" + seed.extension;
    {
      std::ofstream out(file, std::ios::binary);
      out << data;
    }
    if (seed.extension == ".yaml" || seed.extension == ".yml" || seed.extension == ".json")
    {
      std::string error;
      catar::SceneDescription scene;
      catar::CameraModel model;
      const bool sceneOk = catar::ParseScene(data, this->Work, scene, error);
      const bool calibrationOk = catar::ParseCalibration(data, model, error);
      catar::MarkerBoard board;
      const bool boardOk = catar::LoadMarkerBoard(file, board, error);
      return sceneOk || calibrationOk || boardOk;
    }
    if (seed.extension == ".tum")
    {
      // A trajectory file: read, and every pose interpolated.
      catar::Trajectory trajectory;
      std::string error;
      if (!catar::ParseTrajectory(data, "fuzz", trajectory, error))
      {
        return false;
      }
      const catar::Mat4 m =
        trajectory.PoseAt(0.5 * (trajectory.poses.front().time + trajectory.poses.back().time));
      return m.allFinite();
    }
    // A mesh file: read and checked as a scene's mesh object, then projected, sorted and drawn.
    try
    {
      catar::SceneObject object;
      object.type = "mesh";
      object.file = file;
      object.translate = catar::Vec3(0.0, -0.3, 1.0);
      object.scale = catar::Vec3::Constant(0.05);
      vtkSmartPointer<vtkPolyData> mesh = vtkCatadioptricSceneObjects::BuildObject(object);
      vtkNew<vtkCatadioptricProjection> projection;
      projection->SetCamera(this->Camera);
      projection->SetInputData(mesh);
      vtkNew<vtkCatadioptricPainterSort> sort;
      sort->SetInputConnection(projection->GetOutputPort());
      vtkNew<vtkCatadioptricCompositor> compositor;
      compositor->AddMeshConnection(sort->GetOutputPort());
      compositor->SetColorArrayName("Colors");
      compositor->Update();
      return compositor->GetExecutive() && compositor->GetErrorCode() == 0;
    }
    catch (const std::exception&)
    {
      return false;
    }
  }

private:
  std::string Work;
  vtkNew<vtkCatadioptricCamera> Camera;
};
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> folders;
  long iterations = 200;
  double seconds = 1e9;
  unsigned long long seed = 1;
  int maxMutations = 4;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--iterations" && i + 1 < argc)
    {
      iterations = std::atol(argv[++i]);
    }
    else if (arg == "--seconds" && i + 1 < argc)
    {
      seconds = std::atof(argv[++i]);
    }
    else if (arg == "--mutations" && i + 1 < argc)
    {
      maxMutations = std::atoi(argv[++i]);
    }
    else if (arg == "--seed" && i + 1 < argc)
    {
      seed = std::strtoull(argv[++i], nullptr, 10);
    }
    else
    {
      folders.push_back(arg);
    }
  }
  std::vector<Seed> seeds;
  for (const std::string& folder : folders)
  {
    for (const auto& entry : std::filesystem::directory_iterator(folder))
    {
      const std::string ext = entry.path().extension().string();
      static const char* const kTypes[] = { ".yaml", ".yml", ".json", ".tum", ".obj", ".ply",
        ".stl", ".vtk", ".vtp" };
      if (entry.is_regular_file() &&
        std::find(std::begin(kTypes), std::end(kTypes), ext) != std::end(kTypes))
      {
        seeds.push_back({ entry.path().filename().string(), ext, ReadFile(entry.path()) });
      }
    }
  }
  std::sort(
    seeds.begin(), seeds.end(), [](const Seed& a, const Seed& b) { return a.name < b.name; });
  if (seeds.empty() || iterations < 1)
  {
    std::fprintf(
      stderr, "usage: FuzzInputs SEED_DIR... [--iterations N] [--seconds S] [--seed K]\n");
    return 2;
  }
  // The readers' and filters' error messages are expected: counted, not printed.
  vtkObject::GlobalWarningDisplayOff();
  Fuzzer fuzzer(std::filesystem::current_path().string());
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long runs = 0, accepted = 0;
  bool outOfTime = false;
  const bool verbose = std::getenv("CATAR_FUZZ_VERBOSE") != nullptr;
  for (long it = 0; it < iterations && !outOfTime; ++it)
  {
    for (const Seed& s : seeds)
    {
      std::string data = s.bytes;
      const int mutations = maxMutations > 0 ? 1 + static_cast<int>(rng() % maxMutations) : 0;
      for (int m = 0; m < mutations; ++m)
      {
        Mutate(data, seeds[rng() % seeds.size()].bytes, rng);
      }
      if (verbose)
      {
        std::fprintf(stderr, "input %ld: %s\n", runs, s.name.c_str());
        std::ofstream(
          std::string("fuzz-input-") + std::to_string(runs % 2) + s.extension, std::ios::binary)
          << data;
      }
      const bool ok = fuzzer.Run(s, data);
      accepted += ok ? 1 : 0;
      if (maxMutations == 0 && !ok)
      {
        std::printf("FuzzInputs: seed %s is refused\n", s.name.c_str());
      }
      ++runs;
      const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (elapsed > seconds)
      {
        outOfTime = true;
        break;
      }
    }
  }
  const double elapsed =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("FuzzInputs: %ld inputs from %zu seeds in %.1f s: %ld accepted, %ld refused with "
              "an error, none crashed\n",
    runs, seeds.size(), elapsed, accepted, runs - accepted);
  return 0;
}
