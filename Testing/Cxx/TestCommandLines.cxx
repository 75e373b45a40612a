// The four programs' shared command line (CLI11): --version, --threads, one-line usage errors with
// a suggestion for a mistyped option.
#include "TestPrograms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace
{
struct Program
{
  const char* name;
  const char* path;
  const char* misspelt;  ///< an option with one letter wrong
  const char* suggested; ///< the option the program should suggest for it
};

const std::vector<Program>& Programs()
{
  static const std::vector<Program> programs = {
    { "catadioptric-render", CATAR_RENDER_PROGRAM, "--antialas", "--antialias" },
    { "catadioptric-compare", CATAR_COMPARE_PROGRAM, "--tolerence=3", "--tolerance" },
    { "catadioptric-pose", CATAR_POSE_PROGRAM, "--thresold", "--threshold" },
    { "catadioptric-mirror-outline", CATAR_MIRROR_OUTLINE_PROGRAM, "--overlya", "--overlay" },
    { "catadioptric-calibrate", CATAR_CALIBRATE_PROGRAM, "--evrey", "--every" },
  };
  return programs;
}

int Lines(const std::string& text)
{
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
} // namespace

TEST(CommandLines, VersionThreadsAndSuggestions)
{
  for (const Program& p : Programs())
  {
    const auto version = catar_test::RunProgram(p.path, "--version");
    EXPECT_EQ(version.status, 0) << p.name << ": " << version.output;
    EXPECT_EQ(version.output, std::string(p.name) + " " + CATAR_VERSION + "\n");

    const auto help = catar_test::RunProgram(p.path, "--help");
    EXPECT_EQ(help.status, 0) << p.name;
    EXPECT_NE(help.output.find("--threads"), std::string::npos) << p.name << ": " << help.output;

    for (const char* bad : { "--threads 0", "--threads 1025", "--threads two" })
    {
      const auto run = catar_test::RunProgram(p.path, bad);
      EXPECT_EQ(run.status, 2) << p.name << " " << bad << ": " << run.output;
      EXPECT_EQ(Lines(run.output), 1) << p.name << " " << bad << ": " << run.output;
      EXPECT_NE(run.output.find("--threads"), std::string::npos) << run.output;
    }

    const auto misspelt = catar_test::RunProgram(p.path, p.misspelt);
    EXPECT_EQ(misspelt.status, 2) << p.name << ": " << misspelt.output;
    EXPECT_EQ(Lines(misspelt.output), 1) << misspelt.output;
    EXPECT_EQ(misspelt.output.rfind(std::string(p.name) + ": ", 0), 0u) << misspelt.output;
    EXPECT_NE(
      misspelt.output.find(std::string("did you mean ") + p.suggested + "?"), std::string::npos)
      << p.name << ": " << misspelt.output;
    // Nothing is suggested for an option unlike any.
    const auto unlike = catar_test::RunProgram(p.path, "--zzzzzzzz");
    EXPECT_EQ(unlike.status, 2) << unlike.output;
    EXPECT_EQ(unlike.output.find("did you mean"), std::string::npos) << unlike.output;
  }
}

// --threads is applied: the render's summary reports the count asked for, and the image does not
// depend on it.
TEST(CommandLines, RenderThreadsAppliedImageUnchanged)
{
  std::vector<std::string> images;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (const int asked : { 1, 2, cores + 1 })
  {
    // VTK's STDThread backend uses no more threads than cores.
    const int threads = std::min(asked, cores);
    const std::string out =
      ::testing::TempDir() + "/catar_threads_" + std::to_string(asked) + ".png";
    const auto run = catar_test::RunProgram(
      CATAR_RENDER_PROGRAM, "--json --threads " + std::to_string(asked) + " -o '" + out + "'");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_EQ(run.output.find("Warning"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("\"threads\": " + std::to_string(threads) + ","), std::string::npos)
      << run.output;
    images.push_back(Slurp(out));
    ASSERT_FALSE(images.back().empty()) << out;
  }
  EXPECT_EQ(images[0], images[1]);
  EXPECT_EQ(images[0], images[2]);
}

// catadioptric-compare's own checks, now through CLI11: two images, the colour and tolerance
// ranges, and the metrics printed.
TEST(CommandLines, CompareArguments)
{
  const std::string image = std::string(CATAR_SOURCE_DIR) + "/Testing/Baseline/LitFlat.png";
  const std::string quoted = "'" + image + "' ";
  for (const std::string& bad :
    { quoted, quoted + quoted + quoted, quoted + quoted + "--background 1,2",
      quoted + quoted + "--background 1,2,300", quoted + quoted + "--tolerance 256",
      quoted + quoted + "--tolerance=-1", quoted + quoted + "--csv" })
  {
    const auto run = catar_test::RunProgram(CATAR_COMPARE_PROGRAM, bad);
    EXPECT_EQ(run.status, 2) << bad << ": " << run.output;
    EXPECT_EQ(Lines(run.output), 1) << bad << ": " << run.output;
  }
  const auto same = catar_test::RunProgram(
    CATAR_COMPARE_PROGRAM, quoted + quoted + "--background=0,0,0,0 --tolerance 3 --threads 1");
  EXPECT_EQ(same.status, 0) << same.output;
  EXPECT_NE(same.output.find("\niou 1\n"), std::string::npos) << same.output;
  EXPECT_NE(same.output.find("\nmax_boundary_distance 0\n"), std::string::npos) << same.output;
}
