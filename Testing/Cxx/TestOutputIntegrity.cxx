// Outputs whole or absent: a full disk (a real small tmpfs mounted here), an output that is also
// an input, an error in the middle of a sequence, SIGINT and SIGTERM, two writers of one file.
// Each leaves either the whole output or none, and the program says which.
#include "FileOutput.h"
#include "TestPrograms.h"
#include "VideoIO.h"

#include <gtest/gtest.h>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace
{
std::string Folder(const std::string& name)
{
  const std::string dir = std::string(CATAR_TEST_OUTPUT_DIR) + "/integrity-" + name;
  mkdir(CATAR_TEST_OUTPUT_DIR, 0755);
  const std::string wipe = "rm -rf '" + dir + "'";
  EXPECT_EQ(std::system(wipe.c_str()), 0);
  mkdir(dir.c_str(), 0755);
  return dir;
}

std::string Read(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool Exists(const std::string& path)
{
  return ::access(path.c_str(), F_OK) == 0;
}

// The names in a folder (no . and ..).
std::vector<std::string> Names(const std::string& dir)
{
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str()))
  {
    while (dirent* e = readdir(d))
    {
      const std::string n = e->d_name;
      if (n != "." && n != "..")
      {
        names.push_back(n);
      }
    }
    closedir(d);
  }
  return names;
}

// A real file system of `kilobytes`, mounted for the test (needs root, as CI runs).
struct SmallDisk
{
  explicit SmallDisk(int kilobytes)
  {
    char name[] = "/tmp/catar-small-disk-XXXXXX";
    if (mkdtemp(name))
    {
      this->Dir = name;
      const std::string options = "size=" + std::to_string(kilobytes) + "k";
      this->Mounted = ::mount("tmpfs", name, "tmpfs", 0, options.c_str()) == 0;
    }
  }
  ~SmallDisk()
  {
    if (this->Mounted)
    {
      ::umount(this->Dir.c_str());
    }
    if (!this->Dir.empty())
    {
      ::rmdir(this->Dir.c_str());
    }
  }
  std::string Dir;
  bool Mounted = false;
};

