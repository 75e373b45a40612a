#include "DepthOrder.h"

#include "Parallel.h"

#include <algorithm>
#include <cstring>

namespace
{
using Cell = catar::DepthOrder::Cell;

// Cells per part, at least: a part counts and moves its cells on one thread, and waking the
// pool costs more than sorting a few thousand keys.
constexpr std::int64_t kPartCells = 16384;

// The radix digits, on the keys' high 32 bits: [32, 43), [43, 54), [54, 64). A digit that is the
// same for every key (as the sign and exponent of depths within one scene mostly are) costs no
// pass; the runs whose high bits tie (depths within a millionth of each other) are then sorted
// by the whole key.
constexpr int kDigits = 3;
constexpr int kShift[kDigits] = { 32, 43, 54 };
constexpr int kWidth[kDigits] = { 11, 11, 10 };
constexpr std::size_t kBuckets = std::size_t(1) << 11;

bool ByKey(const Cell& a, const Cell& b)
{
  return a.key < b.key;
}
} // namespace

// How many parts for n cells: a part per kPartCells, at most four per thread. Fewer than two
// parts' worth is one part, without asking for the number of threads (vtkCatadioptricParallel's
// reads a system file on every call: 8 % of the frame in a scene of a thousand small objects, a
// sort each).
std::int64_t catar::DepthOrder::NumberOfParts(std::int64_t n)
{
  if (n < 2 * kPartCells)
  {
    return 1;
  }
  if (this->Threads == 0)
  {
    this->Threads = std::max(1, this->ThreadCount ? this->ThreadCount() : 1);
  }
  const std::int64_t most = 4 * static_cast<std::int64_t>(this->Threads);
  return std::max<std::int64_t>(1, std::min(most, n / kPartCells));
}

void catar::DepthOrder::Sort(
  std::int64_t n, const double* depth, const unsigned char* keep, int (*threadCount)())
{
  this->ThreadCount = threadCount;
  this->Threads = 0;
  n = std::max<std::int64_t>(n, 0);
  // The kept cells' keys, each part's from its first cell's place in Scratch on; the bits in
  // which the keys differ (where all agree, a digit needs no pass).
  const std::int64_t nParts = NumberOfParts(n);
  if (static_cast<std::int64_t>(this->Scratch.size()) < n)
  {
    this->Scratch.resize(static_cast<size_t>(n));
  }
  this->Parts.assign(static_cast<size_t>(nParts), Range());
  std::vector<std::uint64_t> anyOne(static_cast<size_t>(nParts), 0);
  std::vector<std::uint64_t> allOnes(static_cast<size_t>(nParts), ~std::uint64_t(0));
  Cell* scratch = this->Scratch.data();
  catar::parallel::For(0, nParts, 1, this->LoopThreads(), [&](std::int64_t p0, std::int64_t p1) {
    for (std::int64_t p = p0; p < p1; ++p)
    {
      const std::int64_t b = n * p / nParts, e = n * (p + 1) / nParts;
      std::int64_t k = b;
      std::uint64_t any = 0, all = ~std::uint64_t(0);
      for (std::int64_t c = b; c < e; ++c)
      {
        if (!keep || keep[c])
        {
          const std::uint64_t key = FarToNearKey(depth[c]);
          scratch[k++] = { key, c };
          any |= key;
          all &= key;
        }
      }
      this->Parts[p] = { b, k - b };
      anyOne[p] = any;
      allOnes[p] = all;
    }
  });
  std::int64_t kept = 0;
  std::uint64_t differ = 0;
  {
    std::uint64_t any = 0, all = ~std::uint64_t(0);
    for (std::int64_t p = 0; p < nParts; ++p)
    {
      kept += this->Parts[p].count;
      any |= anyOne[p];
      all &= allOnes[p];
    }
    differ = any ^ all;
  }
  this->Cells.resize(static_cast<size_t>(kept));
  if (kept == 0)
  {
    return;
  }

  // Radix passes, from Scratch's parts into Cells and back: each pass leaves its result whole.
  bool inCells = false;
  int passes = 0;
  for (int d = 0; d < kDigits; ++d)
  {
    if (((differ >> kShift[d]) & ((std::uint64_t(1) << kWidth[d]) - 1)) == 0)
    {
      continue;
    }
    const Cell* from = inCells ? this->Cells.data() : this->Scratch.data();
    Cell* to = inCells ? this->Scratch.data() : this->Cells.data();
    this->Pass(from, to, kShift[d], kWidth[d]);
    inCells = !inCells;
    ++passes;
    // The result is whole: the next pass reads it in even parts.
    const std::int64_t parts = NumberOfParts(kept);
    this->Parts.assign(static_cast<size_t>(parts), Range());
    for (std::int64_t p = 0; p < parts; ++p)
    {
      const std::int64_t b = kept * p / parts;
      this->Parts[p] = { b, kept * (p + 1) / parts - b };
    }
  }
  if (!inCells && passes > 0)
  {
    // Whole at the front of Scratch: the buffers change places.
    this->Cells.swap(this->Scratch);
    this->Cells.resize(static_cast<size_t>(kept));
  }
  else if (!inCells)
  {
    // No pass: the parts, in order, to the front of Cells.
    const Cell* from = this->Scratch.data();
    std::vector<std::int64_t> to(this->Parts.size(), 0);
    for (size_t p = 1; p < this->Parts.size(); ++p)
    {
      to[p] = to[p - 1] + this->Parts[p - 1].count;
    }
    catar::parallel::For(0, static_cast<std::int64_t>(this->Parts.size()), 1, this->LoopThreads(),
      [&](std::int64_t p0, std::int64_t p1) {
        for (std::int64_t p = p0; p < p1; ++p)
        {
          const Range& r = this->Parts[p];
          std::copy(from + r.begin, from + r.begin + r.count, this->Cells.data() + to[p]);
        }
      });
  }
  this->SettleTies();
}

