/**
 * @class   vtkCatadioptricRemesher
 * @brief   remeshes a surface to a target triangle area or to a pixel tolerance through the mirror
 *
 * The compositor draws each triangle as a straight-edged 2D triangle: accuracy needs small
 * triangles where the mirror bends lines, speed needs no more of them than that. This filter
 * prepares a mesh once (the pipeline caches its output while the input, the parameters and, in
 * pixel mode, the camera do not change).
 *
 * Modes:
 *  - TARGET_AREA: triangles of about TargetArea (model units squared; the paper found 0.12 cm^2 =
 *    1.2e-5 m^2 good for objects farther than 10 cm). CGAL isotropic remeshing to the edge length
 *    of an equilateral triangle of that area, sharp edges (FeatureAngle) and corners protected
 *    when ProtectFeatures is on, boundaries kept when PreserveBoundaries is on; with Strategy
 *    AUTO, over-dense input is first decimated (OpenMesh quadric decimation) and too coarse input
 *    subdivided.
 *  - PIXEL_TOLERANCE: sizes chosen per region through the camera (SetCamera or
 *    CalibrationFileName) so that every visible edge bends at most PixelTolerance pixels in the
 *    image (the bend: the largest distance between the exact image of the edge and the straight
 *    segment the compositor draws), refining where the mirror magnifies and coarsening elsewhere.
 *  - REPAIR_ONLY: only the repairs below.
 *
 * Input: any vtkPolyData. Polygons and strips are triangulated; vertices and lines are ignored
 * with a warning. Bad input is repaired with a warning (NaN points, degenerate and duplicate
 * triangles, coincident points, non-manifold edges and vertices, inconsistent orientation) or
 * refused with an error (nothing usable left). Holes are kept as boundaries.
 *
 * Output: a triangle mesh. Point data (texture coordinates, normals, colours...) are carried over
 * by projecting each new point onto the input surface and interpolating barycentrically; active
 * normals are renormalised. Cell data are copied from the input cell nearest to each new cell's
 * centroid (a box keeps its face colours). Field data: the input's, plus RemeshSteps (string),
 * InputTriangles, OutputTriangles, MeanTriangleArea, TriangleAreaP95 and, in PIXEL_TOLERANCE
 * mode, MaximumEdgeBend, MeanEdgeBend (pixels), VisibleEdges and GeometricErrorBound.
 */
#ifndef vtkCatadioptricRemesher_h
#define vtkCatadioptricRemesher_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"   // for member
#include "vtkPolyDataAlgorithm.h"

