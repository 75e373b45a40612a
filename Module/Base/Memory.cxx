#include "Memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace catar
{
namespace
{
constexpr double kUnbounded = std::numeric_limits<double>::infinity();

#if defined(__linux__)
// A number read from a one-value file (cgroup files); false for "max" or no file.
bool ReadNumberFile(const char* path, double& value)
{
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word == "max")
  {
    return false;
  }
  try
  {
    value = std::stod(word);
    return true;
  }
  catch (const std::exception&)
  {
    return false;
  }
}

// "Key:   N kB" of /proc/meminfo, in bytes; false when absent.
bool ReadMemInfo(const std::string& key, double& bytes)
{
  std::ifstream in("/proc/meminfo");
  std::string name;
  double kb = 0.0;
  std::string unit;
  while (in >> name >> kb)
  {
    std::getline(in, unit);
    if (name == key + ":")
    {
      bytes = kb * 1024.0;
      return true;
    }
  }
  return false;
}

// The process's virtual size (the first field of /proc/self/statm, in pages).
double VirtualSize()
{
  std::ifstream in("/proc/self/statm");
  double pages = 0.0;
  if (!(in >> pages))
  {
    return 0.0;
  }
  return pages * static_cast<double>(sysconf(_SC_PAGESIZE));
}
#endif

void Consider(MemoryHeadroom& h, double bytes, const std::string& bound)
{
  bytes = std::max(0.0, bytes);
  if (bytes < h.bytes)
  {
    h.bytes = bytes;
    h.bound = bound;
  }
}
} // namespace

MemoryHeadroom AvailableMemory()
{
  MemoryHeadroom h;
  h.bytes = kUnbounded;
#if defined(__linux__)
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
  {
    std::ostringstream s;
    s << "the address-space limit (ulimit -v " << limit.rlim_cur / 1024 << ")";
    Consider(h, static_cast<double>(limit.rlim_cur) - VirtualSize(), s.str());
  }
  double max = 0.0;
  double current = 0.0;
  if (ReadNumberFile("/sys/fs/cgroup/memory.max", max) &&
    ReadNumberFile("/sys/fs/cgroup/memory.current", current))
  {
    Consider(h, max - current, "the control group's memory.max");
  }
  double available = 0.0;
  double swap = 0.0;
  if (ReadMemInfo("MemAvailable", available))
  {
    ReadMemInfo("SwapFree", swap);
    Consider(h, available + swap, "the machine's available memory and swap");
  }
#endif
  return h;
}

std::string FormatBytes(double bytes)
{
  const char* units[] = { "bytes", "kB", "MB", "GB", "TB", "PB" };
  int u = 0;
  while (bytes >= 1000.0 && u < 5)
  {
    bytes /= 1000.0;
    ++u;
  }
  char text[64];
  if (u == 0)
  {
    std::snprintf(text, sizeof(text), "%.0f bytes", bytes);
  }
  else
  {
    std::snprintf(text, sizeof(text), bytes < 10.0 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
  }
  return text;
}

void RequireMemory(double bytes, const std::string& what)
{
  const MemoryHeadroom h = AvailableMemory();
  if (bytes > h.bytes)
  {
    throw OutOfMemory(what + " needs about " + FormatBytes(bytes) + "; " + FormatBytes(h.bytes) +
      " is left under " + h.bound);
  }
}

std::string MemoryLeftText()
{
  const MemoryHeadroom h = AvailableMemory();
  return std::isfinite(h.bytes) ? " (" + FormatBytes(h.bytes) + " left under " + h.bound + ")"
                                : std::string();
}

std::string OutOfMemoryWhile(const std::string& what)
{
  return "out of memory while " + what + MemoryLeftText();
}
} // namespace catar
