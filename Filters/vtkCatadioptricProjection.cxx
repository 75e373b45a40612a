#include "vtkCatadioptricProjection.h"

#include "CameraModel.h"
#include "ImageTessellation.h"
#include "Polygons.h"
#include "Projector.h"

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

#include <Eigen/Geometry> // cross products

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricProjection);

namespace
{
// Points (or cells) per parallel task: waking the pool's threads costs more than projecting a
// few hundred points; smaller meshes are projected inline.
constexpr vtkIdType kPointGrain = 512;

// What the cells read of each vertex, in one cache line: the cells visit their vertices in no
// particular order, and four arrays would cost four cache misses per vertex.
struct alignas(64) VertexRecord
{
  double point[3]; // world
  double pixel[2]; // image coordinates
  float mirror[3]; // reflection point (camera frame): where the centroids' Newton starts
  unsigned char visible;
};

// The point arrays the projection writes (ImageCoordinates, MirrorPoint, PathLength,
// ProjectionStatus, Visible), with the vertex records the cells read, filled point by point.
struct PointOutputs
{
  explicit PointOutputs(vtkIdType n)
    : Records(new VertexRecord[std::max<vtkIdType>(n, 1)])
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
      a->SetNumberOfTuples(n);
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
    VertexRecord& r = this->Records[i];
    std::copy(p.data(), p.data() + 3, r.point);
    std::copy(q.pixel.data(), q.pixel.data() + 2, r.pixel);
    for (int k = 0; k < 3; ++k)
    {
      r.mirror[k] = static_cast<float>(q.mirrorPoint[k]);
    }
    r.visible = this->Vi[i];
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
      a->Resize(n);
      a->SetNumberOfTuples(n);
    }
    std::unique_ptr<VertexRecord[]> grown(new VertexRecord[n]);
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
  std::unique_ptr<VertexRecord[]> Records;

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

// How many cells ahead the cell loop asks for its vertices' records.
constexpr vtkIdType kPrefetchCells = 8;

// Projects the polygons' centroids and decides cell visibility; runs over a range of polygons.
struct CellWorker
{
  // For the camera of `projector`: its image size and pose.
  CellWorker(const catar::Projector& projector, bool cullBackFaces)
    : Projector(&projector)
    , Width(projector.GetModel().intrinsics.width)
    , Height(projector.GetModel().intrinsics.height)
    , CullBackFaces(cullBackFaces)
    , CameraToWorldRotation(projector.GetPose().rotationT)
    , CameraCentre(projector.GetPose().centre)
  {
  }

  const catar::Projector* Projector;
  const VertexRecord* Vertices = nullptr;
  double* Depth = nullptr;
  double* CentroidMirror = nullptr;
  unsigned char* Visible = nullptr;
  vtkIdType CellOffset = 0; // cell-data index of the first polygon
  double Width;
  double Height;
  bool CullBackFaces;
  catar::Mat3 CameraToWorldRotation; // R^T
  catar::Vec3 CameraCentre;          // -R^T T: the camera centre in world coordinates
  // Not null: set when a triangle needs the per-frame tessellation's closer look
  // (catar::NeedsFateCheck with these options), the quick pass of
  // vtkCatadioptricTessellatedMesh::Refine done here, on the vertices this pass reads anyway.
  std::atomic<bool>* NeedsFateCheck = nullptr;
  catar::TessellationOptions Tessellation;

