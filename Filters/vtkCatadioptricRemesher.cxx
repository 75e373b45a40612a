#include "vtkCatadioptricRemesher.h"

#include "EdgeBend.h"
#include "MeshMetrics.h"
#include "MeshRepair.h"
#include "Remeshing.h"
#include "ScreenSpaceRemeshing.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricMeshConversion.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <memory>

vtkStandardNewMacro(vtkCatadioptricRemesher);

vtkCatadioptricRemesher::vtkCatadioptricRemesher() = default;
vtkCatadioptricRemesher::~vtkCatadioptricRemesher() = default;

vtkCatadioptricCameraSlotMacro(vtkCatadioptricRemesher);

// The strategies of the wrapped class are the mesh library's, value for value.
static_assert(
  vtkCatadioptricRemesher::AUTO == static_cast<int>(catar::mesh::RemeshStrategy::Auto) &&
    vtkCatadioptricRemesher::ISOTROPIC ==
      static_cast<int>(catar::mesh::RemeshStrategy::Isotropic) &&
    vtkCatadioptricRemesher::DECIMATE == static_cast<int>(catar::mesh::RemeshStrategy::Decimate) &&
    vtkCatadioptricRemesher::SUBDIVIDE == static_cast<int>(catar::mesh::RemeshStrategy::Subdivide),
  "vtkCatadioptricRemesher::Strategies must match catar::mesh::RemeshStrategy");

namespace
{
// Forwards the mesh algorithms' progress to the filter's, and the filter's AbortExecute flag
// (ParaView's abort button, or an observer of the progress event) to them.
void ReportProgress(double fraction, void* clientData)
{
  static_cast<vtkCatadioptricRemesher*>(clientData)->UpdateProgress(0.1 + 0.8 * fraction);
}

bool StopRequested(void* clientData)
{
  return static_cast<vtkCatadioptricRemesher*>(clientData)->GetAbortExecute() != 0;
}

void AddValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
} // namespace

