#include "vtkCatadioptricPointSetSurface.h"

#include "PointSetSurface.h"

#include "vtkCatadioptricMeshConversion.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkCatadioptricPointSetSurface);

vtkCatadioptricPointSetSurface::vtkCatadioptricPointSetSurface() = default;

int vtkCatadioptricPointSetSurface::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

namespace
{
// Forwards the construction's progress to the filter's, and the filter's AbortExecute flag
// (ParaView's abort button, or an observer of the progress event) to it.
void ReportProgress(double fraction, void* clientData)
{
  static_cast<vtkCatadioptricPointSetSurface*>(clientData)->UpdateProgress(0.1 + 0.8 * fraction);
}

bool StopRequested(void* clientData)
{
  return static_cast<vtkCatadioptricPointSetSurface*>(clientData)->GetAbortExecute() != 0;
}
} // namespace

int vtkCatadioptricPointSetSurface::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // An abort asked during an earlier execution is spent (VTK 9.2's executives leave the flag
  // set); set directly, as SetAbortExecute would mark the filter modified.
  this->AbortExecute = 0;
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("The input must be a vtkPointSet and the output vtkPolyData.");
    return 0;
  }
  std::vector<catar::Vec3> points(input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    input->GetPoint(i, points[i].data());
  }
  catar::mesh::PointSetOptions options;
  options.method = static_cast<catar::mesh::PointSetMethod>(this->Method);
  options.radiusRatioBound = this->RadiusRatioBound;
  options.beta = this->Beta;
  options.progress = &ReportProgress;
  options.stop = &StopRequested;
  options.progressData = this;
  this->UpdateProgress(0.1);
  const catar::mesh::PointSetResult result = catar::mesh::SurfaceFromPoints(points, options);
  for (const std::string& w : result.warnings)
  {
    vtkWarningMacro(<< w);
  }
  if (!result.ok && result.error == catar::mesh::kAbortedError)
  {
    output->Initialize(); // aborted (AbortExecute): an empty output, as VTK's filters leave
    return 1;
  }
  if (!result.ok)
  {
    vtkErrorMacro("No surface from " << points.size() << " points: " << result.error);
    return 0;
  }
  this->UpdateProgress(0.9);
  vtkCatadioptricMeshConversion::FromTriangleMesh(result.mesh, nullptr, output);
  output->GetFieldData()->PassData(input->GetFieldData());
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricPointSetSurface::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << (this->Method == CONVEX_HULL ? "CONVEX_HULL" : "ADVANCING_FRONT")
     << "\n";
  os << indent << "RadiusRatioBound: " << this->RadiusRatioBound << "\n";
  os << indent << "Beta: " << this->Beta << "\n";
}