// One stable counting pass on the digit [shift, shift + width) of the keys in Parts of `from`,
// into `to` (whole): each part counts its digits, then moves its cells to its own places in each
// bucket, after those of the parts before it.
void catar::DepthOrder::Pass(const Cell* from, Cell* to, int shift, int width)
{
  const std::int64_t nParts = static_cast<std::int64_t>(this->Parts.size());
  const std::uint64_t mask = (std::uint64_t(1) << width) - 1;
  this->Histograms.assign(static_cast<size_t>(nParts) * kBuckets, 0);
  std::uint32_t* histograms = this->Histograms.data();
  catar::parallel::For(0, nParts, 1, this->LoopThreads(), [&](std::int64_t p0, std::int64_t p1) {
    for (std::int64_t p = p0; p < p1; ++p)
    {
      std::uint32_t* count = histograms + p * kBuckets;
      const Range& r = this->Parts[p];
      for (const Cell* c = from + r.begin; c != from + r.begin + r.count; ++c)
      {
        ++count[(c->key >> shift) & mask];
      }
    }
  });
  // Each part's first place in each bucket: buckets in order, parts in order within a bucket.
  std::uint32_t sum = 0;
  for (std::size_t b = 0; b < kBuckets; ++b)
  {
    for (std::int64_t p = 0; p < nParts; ++p)
    {
      std::uint32_t& count = histograms[p * kBuckets + b];
      const std::uint32_t c = count;
      count = sum;
      sum += c;
    }
  }
  catar::parallel::For(0, nParts, 1, this->LoopThreads(), [&](std::int64_t p0, std::int64_t p1) {
    for (std::int64_t p = p0; p < p1; ++p)
    {
      std::uint32_t* place = histograms + p * kBuckets;
      const Range& r = this->Parts[p];
      for (const Cell* c = from + r.begin; c != from + r.begin + r.count; ++c)
      {
        to[place[(c->key >> shift) & mask]++] = *c;
      }
    }
  });
}

// The runs of Cells whose high 32 bits tie, sorted by the whole key, stably (few and short in
// real scenes). Each part settles the runs that start in it; where a part's first run starts is
// found first, so that no two parts touch the same run.
void catar::DepthOrder::SettleTies()
{
  Cell* cells = this->Cells.data();
  const std::int64_t n = static_cast<std::int64_t>(this->Cells.size());
  const std::int64_t nParts = NumberOfParts(n);
  auto tiesPrevious = [cells](std::int64_t i) {
    return i > 0 && (cells[i].key >> 32) == (cells[i - 1].key >> 32);
  };
  std::vector<std::int64_t> start(static_cast<size_t>(nParts) + 1, n);
  for (std::int64_t p = 0; p < nParts; ++p)
  {
    std::int64_t b = std::max(n * p / nParts, p > 0 ? start[p - 1] : 0);
    while (b < n && tiesPrevious(b))
    {
      ++b;
    }
    start[p] = b;
  }
  catar::parallel::For(0, nParts, 1, this->LoopThreads(), [&](std::int64_t p0, std::int64_t p1) {
    for (std::int64_t p = p0; p < p1; ++p)
    {
      for (std::int64_t b = start[p]; b < start[p + 1];)
      {
        std::int64_t e = b + 1;
        while (e < n && tiesPrevious(e))
        {
          ++e;
        }
        if (e - b > 16)
        {
          std::stable_sort(cells + b, cells + e, ByKey);
        }
        else
        {
          for (std::int64_t i = b + 1; i < e; ++i) // insertion sort: stable
          {
            const Cell c = cells[i];
            std::int64_t j = i;
            for (; j > b && c.key < cells[j - 1].key; --j)
            {
              cells[j] = cells[j - 1];
            }
            cells[j] = c;
          }
        }
        b = e;
      }
    }
  });
}
