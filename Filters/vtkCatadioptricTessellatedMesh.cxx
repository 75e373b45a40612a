#include "vtkCatadioptricTessellatedMesh.h"

#include "MeshRefinement.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace
{
// The most pieces one execution makes (all split triangles together).
constexpr std::size_t kMaxPieces = std::size_t(1) << 22;

// Calls f(points) with the mesh's coordinates (x, y, z per point) as floats or doubles: the
// array itself when it holds either, else a copy as doubles (the values GetPoint gives).
template<typename F>
void WithCoordinates(vtkPoints* points, F&& f)
{
  if (auto* doubles = vtkDoubleArray::FastDownCast(points->GetData()))
  {
    f(static_cast<const double*>(doubles->GetPointer(0)));
    return;
  }
  if (auto* floats = vtkFloatArray::FastDownCast(points->GetData()))
  {
    f(static_cast<const float*>(floats->GetPointer(0)));
    return;
  }
  std::vector<double> copy(static_cast<std::size_t>(3 * points->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->GetPoint(i, copy.data() + 3 * i);
  }
  f(static_cast<const double*>(copy.data()));
}

// The refined mesh: the input's points then the new ones (point data interpolated), the
// polygons with each chosen triangle's pieces in its place (its cell data copied); `sources` (may
// be null): each output cell's input cell, -1 for a piece.
void Assemble(vtkPolyData* input, const std::vector<std::int64_t>& chosen,
  std::vector<catar::Tessellation>& pieces, catar::Tessellation& added, vtkPolyData* output,
  std::vector<std::int64_t>* sources)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  vtkPoints* points = input->GetPoints();
  const vtkIdType nPoints = input->GetNumberOfPoints();
  added.points.clear();
  added.triangles.clear();
  std::vector<std::vector<catar::TessellatedTriangle>> byCell(chosen.size());
  for (std::size_t k = 0; k < chosen.size(); ++k)
  {
    const std::int64_t shift = static_cast<std::int64_t>(added.points.size());
    for (catar::TessellatedTriangle t : pieces[k].triangles)
    {
      for (std::int64_t& id : t.points)
      {
        id = id < nPoints ? id : id + shift;
      }
      byCell[k].push_back(t);
    }
    added.points.insert(added.points.end(), pieces[k].points.begin(), pieces[k].points.end());
  }

  // Points and point data: the input's, then the new ones interpolated.
  const vtkIdType nNew = static_cast<vtkIdType>(added.points.size());
  vtkNew<vtkPoints> outPoints;
  outPoints->SetDataTypeToDouble();
  vtkCatadioptricAllocation::Points(outPoints, nPoints + nNew);
  outPoints->GetData()->InsertTuples(0, nPoints, 0, points->GetData());
  vtkPointData* inPD = input->GetPointData();
  vtkNew<vtkPointData> outPD;
  outPD->InterpolateAllocate(inPD, nPoints + nNew);
  outPD->CopyData(inPD, 0, nPoints, 0);
  vtkNew<vtkIdList> parents;
  parents->SetNumberOfIds(3);
  for (vtkIdType i = 0; i < nNew; ++i)
  {
    const catar::TessellatedPoint& p = added.points[i];
    outPoints->SetPoint(nPoints + i, p.world.data());
    double weights[3];
    for (int k = 0; k < 3; ++k)
    {
      parents->SetId(k, p.parents[k]);
      weights[k] = p.weights[k];
    }
    outPD->InterpolatePoint(inPD, nPoints + i, parents, weights);
  }

  // Cells: verts and lines as they are, the polygons with the split ones' pieces in place, the
  // strips; cell data copied from each piece's triangle.
  vtkCellData* inCD = input->GetCellData();
  vtkNew<vtkCellData> outCD;
  vtkIdType nPieces = 0;
  for (const auto& cell : byCell)
  {
    nPieces += static_cast<vtkIdType>(cell.size());
  }
  const vtkIdType nVerts = input->GetNumberOfVerts(), nLines = input->GetNumberOfLines();
  const vtkIdType nCellsOut =
    input->GetNumberOfCells() - static_cast<vtkIdType>(chosen.size()) + nPieces;
  outCD->CopyAllocate(inCD, nCellsOut);
  // Each output cell's input cell, copied in one call at the end.
  vtkNew<vtkIdList> from;
  from->Allocate(nCellsOut);
  if (sources)
  {
    sources->clear();
    sources->reserve(static_cast<std::size_t>(nCellsOut));
  }
  const auto add = [&](vtkIdType inCell, bool piece) {
    from->InsertNextId(inCell);
    if (sources)
    {
      sources->push_back(piece ? -1 : inCell);
    }
  };
  for (vtkIdType c = 0; c < nVerts + nLines; ++c)
  {
    add(c, false);
  }
  vtkNew<vtkCellArray> outPolys;
  outPolys->AllocateEstimate(nPolys - static_cast<vtkIdType>(chosen.size()) + nPieces, 3);
  vtkNew<vtkIdList> ids;
  std::size_t next = 0;
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    const vtkIdType inCell = nVerts + nLines + c;
    if (next < chosen.size() && chosen[next] == c)
    {
      for (const catar::TessellatedTriangle& t : byCell[next])
      {
        const vtkIdType tri[3] = { t.points[0], t.points[1], t.points[2] };
        outPolys->InsertNextCell(3, tri);
        add(inCell, true);
      }
      ++next;
      continue;
    }
    polys->GetCellAtId(c, ids);
    outPolys->InsertNextCell(ids);
    add(inCell, false);
  }
  const vtkIdType firstStrip = nVerts + nLines + nPolys;
  for (vtkIdType c = 0; c < input->GetNumberOfStrips(); ++c)
  {
    add(firstStrip + c, false);
  }
  outCD->CopyData(inCD, from.Get(), vtkIdType(0));
  output->Initialize();
  output->SetPoints(outPoints);
  output->SetVerts(input->GetVerts());
  output->SetLines(input->GetLines());
  output->SetPolys(outPolys);
  output->SetStrips(input->GetStrips());
  output->GetPointData()->ShallowCopy(outPD);
  output->GetCellData()->ShallowCopy(outCD);
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
}
} // namespace

