#include "vtkCatadioptricPainterSort.h"

#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkSmartPointer.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricPainterSort);

namespace
{
// Elements per parallel copy task: waking the pool's threads costs more than copying a few
// thousand tuples; smaller meshes are copied inline.
constexpr vtkIdType kCopyGrain = 8192;

// A 64-bit key whose unsigned order is the order of decreasing depth (far to near): the IEEE bits
// made monotone (negative numbers reversed), then complemented. -0 is +0, as the comparison of
// doubles has it.
inline std::uint64_t FarToNearKey(double depth)
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

// Stable LSD radix sort of `order` by keys[order[i]] (11-bit digits; passes whose digit is the same
// for every key are skipped, as the high bits of depths within one scene mostly are). Stability
// keeps equal depths in input order.
void RadixSort(std::vector<vtkIdType>& order, const std::vector<std::uint64_t>& keys)
{
  constexpr int kBits = 11;
  constexpr int kPasses = (64 + kBits - 1) / kBits;
  constexpr std::size_t kBuckets = std::size_t(1) << kBits;
  const std::size_t n = order.size();
  std::vector<std::uint32_t> counts(kPasses * kBuckets, 0);
  for (const vtkIdType c : order)
  {
    const std::uint64_t k = keys[c];
    for (int p = 0; p < kPasses; ++p)
    {
      ++counts[p * kBuckets + ((k >> (p * kBits)) & (kBuckets - 1))];
    }
  }
  std::vector<vtkIdType> scratch(n);
  for (int p = 0; p < kPasses; ++p)
  {
    std::uint32_t* count = counts.data() + p * kBuckets;
    if (std::any_of(count, count + kBuckets, [n](std::uint32_t c) { return c == n; }))
    {
      continue; // every key has the same digit here
    }
    std::uint32_t sum = 0;
    for (std::size_t b = 0; b < kBuckets; ++b)
    {
      const std::uint32_t c = count[b];
      count[b] = sum;
      sum += c;
    }
    for (const vtkIdType c : order)
    {
      scratch[count[(keys[c] >> (p * kBits)) & (kBuckets - 1)]++] = c;
    }
    order.swap(scratch);
  }
}

// The polygons of `polys` in the given order (offsets/connectivity gathered directly, in the
// input's storage type).
template<typename ArrayT>
vtkSmartPointer<vtkCellArray> Reordered(
  ArrayT* inOffsets, ArrayT* inConnectivity, const std::vector<vtkIdType>& order)
{
  using ValueT = typename ArrayT::ValueType;
  const auto* off = inOffsets->GetPointer(0);
  const auto* conn = inConnectivity->GetPointer(0);
  const vtkIdType n = static_cast<vtkIdType>(order.size());
  vtkNew<ArrayT> offsets;
  offsets->SetNumberOfValues(n + 1);
  ValueT* outOff = offsets->GetPointer(0);
  outOff[0] = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtkIdType c = order[i];
    outOff[i + 1] = outOff[i] + (off[c + 1] - off[c]);
  }
  vtkNew<ArrayT> connectivity;
  connectivity->SetNumberOfValues(outOff[n]);
  ValueT* outConn = connectivity->GetPointer(0);
  vtkCatadioptricParallel::For(0, n, kCopyGrain, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      const vtkIdType c = order[i];
      const auto* from = conn + off[c];
      auto* to = outConn + outOff[i];
      const auto size = off[c + 1] - off[c];
      if (size == 3) // triangles, inline
      {
        to[0] = from[0];
        to[1] = from[1];
        to[2] = from[2];
      }
      else
      {
        std::copy(from, from + size, to);
      }
    }
  });
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  polys->SetData(offsets, connectivity);
  return polys;
}