  // Polygon c has the points conn[off[c]], ..., conn[off[c + 1] - 1].
  template<typename IdT>
  void operator()(const IdT* off, const IdT* conn, vtkIdType begin, vtkIdType end) const
  {
    Batch batch(this->Projector->GetBatchSize());
    bool needsFateCheck = false;
    for (vtkIdType c = begin; c < end; ++c)
    {
      if (c + kPrefetchCells < end)
      {
        // The vertices of a cell a few ahead: their cache misses overlap this cell's work.
        for (IdT k = off[c + kPrefetchCells]; k < off[c + kPrefetchCells + 1]; ++k)
        {
          vtkCatadioptricParallel::Prefetch(this->Vertices + conn[k]);
        }
      }
      const IdT* ids = conn + off[c];
      const vtkIdType n = static_cast<vtkIdType>(off[c + 1] - off[c]);
      const vtkIdType out = this->CellOffset + c;
      this->Depth[out] = 0.0;
      this->Visible[out] = 0;
      std::fill(this->CentroidMirror + 3 * out, this->CentroidMirror + 3 * out + 3, 0.0);
      if (n < 3)
      {
        continue;
      }
      catar::Vec3 centroid = catar::Vec3::Zero();
      catar::Vec3 guess = catar::Vec3::Zero();
      const double* lp = this->Vertices[ids[n - 1]].point;
      catar::NewellNormal newell(catar::Vec3(lp[0], lp[1], lp[2])); // |normal| = 2 area
      bool all = true;
      double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
      for (vtkIdType k = 0; k < n; ++k)
      {
        const VertexRecord& v = this->Vertices[ids[k]];
        if (!v.visible)
        {
          all = false;
          break;
        }
        const catar::Vec3 p(v.point[0], v.point[1], v.point[2]);
        centroid += p;
        if (this->CullBackFaces)
        {
          newell.Add(p);
        }
        guess += catar::Vec3(v.mirror[0], v.mirror[1], v.mirror[2]);
        xmin = std::min(xmin, v.pixel[0]);
        xmax = std::max(xmax, v.pixel[0]);
        ymin = std::min(ymin, v.pixel[1]);
        ymax = std::max(ymax, v.pixel[1]);
      }
      if (this->NeedsFateCheck && n == 3 && !needsFateCheck)
      {
        const double* const px[3] = { this->Vertices[ids[0]].pixel, this->Vertices[ids[1]].pixel,
          this->Vertices[ids[2]].pixel };
        needsFateCheck = catar::NeedsFateCheck(all, px, this->Tessellation);
      }
      if (!all)
      {
        continue;
      }
      centroid /= static_cast<double>(n);
      guess /= static_cast<double>(n);
      const catar::Vec3& normal = newell.Sum();
      if (this->CullBackFaces)
      {
        // Facing away from the viewer (the reflection point) by more than a sliver: dropped
        // before its exact projection. The mean of the vertices' reflection points stands in
        // for the centroid's; cells within 1e-3 of edge-on wait for the exact one below.
        const catar::Vec3 toViewer =
          this->CameraToWorldRotation * guess + this->CameraCentre - centroid;
        if (normal.dot(toViewer) < -1e-3 * normal.norm() * toViewer.norm())
        {
          continue;
        }
      }
      // The centroid reflects next to its vertices: Newton from the mean of their reflection
      // points converges in one or two steps, to the same answer as either solver. Centroids are
      // solved a batch at a time (side by side, see Projector::ProjectWorldNear).
      batch.Add(out, centroid, guess, normal, xmin, xmax, ymin, ymax);
      if (batch.Full())
      {
        this->Finish(batch);
      }
    }
    this->Finish(batch);
    if (needsFateCheck)
    {
      this->NeedsFateCheck->store(true, std::memory_order_relaxed);
    }
  }

  // Cells whose centroid is still to be projected.
  struct Batch
  {
    static constexpr int W = catar::Mirror::kMaxBatchSize;
    explicit Batch(int size)
      : size(size)
    {
    }
    int size; // the projector's batch size
    int n = 0;
    vtkIdType out[W];
    catar::Vec3 centroid[W], guess[W], normal[W];
    double bounds[W][4];
    catar::ProjectedPoint q[W];
    bool Full() const { return this->n == this->size; }
    void Add(vtkIdType o, const catar::Vec3& c, const catar::Vec3& g, const catar::Vec3& nrm,
      double xmin, double xmax, double ymin, double ymax)
    {
      this->out[this->n] = o;
      this->centroid[this->n] = c;
      this->guess[this->n] = g;
      this->normal[this->n] = nrm;
      this->bounds[this->n][0] = xmin;
      this->bounds[this->n][1] = xmax;
      this->bounds[this->n][2] = ymin;
      this->bounds[this->n][3] = ymax;
      ++this->n;
    }
  };

  void Finish(Batch& batch) const
  {
    this->Projector->ProjectWorldNear(batch.n, batch.centroid, batch.guess, batch.q, false);
    for (int k = 0; k < batch.n; ++k)
    {
      const catar::ProjectedPoint& q = batch.q[k];
      const vtkIdType out = batch.out[k];
      if (!catar::HasProjection(q.status))
      {
        continue;
      }
      this->Depth[out] = q.pathLength;
      std::copy(q.mirrorPoint.data(), q.mirrorPoint.data() + 3, this->CentroidMirror + 3 * out);
      if (this->CullBackFaces &&
        batch.normal[k].dot(this->CameraToWorldRotation * q.mirrorPoint + this->CameraCentre -
          batch.centroid[k]) <= 0.0)
      {
        continue;
      }
      const double* b = batch.bounds[k];
      const bool overlapsImage =
        b[1] >= -0.5 && b[3] >= -0.5 && b[0] < this->Width - 0.5 && b[2] < this->Height - 0.5;
      this->Visible[out] = overlapsImage ? 1 : 0;
    }
    batch.n = 0;
  }
};

struct CellDispatch
{
  template<typename CellStateT>
  void operator()(CellStateT& state, const CellWorker& worker) const
  {
    const auto* off = state.GetOffsets()->GetPointer(0);
    const auto* conn = state.GetConnectivity()->GetPointer(0);
    vtkCatadioptricParallel::For(0, state.GetNumberOfCells(), kPointGrain,
      [&](vtkIdType b, vtkIdType e) { worker(off, conn, b, e); });
  }
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
    this->Depth->SetNumberOfTuples(n);
    this->Mirror->SetName("CentroidMirrorPoint");
    this->Mirror->SetNumberOfComponents(3);
    this->Mirror->SetNumberOfTuples(n);
    this->Visible->SetName(vtkCatadioptricArrayNames::Visible);
    this->Visible->SetNumberOfTuples(n);
  }
};

