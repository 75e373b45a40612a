// vtkCatadioptricParallel: every index visited exactly once, ranges of at least the grain, loops
// inside loops and loops from two threads at once, and vtkSMPTools' thread settings followed.
#include "vtkCatadioptricParallel.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#if defined(__unix__)
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace
{
// Runs a loop over [begin, end) and checks that the ranges tile it exactly.
void ExpectTiles(vtkIdType begin, vtkIdType end, vtkIdType grain)
{
  std::vector<std::atomic<int>> visits(static_cast<std::size_t>(end > begin ? end - begin : 0));
  std::mutex mutex;
  std::vector<std::pair<vtkIdType, vtkIdType>> ranges;
  std::set<std::thread::id> threads;
  vtkCatadioptricParallel::For(begin, end, grain, [&](vtkIdType b, vtkIdType e) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      ranges.emplace_back(b, e);
      threads.insert(std::this_thread::get_id());
    }
    for (vtkIdType i = b; i < e; ++i)
    {
      visits[static_cast<std::size_t>(i - begin)].fetch_add(1);
    }
  });
  for (std::size_t i = 0; i < visits.size(); ++i)
  {
    ASSERT_EQ(visits[i].load(), 1) << "index " << begin + static_cast<vtkIdType>(i);
  }
  for (const auto& r : ranges)
  {
    EXPECT_LT(r.first, r.second);
    if (r.second != end)
    {
      EXPECT_GE(r.second - r.first, grain);
    }
  }
  EXPECT_LE(static_cast<int>(threads.size()), vtkCatadioptricParallel::GetNumberOfThreads());
}
} // namespace

TEST(vtkCatadioptricParallel, VisitsEveryIndexOnce)
{
  vtkSMPTools::SetBackend("STDThread");
  ExpectTiles(0, 0, 1);
  ExpectTiles(5, 6, 1);
  ExpectTiles(0, 100, 1000); // one range, the caller's thread
  ExpectTiles(-37, 100003, 7);
  for (int repeat = 0; repeat < 200; ++repeat)
  {
    ExpectTiles(0, 4096, 64); // many loops in a row: the pool's threads wake each time
  }
}

TEST(vtkCatadioptricParallel, ForEachIndexHandsOutOneIndexAtATime)
{
  vtkSMPTools::SetBackend("STDThread");
  // Every index once.
  std::vector<std::atomic<int>> visits(1000);
  vtkCatadioptricParallel::ForEachIndex(0, 1000, [&](vtkIdType i) { visits[i].fetch_add(1); });
  for (std::size_t i = 0; i < visits.size(); ++i)
  {
    ASSERT_EQ(visits[i].load(), 1) << i;
  }
  if (vtkCatadioptricParallel::GetNumberOfThreads() < 2)
  {
    GTEST_SKIP() << "one thread: nothing to hand out";
  }
  // The first (costliest) task keeps its thread until all the others are done: they can only
  // finish if the other threads take them, which they cannot when a thread owns a range of
  // indices (as For's ranges of n / (4 threads) would give it here).
  const vtkIdType n = 33;
  std::atomic<int> done{ 0 };
  std::atomic<bool> othersFinished{ false };
  vtkCatadioptricParallel::ForEachIndex(0, n, [&](vtkIdType i) {
    if (i == 0)
    {
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (done.load() < n - 1 && std::chrono::steady_clock::now() < until)
      {
        std::this_thread::yield();
      }
      othersFinished = done.load() == n - 1;
    }
    done.fetch_add(1);
  });
  EXPECT_TRUE(othersFinished.load());
  EXPECT_EQ(done.load(), n);
}

TEST(vtkCatadioptricParallel, LoopsInsideLoopsAndFromTwoThreads)
{
  vtkSMPTools::SetBackend("STDThread");
  std::atomic<long> sum{ 0 };
  vtkCatadioptricParallel::For(0, 64, 1, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      vtkCatadioptricParallel::For(0, 100, 1, [&](vtkIdType b2, vtkIdType e2) {
        for (vtkIdType j = b2; j < e2; ++j)
        {
          sum += j;
        }
      });
    }
  });
  EXPECT_EQ(sum.load(), 64L * 4950L);

  std::atomic<long> a{ 0 }, b{ 0 };
  auto run = [](std::atomic<long>& total) {
    for (int repeat = 0; repeat < 100; ++repeat)
    {
      vtkCatadioptricParallel::For(0, 10000, 16, [&](vtkIdType i0, vtkIdType i1) {
        for (vtkIdType i = i0; i < i1; ++i)
        {
          total += i;
        }
      });
    }
  };
  std::thread other(run, std::ref(a));
  run(b);
  other.join();
  EXPECT_EQ(a.load(), 100L * 49995000L);
  EXPECT_EQ(b.load(), 100L * 49995000L);
}

#if defined(__unix__)
TEST(vtkCatadioptricParallel, WorksInAForkedChild)
{
  // The parent's pool threads do not exist in a child of fork(): the child must not wait for them.
  vtkSMPTools::SetBackend("STDThread");
  ExpectTiles(0, 100000, 16); // the parent's pool is running
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0)
  {
    std::atomic<long> sum{ 0 };
    vtkCatadioptricParallel::For(0, 100000, 16, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType i = b; i < e; ++i)
      {
        sum += i;
      }
    });
    _exit(sum.load() == 4999950000L ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}
#endif

TEST(vtkCatadioptricParallel, FollowsTheSMPToolsSettings)
{
  ASSERT_TRUE(vtkSMPTools::SetBackend("Sequential"));
  EXPECT_EQ(vtkCatadioptricParallel::GetNumberOfThreads(), 1);
  std::set<std::thread::id> threads;
  vtkCatadioptricParallel::For(0, 100000, 1, [&](vtkIdType, vtkIdType) {
    threads.insert(std::this_thread::get_id()); // no lock: one thread only
  });
  EXPECT_EQ(threads.size(), 1u);
  EXPECT_EQ(*threads.begin(), std::this_thread::get_id());

  ASSERT_TRUE(vtkSMPTools::SetBackend("STDThread"));
  vtkSMPTools::Initialize(3); // at most the number of cores
  EXPECT_EQ(
    vtkCatadioptricParallel::GetNumberOfThreads(), vtkSMPTools::GetEstimatedNumberOfThreads());
  ExpectTiles(0, 30000, 10);
  vtkSMPTools::Initialize(1);
  EXPECT_EQ(vtkCatadioptricParallel::GetNumberOfThreads(), 1);
  ExpectTiles(0, 30000, 10);
  vtkSMPTools::Initialize(0); // back to the default
  EXPECT_GE(vtkCatadioptricParallel::GetNumberOfThreads(), 1);
  ExpectTiles(0, 30000, 10);
}
