// catar::DepthOrder: the order of std::stable_sort by decreasing depth, for any number of
// threads and parts, with the radix making no pass, one pass (the result lands in the other
// buffer) and two or three passes, kept and dropped cells, and buffers reused between sorts.
#include "DepthOrder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace
{
// The expected order: the kept cells, stably sorted by decreasing depth.
std::vector<std::int64_t> Expected(
  const std::vector<double>& depth, const std::vector<unsigned char>& keep)
{
  std::vector<std::int64_t> cells;
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(depth.size()); ++c)
  {
    if (keep.empty() || keep[c])
    {
      cells.push_back(c);
    }
  }
  std::stable_sort(cells.begin(), cells.end(),
    [&](std::int64_t a, std::int64_t b) { return depth[a] > depth[b]; });
  return cells;
}

void ExpectOrder(catar::DepthOrder& order, const std::vector<double>& depth,
  const std::vector<unsigned char>& keep, const char* what, int (*threads)())
{
  order.Sort(static_cast<std::int64_t>(depth.size()), depth.data(),
    keep.empty() ? nullptr : keep.data(), threads);
  const std::vector<std::int64_t> expected = Expected(depth, keep);
  const std::vector<catar::DepthOrder::Cell>& cells = order.GetCells();
  ASSERT_EQ(cells.size(), expected.size()) << what;
  for (std::size_t i = 0; i < expected.size(); ++i)
  {
    ASSERT_EQ(cells[i].cell, expected[i]) << what << ", place " << i;
    const double d = depth[expected[i]];
    ASSERT_EQ(catar::DepthOrder::DepthOfKey(cells[i].key), d == 0.0 ? 0.0 : d) << what;
  }
}

// A depth of 1 + k ulps of bit `bit` of the mantissa-and-exponent word.
double Bits(std::uint64_t base, std::uint64_t k, int bit)
{
  const std::uint64_t bits = base + (k << bit);
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
} // namespace

TEST(DepthOrder, StableFarToNearForAnyThreadsAndPasses)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::int64_t n = 200000; // parts of 16384 cells and more
  std::uint64_t one;
  const double oneValue = 1.0;
  std::memcpy(&one, &oneValue, sizeof one);

  std::vector<std::vector<double>> scenes(5, std::vector<double>(n));
  std::vector<const char*> names = { "scene depths with ties, -0 and negatives",
    "all equal (no pass)", "one digit varies (one pass)", "near ties only (runs)",
    "few cells (one part)" };
  for (std::int64_t c = 0; c < n; ++c)
  {
    const int kind = static_cast<int>(c % 10);
    scenes[0][c] = kind == 0 ? 0.6
      : kind == 1            ? -0.0
      : kind == 2            ? 0.0
      : kind == 3            ? -unit(rng)
                             : 0.3 + unit(rng);
    scenes[1][c] = 0.75;
    scenes[2][c] = Bits(one, rng() % 1024, 43); // bits 43-52: the digit [43, 54) only
    scenes[3][c] = Bits(one, rng() % 5000, 0);  // all within the low 32 bits: one long run
  }
  scenes[4].resize(1000);
  for (double& d : scenes[4])
  {
    d = unit(rng);
  }
  std::vector<unsigned char> some(n);
  for (unsigned char& k : some)
  {
    k = rng() % 5 != 0 ? 1 : 0;
  }

  catar::DepthOrder order; // one object throughout: its buffers are reused
  for (int (*threads)() : { +[] { return 1; }, +[] { return 2; }, +[] { return 3; } })
  {
    for (std::size_t s = 0; s < scenes.size(); ++s)
    {
      ExpectOrder(order, scenes[s], {}, names[s], threads);
      std::vector<unsigned char> keep(some.begin(), some.begin() + scenes[s].size());
      ExpectOrder(order, scenes[s], keep, names[s], threads);
    }
  }

  // Nothing kept, nothing at all.
  std::vector<unsigned char> none(100, 0);
  std::vector<double> depths(100, 1.0);
  order.Sort(100, depths.data(), none.data(), nullptr);
  EXPECT_TRUE(order.GetCells().empty());
  order.Sort(0, nullptr, nullptr, nullptr);
  EXPECT_TRUE(order.GetCells().empty());
}

TEST(DepthOrder, KeysOrderDepthsFarToNear)
{
  const double depths[] = { -1e300, -2.5, -1e-300, 0.0, 1e-300, 0.5, 1.0, 3.0, 1e300,
    std::numeric_limits<double>::infinity() };
  for (std::size_t i = 0; i + 1 < sizeof depths / sizeof depths[0]; ++i)
  {
    EXPECT_GT(
      catar::DepthOrder::FarToNearKey(depths[i]), catar::DepthOrder::FarToNearKey(depths[i + 1]))
      << depths[i];
    EXPECT_EQ(catar::DepthOrder::DepthOfKey(catar::DepthOrder::FarToNearKey(depths[i])), depths[i]);
  }
  EXPECT_EQ(catar::DepthOrder::FarToNearKey(-0.0), catar::DepthOrder::FarToNearKey(0.0));
}