vtkIdType vtkCatadioptricTessellatedMesh::Refine(vtkPolyData* input,
  const catar::Projector& projector, const catar::TessellationOptions& options,
  const unsigned char* status, const double* pixels, const double* mirrorPoints,
  catar::Tessellation& added, vtkPolyData* output, std::vector<std::int64_t>* sources)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  if (nPolys == 0 || !(options.boundaryTolerance > 0.0 || options.bendTolerance > 0.0))
  {
    return 0;
  }
  const vtkIdType nPoints = input->GetNumberOfPoints();
  // With neither tolerance only triangles with an unseen corner can need it: none when every
  // point is seen, found without a pass over the cells. (With a boundary tolerance, a triangle
  // seen at its corners may still have a hidden middle: the pass looks at those with long edges.)
  if (!(options.bendTolerance > 0.0) && !(options.boundaryTolerance > 0.0) &&
    std::all_of(status, status + nPoints, [](unsigned char s) {
      return catar::HasProjection(static_cast<catar::ProjectionStatus>(s));
    }))
  {
    return 0;
  }
  const catar::PointProjections at{ status, pixels, mirrorPoints };
  const int threads = vtkCatadioptricParallel::GetNumberOfThreads();
  std::vector<std::int64_t> chosen;
  std::vector<catar::Tessellation> pieces;
  WithCoordinates(input->GetPoints(), [&](const auto* coordinates) {
    polys->Visit([&](auto& state) {
      using Index = typename std::remove_const<
        typename std::remove_reference<decltype(*state.GetOffsets()->GetPointer(0))>::type>::type;
      using Real = typename std::remove_const<
        typename std::remove_reference<decltype(*coordinates)>::type>::type;
      catar::PolygonMeshView<Index, Real> mesh;
      mesh.points = coordinates;
      mesh.numberOfPoints = nPoints;
      mesh.offsets = state.GetOffsets()->GetPointer(0);
      mesh.connectivity = state.GetConnectivity()->GetPointer(0);
      mesh.numberOfPolygons = nPolys;
      chosen = catar::ChooseTriangles(mesh, projector, options, at, threads);
      if (!chosen.empty())
      {
        pieces = catar::TessellateAlike(mesh, projector, options, at, chosen, kMaxPieces, threads);
      }
    });
  });
  if (chosen.empty())
  {
    return 0;
  }
  Assemble(input, chosen, pieces, added, output, sources);
  return static_cast<vtkIdType>(chosen.size());
}
