// CatadioptricAR Core: the painter's order of cells, a stable far-to-near sort of their depths,
// in parallel.
//
// Sort() makes the keys of the kept cells and sorts them far to near, equal depths in cell order:
// the order std::stable_sort gives with `>` on the depths (-0 equals +0; NaNs, which `>` cannot
// order, keep the places of their bits). The keys are made and radix-sorted part by part on the
// threads of the project's pool (Parallel.h): each part counts its keys' digits and moves them to
// its own places in every bucket, the parts in order, so the result does not depend on the number
// of threads. An object keeps its buffers between sorts (a frame's sort allocates nothing once the
// buffers have grown). vtkCatadioptricPainterSort orders its cells with it.
#ifndef catarDepthOrder_h
#define catarDepthOrder_h

#include <cstdint>
#include <cstring>
#include <vector>

namespace catar
{
class DepthOrder
{
public:
  /// A cell to draw: its key and its index.
  struct Cell
  {
    std::uint64_t key;
    std::int64_t cell;
  };

  /// A 64-bit key whose unsigned order is the order of decreasing depth (far to near): the IEEE
  /// bits made monotone (negative numbers reversed), then complemented. -0 is +0.
  static std::uint64_t FarToNearKey(double depth)
  {
    if (depth == 0.0)
    {
      depth = 0.0;
    }
    std::uint64_t bits;
    std::memcpy(&bits, &depth, sizeof bits);
    const std::uint64_t ascending = (bits >> 63) ? ~bits : (bits | (std::uint64_t(1) << 63));
    return ~ascending;
  }

  /// The depth a key was made from (-0 comes back as +0).
  static double DepthOfKey(std::uint64_t key)
  {
    const std::uint64_t ascending = ~key;
    const std::uint64_t bits =
      (ascending >> 63) ? (ascending & ~(std::uint64_t(1) << 63)) : ~ascending;
    double depth;
    std::memcpy(&depth, &bits, sizeof depth);
    return depth;
  }

  /// Sorts the cells c in [0, n) with keep[c] != 0 (every cell when keep is null), depth[c]
  /// theirs, far to near, equal depths in cell order, on threadCount() threads (asked for only
  /// when there are enough cells to share: it may be costly; the order does not depend on it).
  /// GetCells() returns them.
  void Sort(std::int64_t n, const double* depth, const unsigned char* keep, int (*threadCount)());

  /// The cells of the last Sort(), in order.
  const std::vector<Cell>& GetCells() const { return this->Cells; }

private:
  // A stretch [begin, begin + count) of a buffer.
  struct Range
  {
    std::int64_t begin = 0;
    std::int64_t count = 0;
  };
  std::int64_t NumberOfParts(std::int64_t n);
  // The threads of this Sort's loops: ThreadCount()'s answer once NumberOfParts asked for it (a
  // loop over more than one part), else 1 (a loop over one part runs inline).
  int LoopThreads() const { return this->Threads > 0 ? this->Threads : 1; }
  void Pass(const Cell* from, Cell* to, int shift, int width);
  void SettleTies();

  std::vector<Cell> Cells;
  std::vector<Cell> Scratch;
  std::vector<Range> Parts;              // where the cells to move next are
  std::vector<std::uint32_t> Histograms; // a bucket count per part
  int (*ThreadCount)() = nullptr;        // this Sort's
  int Threads = 0;                       // ThreadCount(), once asked for; 0 before
};
} // namespace catar

#endif
