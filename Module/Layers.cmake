# The Core's concept folders, lowest first, and what each may use. A folder includes headers and
# links libraries only of the folders in its DEPENDS, and those come before it in
# catar_core_layers: dependencies point down, so there are no cycles. A folder lists only what its
# own files include (what it reaches through another folder's headers comes with that folder). Module/CMakeLists.txt builds
# one library a folder from these lists; Testing/CheckCoreLayers.cmake (the test
# Layout.CoreLayers) checks every #include against them. Documentation/layout-and-conventions.md
# says what each folder holds.
set(catar_core_layers
  Base       # plain types (vectors, statuses, results, rotations), polynomials, the thread pool
  Mirror     # the mirror interface and its shapes (sphere, quadrics), mirror descriptions
  Camera     # the lens (intrinsics, distortion), image size, pose
  Projection # forward and back projection through the mirror, per-frame tessellation
  Raster     # the CPU rasteriser (coverage, textures, image views)
  Trace      # ray queries against meshes (Embree)
  Shading    # Phong lighting, batches of points, shadows
  IO         # files: outputs whole or absent, CSV, configuration, calibration, video, mesh checks
  Metrics    # image comparison
  Vision     # from images: markers, pose, the mirror's outline, conic fits
  Reference  # the exact reference renderer (ray tracing)
  Scene      # scene files, trajectories and keyframes, frames of a sequence, the room, the rig
  MeshPrep)  # mesh preparation: repair, remeshing (CGAL, OpenMesh), point-set surfaces
set(catar_layer_Base_DEPENDS "")
set(catar_layer_Mirror_DEPENDS Base)
set(catar_layer_Camera_DEPENDS Base Mirror)
set(catar_layer_Projection_DEPENDS Base Mirror Camera)
set(catar_layer_Raster_DEPENDS Base)
set(catar_layer_Trace_DEPENDS Base)
set(catar_layer_Shading_DEPENDS Base Trace)
set(catar_layer_IO_DEPENDS Base Mirror Camera)
set(catar_layer_Metrics_DEPENDS Raster)
set(catar_layer_Vision_DEPENDS Mirror Camera Projection IO)
set(catar_layer_Reference_DEPENDS Projection Raster Trace Shading)
set(catar_layer_Scene_DEPENDS Base Mirror Camera Projection Raster IO Vision)
set(catar_layer_MeshPrep_DEPENDS Base)
