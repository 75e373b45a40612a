#include "vtkCatadioptricMeshCheck.h"

#include "vtkAlgorithm.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <limits>
#include <sstream>
#include <vector>

namespace
{
// The cached id range of a connectivity array (its information object): smallest, largest, and
// the number of ids it was computed for (ids appended through InsertNextCell change the number
// but not always the array's MTime).
vtkInformationDoubleVectorKey* IdRangeKey()
{
  static vtkInformationDoubleVectorKey* key =
    new vtkInformationDoubleVectorKey("CATADIOPTRIC_ID_RANGE", "vtkCatadioptricMeshCheck", 3);
  return key;
}

// Ids per task: reading them costs ~0.3 ns each, waking the pool ~10 us.
constexpr vtkIdType kIdsPerTask = 1 << 16;

template<typename IdT>
void Range(const IdT* ids, vtkIdType n, vtkIdType range[2])
{
  const vtkIdType nTasks = (n + kIdsPerTask - 1) / kIdsPerTask;
  std::vector<IdT> lo(static_cast<size_t>(nTasks)), hi(static_cast<size_t>(nTasks));
  vtkCatadioptricParallel::For(0, nTasks, nTasks < 4 ? nTasks : 1, [&](vtkIdType t0, vtkIdType t1) {
    for (vtkIdType t = t0; t < t1; ++t)
    {
      const IdT* b = ids + t * kIdsPerTask;
      const IdT* e = ids + std::min(n, (t + 1) * kIdsPerTask);
      IdT mn = std::numeric_limits<IdT>::max(), mx = std::numeric_limits<IdT>::lowest();
      for (const IdT* p = b; p < e; ++p)
      {
        mn = std::min(mn, *p);
        mx = std::max(mx, *p);
      }
      lo[t] = mn;
      hi[t] = mx;
    }
  });
  range[0] = static_cast<vtkIdType>(*std::min_element(lo.begin(), lo.end()));
  range[1] = static_cast<vtkIdType>(*std::max_element(hi.begin(), hi.end()));
}

// The first cell of `cells` (counted from `firstCell`) with an id outside [0, nPts), for the
// error message; -1 when none.
void FirstBadCell(
  vtkCellArray* cells, vtkIdType nPts, vtkIdType firstCell, vtkIdType& cell, vtkIdType& id)
{
  cell = -1;
  id = 0;
  const vtkIdType n = cells->GetNumberOfCells();
  for (vtkIdType c = 0; c < n; ++c)
  {
    const vtkIdType size = cells->GetCellSize(c);
    for (vtkIdType k = 0; k < size; ++k)
    {
      // Read through the offsets: GetCellAtId would do the same, with a temporary list.
      const vtkIdType p = cells->GetConnectivityArray()->GetComponent(
        static_cast<vtkIdType>(cells->GetOffsetsArray()->GetComponent(c, 0)) + k, 0);
      if (p < 0 || p >= nPts)
      {
        cell = firstCell + c;
        id = p;
        return;
      }
    }
  }
}
} // namespace

void vtkCatadioptricMeshCheck::IdRange(vtkCellArray* cells, vtkIdType range[2])
{
  range[0] = 0;
  range[1] = -1;
  vtkDataArray* conn = cells ? cells->GetConnectivityArray() : nullptr;
  const vtkIdType n = conn ? conn->GetNumberOfValues() : 0;
  if (n == 0)
  {
    return;
  }
  vtkInformation* info = conn->GetInformation();
  const double* r = info->Has(IdRangeKey()) ? info->Get(IdRangeKey()) : nullptr;
  if (r && info->GetMTime() > conn->GetMTime() && r[2] == static_cast<double>(n))
  {
    range[0] = static_cast<vtkIdType>(r[0]);
    range[1] = static_cast<vtkIdType>(r[1]);
    return;
  }
  if (cells->IsStorage64Bit())
  {
    Range(cells->GetConnectivityArray64()->GetPointer(0), n, range);
  }
  else
  {
    Range(cells->GetConnectivityArray32()->GetPointer(0), n, range);
  }
  const double cached[3] = { static_cast<double>(range[0]), static_cast<double>(range[1]),
    static_cast<double>(n) };
  info->Set(IdRangeKey(), cached, 3);
}

bool vtkCatadioptricMeshCheck::CheckPointIds(vtkPolyData* mesh, std::string& error)
{
  const vtkIdType nPts = mesh->GetNumberOfPoints();
  vtkCellArray* arrays[4] = { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(),
    mesh->GetStrips() };
  vtkIdType firstCell = 0;
  for (vtkCellArray* cells : arrays)
  {
    if (!cells)
    {
      continue;
    }
    vtkIdType range[2];
    IdRange(cells, range);
    if (range[1] >= range[0] && (range[0] < 0 || range[1] >= nPts))
    {
      vtkIdType cell = -1, id = 0;
      FirstBadCell(cells, nPts, firstCell, cell, id);
      std::ostringstream s;
      s << "cell " << cell << " names point " << id << ", but the mesh has " << nPts << " point"
        << (nPts == 1 ? "" : "s");
      if (nPts > 0)
      {
        s << " (ids 0 to " << nPts - 1 << ")";
      }
      s << ": the mesh's cells and points do not match.";
      error = s.str();
      return false;
    }
    firstCell += cells->GetNumberOfCells();
  }
  return true;
}

bool vtkCatadioptricMeshCheck::CheckArraySizes(vtkPolyData* mesh, std::string& error)
{
  struct Part
  {
    vtkDataSetAttributes* Data;
    vtkIdType Tuples;
    const char* What;
  };
  const Part parts[2] = { { mesh->GetPointData(), mesh->GetNumberOfPoints(), "point" },
    { mesh->GetCellData(), mesh->GetNumberOfCells(), "cell" } };
  for (const Part& part : parts)
  {
    for (int a = 0; a < part.Data->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = part.Data->GetAbstractArray(a);
      if (array && array->GetNumberOfTuples() < part.Tuples)
      {
        std::ostringstream s;
        s << "the " << part.What << " array '"
          << (array->GetName() ? array->GetName() : "(unnamed)") << "' has "
          << array->GetNumberOfTuples() << " tuples for " << part.Tuples << " " << part.What
          << "s.";
        error = s.str();
        return false;
      }
    }
  }
  return true;
}

bool vtkCatadioptricMeshCheck::Check(vtkPolyData* mesh, std::string& error)
{
  return CheckPointIds(mesh, error) && CheckArraySizes(mesh, error);
}

bool vtkCatadioptricMeshCheck::InputAndOutput(vtkAlgorithm* filter,
  vtkInformationVector** inputVector, vtkInformationVector* outputVector, vtkPolyData*& input,
  vtkPolyData*& output)
{
  input = vtkPolyData::GetData(inputVector[0]);
  output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorWithObjectMacro(filter, "Input and output must be vtkPolyData.");
    return false;
  }
  std::string error;
  if (!Check(input, error))
  {
    vtkErrorWithObjectMacro(filter, "Bad input mesh: " << error);
    return false;
  }
  return true;
}
