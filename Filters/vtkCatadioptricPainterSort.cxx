#include "vtkCatadioptricPainterSort.h"

#include "DepthOrder.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricPainterSort);

vtkCatadioptricPainterSort::vtkCatadioptricPainterSort()
  : Order(new catar::DepthOrder)
{
}

vtkCatadioptricPainterSort::~vtkCatadioptricPainterSort() = default;

namespace
{
// Elements per parallel copy task: waking the pool's threads costs more than copying a few
// thousand tuples; smaller meshes are copied inline.
constexpr vtkIdType kCopyGrain = 8192;

// A cell to draw, in order: its key and its polygon index.
using KeyedCell = catar::DepthOrder::Cell;

// How many cells ahead the gather asks for what it will read.
constexpr vtkIdType kPrefetchCells = 64;

// One cell-data array with the standard memory layout, copied tuple by tuple as bytes.
struct TupleGather
{
  const unsigned char* from;
  unsigned char* to;
  std::size_t width; // bytes per tuple
};

// The tuples of one standard-layout cell array in the sorted order: to[i] = from[first +
// order[i].cell], for i in [b, e). The reads are random: the loop asks for the tuple a few cells
// ahead. Tuples of the sizes the pipeline makes (1, 8 and 24 bytes) are copied by a loop of their
// own, without a call per tuple.
template<std::size_t Width>
void GatherTuplesOf(
  const TupleGather& t, const KeyedCell* order, vtkIdType first, vtkIdType b, vtkIdType e)
{
  const std::size_t width = Width > 0 ? Width : t.width;
  const unsigned char* const from = t.from + first * width;
  unsigned char* const to = t.to;
  for (vtkIdType i = b; i < e; ++i)
  {
    if (i + kPrefetchCells < e)
    {
      vtkCatadioptricParallel::Prefetch(from + order[i + kPrefetchCells].cell * width);
    }
    std::memcpy(to + i * width, from + order[i].cell * width, width);
  }
}

void GatherTuples(
  const TupleGather& t, const KeyedCell* order, vtkIdType first, vtkIdType b, vtkIdType e)
{
  switch (t.width)
  {
    case 1:
      GatherTuplesOf<1>(t, order, first, b, e);
      break;
    case 8:
      GatherTuplesOf<8>(t, order, first, b, e);
      break;
    case 24:
      GatherTuplesOf<24>(t, order, first, b, e);
      break;
    default:
      GatherTuplesOf<0>(t, order, first, b, e);
      break;
  }
}

// What the gather writes besides polygons and tuples, in the sorted order (null: not wanted).
struct SortedExtras
{
  double* Depths = nullptr;         // the depth each key was made from
  vtkIdType* OriginalIds = nullptr; // first + the cell's polygon index
};

// The polygons in `order` (cell c is polygon c of the input, cell data index first + c), the
// tuples of the standard-layout cell arrays and the extras, in one parallel pass (no serial pass
// for the ids, no loop of its own for the depths). The reads go through the order,
// so they are random: each loop asks for what it reads a few cells ahead. Each task runs a loop
// for the polygons and the extras, then one per cell array: short loops without calls, whose
// random reads the processor overlaps. Connectivity is written in 32-bit storage (OutT) when the
// ids fit: half the bytes to write here and to read in the compositor. `triangles`: every input
// polygon has three points (offsets 3c, no offsets to read).
template<typename InT, typename OutT>
void GatherCells(const InT* off, const InT* conn, const std::vector<KeyedCell>& order,
  vtkIdType first, bool triangles, const std::vector<TupleGather>& tuples,
  const SortedExtras& extras, OutT* outOff, OutT* outConn)
{
  const vtkIdType n = static_cast<vtkIdType>(order.size());
  const KeyedCell* const cells = order.data();
  if (!triangles)
  {
    outOff[0] = 0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      const vtkIdType c = cells[i].cell;
      outOff[i + 1] = outOff[i] + static_cast<OutT>(off[c + 1] - off[c]);
    }
  }
  vtkCatadioptricParallel::For(0, n, kCopyGrain, [&](vtkIdType b, vtkIdType e) {
    if (extras.Depths)
    {
      double* const depths = extras.Depths;
      for (vtkIdType i = b; i < e; ++i)
      {
        depths[i] = catar::DepthOrder::DepthOfKey(cells[i].key);
      }
    }
    if (extras.OriginalIds)
    {
      vtkIdType* const ids = extras.OriginalIds;
      for (vtkIdType i = b; i < e; ++i)
      {
        ids[i] = first + cells[i].cell;
      }
    }
    if (triangles)
    {
      for (vtkIdType i = b; i < e; ++i)
      {
        if (i + kPrefetchCells < e)
        {
          vtkCatadioptricParallel::Prefetch(conn + 3 * cells[i + kPrefetchCells].cell);
        }
        const InT* from = conn + 3 * cells[i].cell;
        OutT* to = outConn + 3 * i;
        outOff[i] = static_cast<OutT>(3 * i);
        to[0] = static_cast<OutT>(from[0]);
        to[1] = static_cast<OutT>(from[1]);
        to[2] = static_cast<OutT>(from[2]);
      }
    }
    else
    {
      for (vtkIdType i = b; i < e; ++i)
      {
        const vtkIdType c = cells[i].cell;
        std::transform(conn + off[c], conn + off[c + 1], outConn + outOff[i],
          [](InT v) { return static_cast<OutT>(v); });
      }
    }
    for (const TupleGather& t : tuples)
    {
      GatherTuples(t, cells, first, b, e);
    }
  });
  if (triangles)
  {
    outOff[n] = static_cast<OutT>(3 * n);
  }
}

