// The command-line programs' --threads: one count for every parallel loop a program runs.
#ifndef catarThreads_h
#define catarThreads_h

#include "Parallel.h"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <thread>

namespace catar
{
/// Sets the thread count of the Core's parallel loops and of OpenCV's (marker detection, image
/// filters) to `threads`; 0 leaves the defaults (one a core). Programs with VTK filters also call
/// vtkCatadioptricParallel::EnableThreads(threads).
inline void UseThreads(int threads)
{
  if (threads > 0)
  {
    parallel::SetDefaultThreads(threads);
    // No more than the cores for OpenCV: its TBB backend warns on standard error when asked for
    // more workers than it allows (VTK's STDThread backend is capped the same way).
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    cv::setNumThreads(std::min(threads, cores));
  }
}
} // namespace catar

#endif
