// The scene the benchmarks share: the demo camera and the Stanford bunny placed in its view.
#ifndef catarBenchmarkScene_h
#define catarBenchmarkScene_h

#include "../Cxx/TestCameras.h"

#include "vtkCatadioptricCamera.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"
#include "vtksys/SystemTools.hxx"

#include <cstdlib>
#include <string>

namespace catar_benchmark
{
/// The demo camera (Testing/Cxx/TestCameras.h): at world (0, -0.14, 1), looking along +y at a 5 cm
/// mirror 14 cm away.
inline void DemoCamera(vtkCatadioptricCamera* cam)
{
  cam->SetModel(catar_test::DemoCameraModel());
}

/// Moves `mesh` by `transform` applied after `before` (a transform to the origin, or null): the
/// objects sit 25 cm behind the camera, at (0, -0.25, 0.9).
inline vtkSmartPointer<vtkPolyData> PlaceInView(vtkPolyData* mesh, vtkTransform* before)
{
  vtkNew<vtkTransform> place;
  place->PostMultiply();
  if (before)
  {
    place->Concatenate(before);
  }
  place->Translate(0.0, -0.25, 0.9);
  vtkNew<vtkTransformPolyDataFilter> xf;
  xf->SetTransform(place);
  xf->SetInputData(mesh);
  xf->Update();
  return xf->GetOutput();
}

/// The paper's parallelepiped (30 x 12 x 9 cm) where the demo puts it, 2 triangles per face.
inline vtkSmartPointer<vtkPolyData> PaperBox()
{
  vtkNew<vtkTessellatedBoxSource> box;
  box->SetBounds(-0.15, 0.15, -0.06, 0.06, -0.045, 0.045);
  box->SetLevel(0);
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(box->GetOutputPort());
  vtkNew<vtkTransform> t;
  t->PostMultiply();
  t->RotateZ(30);
  t->Translate(0.14, -0.22, 0.87);
  vtkNew<vtkTransformPolyDataFilter> xf;
  xf->SetTransform(t);
  xf->SetInputConnection(tri->GetOutputPort());
  xf->Update();
  return xf->GetOutput();
}

/// The Stanford bunny (69,451 triangles, about 15 cm) from CATAR_SHARED_DATA, z up, placed in
/// view; null when CATAR_SHARED_DATA does not name a folder holding stanford-bunny.obj.
inline vtkSmartPointer<vtkPolyData> SharedBunny()
{
  const char* shared = std::getenv("CATAR_SHARED_DATA");
  const std::string file = shared ? std::string(shared) + "/stanford-bunny.obj" : "";
  if (file.empty() || !vtksys::SystemTools::FileExists(file, true))
  {
    return nullptr;
  }
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkNew<vtkTransform> centre;
  centre->PostMultiply();
  centre->Translate(0.017, -0.11, -0.0016); // bounding-box centre to the origin
  centre->RotateX(90);                      // y up -> z up
  return PlaceInView(reader->GetOutput(), centre);
}

/// A sphere of radius 7.5 cm (the bunny's size) with theta x phi resolution, placed in view.
inline vtkSmartPointer<vtkPolyData> Sphere(int theta, int phi)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.075);
  sphere->SetThetaResolution(theta);
  sphere->SetPhiResolution(phi);
  sphere->Update();
  return PlaceInView(sphere->GetOutput(), nullptr);
}

/// The bunny, or without the shared data a sphere of 69,696 triangles in the same place; name
/// is set to which.
inline vtkSmartPointer<vtkPolyData> BunnyOrSphere(std::string& name)
{
  if (vtkSmartPointer<vtkPolyData> bunny = SharedBunny())
  {
    name = "bunny";
    return bunny;
  }
  name = "sphere";
  return Sphere(264, 134);
}
} // namespace catar_benchmark

#endif