class vtkCatadioptricCamera;

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricRemesher : public vtkPolyDataAlgorithm
{
public:
  static vtkCatadioptricRemesher* New();
  vtkTypeMacro(vtkCatadioptricRemesher, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    REPAIR_ONLY = 0,
    TARGET_AREA = 1,
    PIXEL_TOLERANCE = 2
  };
  ///@{
  /// What decides triangle sizes. Default TARGET_AREA.
  vtkSetClampMacro(Mode, int, REPAIR_ONLY, PIXEL_TOLERANCE);
  vtkGetMacro(Mode, int);
  void SetModeToRepairOnly() { this->SetMode(REPAIR_ONLY); }
  void SetModeToTargetArea() { this->SetMode(TARGET_AREA); }
  void SetModeToPixelTolerance() { this->SetMode(PIXEL_TOLERANCE); }
  ///@}

  ///@{
  /// Target triangle area in model units squared (TARGET_AREA mode). Default 1.2e-5 (0.12 cm^2
  /// for a mesh in metres, the paper's choice).
  vtkSetClampMacro(TargetArea, double, 1e-300, VTK_DOUBLE_MAX);
  vtkGetMacro(TargetArea, double);
  ///@}

  ///@{
  /// Largest bend of a visible edge in the image, pixels (PIXEL_TOLERANCE mode). Default 0.5.
  vtkSetClampMacro(PixelTolerance, double, 1e-6, VTK_DOUBLE_MAX);
  vtkGetMacro(PixelTolerance, double);
  ///@}

  ///@{
  /// Bounds on edge lengths in PIXEL_TOLERANCE mode, model units; 0 chooses from the bounding
  /// box (1e-4 and 0.25 of its diagonal). Edges of parts the camera does not see get the maximum.
  vtkSetClampMacro(MinimumEdgeLength, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinimumEdgeLength, double);
  vtkSetClampMacro(MaximumEdgeLength, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumEdgeLength, double);
  ///@}

  ///@{
  /// Bound on the distance to the input surface when PIXEL_TOLERANCE mode coarsens, model units.
  /// 0 (default): the distance that moves the object's image by PixelTolerance where the mirror
  /// magnifies it most, kept between 1e-4 and 2e-2 of the bounding-box diagonal (1e-3 of it when
  /// the object is not seen).
  vtkSetClampMacro(MaximumGeometricError, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumGeometricError, double);
  ///@}

  ///@{
  /// Isotropic remeshing iterations (TARGET_AREA), or refine/coarsen rounds (PIXEL_TOLERANCE).
  /// Default 3.
  vtkSetClampMacro(Iterations, int, 1, 100);
  vtkGetMacro(Iterations, int);
  ///@}

  ///@{
  /// PIXEL_TOLERANCE: the triangle budget (default 4,000,000). The triangles the tolerance needs
  /// are estimated before any work; past twice the budget the filter fails at once, with the
  /// estimate, instead of refining for minutes. Refinement also stops at the budget (with a
  /// warning).
  vtkSetClampMacro(MaximumTriangles, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumTriangles, vtkIdType);
  ///@}

  ///@{
  /// Keep sharp edges and corners: edges whose dihedral angle deviates from flat by more than
  /// FeatureAngle degrees. Default on, 60 degrees.
  vtkSetMacro(ProtectFeatures, bool);
  vtkGetMacro(ProtectFeatures, bool);
  vtkBooleanMacro(ProtectFeatures, bool);
  vtkSetClampMacro(FeatureAngle, double, 0.0, 180.0);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  ///@{
  /// Keep boundary polylines (holes, open borders) where they are. Default on.
  vtkSetMacro(PreserveBoundaries, bool);
  vtkGetMacro(PreserveBoundaries, bool);
  vtkBooleanMacro(PreserveBoundaries, bool);
  ///@}

  enum Strategies
  {
    AUTO = 0,      ///< decimate or subdivide first when far from the target, then isotropic
    ISOTROPIC = 1, ///< CGAL isotropic remeshing only
    DECIMATE = 2,  ///< OpenMesh quadric decimation only
    SUBDIVIDE = 3  ///< subdivision only
  };
  ///@{
  /// How TARGET_AREA mode gets there. Default AUTO.
  vtkSetClampMacro(Strategy, int, AUTO, SUBDIVIDE);
  vtkGetMacro(Strategy, int);
  ///@}

  ///@{
  /// The camera (vtkCatadioptricCameraSlot.h): SetCamera (takes precedence), else
  /// SetCalibrationFileName (a YAML/JSON calibration file), else the panel camera
  /// (SetCameraImageSize, SetFocalLength, SetPrincipalPoint, SetDistortion, SetWorldToCamera: the
  /// built-in demo camera's values until changed); SetMirrorType and SetMirrorParameter put
  /// another mirror in the camera's place. Each with its getter. Used in PIXEL_TOLERANCE mode.
  vtkCatadioptricCameraSlotDeclareMacro();
  ///@}

  /// The modification time includes the camera's.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricRemesher();
  ~vtkCatadioptricRemesher() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkCatadioptricCameraSlotMembersMacro();
  int Mode = TARGET_AREA;
  double TargetArea = 1.2e-5;
  double PixelTolerance = 0.5;
  double MinimumEdgeLength = 0.0;
  double MaximumEdgeLength = 0.0;
  double MaximumGeometricError = 0.0;
  int Iterations = 3;
  vtkIdType MaximumTriangles = 4000000;
  bool ProtectFeatures = true;
  double FeatureAngle = 60.0;
  bool PreserveBoundaries = true;
  int Strategy = AUTO;

private:
  vtkCatadioptricRemesher(const vtkCatadioptricRemesher&) = delete;
  void operator=(const vtkCatadioptricRemesher&) = delete;
};

#endif