template<typename OutArrayT, typename InArrayT>
vtkSmartPointer<vtkCellArray> Gathered(InArrayT* inOffsets, InArrayT* inConnectivity,
  const std::vector<KeyedCell>& order, vtkIdType first, bool triangles,
  const std::vector<TupleGather>& tuples, const SortedExtras& extras)
{
  const auto* off = inOffsets->GetPointer(0);
  vtkIdType total = 0;
  if (triangles)
  {
    total = 3 * static_cast<vtkIdType>(order.size());
  }
  else
  {
    for (const KeyedCell& k : order)
    {
      total += static_cast<vtkIdType>(off[k.cell + 1] - off[k.cell]);
    }
  }
  vtkNew<OutArrayT> offsets;
  vtkCatadioptricAllocation::Tuples(offsets, static_cast<vtkIdType>(order.size()) + 1);
  vtkNew<OutArrayT> connectivity;
  vtkCatadioptricAllocation::Tuples(connectivity, total);
  GatherCells(off, inConnectivity->GetPointer(0), order, first, triangles, tuples, extras,
    offsets->GetPointer(0), connectivity->GetPointer(0));
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  polys->SetData(offsets, connectivity);
  return polys;
}

template<typename InArrayT>
vtkSmartPointer<vtkCellArray> Gathered(InArrayT* inOffsets, InArrayT* inConnectivity,
  const std::vector<KeyedCell>& order, vtkIdType first, bool triangles,
  const std::vector<TupleGather>& tuples, const SortedExtras& extras, bool ids32)
{
  if (ids32)
  {
    return Gathered<vtkTypeInt32Array>(
      inOffsets, inConnectivity, order, first, triangles, tuples, extras);
  }
  return Gathered<vtkTypeInt64Array>(
    inOffsets, inConnectivity, order, first, triangles, tuples, extras);
}

// Whether every polygon has three points (offsets 0, 3, 6, ...): one pass over the offsets.
// vtkCellArray::IsHomogeneous, which asks each cell its size, took 0.2-0.3 ms on the bunny's 69k
// polygons, an eighth of the sort.
template<typename ArrayT>
bool AllTriangles(ArrayT* offsets)
{
  const auto* off = offsets->GetPointer(0);
  const vtkIdType n = offsets->GetNumberOfValues();
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (off[i] != 3 * i)
    {
      return false;
    }
  }
  return n > 1;
}

