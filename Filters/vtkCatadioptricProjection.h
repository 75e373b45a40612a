/**
 * @class   vtkCatadioptricProjection
 * @brief   projects a surface mesh through a catadioptric camera's mirror
 *
 * The camera enters the pipeline here, once per frame. Points stay in world coordinates; the
 * filter adds
 *  - point data: ImageCoordinates (2, pixels), MirrorPoint (3, camera frame), PathLength (mirror
 *    point to vertex), ProjectionStatus (uint8, vtkCatadioptricCamera::StatusCodes) and Visible
 *    (uint8: 1 when the vertex has a reflection and a pixel, inside the image or not);
 *  - cell data: CentroidDepth (the distance from the cell centroid to the centroid's own reflection
 *    point, the painter key of the method), CentroidMirrorPoint (3, camera frame: that reflection
 *    point, the viewer of flat shading) and Visible (uint8: 1 when every vertex and the
 *    centroid project and the cell's pixel bounding box meets the image);
 *  - field data: the camera (vtkCatadioptricCamera::WriteToFieldData).
 * Vertices and lines are passed through with Visible 0. Work is split over points and cells on
 * the threads of vtkCatadioptricParallel (as many as vtkSMPTools would use).
 *
 * The camera comes from SetCamera(), or, when no camera object is set, from CalibrationFileName,
 * or else from the panel camera (CameraImageSize, FocalLength, ..., WorldToCamera: the demo camera
 * by default).
 */
#ifndef vtkCatadioptricProjection_h
#define vtkCatadioptricProjection_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"   // for member
#include "vtkPolyDataAlgorithm.h"

class vtkCatadioptricCamera;

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricProjection : public vtkPolyDataAlgorithm
{
public:
  static vtkCatadioptricProjection* New();
  vtkTypeMacro(vtkCatadioptricProjection, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera (vtkCatadioptricCameraSlot.h): SetCamera (takes precedence), else
  /// SetCalibrationFileName (a YAML/JSON calibration file), else the panel camera
  /// (SetCameraImageSize, SetFocalLength, SetPrincipalPoint, SetDistortion, SetWorldToCamera: the
  /// built-in demo camera's values until changed); SetMirrorType and SetMirrorParameter put
  /// another mirror in the camera's place;
  /// SetTrajectoryFileName moves the camera over time. Each with its getter.
  vtkCatadioptricCameraSlotDeclareMacro();
  vtkCatadioptricCameraSlotDeclareTrajectoryMacro();
  ///@}

  /// Solvers for the reflection point.
  enum Solvers
  {
    QUARTIC = 0,   ///< closed-form quartic + Newton polish
    ITERATIVE = 1, ///< safeguarded Newton from a nearby point's reflection
    AUTOMATIC = 2  ///< the default: the faster where exact (catar::SolverType::Automatic)
  };
  ///@{
  /// Which solver finds each vertex's reflection point. Both end with the same safeguarded
  /// Newton and reach the same answer to rounding: QUARTIC starts it at Ferrari's closed-form
  /// root (the paper's method); ITERATIVE at the previous vertex's reflection point (vertices
  /// that follow each other in a mesh are mostly neighbours), else at a far-field guess, and is
  /// the faster (see BenchmarkProjection, BenchmarkSpeed). AUTOMATIC, the default, is ITERATIVE
  /// for the sphere and most quadrics (the same image, 2.5 to 5 times faster) and QUARTIC for a
  /// quadric with the camera on its axis, where a point may have several images and the quartic
  /// keeps the shortest path. Cell centroids always start at the mean of their vertices'
  /// reflection points and need one or two steps.
  vtkSetClampMacro(Solver, int, QUARTIC, AUTOMATIC);
  vtkGetMacro(Solver, int);
  void SetSolverToQuartic() { this->SetSolver(QUARTIC); }
  void SetSolverToIterative() { this->SetSolver(ITERATIVE); }
  void SetSolverToAutomatic() { this->SetSolver(AUTOMATIC); }
  ///@}

  ///@{
  /// Back-face culling (default off): a polygon whose normal (right-hand rule on its point
  /// order, Newell's method) points away from its own reflection point -- the viewer of the
  /// method -- gets Visible 0, and its centroid is not projected (CentroidDepth and
  /// CentroidMirrorPoint stay 0). For closed, consistently oriented meshes every such polygon is
  /// hidden by the front of the mesh, so the image does not change (painter order errors between
  /// front and back faces go away) while the sort and the compositor draw about half the cells.
  /// Leave it off for open or inconsistently oriented meshes.
  vtkSetMacro(BackFaceCulling, bool);
  vtkGetMacro(BackFaceCulling, bool);
  vtkBooleanMacro(BackFaceCulling, bool);
  ///@}

  ///@{
  /// Per-frame tessellation (Documentation/edges-and-rasterisation.md), in pixels.
  /// BoundaryTolerance (default 0.25): triangles that cross the visibility boundary (part of them
  /// reflected, part hidden by the mirror, outside a quadric's z_range, ...) are split and cut at
  /// the boundary until it is drawn within this many pixels; 0 drops them whole. AdaptiveTolerance
  /// (default 0, off): triangles whose edges bend more than this many pixels in this frame's image
  /// are split, again and again, until none does. Split triangles' pieces take their triangle's
  /// cell data, new points point data interpolated from its vertices; other triangles are left as
  /// they are.
  vtkSetClampMacro(BoundaryTolerance, double, 0.0, 1e6);
  vtkGetMacro(BoundaryTolerance, double);
  vtkSetClampMacro(AdaptiveTolerance, double, 0.0, 1e6);
  vtkGetMacro(AdaptiveTolerance, double);
  ///@}

  /// Triangles the last execution split (per-frame tessellation).
  vtkGetMacro(NumberOfSplitTriangles, vtkIdType);

  /// The modification time includes the camera's.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricProjection();
  ~vtkCatadioptricProjection() override;

  /// Announces the camera's image size downstream (vtkCatadioptricCamera::IMAGE_SIZE).
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkCatadioptricCameraSlotMembersMacro();
  int Solver = AUTOMATIC;
  bool BackFaceCulling = false;
  double BoundaryTolerance = 0.25;
  double AdaptiveTolerance = 0.0;
  vtkIdType NumberOfSplitTriangles = 0;

private:
  // RequestData's work once the input and the camera are checked.
  int Project(vtkPolyData* input, vtkPolyData* output, vtkCatadioptricCamera* camera);

  vtkCatadioptricProjection(const vtkCatadioptricProjection&) = delete;
  void operator=(const vtkCatadioptricProjection&) = delete;
};

#endif
