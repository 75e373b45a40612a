// ProjectMesh: the C++ pipeline by hand. Loads a calibration, projects a mesh (a PLY/OBJ file, or
// a sphere when none is given) through the mirror, sorts it, and composites it onto a synthesised
// frame.
//
//   ProjectMesh CALIBRATION.yaml OUT.png [MESH.ply|MESH.obj]
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricProjection.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <cstdio>
#include <string>

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: %s CALIBRATION.yaml OUT.png [MESH.ply|MESH.obj]\n", argv[0]);
    return 2;
  }
  vtkCatadioptricParallel::EnableThreads();
  vtkNew<vtkCatadioptricCamera> camera;
  if (!camera->Load(argv[1]))
  {
    return 1;
  }
  vtkSmartPointer<vtkAlgorithm> source;
  if (argc > 3)
  {
    const std::string file = argv[3];
    if (file.size() > 4 && file.substr(file.size() - 4) == ".obj")
    {
      auto r = vtkSmartPointer<vtkOBJReader>::New();
      r->SetFileName(file.c_str());
      source = r;
    }
    else
    {
      auto r = vtkSmartPointer<vtkPLYReader>::New();
      r->SetFileName(file.c_str());
      source = r;
    }
  }
  else
  {
    auto s = vtkSmartPointer<vtkSphereSource>::New();
    s->SetRadius(1.0);
    s->SetThetaResolution(64);
    s->SetPhiResolution(32);
    source = s;
  }
  // Place the object (unit size) 35 cm behind the camera of the demo calibration.
  vtkNew<vtkTransform> place;
  place->Translate(0.1, -0.35, 0.95);
  place->Scale(0.05, 0.05, 0.05);
  vtkNew<vtkTransformPolyDataFilter> placed;
  placed->SetTransform(place);
  placed->SetInputConnection(source->GetOutputPort());

  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetCamera(camera);
  projection->SetInputConnection(placed->GetOutputPort());
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(projection->GetOutputPort());
  sort->DropInvisibleCellsOn();
  vtkNew<vtkCatadioptricEnvironmentSource> frame;
  frame->SetCamera(camera);
  frame->SetSamples(1);
  vtkNew<vtkCatadioptricCompositor> compositor;
  compositor->SetFrameConnection(frame->GetOutputPort());
  compositor->AddMeshConnection(sort->GetOutputPort());
  compositor->SetColor(0.9, 0.6, 0.2);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(compositor->GetOutputPort());
  writer->SetFileName(argv[2]);
  writer->Write();
  if (compositor->GetNumberOfDrawnTriangles() == 0)
  {
    std::fprintf(stderr, "nothing was drawn: is the object in the mirror's view?\n");
    return 1;
  }
  std::printf("drew %lld triangles into %s\n",
    static_cast<long long>(compositor->GetNumberOfDrawnTriangles()), argv[2]);
  return writer->GetErrorCode() == 0 ? 0 : 1;
}
