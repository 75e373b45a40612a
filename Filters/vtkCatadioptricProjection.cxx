#include "vtkCatadioptricProjection.h"

#include "CameraModel.h"
#include "ImageTessellation.h"
#include "PolygonProjection.h"
#include "Projector.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricPointReader.h"
#include "vtkCatadioptricTessellatedMesh.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricProjection);

namespace
{
// Points (or cells) per parallel task: waking the pool's threads costs more than projecting a
// few hundred points; smaller meshes are projected inline.
constexpr vtkIdType kPointGrain = 512;

// The point arrays the projection writes (ImageCoordinates, MirrorPoint, PathLength,
// ProjectionStatus, Visible), with the vertex records the cells read, filled point by point.
struct PointOutputs
{
  explicit PointOutputs(vtkIdType n)
    : Records(new catar::VertexRecord[std::max<vtkIdType>(n, 1)])
  {
    this->Pixels->SetName(vtkCatadioptricArrayNames::ImageCoordinates);
    this->Pixels->SetNumberOfComponents(2);
    this->Mirror->SetName(vtkCatadioptricArrayNames::MirrorPoint);
    this->Mirror->SetNumberOfComponents(3);
    this->Path->SetName(vtkCatadioptricArrayNames::PathLength);
    this->Status->SetName(vtkCatadioptricArrayNames::ProjectionStatus);
    this->Visible->SetName(vtkCatadioptricArrayNames::Visible);
    for (vtkDataArray* a : this->Arrays())
    {
      vtkCatadioptricAllocation::Tuples(a, n);
    }
    this->Bind();
  }

  std::array<vtkDataArray*, 5> Arrays()
  {
    return { this->Pixels.Get(), this->Mirror.Get(), this->Path.Get(), this->Status.Get(),
      this->Visible.Get() };
  }

  // Point i: world position p, projected q.
  void Store(vtkIdType i, const catar::Vec3& p, const catar::ProjectedPoint& q) const
  {
    this->Px[2 * i] = q.pixel.x();
    this->Px[2 * i + 1] = q.pixel.y();
    this->Mp[3 * i] = q.mirrorPoint.x();
    this->Mp[3 * i + 1] = q.mirrorPoint.y();
    this->Mp[3 * i + 2] = q.mirrorPoint.z();
    this->Pl[i] = q.pathLength;
    this->St[i] = static_cast<unsigned char>(q.status);
    this->Vi[i] = catar::HasProjection(q.status) ? 1 : 0;
    this->Records[i].Set(p, q);
  }

  // The vertex pass: the n points projected in parallel runs, each point's search started from
  // its neighbour's answer (catar::ProjectRun).
  void Project(
    const catar::Projector& projector, catar::SolverType solver, vtkPoints* from, vtkIdType n)
  {
    if (n == 0)
    {
      return;
    }
    const vtkCatadioptricPointReader points(from);
    vtkCatadioptricParallel::For(0, n, kPointGrain, [&](vtkIdType begin, vtkIdType end) {
      catar::ProjectRun(projector, solver, begin, end, points,
        [&](vtkIdType i, const catar::Vec3& p, const catar::ProjectedPoint& q) {
          this->Store(i, p, q);
        });
    });
  }

  // Room for n points, the first `kept` points' values kept.
  void Grow(vtkIdType kept, vtkIdType n)
  {
    for (vtkDataArray* a : this->Arrays())
    {
      vtkCatadioptricAllocation::Grow(a, n);
    }
    std::unique_ptr<catar::VertexRecord[]> grown(new catar::VertexRecord[n]);
    std::copy(this->Records.get(), this->Records.get() + kept, grown.get());
    this->Records.swap(grown);
    this->Bind();
  }

  void AddTo(vtkPointData* pd)
  {
    for (vtkDataArray* a : this->Arrays())
    {
      pd->AddArray(a);
    }
  }

