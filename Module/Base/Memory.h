// CatadioptricAR Core: how much memory a stage may still take, and the error that says which
// stage ran out and by how much. A stage that is about to allocate in proportion to its input
// (a mesh's triangles, an image's pixels, a batch of points) asks RequireMemory first, with its
// estimate; one that runs out anyway throws OutOfMemory with its own sizes (OutOfMemoryWhile).
#ifndef catarMemory_h
#define catarMemory_h

#include <stdexcept>
#include <string>

namespace catar
{
/// Memory this process can still allocate, and what bounds it.
struct MemoryHeadroom
{
  double bytes = 0.0; ///< +infinity where nothing bounds it (or nothing could be read)
  std::string bound;  ///< e.g. "the address-space limit (ulimit -v 900000)"
};

/// The smallest of: what the address-space limit (RLIMIT_AS, `ulimit -v`) leaves above the
/// process's present size; what the control group's memory.max leaves above memory.current;
/// the machine's available memory and free swap (MemAvailable + SwapFree). Linux; elsewhere
/// unbounded.
MemoryHeadroom AvailableMemory();

/// A stage ran out of memory: its message names the stage and the sizes ("projecting 1046530
/// points and 2093056 triangles needs about 1.1 GB; 430 MB is left under the address-space
/// limit (ulimit -v 900000)").
class OutOfMemory : public std::runtime_error
{
public:
  explicit OutOfMemory(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

/// "1.2 GB", "430 MB", "12 kB", "512 bytes" (powers of 1000).
std::string FormatBytes(double bytes);

/// Throws OutOfMemory ("WHAT needs about N; M is left under BOUND") when `bytes` is more than
/// AvailableMemory() leaves. `what` names the stage and its sizes.
void RequireMemory(double bytes, const std::string& what);

/// " (430 MB left under the address-space limit (ulimit -v 900000))" from AvailableMemory(), or
/// "" when nothing bounds it: what an allocation that failed had left.
std::string MemoryLeftText();

/// The message for a std::bad_alloc caught while doing `what`: "out of memory while WHAT"
/// and, when known, what is left ("; 430 MB is left under ...").
std::string OutOfMemoryWhile(const std::string& what);
} // namespace catar

#endif
