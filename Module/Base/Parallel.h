// CatadioptricAR Core: parallel loops on one pool of threads that outlive the loops. Every
// parallel loop of the project runs here: the VTK filters through vtkCatadioptricParallel (which
// takes the thread count from vtkSMPTools), the mesh preparation library directly.
//
// Why a pool: the per-frame filters run a dozen parallel loops a frame, and VTK 9.2's STDThread
// backend starts and joins its threads inside every vtkSMPTools::For, about 0.13 ms a loop on two
// cores (a tenth of a 10 ms frame). Here the threads are made once and wait between loops.
//
// A loop started while another runs (from another thread, or from inside a loop body) runs on its
// caller's thread alone. Loop bodies must not throw (ForCatching carries exceptions over).
#ifndef catarParallel_h
#define catarParallel_h

#include <algorithm>
#include <cstdint>
#include <exception>
#include <mutex>
#include <type_traits>

namespace catar
{
namespace parallel
{
using RangeFunction = void (*)(void* functor, std::int64_t begin, std::int64_t end);

/// Calls call(functor, b, e) on disjoint ranges [b, e) covering [begin, end), each of at least
/// `grain` elements (but the last; grain 0: ranges of one index), on `threads` threads (the
/// caller's included; < 1 means DefaultThreads()); returns when all are done.
void Run(std::int64_t begin, std::int64_t end, std::int64_t grain, int threads, RangeFunction call,
  void* functor);

/// The thread count of loops given none: std::thread::hardware_concurrency() unless set.
int DefaultThreads();

/// Asks for the cache line at p, which a loop body will read soon (gathers through an index: the
/// misses of several elements then overlap). A hint only; nothing on other compilers.
inline void Prefetch(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}
/// Sets it (< 1: back to the hardware's).
void SetDefaultThreads(int threads);

/// f(b, e) on ranges of at least `grain` elements, on `threads` threads (< 1: the default).
template<typename Functor>
void For(std::int64_t begin, std::int64_t end, std::int64_t grain, int threads, Functor&& f)
{
  using F = typename std::remove_reference<Functor>::type;
  Run(
    begin, end, std::max<std::int64_t>(grain, 1), threads,
    [](void* fn, std::int64_t b, std::int64_t e) { (*static_cast<F*>(fn))(b, e); },
    const_cast<void*>(static_cast<const void*>(&f)));
}

/// f(i) for every i, the threads taking one index at a time as they become free (for a few tasks
/// of uneven cost, listed from the costliest down).
template<typename Functor>
void ForEachIndex(std::int64_t begin, std::int64_t end, int threads, Functor&& f)
{
  using F = typename std::remove_reference<Functor>::type;
  Run(
    begin, end, 0, threads,
    [](void* fn, std::int64_t b, std::int64_t e) {
      for (std::int64_t i = b; i < e; ++i)
      {
        (*static_cast<F*>(fn))(i);
      }
    },
    const_cast<void*>(static_cast<const void*>(&f)));
}

/// As For, for bodies that may throw: the first exception is rethrown on the caller's thread
/// once the loop is over (the ranges after it may or may not have run).
template<typename Functor>
void ForCatching(std::int64_t begin, std::int64_t end, std::int64_t grain, int threads, Functor&& f)
{
  std::exception_ptr error;
  std::mutex mutex;
  For(begin, end, grain, threads, [&](std::int64_t b, std::int64_t e) {
    try
    {
      f(b, e);
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error)
      {
        error = std::current_exception();
      }
    }
  });
  if (error)
  {
    std::rethrow_exception(error);
  }
}
} // namespace parallel
} // namespace catar

#endif