// out[i] = in[source[i]], tuple by tuple, for every cell array; attributes (active scalars,
// normals, ...) are kept.
void GatherCellData(vtkCellData* in, vtkCellData* out, const std::vector<vtkIdType>& source)
{
  const vtkIdType n = static_cast<vtkIdType>(source.size());
  for (int a = 0; a < in->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* src = in->GetAbstractArray(a);
    vtkSmartPointer<vtkAbstractArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->CopyComponentNames(src);
    dst->SetNumberOfTuples(n);
    if (src->HasStandardMemoryLayout() && dst->HasStandardMemoryLayout())
    {
      const std::size_t bytes =
        static_cast<std::size_t>(src->GetNumberOfComponents()) * src->GetDataTypeSize();
      const auto* from = static_cast<const unsigned char*>(src->GetVoidPointer(0));
      auto* to = static_cast<unsigned char*>(dst->GetVoidPointer(0));
      // Tuples of a size known at compile time are copied inline, not by a call per tuple.
      auto gather = [&](auto size) {
        constexpr std::size_t B = decltype(size)::value;
        const std::size_t width = B ? B : bytes;
        vtkCatadioptricParallel::For(0, n, kCopyGrain, [&](vtkIdType b, vtkIdType e) {
          for (vtkIdType i = b; i < e; ++i)
          {
            std::memcpy(to + i * width, from + source[i] * width, B ? B : width);
          }
        });
      };
      switch (bytes)
      {
        case 1: gather(std::integral_constant<std::size_t, 1>()); break;
        case 4: gather(std::integral_constant<std::size_t, 4>()); break;
        case 8: gather(std::integral_constant<std::size_t, 8>()); break;
        case 12: gather(std::integral_constant<std::size_t, 12>()); break;
        case 24: gather(std::integral_constant<std::size_t, 24>()); break;
        default: gather(std::integral_constant<std::size_t, 0>()); break;
      }
    }
    else
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        dst->SetTuple(i, source[i], src);
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
}
} // namespace

int vtkCatadioptricPainterSort::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkPolyData.");
    return 0;
  }
  const vtkIdType nCells = input->GetNumberOfCells();
  vtkDataArray* depthArray = input->GetCellData()->GetArray("CentroidDepth");
  if (nCells > 0 &&
    (!depthArray || depthArray->GetNumberOfComponents() != 1 ||
      depthArray->GetNumberOfTuples() != nCells))
  {
    vtkErrorMacro("The input has no CentroidDepth cell array: run vtkCatadioptricProjection "
                  "before vtkCatadioptricPainterSort.");
    return 0;
  }
  vtkUnsignedCharArray* visible =
    vtkUnsignedCharArray::SafeDownCast(input->GetCellData()->GetArray("Visible"));
  if (this->DropInvisibleCells && nCells > 0 && !visible)
  {
    vtkErrorMacro("DropInvisibleCells is on but the input has no uint8 Visible cell array.");
    return 0;
  }
  if (input->GetNumberOfVerts() + input->GetNumberOfLines() + input->GetNumberOfStrips() > 0)
  {
    vtkWarningMacro("Only polygons are sorted; vertices, lines and strips are dropped.");
  }

  const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType nPolys = input->GetNumberOfPolys();
  std::vector<vtkIdType> order;
  order.reserve(nPolys);
  const unsigned char* vis = visible ? visible->GetPointer(first) : nullptr;
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    if (!this->DropInvisibleCells || vis[c])
    {
      order.push_back(c);
    }
  }
  std::vector<std::uint64_t> keys(nPolys);
  auto* depthDoubles = vtkDoubleArray::SafeDownCast(depthArray);
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    keys[c] = FarToNearKey(depthDoubles ? depthDoubles->GetValue(first + c)
                                        : depthArray->GetComponent(first + c, 0));
  }
  this->UpdateProgress(0.2);
  // Far to near; equal depths keep input order (a stable sort of indices in input order).
  RadixSort(order, keys);
  this->UpdateProgress(0.6);

  // New polygon connectivity in the sorted order.
  vtkCellArray* inPolys = input->GetPolys();
  vtkSmartPointer<vtkCellArray> polys = inPolys->IsStorage64Bit()
    ? Reordered(inPolys->GetOffsetsArray64(), inPolys->GetConnectivityArray64(), order)
    : Reordered(inPolys->GetOffsetsArray32(), inPolys->GetConnectivityArray32(), order);

  output->SetPoints(input->GetPoints());
  output->GetPointData()->PassData(input->GetPointData());
  output->GetFieldData()->PassData(input->GetFieldData());
  output->SetPolys(polys);

  // Cell data follows the cells.
  const vtkIdType nOut = static_cast<vtkIdType>(order.size());
  std::vector<vtkIdType> source(order.size());
  for (vtkIdType i = 0; i < nOut; ++i)
  {
    source[i] = first + order[i];
  }
  vtkCellData* outCD = output->GetCellData();
  GatherCellData(input->GetCellData(), outCD, source);
  // OriginalCellId: each cell's index in the input, unless the input already carries the ids of
  // an earlier stage (then they were copied above, reordered with the cells).
  if (!input->GetCellData()->GetArray("OriginalCellId"))
  {
    vtkNew<vtkIdTypeArray> original;
    original->SetName("OriginalCellId");
    original->SetNumberOfTuples(nOut);
    std::copy(source.begin(), source.end(), original->GetPointer(0));
    outCD->AddArray(original);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricPainterSort::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DropInvisibleCells: " << (this->DropInvisibleCells ? "On" : "Off") << "\n";
}
