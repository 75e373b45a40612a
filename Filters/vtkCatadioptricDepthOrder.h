/**
 * @class   vtkCatadioptricDepthOrder
 * @brief   the painter's order of cells: a stable far-to-near sort of their depths, in parallel
 *
 * Sort() makes the keys of the kept cells and sorts them far to near, equal depths in cell order:
 * the order std::stable_sort gives with `>` on the depths (-0 equals +0; NaNs, which `>` cannot
 * order, keep the places of their bits). The keys are made and radix-sorted part by part on the
 * threads of vtkCatadioptricParallel: each part counts its keys' digits and moves them to its own
 * places in every bucket, the parts in order, so the result does not depend on the number of
 * threads. An object keeps its buffers between sorts (a frame's sort allocates nothing once the
 * buffers have grown). vtkCatadioptricPainterSort orders its cells with it.
 */
#ifndef vtkCatadioptricDepthOrder_h
#define vtkCatadioptricDepthOrder_h

#include "CatadioptricARFiltersModule.h" // export macro
#include "vtkType.h"

#include <cstdint> // std::uint64_t
#include <cstring> // std::memcpy
#include <vector>  // std::vector

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricDepthOrder
{
public:
  /// A cell to draw: its key and its index.
  struct Cell
  {
    std::uint64_t key;
    vtkIdType cell;
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
  /// theirs, far to near, equal depths in cell order. GetCells() returns them.
  void Sort(vtkIdType n, const double* depth, const unsigned char* keep);

  /// The cells of the last Sort(), in order.
  const std::vector<Cell>& GetCells() const { return this->Cells; }

private:
  // A stretch [begin, begin + count) of a buffer.
  struct Range
  {
    vtkIdType begin = 0;
    vtkIdType count = 0;
  };
  void Pass(const Cell* from, Cell* to, int shift, int width);
  void SettleTies();

  std::vector<Cell> Cells;
  std::vector<Cell> Scratch;
  std::vector<Range> Parts;              // where the cells to move next are
  std::vector<std::uint32_t> Histograms; // a bucket count per part
};

#endif
