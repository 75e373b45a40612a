/**
 * @class   vtkCatadioptricParallel
 * @brief   parallel loops on a pool of threads that outlive the loop: the project's one policy
 *
 * Every parallel loop of the project runs on Core's pool (Module/Base/Parallel.h: threads made once
 * and kept waiting between loops; VTK 9.2's STDThread backend starts and joins its threads inside
 * every vtkSMPTools::For, about 0.13 ms a loop on two cores, a tenth of a 10 ms frame). This class
 * is the VTK side of it: the filters' loops, with the thread count VTK's settings give.
 *
 * Threads are opt-in, as in VTK: EnableThreads() (programs, and `catadioptricar.enable_threads()`
 * in Python) selects VTK's STDThread backend; without it Debian's VTK runs loops on one thread.
 *
 * It follows vtkSMPTools' settings: as many threads as
 * vtkSMPTools::GetEstimatedNumberOfThreads() (vtkSMPTools::Initialize(n), VTK_SMP_MAX_THREADS),
 * and none but the caller's with the Sequential backend. A loop started while another runs (from
 * another thread, or from inside a loop body) runs on its caller's thread alone. Loop bodies must
 * not throw.
 */
#ifndef vtkCatadioptricParallel_h
#define vtkCatadioptricParallel_h

#include "CatadioptricARCommonModule.h" // export macro
#include "vtkType.h"

#include <type_traits>

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricParallel
{
public:
  /// Calls f(b, e) on disjoint ranges [b, e) covering [begin, end), each of at least `grain`
  /// elements (but the last), from the pool's threads and the caller's; returns when all are done.
  /// Ranges of `grain` elements or fewer run on the caller's thread.
  template<typename Functor>
  static void For(vtkIdType begin, vtkIdType end, vtkIdType grain, Functor&& f)
  {
    using F = typename std::remove_reference<Functor>::type;
    Run(
      begin, end, grain, [](void* fn, vtkIdType b, vtkIdType e) { (*static_cast<F*>(fn))(b, e); },
      const_cast<void*>(static_cast<const void*>(&f)));
  }

  /// Calls f(i) for every i in [begin, end), the threads taking one index at a time as they
  /// become free: for a few tasks of uneven cost, listed from the costliest down (a range per
  /// thread, as For makes them, could give one thread all the costly ones).
  template<typename Functor>
  static void ForEachIndex(vtkIdType begin, vtkIdType end, Functor&& f)
  {
    using F = typename std::remove_reference<Functor>::type;
    Run(
      begin, end, 0,
      [](void* fn, vtkIdType b, vtkIdType e) {
        for (vtkIdType i = b; i < e; ++i)
        {
          (*static_cast<F*>(fn))(i);
        }
      },
      const_cast<void*>(static_cast<const void*>(&f)));
  }

  /// The number of threads a loop uses (the caller's included).
  static int GetNumberOfThreads();

  /// The one opt-in for threads: selects vtkSMPTools' STDThread backend and, when threads > 0,
  /// that many threads (vtkSMPTools::Initialize). The environment variable
  /// VTK_SMP_BACKEND_IN_USE, read by VTK at start, does the same without code.
  static void EnableThreads(int threads = 0);

  /// Asks for the cache line at p, which a loop body will read soon (gathers through an index:
  /// the misses of several elements then overlap). A hint only; nothing on other compilers.
  static void Prefetch(const void* p)
  {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
  }

private:
  using RangeFunction = void (*)(void*, vtkIdType, vtkIdType);
  // grain 0: ranges of one index.
  static void Run(
    vtkIdType begin, vtkIdType end, vtkIdType grain, RangeFunction call, void* functor);
};

#endif
// VTK-HeaderTest-Exclude: vtkCatadioptricParallel.h
