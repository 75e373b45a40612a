// CatadioptricAR Core: a procedural environment and the synthetic camera frame it gives.
//
// The room is an axis-aligned box in world coordinates (z up): a checkered floor, walls with a
// tiled grid, a lit ceiling, a window and a door, so that the mirror's bending of straight lines
// shows. A camera frame is made by back-projecting every pixel: pixels that see the mirror take
// the room's colour along the reflected ray; the others see the room directly from the camera.
#ifndef catarEnvironment_h
#define catarEnvironment_h

#include "CameraModel.h"
#include "Rasterizer.h"

namespace catar
{
class SphereProjector;

/// A box-shaped room, world coordinates, metres.
struct RoomEnvironment
{
  Vec3 minCorner = Vec3(-2.0, -2.0, 0.0);
  Vec3 maxCorner = Vec3(2.0, 2.0, 2.6);
  double floorTile = 0.25; ///< floor checker square size
  double wallTile = 0.5;   ///< wall grid spacing
};

/// Colour (RGB in [0,1]) seen along a ray (origin inside the room, unit direction), world frame.
Vec3 RoomColor(const RoomEnvironment& room, const Vec3& origin, const Vec3& direction);

/// Fills rows [y0, y1) of `target` (RGBA8, alpha 255) with the camera frame of `room` seen by
/// the camera of `projector`, with samples x samples supersampling per pixel. Rows are
/// independent, so callers may split the image between threads.
void RenderEnvironmentRows(const SphereProjector& projector, const RoomEnvironment& room,
  int samples, const ImageView& target, int y0, int y1);
} // namespace catar

#endif