  vtkNew<vtkDoubleArray> Pixels;
  vtkNew<vtkDoubleArray> Mirror;
  vtkNew<vtkDoubleArray> Path;
  vtkNew<vtkUnsignedCharArray> Status;
  vtkNew<vtkUnsignedCharArray> Visible;
  std::unique_ptr<catar::VertexRecord[]> Records;

private:
  void Bind()
  {
    this->Px = this->Pixels->GetPointer(0);
    this->Mp = this->Mirror->GetPointer(0);
    this->Pl = this->Path->GetPointer(0);
    this->St = this->Status->GetPointer(0);
    this->Vi = this->Visible->GetPointer(0);
  }
  double* Px = nullptr;
  double* Mp = nullptr;
  double* Pl = nullptr;
  unsigned char* St = nullptr;
  unsigned char* Vi = nullptr;
};

// A mesh's cell arrays: CentroidDepth, CentroidMirrorPoint and Visible.
struct CellArrays
{
  vtkSmartPointer<vtkDoubleArray> Depth;
  vtkSmartPointer<vtkDoubleArray> Mirror;
  vtkSmartPointer<vtkUnsignedCharArray> Visible;

  CellArrays() = default;
  // For n cells, not filled.
  explicit CellArrays(vtkIdType n)
    : Depth(vtkSmartPointer<vtkDoubleArray>::New())
    , Mirror(vtkSmartPointer<vtkDoubleArray>::New())
    , Visible(vtkSmartPointer<vtkUnsignedCharArray>::New())
  {
    this->Depth->SetName(vtkCatadioptricArrayNames::CentroidDepth);
    vtkCatadioptricAllocation::Tuples(this->Depth, n);
    this->Mirror->SetName("CentroidMirrorPoint");
    this->Mirror->SetNumberOfComponents(3);
    vtkCatadioptricAllocation::Tuples(this->Mirror, n);
    this->Visible->SetName(vtkCatadioptricArrayNames::Visible);
    vtkCatadioptricAllocation::Tuples(this->Visible, n);
  }

  // Where catar::PolygonProjection writes, its first polygon at cell firstPoly.
  catar::PolygonOutputs Outputs(vtkIdType firstPoly) const
  {
    catar::PolygonOutputs out;
    out.depth = this->Depth->GetPointer(0);
    out.centroidMirror = this->Mirror->GetPointer(0);
    out.visible = this->Visible->GetPointer(0);
    out.cellOffset = firstPoly;
    return out;
  }
};

// Calls f(polygons) with `mesh`'s polygons as catar::PolygonsView, vertices[i] the record of
// point i.
template<typename F>
void WithPolygons(vtkPolyData* mesh, const catar::VertexRecord* vertices, F&& f)
{
  mesh->GetPolys()->Visit([&](auto& state) {
    using Index = typename std::remove_const<
      typename std::remove_reference<decltype(*state.GetOffsets()->GetPointer(0))>::type>::type;
    catar::PolygonsView<Index> polygons;
    polygons.offsets = state.GetOffsets()->GetPointer(0);
    polygons.connectivity = state.GetConnectivity()->GetPointer(0);
    polygons.numberOfPolygons = state.GetNumberOfCells();
    polygons.vertices = vertices;
    f(polygons);
  });
}

// Projects the centroids of `mesh`'s polygons (whose points' records are `vertices`) and decides
// their visibility (catar::PolygonProjection); zeros for its other cells.
CellArrays ProjectCells(vtkPolyData* mesh, const catar::PolygonProjection& polygons,
  const catar::VertexRecord* vertices, int threads, std::atomic<bool>* needsFateCheck)
{
  const vtkIdType nCells = mesh->GetNumberOfCells();
  CellArrays out(nCells);
  // Zeros for vertices, lines and strips; the polygons' values are all written below.
  const vtkIdType firstPoly = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  const vtkIdType endPoly = firstPoly + mesh->GetNumberOfPolys();
  const bool polysWritten = mesh->GetNumberOfPolys() > 0 && mesh->GetNumberOfPoints() > 0;
  for (const auto& range : { std::make_pair(vtkIdType(0), polysWritten ? firstPoly : nCells),
         std::make_pair(polysWritten ? endPoly : nCells, nCells) })
  {
    std::fill(out.Depth->GetPointer(range.first), out.Depth->GetPointer(range.second), 0.0);
    std::fill(
      out.Mirror->GetPointer(3 * range.first), out.Mirror->GetPointer(3 * range.second), 0.0);
    std::fill(out.Visible->GetPointer(range.first), out.Visible->GetPointer(range.second), 0);
  }
  if (polysWritten)
  {
    WithPolygons(mesh, vertices, [&](const auto& view) {
      polygons.Project(view, out.Outputs(firstPoly), threads, needsFateCheck);
    });
  }
  return out;
}

// The cell arrays of `mesh`, refined from the mesh `first` was computed for: a cell copied as it
// is (sources[c] >= 0, its cell there) keeps its values, the pieces (-1) are projected.
CellArrays ProjectPieces(vtkPolyData* mesh, const catar::PolygonProjection& polygons,
  const catar::VertexRecord* vertices, const CellArrays& first,
  const std::vector<std::int64_t>& sources, int threads)
{
  CellArrays out(mesh->GetNumberOfCells());
  const vtkIdType firstPoly = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  WithPolygons(mesh, vertices, [&](const auto& view) {
    polygons.ProjectPieces(view, mesh->GetNumberOfCells(), sources.data(), first.Outputs(0),
      out.Outputs(firstPoly), threads);
  });
  return out;
}
} // namespace