int vtkCatadioptricRemesher::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // An abort asked during an earlier execution is spent (VTK 9.2's executives leave the flag
  // set); set directly, as SetAbortExecute would mark the filter modified.
  this->AbortExecute = 0;
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkPolyData.");
    return 0;
  }
  if (input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    vtkErrorMacro("The input has no polygons or strips to remesh ("
      << input->GetNumberOfPoints() << " points, " << input->GetNumberOfCells() << " cells).");
    return 0;
  }

  // Bad point ids and non-finite points are repaired; arrays shorter than what they describe
  // cannot be.
  std::string inputError;
  if (!vtkCatadioptricMeshCheck::CheckArraySizes(input, inputError))
  {
    vtkErrorMacro("Bad input: " << inputError);
    return 0;
  }

  catar::mesh::TriangleMesh mesh;
  catar::mesh::Warnings warnings;
  vtkCatadioptricMeshConversion::ToTriangleMesh(input, mesh, warnings);
  const std::size_t inputTriangles = mesh.NumberOfTriangles();
  this->UpdateProgress(0.1);

  std::string error, steps;
  double maxBend = -1.0, meanBend = -1.0, geometricBound = -1.0;
  std::size_t visibleEdges = 0;
  bool ok = false;
  if (this->Mode == REPAIR_ONLY)
  {
    catar::mesh::RepairReport report;
    ok = catar::mesh::RepairMesh(mesh, report, warnings, error);
    steps = "repair";
  }
  else if (this->Mode == TARGET_AREA)
  {
    catar::mesh::RemeshOptions options;
    options.targetArea = this->TargetArea;
    options.iterations = this->Iterations;
    options.protectFeatures = this->ProtectFeatures;
    options.featureAngle = this->FeatureAngle;
    options.preserveBoundaries = this->PreserveBoundaries;
    options.strategy = static_cast<catar::mesh::RemeshStrategy>(this->Strategy);
    options.progress = &ReportProgress;
    options.stop = &StopRequested;
    options.progressData = this;
    catar::mesh::RemeshResult result = catar::mesh::RemeshToArea(mesh, options);
    ok = result.ok;
    error = result.error;
    warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
    steps = result.steps;
    mesh = std::move(result.mesh);
  }
  else
  {
    vtkCatadioptricCamera* camera = this->ResolveCamera();
    if (!camera)
    {
      return 0;
    }
    auto projector = std::make_shared<catar::Projector>(camera->GetModel());
    if (!projector->IsValid())
    {
      vtkErrorMacro("Invalid camera: " << projector->GetError());
      return 0;
    }
    catar::mesh::ScreenSpaceOptions options;
    options.tolerance = this->PixelTolerance;
    options.minEdgeLength = this->MinimumEdgeLength;
    options.maxEdgeLength = this->MaximumEdgeLength;
    options.maxGeometricError = this->MaximumGeometricError > 0.0
      ? this->MaximumGeometricError
      : catar::GeometricErrorForTolerance(*projector, mesh.points, this->PixelTolerance);
    geometricBound = options.maxGeometricError;
    options.protectFeatures = this->ProtectFeatures;
    options.featureAngle = this->FeatureAngle;
    options.maxIterations = this->Iterations;
    options.threads = vtkCatadioptricParallel::GetNumberOfThreads();
    options.maxTriangles = static_cast<std::size_t>(this->MaximumTriangles);
    options.progress = &ReportProgress;
    options.stop = &StopRequested;
    options.progressData = this;
    const catar::mesh::EdgeErrorFunction bend = [projector](
                                                  const catar::Vec3& a, const catar::Vec3& b) {
      return catar::EdgeBendPixels(*projector, a, b);
    };
    catar::mesh::ScreenSpaceResult result =
      catar::mesh::RemeshToPixelTolerance(mesh, bend, options);
    ok = result.ok;
    error = result.error;
    warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
    steps = "pixel tolerance, " + std::to_string(result.iterations) + " rounds";
    maxBend = result.maxError;
    meanBend = result.meanError;
    visibleEdges = result.visibleEdges;
    mesh = std::move(result.mesh);
  }
  for (const std::string& w : warnings)
  {
    vtkWarningMacro(<< w);
  }
  if (!ok && error == catar::mesh::kAbortedError)
  {
    output->Initialize(); // aborted (AbortExecute): an empty output, as VTK's filters leave
    return 1;
  }
  if (!ok)
  {
    vtkErrorMacro("Remeshing failed: " << error);
    return 0;
  }
  this->UpdateProgress(0.9);

  vtkCatadioptricMeshConversion::FromTriangleMesh(mesh, input, output);
  vtkCatadioptricMeshConversion::TransferCellData(input, output);
  output->GetFieldData()->PassData(input->GetFieldData());
  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkStringArray> stepsArray;
  stepsArray->SetName("RemeshSteps");
  stepsArray->InsertNextValue(steps);
  fd->AddArray(stepsArray);
  AddValue(fd, "InputTriangles", static_cast<double>(inputTriangles));
  AddValue(fd, "OutputTriangles", static_cast<double>(mesh.NumberOfTriangles()));
  const catar::mesh::AreaStatistics areas = catar::mesh::TriangleAreaStatistics(mesh);
  AddValue(fd, "MeanTriangleArea", areas.mean);
  AddValue(fd, "TriangleAreaP95", areas.p95);
  if (this->Mode == PIXEL_TOLERANCE)
  {
    AddValue(fd, "MaximumEdgeBend", maxBend);
    AddValue(fd, "MeanEdgeBend", meanBend);
    AddValue(fd, "VisibleEdges", static_cast<double>(visibleEdges));
    AddValue(fd, "GeometricErrorBound", geometricBound); // 0: the core's default
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricRemesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* modes[] = { "REPAIR_ONLY", "TARGET_AREA", "PIXEL_TOLERANCE" };
  static const char* strategies[] = { "AUTO", "ISOTROPIC", "DECIMATE", "SUBDIVIDE" };
  os << indent << "Mode: " << modes[this->Mode] << "\n";
  os << indent << "TargetArea: " << this->TargetArea << "\n";
  os << indent << "PixelTolerance: " << this->PixelTolerance << "\n";
  os << indent << "MinimumEdgeLength: " << this->MinimumEdgeLength << "\n";
  os << indent << "MaximumEdgeLength: " << this->MaximumEdgeLength << "\n";
  os << indent << "MaximumGeometricError: " << this->MaximumGeometricError << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "MaximumTriangles: " << this->MaximumTriangles << "\n";
  os << indent << "ProtectFeatures: " << (this->ProtectFeatures ? "On" : "Off") << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "PreserveBoundaries: " << (this->PreserveBoundaries ? "On" : "Off") << "\n";
  os << indent << "Strategy: " << strategies[this->Strategy] << "\n";
  os << indent << "CalibrationFileName: "
     << (this->GetCalibrationFileName() ? this->GetCalibrationFileName() : "(none)") << "\n";
}