// Output cell arrays like the input's (name, components, attributes), sized for n tuples. Arrays
// with the standard memory layout are listed in `tuples` for GatherCells, but those in `skip`
// (left for the caller to fill); the others are filled here, tuple by tuple.
std::vector<TupleGather> PrepareCellData(vtkCellData* in, vtkCellData* out,
  const std::vector<KeyedCell>& order, vtkIdType first,
  std::initializer_list<const vtkAbstractArray*> skip)
{
  std::vector<TupleGather> tuples;
  const vtkIdType n = static_cast<vtkIdType>(order.size());
  for (int a = 0; a < in->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* src = in->GetAbstractArray(a);
    vtkSmartPointer<vtkAbstractArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->CopyComponentNames(src);
    vtkCatadioptricAllocation::Tuples(dst, n);
    if (std::find(skip.begin(), skip.end(), src) != skip.end())
    {
    }
    else if (src->HasStandardMemoryLayout() && dst->HasStandardMemoryLayout())
    {
      tuples.push_back({ static_cast<const unsigned char*>(src->GetVoidPointer(0)),
        static_cast<unsigned char*>(dst->GetVoidPointer(0)),
        static_cast<std::size_t>(src->GetNumberOfComponents()) * src->GetDataTypeSize() });
    }
    else
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        dst->SetTuple(i, first + order[i].cell, src);
      }
    }
    out->AddArray(dst);
    for (int t = 0; t < vtkDataSetAttributes::NUM_ATTRIBUTES; ++t)
    {
      if (in->GetAbstractAttribute(t) == src)
      {
        out->SetActiveAttribute(a, t);
      }
    }
  }
  return tuples;
}
// The input's CentroidDepth cell array (one value a cell) and its Visible cell array (uint8; may
// be null unless dropInvisible), checked. False, with the error reported by `self`, when one is
// missing.
bool SortArrays(vtkObject* self, vtkPolyData* input, bool dropInvisible, vtkDataArray*& depth,
  vtkUnsignedCharArray*& visible)
{
  const vtkIdType nCells = input->GetNumberOfCells();
  depth = input->GetCellData()->GetArray(vtkCatadioptricArrayNames::CentroidDepth);
  if (nCells > 0 &&
    (!depth || depth->GetNumberOfComponents() != 1 || depth->GetNumberOfTuples() != nCells))
  {
    vtkErrorWithObjectMacro(self,
      "The input has no CentroidDepth cell array: run vtkCatadioptricProjection "
      "before vtkCatadioptricPainterSort.");
    return false;
  }
  visible = vtkUnsignedCharArray::SafeDownCast(
    input->GetCellData()->GetArray(vtkCatadioptricArrayNames::Visible));
  if (dropInvisible && nCells > 0 && !visible)
  {
    vtkErrorWithObjectMacro(
      self, "DropInvisibleCells is on but the input has no uint8 Visible cell array.");
    return false;
  }
  return true;
}

// The depths of the n polygons from cell `first` on: the array's own values when it holds
// doubles, else converted once into `converted`.
const double* PolygonDepths(
  vtkDataArray* depth, vtkIdType first, vtkIdType n, std::vector<double>& converted)
{
  if (auto* doubles = vtkDoubleArray::SafeDownCast(depth))
  {
    return doubles->GetPointer(first);
  }
  converted.resize(static_cast<size_t>(n));
  for (vtkIdType c = 0; c < n; ++c)
  {
    converted[c] = depth->GetComponent(first + c, 0);
  }
  return converted.data();
}
} // namespace

int vtkCatadioptricPainterSort::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Out of memory (a mesh or an image too large for the memory left): the filter's error.
  return vtkCatadioptricAllocation::Guard(
    this, [&] { return this->Execute(inputVector, outputVector); },
    [&] { return "sorting " + vtkCatadioptricAllocation::DescribeInput(inputVector[0]); });
}