// Projects the centroids of `mesh`'s polygons (whose points' records are `vertices`) and decides
// their visibility with `worker`'s settings; zeros for its other cells.
CellArrays ProjectCells(vtkPolyData* mesh, CellWorker& worker, const VertexRecord* vertices)
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
    worker.Vertices = vertices;
    worker.Depth = out.Depth->GetPointer(0);
    worker.CentroidMirror = out.Mirror->GetPointer(0);
    worker.Visible = out.Visible->GetPointer(0);
    worker.CellOffset = firstPoly;
    mesh->GetPolys()->Visit(CellDispatch{}, worker);
  }
  return out;
}

// The cell arrays of `mesh`, refined from the mesh `first` was computed for: a cell copied as it
// is (sources[c] >= 0, its cell there) keeps its values, the pieces (-1) are projected.
CellArrays ProjectPieces(vtkPolyData* mesh, CellWorker& worker, const VertexRecord* vertices,
  const CellArrays& first, const std::vector<vtkIdType>& sources)
{
  const vtkIdType nCells = mesh->GetNumberOfCells();
  CellArrays out(nCells);
  const double* fromDepth = first.Depth->GetPointer(0);
  const double* fromMirror = first.Mirror->GetPointer(0);
  const unsigned char* fromVisible = first.Visible->GetPointer(0);
  double* depth = out.Depth->GetPointer(0);
  double* mirror = out.Mirror->GetPointer(0);
  unsigned char* visible = out.Visible->GetPointer(0);
  vtkCatadioptricParallel::For(0, nCells, kPointGrain, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType c = b; c < e; ++c)
    {
      const vtkIdType s = sources[c];
      depth[c] = s >= 0 ? fromDepth[s] : 0.0;
      for (int k = 0; k < 3; ++k)
      {
        mirror[3 * c + k] = s >= 0 ? fromMirror[3 * s + k] : 0.0;
      }
      visible[c] = s >= 0 ? fromVisible[s] : 0;
    }
  });
  // The pieces: runs of polygons.
  const vtkIdType firstPoly = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  const vtkIdType nPolys = mesh->GetNumberOfPolys();
  worker.Vertices = vertices;
  worker.Depth = depth;
  worker.CentroidMirror = mirror;
  worker.Visible = visible;
  worker.CellOffset = firstPoly;
  mesh->GetPolys()->Visit([&](auto& state) {
    const auto* off = state.GetOffsets()->GetPointer(0);
    const auto* conn = state.GetConnectivity()->GetPointer(0);
    for (vtkIdType p = 0; p < nPolys;)
    {
      if (sources[firstPoly + p] >= 0)
      {
        ++p;
        continue;
      }
      vtkIdType e = p + 1;
      while (e < nPolys && sources[firstPoly + e] < 0)
      {
        ++e;
      }
      worker(off, conn, p, e);
      p = e;
    }
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
  const catar::Projector projector(camera->GetModel());
  const catar::SolverType solver =
    this->Solver == ITERATIVE ? catar::SolverType::Iterative : catar::SolverType::Quartic;

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
  CellWorker worker(projector, this->BackFaceCulling);
  worker.Tessellation.boundaryTolerance = this->BoundaryTolerance;
  worker.Tessellation.bendTolerance = this->AdaptiveTolerance;
  worker.Tessellation.solver = solver;

  // Per-frame tessellation: triangles across the visibility boundary (and, adaptive, those that
  // bend too much) replaced by their pieces; the new points' projections appended. Without a
  // bend tolerance most frames split nothing: the cells are projected first, and that pass also
  // finds whether any triangle needs a closer look (catar::NeedsFateCheck); only then is the mesh
  // refined, and when a triangle was split its pieces projected (the other cells keep their
  // values). With one, every triangle needs it: the mesh is refined first.
  this->NumberOfSplitTriangles = 0;
  const bool refineFirst = worker.Tessellation.bendTolerance > 0.0;
  const bool polys = nPts > 0 && input->GetNumberOfPolys() > 0;
  std::atomic<bool> needsFateCheck(polys);
  CellArrays cells;
  std::vector<vtkIdType> sources; // the refined mesh's cells' cells in the input (-1: pieces)
  if (!refineFirst)
  {
    worker.NeedsFateCheck = &needsFateCheck;
    needsFateCheck = false;
    cells = ProjectCells(input, worker, out.Records.get());
    worker.NeedsFateCheck = nullptr;
  }
  if (polys && needsFateCheck)
  {
    catar::Tessellation added;
    this->NumberOfSplitTriangles = vtkCatadioptricTessellatedMesh::Refine(input, projector,
      worker.Tessellation, out.Status->GetPointer(0), out.Pixels->GetPointer(0),
      out.Mirror->GetPointer(0), added, output, refineFirst ? nullptr : &sources);
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
    cells =
      ProjectCells(this->NumberOfSplitTriangles > 0 ? output : input, worker, out.Records.get());
  }
  else if (this->NumberOfSplitTriangles > 0)
  {
    cells = ProjectPieces(output, worker, out.Records.get(), cells, sources);
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
