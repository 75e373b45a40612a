// A downstream program: the Core (a calibration, a back projection and the forward projection of
// the point found), MeshPrep (a triangle's area) and the VTK modules (a scene that names the
// installed camera and sample mesh by their data-path names, rendered and written).
//
//   downstream OUT_DIR
#include "CalibrationIO.h"
#include "MeshMetrics.h"
#include "Projector.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkImageData.h"
#include "vtkNew.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: downstream OUT_DIR\n");
    return 2;
  }
  const std::string out = argv[1];
  catar::CameraModel model;
  std::string error;
  if (!catar::LoadCalibration(
        std::string(CATAR_DATA_DIR) + "/calibration/demo-camera.yaml", model, error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  // A pixel's ray, a point 0.5 m along it, and that point projected back: the same pixel.
  const catar::Projector projector(model);
  const catar::Vec2 pixel(700.25, 400.5);
  const catar::BackProjectedRay ray = projector.BackProjectCamera(pixel);
  const catar::ProjectedPoint p =
    projector.ProjectCamera(ray.mirrorPoint + 0.5 * ray.direction, catar::SolverType::Quartic);
  const double pixelError = (p.pixel - pixel).norm();
  std::printf("round trip through the mirror: %.3g px\n", pixelError);
  if (!(ray.status == catar::ProjectionStatus::Valid && pixelError < 1e-6))
  {
    return 1;
  }

  catar::mesh::TriangleMesh triangle;
  triangle.points = { catar::Vec3(0, 0, 0), catar::Vec3(2, 0, 0), catar::Vec3(0, 1, 0) };
  triangle.triangles = { { 0, 1, 2 } };
  const double area = catar::mesh::TriangleAreaStatistics(triangle).total;
  std::printf("triangle area: %g\n", area);
  if (std::abs(area - 1.0) > 1e-12)
  {
    return 1;
  }

  // Written where no camera or mesh is: both are found in the installed data.
  const std::string scene = out + "/downstream.yaml";
  std::ofstream(scene) << "camera: calibration/demo-camera.yaml\n"
                          "output: { width: 332, height: 262 }\n"
                          "background: { type: color, color: [0, 0, 0] }\n"
                          "objects:\n"
                          "  - { type: mesh, file: meshes/trefoil-knot.ply,\n"
                          "      translate: [0.0, -0.35, 0.95], color: [1, 1, 1] }\n";
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scene.c_str());
  if (!renderer->Render() || !renderer->WriteImage((out + "/downstream.png").c_str()))
  {
    std::fprintf(stderr, "%s\n", renderer->GetLastError());
    return 1;
  }
  vtkImageData* image = renderer->GetOutput();
  const int* dims = image->GetDimensions();
  const auto* rgb = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int components = image->GetNumberOfScalarComponents();
  long lit = 0;
  for (long i = 0; i < static_cast<long>(dims[0]) * dims[1]; ++i)
  {
    lit += rgb[i * components] > 0 || rgb[i * components + 1] > 0 || rgb[i * components + 2] > 0;
  }
  std::printf("image %dx%d, %ld pixels of the knot\n", dims[0], dims[1], lit);
  return dims[0] == 332 && dims[1] == 262 && lit > 50 ? 0 : 1;
}