int vtkCatadioptricPainterSort::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = nullptr;
  vtkPolyData* output = nullptr;
  if (!vtkCatadioptricMeshCheck::InputAndOutput(this, inputVector, outputVector, input, output))
  {
    return 0;
  }
  vtkDataArray* depthArray = nullptr;
  vtkUnsignedCharArray* visible = nullptr;
  if (!SortArrays(this, input, this->DropInvisibleCells, depthArray, visible))
  {
    return 0;
  }
  if (input->GetNumberOfVerts() + input->GetNumberOfLines() + input->GetNumberOfStrips() > 0)
  {
    vtkWarningMacro("Only polygons are sorted; vertices, lines and strips are dropped.");
  }

  const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType nPolys = input->GetNumberOfPolys();
  const unsigned char* vis = visible ? visible->GetPointer(first) : nullptr;
  auto* depthDoubles = vtkDoubleArray::SafeDownCast(depthArray);
  // Whether every kept cell's Visible is 1 (as vtkCatadioptricProjection writes it): then the
  // output's Visible is all ones, written in order instead of gathered from random places.
  const bool keptVisibleOnes = this->DropInvisibleCells && vis &&
    std::all_of(vis, vis + nPolys, [](unsigned char v) { return v <= 1; });
  std::vector<double> converted;
  const double* depths = PolygonDepths(depthArray, first, nPolys, converted);
  this->UpdateProgress(0.2);
  // Far to near; equal depths keep input order (a stable sort of cells in input order).
  this->Order->Sort(nPolys, depths, this->DropInvisibleCells ? vis : nullptr,
    &vtkCatadioptricParallel::GetNumberOfThreads);
  const std::vector<KeyedCell>& cells = this->Order->GetCells();
  this->UpdateProgress(0.6);

  // New polygon connectivity and cell data in the sorted order.
  vtkCellArray* inPolys = input->GetPolys();
  const bool ids32 = input->GetNumberOfPoints() <= VTK_TYPE_INT32_MAX &&
    inPolys->GetNumberOfConnectivityIds() <= VTK_TYPE_INT32_MAX;
  const bool triangles = inPolys->IsStorage64Bit() ? AllTriangles(inPolys->GetOffsetsArray64())
                                                   : AllTriangles(inPolys->GetOffsetsArray32());
  vtkCellData* outCD = output->GetCellData();
  vtkUnsignedCharArray* visibleOnes = keptVisibleOnes ? visible : nullptr;
  const std::vector<TupleGather> tuples =
    PrepareCellData(input->GetCellData(), outCD, cells, first, { depthDoubles, visibleOnes });
  if (visibleOnes)
  {
    auto* out = vtkUnsignedCharArray::SafeDownCast(outCD->GetAbstractArray(visible->GetName()));
    std::fill(out->GetPointer(0), out->GetPointer(0) + out->GetNumberOfValues(), 1);
  }
  const vtkIdType nOut = static_cast<vtkIdType>(cells.size());
  SortedExtras extras;
  // The depths come back from the sorted keys, in order, instead of from random places.
  if (depthDoubles)
  {
    extras.Depths =
      vtkDoubleArray::SafeDownCast(outCD->GetArray(vtkCatadioptricArrayNames::CentroidDepth))
        ->GetPointer(0);
  }
  // OriginalCellId: each cell's index in the input, unless the input already carries the ids of
  // an earlier stage (then they are gathered with the other cell data).
  if (!input->GetCellData()->GetArray(vtkCatadioptricArrayNames::OriginalCellId))
  {
    vtkNew<vtkIdTypeArray> original;
    original->SetName(vtkCatadioptricArrayNames::OriginalCellId);
    vtkCatadioptricAllocation::Tuples(original, nOut);
    extras.OriginalIds = original->GetPointer(0);
    outCD->AddArray(original);
  }
  vtkSmartPointer<vtkCellArray> polys = inPolys->IsStorage64Bit()
    ? Gathered(inPolys->GetOffsetsArray64(), inPolys->GetConnectivityArray64(), cells, first,
        triangles, tuples, extras, ids32)
    : Gathered(inPolys->GetOffsetsArray32(), inPolys->GetConnectivityArray32(), cells, first,
        triangles, tuples, extras, ids32);

  output->SetPoints(input->GetPoints());
  output->GetPointData()->PassData(input->GetPointData());
  output->GetFieldData()->PassData(input->GetFieldData());
  output->SetPolys(polys);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricPainterSort::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DropInvisibleCells: " << (this->DropInvisibleCells ? "On" : "Off") << "\n";
}