vtkCatadioptricProjection::vtkCatadioptricProjection() = default;

vtkCatadioptricProjection::~vtkCatadioptricProjection() = default;

vtkCatadioptricCameraSlotMacro(vtkCatadioptricProjection);
vtkCatadioptricCameraSlotValidMacro(vtkCatadioptricProjection);
vtkCatadioptricCameraSlotTrajectoryMacro(vtkCatadioptricProjection);

int vtkCatadioptricProjection::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  std::string ignored; // a missing camera is reported once, by RequestData
  if (vtkCatadioptricCamera* camera = this->CameraSlot.Resolve(ignored))
  {
    const int size[2] = { camera->GetImageWidth(), camera->GetImageHeight() };
    outInfo->Set(vtkCatadioptricCamera::IMAGE_SIZE(), size, 2);
  }
  else
  {
    outInfo->Remove(vtkCatadioptricCamera::IMAGE_SIZE());
  }
  std::string error;
  if (!this->CameraSlot.AnnounceTimeSteps(outInfo, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  return 1;
}

int vtkCatadioptricProjection::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = nullptr;
  vtkPolyData* output = nullptr;
  if (!vtkCatadioptricMeshCheck::InputAndOutput(this, inputVector, outputVector, input, output))
  {
    return 0;
  }
  vtkCatadioptricCamera* camera = this->ResolveValidCamera(outputVector->GetInformationObject(0));
  if (!camera)
  {
    return 0;
  }
  // Out of memory (a mesh too large for the memory left): the filter's error, with the sizes.
  return vtkCatadioptricAllocation::Guard(
    this, [&] { return this->Project(input, output, camera); },
    [&] {
      return "projecting " + std::to_string(input->GetNumberOfPoints()) + " points and " +
        std::to_string(input->GetNumberOfCells()) + " cells";
    });
}

