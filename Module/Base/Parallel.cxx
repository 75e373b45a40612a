#include "Parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h> // getpid
#endif

namespace catar
{
namespace parallel
{
namespace
{

// Worker threads that wait for a loop, take ranges from a shared counter until none is left, and
// wait again. One loop at a time: Busy is taken by the loop's caller. Waiting threads spin for a
// while before they sleep: the next loop of a frame usually starts within a millisecond, and
// waking a sleeping thread costs tens of microseconds.
class Pool
{
public:
  ~Pool() { this->Resize(0); }

  // Makes the pool `workers` threads (besides the caller's).
  void Resize(int workers)
  {
    if (static_cast<int>(this->Threads.size()) == workers)
    {
      return;
    }
    this->Stop.store(true);
    this->Publish();
    for (std::thread& t : this->Threads)
    {
      t.join();
    }
    this->Threads.clear();
    this->Stop.store(false);
    // A new thread starts from the current generation: it runs the next loop, not an old one.
    const unsigned long generation = this->Generation.load();
    for (int i = 0; i < workers; ++i)
    {
      try
      {
        this->Threads.emplace_back([this, generation] { this->Work(generation); });
      }
      catch (const std::system_error&)
      {
        // No thread can be started now (no memory left for its stack, or the process's thread
        // limit): the loops run on the threads there are, the caller's at least.
        break;
      }
    }
  }

  void Loop(
    std::int64_t begin, std::int64_t end, std::int64_t chunk, RangeFunction call, void* functor)
  {
    this->Call = call;
    this->Functor = functor;
    this->End = end;
    this->Chunk = chunk;
    this->Next.store(begin);
    this->Running.store(static_cast<int>(this->Threads.size()));
    this->Publish();
    this->Take();
    if (!SpinUntil([this] { return this->Running.load() == 0; }))
    {
      Sleep(this->CallerSleeping, this->Done, [this] { return this->Running.load() == 0; });
    }
  }

  std::atomic<bool> Busy{ false };

private:
  static void Pause()
  {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#else
    std::this_thread::yield();
#endif
  }

  // Polls `ready` for up to ~0.2 ms, giving the core away every 64 polls (on a busy machine the
  // thread waited for may be runnable but off a core); true when it held.
  template<typename Ready>
  static bool SpinUntil(Ready ready)
  {
    using Clock = std::chrono::steady_clock;
    const auto until = Clock::now() + std::chrono::microseconds(200);
    for (int i = 0;; ++i)
    {
      if (ready())
      {
        return true;
      }
      if ((i & 63) == 63)
      {
        if (Clock::now() > until)
        {
          return false;
        }
        std::this_thread::yield();
      }
      Pause();
    }
  }

  // Sleeps until `ready`. The thread that makes it ready checks `sleeping` after doing so and
  // notifies under the mutex (sequentially consistent atomics: one of the two sees the other).
  template<typename Ready>
  void Sleep(std::atomic<int>& sleeping, std::condition_variable& cv, Ready ready)
  {
    sleeping.fetch_add(1);
    {
      std::unique_lock<std::mutex> lock(this->Mutex);
      cv.wait(lock, ready);
    }
    sleeping.fetch_sub(1);
  }

  void WakeUp(std::atomic<int>& sleeping, std::condition_variable& cv)
  {
    if (sleeping.load() > 0)
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      cv.notify_all();
    }
  }

  // A new generation: a loop to run, or Stop.
  void Publish()
  {
    this->Generation.fetch_add(1);
    this->WakeUp(this->WorkersSleeping, this->Wake);
  }

  // Runs ranges until none is left.
  void Take()
  {
    for (;;)
    {
      const std::int64_t b = this->Next.fetch_add(this->Chunk);
      if (b >= this->End)
      {
        return;
      }
      this->Call(this->Functor, b, std::min(b + this->Chunk, this->End));
    }
  }

  void Work(unsigned long seen)
  {
    for (;;)
    {
      auto changed = [&] { return this->Generation.load() != seen; };
      if (!SpinUntil(changed))
      {
        Sleep(this->WorkersSleeping, this->Wake, changed);
      }
      seen = this->Generation.load();
      if (this->Stop.load())
      {
        return;
      }
      this->Take();
      if (this->Running.fetch_sub(1) == 1)
      {
        this->WakeUp(this->CallerSleeping, this->Done);
      }
    }
  }

  std::vector<std::thread> Threads;
  std::mutex Mutex;
  std::condition_variable Wake;
  std::condition_variable Done;
  std::atomic<int> WorkersSleeping{ 0 };
  std::atomic<int> CallerSleeping{ 0 };
  std::atomic<unsigned long> Generation{ 0 };
  std::atomic<int> Running{ 0 };
  std::atomic<bool> Stop{ false };
  // The loop: written before Generation changes, read by the workers after they see it change.
  RangeFunction Call = nullptr;
  void* Functor = nullptr;
  std::int64_t End = 0;
  std::int64_t Chunk = 1;
  std::atomic<std::int64_t> Next{ 0 };
};

Pool& ThePool()
{
  static Pool pool;
#if defined(__unix__) || defined(__APPLE__)
  // A child of fork() has none of its parent's pool threads: it gets a pool of its own (the
  // parent's copy is left alone; its threads do not exist in the child).
  static const pid_t owner = getpid();
  static Pool* child = nullptr;
  static pid_t childPid = 0;
  const pid_t pid = getpid();
  if (pid != owner)
  {
    if (!child || childPid != pid)
    {
      child = new Pool; // never destroyed: a forked child may hold copies of several
      childPid = pid;
    }
    return *child;
  }
#endif
  return pool;
}

std::atomic<int> defaultThreads{ 0 };
} // namespace

int DefaultThreads()
{
  const int set = defaultThreads.load();
  return set > 0 ? set : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void SetDefaultThreads(int threads)
{
  defaultThreads.store(std::max(0, threads));
}

void Run(std::int64_t begin, std::int64_t end, std::int64_t grain, int threads, RangeFunction call,
  void* functor)
{
  const std::int64_t n = end - begin;
  if (n <= 0)
  {
    return;
  }
  const bool single = grain == 0; // one index per range
  grain = std::max<std::int64_t>(grain, 1);
  if (threads < 1)
  {
    threads = DefaultThreads();
  }
  if (n <= grain)
  {
    threads = 1;
  }
  Pool& pool = ThePool();
  bool idle = false;
  if (threads == 1 || !pool.Busy.compare_exchange_strong(idle, true))
  {
    call(functor, begin, end); // one thread, or a loop inside a loop
    return;
  }
  pool.Resize(threads - 1);
  // Ranges of at least `grain`, about four per thread so that uneven ones even out.
  const std::int64_t chunk =
    single ? 1 : std::max(grain, (n + 4 * threads - 1) / (4 * std::int64_t(threads)));
  pool.Loop(begin, end, chunk, call, functor);
  pool.Busy.store(false);
}
} // namespace parallel
} // namespace catar