// A small sequence: `frames` numbered background frames (bg_001.png ...) and a scene over them.
std::string MakeSequence(const std::string& dir, int frames, const std::string& colour = "0.9")
{
  const int w = 240, h = 190;
  catar::FrameWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(dir + "/bg_%03d.png", w, h, 0.0, error)) << error;
  for (int k = 0; k < frames; ++k)
  {
    catar::Frame f;
    f.width = w;
    f.height = h;
    f.rgba.assign(static_cast<std::size_t>(w) * h * 4, 255);
    for (std::size_t i = 0; i < f.rgba.size(); i += 4)
    {
      f.rgba[i] = static_cast<unsigned char>((5 * k) % 256);
      f.rgba[i + 1] = static_cast<unsigned char>((i / 4) % 251);
      f.rgba[i + 2] = static_cast<unsigned char>((i / 4 / w) % 199);
    }
    EXPECT_TRUE(writer.Write(k + 1, f, error)) << error;
  }
  const std::string scene = dir + "/scene.yaml";
  std::ofstream(scene) << R"(camera:
  image_width: 240
  image_height: 190
  camera_matrix: [ 180.0, 0.0, 119.5, 0.0, 180.0, 94.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
background: { type: video, file: bg_%03d.png, fps: 25 }
objects:
  - { type: sphere, radius: 0.05, resolution: 24, translate: [ 0.0, -0.2, 0.95 ],
      color: [ )" << colour
                       << ", 0.3, 0.2 ] }\n";
  return scene;
}

catar_test::ProgramRun Render(const std::string& arguments)
{
  return catar_test::RunProgram(CATAR_RENDER_PROGRAM, arguments);
}

// Runs catadioptric-render with `arguments` (CATAR_PROGRESS_AFTER=0: progress at once), reads its
// output until `waitFor` appears, sends `signal`, and reads the rest. Exited: the status; killed
// by a signal: -1.
catar_test::ProgramRun RenderUntilThenSignal(
  const std::vector<std::string>& arguments, const std::string& waitFor, int signal)
{
  catar_test::ProgramRun run;
  int fds[2];
  if (::pipe(fds) != 0)
  {
    return run;
  }
  const pid_t pid = ::fork();
  if (pid < 0)
  {
    return run;
  }
  if (pid == 0)
  {
    ::dup2(fds[1], 2);
    ::dup2(fds[1], 1);
    ::close(fds[0]);
    ::setenv("CATAR_PROGRESS_AFTER", "0", 1);
    std::vector<char*> argv{ const_cast<char*>(CATAR_RENDER_PROGRAM) };
    for (const std::string& a : arguments)
    {
      argv.push_back(const_cast<char*>(a.c_str()));
    }
    argv.push_back(nullptr);
    ::execv(CATAR_RENDER_PROGRAM, argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  char buffer[4096];
  while (run.output.find(waitFor) == std::string::npos)
  {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n <= 0)
    {
      break;
    }
    run.output.append(buffer, static_cast<std::size_t>(n));
  }
  ::kill(pid, signal);
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;)
  {
    run.output.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  if (::waitpid(pid, &status, 0) == pid && WIFEXITED(status))
  {
    run.status = WEXITSTATUS(status);
  }
  return run;
}

// Frames of a video that can be read back.
long long Frames(const std::string& video)
{
  catar::FrameReader reader;
  std::string error;
  return reader.Open(video, error) ? reader.GetNumberOfFrames() : -1;
}
} // namespace

// One file written whole, to a temporary name beside it, renamed into place: no other file is
// left, an older file is replaced whole; on a full disk the older file is left as it was and
// nothing else is left behind.
TEST(OutputIntegrity, WholeFileOrTheOldOne)
{
  const std::string dir = Folder("whole-file");
  std::string error;
  ASSERT_TRUE(catar::WriteWholeFile(dir + "/a.bin", std::string(1000, 'x'), error)) << error;
  EXPECT_EQ(Read(dir + "/a.bin"), std::string(1000, 'x'));
  EXPECT_EQ(Names(dir), std::vector<std::string>{ "a.bin" });

  SmallDisk disk(64);
  if (!disk.Mounted)
  {
    GTEST_SKIP() << "cannot mount a small tmpfs here (needs root): the full-disk case is not run";
  }
  const std::string old = disk.Dir + "/old.bin";
  ASSERT_TRUE(catar::WriteWholeFile(old, std::string(20000, 'o'), error)) << error;
  EXPECT_FALSE(catar::WriteWholeFile(old, std::string(200000, 'n'), error));
  EXPECT_NE(error.find("No space left on device"), std::string::npos) << error;
  EXPECT_EQ(Read(old), std::string(20000, 'o')); // the older file, whole
  EXPECT_EQ(Names(disk.Dir), std::vector<std::string>{ "old.bin" });
  EXPECT_FALSE(catar::WriteWholeFile(disk.Dir + "/new.bin", std::string(200000, 'n'), error));
  EXPECT_EQ(Names(disk.Dir), std::vector<std::string>{ "old.bin" });
}

// Another path to the same file (a hard link, "..") is the same file.
TEST(OutputIntegrity, FileIdentities)
{
  const std::string dir = Folder("identities");
  std::ofstream(dir + "/in.png") << "x";
  std::ofstream(dir + "/other.png") << "x";
  ASSERT_EQ(::link((dir + "/in.png").c_str(), (dir + "/linked.png").c_str()), 0);
  catar::FileIdentities inputs;
  inputs.Add(dir + "/in.png");
  inputs.Add(dir + "/missing.png");
  EXPECT_TRUE(inputs.Contains(dir + "/in.png"));
  EXPECT_TRUE(inputs.Contains(dir + "/../integrity-identities/./in.png"));
  EXPECT_TRUE(inputs.Contains(dir + "/linked.png"));
  EXPECT_FALSE(inputs.Contains(dir + "/other.png"));
  EXPECT_FALSE(inputs.Contains(dir + "/missing.png"));
}

// A video to a disk too small for it: refused (status 1, it says so), and neither the video nor
// its temporary file is left; before, it said "wrote" and left an mp4 that could not be opened.
TEST(OutputIntegrity, VideoOnAFullDisk)
{
  const std::string dir = Folder("full-disk");
  const std::string scene = MakeSequence(dir, 30);
  SmallDisk disk(48);
  if (!disk.Mounted)
  {
    GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
  }
  for (const char* name : { "/out.mp4", "/out.avi" })
  {
    const catar_test::ProgramRun run = Render("'" + scene + "' -o '" + disk.Dir + name + "'");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_EQ(run.output.find("wrote"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("could not be written whole"), std::string::npos) << run.output;
    EXPECT_TRUE(Names(disk.Dir).empty()) << Names(disk.Dir).front();
  }
}

// An output that is one of the inputs, by any name, is refused before anything is written: the
// input is left as it was.
TEST(OutputIntegrity, OutputThatIsAnInputIsRefused)
{
  const std::string dir = Folder("same-file");
  const std::string scene = MakeSequence(dir, 4);
  // A video background rendered once to clip.avi, then used as the input of a second scene.
  ASSERT_EQ(Render("'" + scene + "' -o '" + dir + "/clip.avi' --quiet").status, 0);
  std::string text = Read(scene);
  text.replace(text.find("bg_%03d.png"), 11, "clip.avi");
  std::ofstream(dir + "/video.yaml") << text;
  const std::string before = Read(dir + "/clip.avi");
  ASSERT_FALSE(before.empty());
  for (const std::string& out : { dir + "/clip.avi", dir + "/./../integrity-same-file/clip.avi" })
  {
    const catar_test::ProgramRun run = Render("'" + dir + "/video.yaml' -o '" + out + "'");
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("one of the scene's inputs"), std::string::npos) << run.output;
    EXPECT_EQ(Read(dir + "/clip.avi"), before);
  }
  // A background frame as the output pattern, and the scene file as an image output's mask.
  const catar_test::ProgramRun pattern = Render("'" + scene + "' -o '" + dir + "/bg_%03d.png'");
  EXPECT_EQ(pattern.status, 2) << pattern.output;
  const catar_test::ProgramRun mask =
    Render("'" + scene + "' -o '" + dir + "/one.png' --mask '" + dir + "/bg_002.png'");
  EXPECT_EQ(mask.status, 2) << mask.output;
  EXPECT_FALSE(Exists(dir + "/one.png"));
}

// An error in the middle of a sequence (a background frame that cannot be read): status 1, the
// frames written so far kept as out.partial.mp4 and said so; out.mp4 is not written.
TEST(OutputIntegrity, ErrorInTheMiddleKeepsAPartialVideo)
{
  const std::string dir = Folder("error");
  const std::string scene = MakeSequence(dir, 12);
  std::ofstream(dir + "/bg_008.png", std::ios::trunc) << "not a PNG";
  const catar_test::ProgramRun run = Render("'" + scene + "' -o '" + dir + "/out.mp4'");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("frame 7"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("out.partial.mp4"), std::string::npos) << run.output;
  EXPECT_FALSE(Exists(dir + "/out.mp4"));
  EXPECT_EQ(Frames(dir + "/out.partial.mp4"), 7);
  for (const std::string& n : Names(dir))
  {
    EXPECT_EQ(n.find(".partial-"), std::string::npos) << "temporary file left: " << n;
  }
}

// SIGINT and SIGTERM in the middle of a sequence: the program stops after the frame it is on,
// keeps what it wrote as out.partial.mp4 (readable), says so, and exits with 128 + the signal.
TEST(OutputIntegrity, SignalsKeepAPartialVideo)
{
  const std::string dir = Folder("signals");
  const std::string scene = MakeSequence(dir, 400);
  for (const int signal : { SIGINT, SIGTERM })
  {
    std::remove((dir + "/out.partial.mp4").c_str());
    // Its first progress line (10 % of the frames) says it is writing: then the signal.
    const auto run = RenderUntilThenSignal({ scene, "-o", dir + "/out.mp4" }, "frames,", signal);
    const std::string& output = run.output;
    EXPECT_EQ(run.status, 128 + signal) << output;
    EXPECT_NE(output.find(signal == SIGINT ? "SIGINT" : "SIGTERM"), std::string::npos) << output;
    EXPECT_NE(output.find("out.partial.mp4"), std::string::npos) << output;
    EXPECT_FALSE(Exists(dir + "/out.mp4"));
    const long long kept = Frames(dir + "/out.partial.mp4");
    EXPECT_GE(kept, 40) << output;
    EXPECT_LT(kept, 400) << output;
  }
}

// SIGINT while the scene loads (a remeshing of about 250 000 triangles, seconds of work): the
// remesher stops at its next step, the program says so, writes nothing and exits with 130
// (before, the signal's default action killed it in the middle of the remeshing).
TEST(OutputIntegrity, SignalStopsTheRemeshing)
{
  const std::string dir = Folder("signal-remesh");
  std::ofstream(dir + "/scene.yaml")
    << "camera: " << CATAR_SOURCE_DIR << "/Data/calibration/demo-camera.yaml\n"
    << "background: { type: color }\n"
    << "objects:\n  - { type: sphere, radius: 0.2, translate: [ 0, -0.5, 1.0 ], "
       "remesh: { target_area: 2e-6 } }\n";
  const std::string out = dir + "/out.png";
  std::remove(out.c_str());
  const auto run =
    RenderUntilThenSignal({ dir + "/scene.yaml", "-o", out }, "remeshing sphere", SIGINT);
  const std::string& output = run.output;
  EXPECT_EQ(run.status, 130) << "killed by the signal, or another status: " << output;
  EXPECT_NE(output.find("stopped while remeshing"), std::string::npos) << output;
  EXPECT_NE(output.find("stopped by SIGINT while reading the scene; nothing was written"),
    std::string::npos)
    << output;
  EXPECT_EQ(output.find("252"), std::string::npos) << "the remeshing finished: " << output;
  EXPECT_FALSE(Exists(out));
}

// A video whose name is a FIFO or a link to a device is refused at once, and left as it was
// (before, the FIFO was opened to see whether it existed, which waited for a writer forever).
TEST(OutputIntegrity, VideoToAFifoOrADeviceIsRefused)
{
  const std::string dir = Folder("video-special");
  const std::string scene = MakeSequence(dir, 3);
  const std::string fifo = dir + "/out.mp4";
  const std::string device = dir + "/null.avi";
  std::remove(fifo.c_str());
  std::remove(device.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  ASSERT_EQ(::symlink("/dev/null", device.c_str()), 0);
  for (const std::string& out : { fifo, device })
  {
    // `timeout`: a program that waits on the FIFO fails here instead of hanging the test.
    const auto run = catar_test::RunProgram(
      "timeout", "60 '" + std::string(CATAR_RENDER_PROGRAM) + "' '" + scene + "' -o '" + out + "'");
    EXPECT_EQ(run.status, 1) << out << ": " << run.output;
    EXPECT_NE(run.output.find("is not a regular file (a FIFO or a device)"), std::string::npos)
      << run.output;
  }
  struct stat st;
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  ASSERT_EQ(::lstat(device.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
}

// Two renders to one file at once: the file is one of the two videos, whole (before, both
// exited 0 and the file mixed their frames).
TEST(OutputIntegrity, TwoWritersLeaveOneWholeVideo)
{
  const std::string dir = Folder("two-writers");
  const std::string red = MakeSequence(dir, 300, "0.9");
  std::string text = Read(red);
  text.replace(text.find("color: [ 0.9"), 12, "color: [ 0.1");
  std::ofstream(dir + "/blue.yaml") << text;
  // Each alone, for reference.
  ASSERT_EQ(Render("'" + red + "' -o '" + dir + "/red.avi' --quiet").status, 0);
  ASSERT_EQ(Render("'" + dir + "/blue.yaml' -o '" + dir + "/blue.avi' --quiet").status, 0);
  ASSERT_NE(Read(dir + "/red.avi"), Read(dir + "/blue.avi")); // the two can be told apart
  const std::string command = "'" + std::string(CATAR_RENDER_PROGRAM) + "' '" + red + "' -o '" +
    dir + "/both.avi' --quiet & '" + std::string(CATAR_RENDER_PROGRAM) + "' '" + dir +
    "/blue.yaml' -o '" + dir + "/both.avi' --quiet; wait";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string both = Read(dir + "/both.avi");
  EXPECT_TRUE(both == Read(dir + "/red.avi") || both == Read(dir + "/blue.avi"))
    << "the file is neither video whole";
  EXPECT_EQ(Frames(dir + "/both.avi"), 300);
}

// A video codec that takes even sizes only: a 161 x 121 camera's video is 160 x 120, and the
// program says so (it said nothing before).
TEST(OutputIntegrity, OddSizedVideoIsSaid)
{
  const std::string dir = Folder("odd-size");
  std::ofstream(dir + "/odd.yaml") << R"(camera:
  image_width: 161
  image_height: 121
  camera_matrix: [ 120.0, 0.0, 80.0, 0.0, 120.0, 60.0, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
background: { type: color }
sequence: { frames: 3 }
objects:
  - { type: sphere, radius: 0.05, translate: [ 0.0, -0.2, 0.95 ] }
)";
  const catar_test::ProgramRun run =
    Render("'" + dir + "/odd.yaml' -o '" + dir + "/odd.avi' --quiet");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("warning: the video"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("is 160x120, not 161x121"), std::string::npos) << run.output;
  EXPECT_EQ(Frames(dir + "/odd.avi"), 3);
}
