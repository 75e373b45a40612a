#include "vtkCatadioptricParallel.h"

#include "vtkSMPTools.h"

#include "Parallel.h"

#include <algorithm>
#include <cstring>

namespace
{
// The pool's ranges, handed to a loop body of this class.
struct Call
{
  void (*Function)(void*, vtkIdType, vtkIdType);
  void* Functor;
};

void Adapter(void* call, std::int64_t b, std::int64_t e)
{
  const Call& c = *static_cast<const Call*>(call);
  c.Function(c.Functor, static_cast<vtkIdType>(b), static_cast<vtkIdType>(e));
}
} // namespace

int vtkCatadioptricParallel::GetNumberOfThreads()
{
  if (!std::strcmp(vtkSMPTools::GetBackend(), "Sequential"))
  {
    return 1;
  }
  return std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
}

void vtkCatadioptricParallel::EnableThreads(int threads)
{
  vtkSMPTools::SetBackend("STDThread");
  if (threads > 0)
  {
    vtkSMPTools::Initialize(threads);
  }
}

void vtkCatadioptricParallel::Run(
  vtkIdType begin, vtkIdType end, vtkIdType grain, RangeFunction call, void* functor)
{
  if (end <= begin)
  {
    return;
  }
  // The thread count is asked for only when the loop can use threads (asking VTK costs).
  const int threads = end - begin > std::max<vtkIdType>(grain, 1) ? GetNumberOfThreads() : 1;
  if (threads == 1)
  {
    call(functor, begin, end);
    return;
  }
  Call c{ call, functor };
  catar::parallel::Run(begin, end, grain, threads, &Adapter, &c);
}
