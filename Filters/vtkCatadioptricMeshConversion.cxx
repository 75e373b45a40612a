#include "vtkCatadioptricMeshConversion.h"

#include "Polygons.h"
#include "TriangleMesh.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkGenericCell.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStaticCellLocator.h"

#include <cmath>
#include <vector>

void vtkCatadioptricMeshConversion::ToTriangleMesh(
  vtkPolyData* input, catar::mesh::TriangleMesh& mesh, std::vector<std::string>& warnings)
{
  mesh = catar::mesh::TriangleMesh();
  const vtkIdType nPoints = input->GetNumberOfPoints();
  mesh.points.resize(nPoints);
  for (vtkIdType i = 0; i < nPoints; ++i)
  {
    input->GetPoint(i, mesh.points[i].data());
  }
  const vtkIdType ignored = input->GetNumberOfVerts() + input->GetNumberOfLines();
  if (ignored > 0)
  {
    warnings.push_back(std::to_string(input->GetNumberOfVerts()) + " vertex cells and " +
      std::to_string(input->GetNumberOfLines()) +
      " line cells ignored: only surfaces are remeshed");
  }
  // Ids that name no point become -1 (the repair drops their triangles): a cast of a huge id
  // to int could wrap to a point that exists.
  const auto index = [nPoints](vtkIdType id) {
    return id >= 0 && id < nPoints ? static_cast<int>(id) : -1;
  };
  auto add = [&](vtkIdType a, vtkIdType b, vtkIdType c) {
    mesh.triangles.push_back({ index(a), index(b), index(c) });
  };
  vtkIdType nPolygons = 0;
  auto polys = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    polys->GetCurrentCell(n, ids);
    nPolygons += n > 3;
    catar::PolygonTriangles(ids, static_cast<std::size_t>(n), add);
  }
  if (nPolygons > 0)
  {
    warnings.push_back(std::to_string(nPolygons) +
      " polygons with more than 3 points split "
      "into triangles");
  }
  auto strips = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    strips->GetCurrentCell(n, ids);
    catar::StripTriangles(ids, static_cast<std::size_t>(n), add);
  }
  vtkPointData* pd = input->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (!array || !array->GetName() || array->GetNumberOfTuples() != nPoints)
    {
      continue;
    }
    catar::mesh::PointAttribute attribute;
    attribute.name = array->GetName();
    attribute.components = array->GetNumberOfComponents();
    attribute.values.resize(static_cast<size_t>(nPoints) * attribute.components);
    for (vtkIdType i = 0; i < nPoints; ++i)
    {
      for (int c = 0; c < attribute.components; ++c)
      {
        attribute.values[i * attribute.components + c] = array->GetComponent(i, c);
      }
    }
    mesh.pointData.push_back(std::move(attribute));
  }
}

void vtkCatadioptricMeshConversion::FromTriangleMesh(
  const catar::mesh::TriangleMesh& mesh, vtkPolyData* prototype, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkCatadioptricAllocation::Points(points, static_cast<vtkIdType>(mesh.points.size()));
  for (size_t i = 0; i < mesh.points.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), mesh.points[i].data());
  }
  vtkNew<vtkCellArray> triangles;
  triangles->AllocateExact(static_cast<vtkIdType>(mesh.triangles.size()),
    3 * static_cast<vtkIdType>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    triangles->InsertNextCell(3, ids);
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(triangles);
  vtkPointData* in = prototype ? prototype->GetPointData() : nullptr;
  vtkPointData* out = output->GetPointData();
  const vtkIdType n = static_cast<vtkIdType>(mesh.points.size());
  for (const auto& attribute : mesh.pointData)
  {
    vtkDataArray* model = in ? in->GetArray(attribute.name.c_str()) : nullptr;
    vtkSmartPointer<vtkDataArray> array = model
      ? vtk::TakeSmartPointer(model->NewInstance())
      : vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkDoubleArray>::New());
    array->SetName(attribute.name.c_str());
    array->SetNumberOfComponents(attribute.components);
    vtkCatadioptricAllocation::Tuples(array, n);
    const bool isNormals = model && in->GetNormals() == model && attribute.components == 3;
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double* v = attribute.values.data() + i * attribute.components;
      double scale = 1.0;
      if (isNormals)
      {
        const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        scale = len > 0.0 ? 1.0 / len : 0.0;
      }
      for (int c = 0; c < attribute.components; ++c)
      {
        array->SetComponent(i, c, scale * v[c]);
      }
    }
    out->AddArray(array);
    if (model && in->GetScalars() == model)
    {
      out->SetScalars(array);
    }
    if (isNormals)
    {
      out->SetNormals(array);
    }
    if (model && in->GetTCoords() == model)
    {
      out->SetTCoords(array);
    }
  }
}