int vtkCatadioptricProjection::Project(
  vtkPolyData* input, vtkPolyData* output, vtkCatadioptricCamera* camera)
{
  const catar::Projector projector(camera->GetModel());
  // AUTOMATIC: the mirror's choice, resolved once (the batches below follow the choice).
  const catar::SolverType solver =
    projector.GetMirror()->Resolve(static_cast<catar::SolverType>(this->Solver));

  output->ShallowCopy(input);
  camera->WriteToFieldData(output->GetFieldData());

  const vtkIdType nPts = input->GetNumberOfPoints();
  this->UpdateProgress(0.0);
  PointOutputs out(nPts);
  out.Project(projector, solver, input->GetPoints(), nPts);
  this->UpdateProgress(0.5);
  if (input->GetNumberOfStrips() > 0)
  {
    vtkWarningMacro("Triangle strips are not drawn; run vtkTriangleFilter first.");
  }
  catar::PolygonProjection polygons(projector, this->BackFaceCulling);
  const int threads = vtkCatadioptricParallel::GetNumberOfThreads();
  catar::TessellationOptions& tessellation = polygons.Tessellation;
  tessellation.boundaryTolerance = this->BoundaryTolerance;
  tessellation.bendTolerance = this->AdaptiveTolerance;
  tessellation.solver = solver;

  // Per-frame tessellation: triangles across the visibility boundary (and, adaptive, those that
  // bend too much) replaced by their pieces; the new points' projections appended. Without a
  // bend tolerance most frames split nothing: the cells are projected first, and that pass also
  // finds whether any triangle needs a closer look (catar::NeedsFateCheck); only then is the mesh
  // refined, and when a triangle was split its pieces projected (the other cells keep their
  // values). With one, every triangle needs it: the mesh is refined first.
  this->NumberOfSplitTriangles = 0;
  const bool refineFirst = tessellation.bendTolerance > 0.0;
  const bool polys = nPts > 0 && input->GetNumberOfPolys() > 0;
  std::atomic<bool> needsFateCheck(polys);
  CellArrays cells;
  std::vector<std::int64_t> sources; // the refined mesh's cells' cells in the input (-1: pieces)
  if (!refineFirst)
  {
    needsFateCheck = false;
    cells = ProjectCells(input, polygons, out.Records.get(), threads, &needsFateCheck);
  }
  if (polys && needsFateCheck)
  {
    catar::Tessellation added;
    this->NumberOfSplitTriangles = vtkCatadioptricTessellatedMesh::Refine(input, projector,
      tessellation, out.Status->GetPointer(0), out.Pixels->GetPointer(0), out.Mirror->GetPointer(0),
      added, output, refineFirst ? nullptr : &sources);
    if (this->NumberOfSplitTriangles > 0)
    {
      camera->WriteToFieldData(output->GetFieldData());
      const vtkIdType nNew = static_cast<vtkIdType>(added.points.size());
      out.Grow(nPts, nPts + nNew);
      for (vtkIdType k = 0; k < nNew; ++k)
      {
        out.Store(nPts + k, added.points[k].world, added.points[k].projected);
      }
    }
  }
  if (refineFirst)
  {
    cells = ProjectCells(this->NumberOfSplitTriangles > 0 ? output : input, polygons,
      out.Records.get(), threads, nullptr);
  }
  else if (this->NumberOfSplitTriangles > 0)
  {
    cells = ProjectPieces(output, polygons, out.Records.get(), cells, sources, threads);
  }
  out.AddTo(output->GetPointData());
  vtkCellData* cd = output->GetCellData();
  cd->AddArray(cells.Depth);
  cd->AddArray(cells.Mirror);
  cd->AddArray(cells.Visible);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricProjection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->CameraSlot.GetCamera() << "\n";
  const char* file = this->CameraSlot.GetCalibrationFileName();
  os << indent << "CalibrationFileName: " << (file ? file : "(none)") << "\n";
  os << indent << "Solver: " << (this->Solver == ITERATIVE ? "Iterative" : "Quartic") << "\n";
  os << indent << "BackFaceCulling: " << (this->BackFaceCulling ? "On" : "Off") << "\n";
  os << indent << "BoundaryTolerance: " << this->BoundaryTolerance << "\n";
  os << indent << "AdaptiveTolerance: " << this->AdaptiveTolerance << "\n";
}