void vtkCatadioptricMeshConversion::TransferCellData(vtkPolyData* input, vtkPolyData* output)
{
  vtkCellData* in = input->GetCellData();
  if (in->GetNumberOfArrays() == 0 || input->GetNumberOfCells() == 0)
  {
    return;
  }
  // The locator is built on the input cells that can be located: every id names a point and
  // every point is finite (the repair dropped the others; a locator over them reads out of
  // bounds). `source` maps them back to the input's cell ids.
  const vtkIdType nPoints = input->GetNumberOfPoints();
  std::vector<char> finite(static_cast<size_t>(nPoints));
  for (vtkIdType i = 0; i < nPoints; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    finite[i] = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  }
  vtkNew<vtkPolyData> located;
  located->SetPoints(input->GetPoints());
  // Cells keep their kind (vertices, lines, polygons, strips: the order vtkPolyData numbers
  // them in, so the located cells' ids follow the input's).
  vtkNew<vtkCellArray> cells[4];
  std::vector<vtkIdType> source;
  vtkNew<vtkIdList> ids;
  const vtkIdType ends[4] = { input->GetNumberOfVerts(),
    input->GetNumberOfVerts() + input->GetNumberOfLines(),
    input->GetNumberOfVerts() + input->GetNumberOfLines() + input->GetNumberOfPolys(),
    input->GetNumberOfCells() };
  int kind = 0;
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    while (c >= ends[kind])
    {
      ++kind;
    }
    input->GetCellPoints(c, ids);
    bool ok = ids->GetNumberOfIds() > 0;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds() && ok; ++k)
    {
      const vtkIdType p = ids->GetId(k);
      ok = p >= 0 && p < nPoints && finite[p];
    }
    if (ok)
    {
      cells[kind]->InsertNextCell(ids);
      source.push_back(c);
    }
  }
  vtkCellData* out = output->GetCellData();
  const vtkIdType nCells = output->GetNumberOfCells();
  out->CopyAllocate(in, nCells);
  if (source.empty())
  {
    for (vtkIdType c = 0; c < nCells; ++c)
    {
      out->CopyData(in, vtkIdType(0), c);
    }
    return;
  }
  located->SetVerts(cells[0]);
  located->SetLines(cells[1]);
  located->SetPolys(cells[2]);
  located->SetStrips(cells[3]);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(located);
  locator->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType c = 0; c < nCells; ++c)
  {
    output->GetCellPoints(c, ids);
    double centroid[3] = { 0.0, 0.0, 0.0 };
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double p[3];
      output->GetPoint(ids->GetId(k), p);
      for (int j = 0; j < 3; ++j)
      {
        centroid[j] += p[j] / ids->GetNumberOfIds();
      }
    }
    double closest[3], dist2;
    vtkIdType cellId = -1;
    int subId;
    locator->FindClosestPoint(centroid, closest, cell, cellId, subId, dist2);
    out->CopyData(in, cellId >= 0 ? source[cellId] : source[0], c);
  }
}
