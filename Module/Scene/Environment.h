// CatadioptricAR Core: environments and the synthetic camera frames they give.
//
// Two environments:
//  - a procedural room: an axis-aligned box in world coordinates (z up): a checkered floor, walls
//    with a tiled grid, a lit ceiling, a window and a door, so that the mirror's bending of
//    straight lines shows;
//  - an equirectangular panorama (a photograph of a real place, or the room rendered into one),
//    seen at infinity: only a ray's direction picks its colour.
// A camera frame is made by back-projecting every pixel. With the room, pixels that see the
// mirror take the room's colour along the reflected ray and the others see the room directly from
// the camera; with a panorama, pixels that see the mirror take the panorama's colour along the
// reflected direction and the others a plain backdrop colour.
//
// Panorama mapping (world frame, z up), with pixel (i, j) = column i from the left, row j from
// the TOP of the image file, and pixel coordinates whose integer values are pixel centres (as for
// camera images):
//   longitude lon = atan2(d.y, d.x) in (-pi, pi]: 0 towards +x, +90 degrees towards +y;
//   latitude  lat = asin(d.z / |d|) in [-pi/2, pi/2]: +90 degrees (zenith) at the top;
//   column  x = (0.5 - lon / (2 pi)) * width  - 0.5   (lon = 0 in the middle of the image,
//                                                      longitude grows to the LEFT)
//   row     y = (0.5 - lat / pi)     * height - 0.5.
// That is the usual layout of panoramas photographed from inside: seen from above, turning right
// (clockwise, towards -y from +x) moves right in the image. Lookups are bilinear, wrap around in
// longitude (column -0.5 meets column width-0.5) and clamp in latitude (to the top/bottom row).
#ifndef catarEnvironment_h
#define catarEnvironment_h

#include "CameraModel.h"
#include "Rasterizer.h"

#include <cstdint>
#include <vector>

namespace catar
{
class Projector;

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
void RenderEnvironmentRows(const Projector& projector, const RoomEnvironment& room, int samples,
  const ImageView& target, int y0, int y1);

/// An equirectangular (latitude-longitude) panorama: width x height pixels of `channels` bytes
/// (3: RGB8, 4: RGBA8; alpha is kept but not used), rows from the top (zenith) down, no padding.
/// See the mapping at the top of this file.
struct EquirectangularPanorama
{
  int width = 0;
  int height = 0;
  int channels = 3;
  std::vector<std::uint8_t> pixels; ///< width * height * channels bytes, row 0 at the top

  /// Sizes positive, channels 3 or 4, and pixels.size() == width * height * channels.
  bool IsValid() const;
  /// Address of the first (R) byte of pixel (i, j) (column i, row j from the top); no check.
  const std::uint8_t* texel(int i, int j) const
  {
    return pixels.data() + (static_cast<std::size_t>(j) * width + i) * channels;
  }
  std::uint8_t* texel(int i, int j)
  {
    return pixels.data() + (static_cast<std::size_t>(j) * width + i) * channels;
  }
};

/// Pixel coordinates (x = column, y = row from the top; integers are pixel centres) of a world
/// direction (any length > 0) in a width x height panorama. x is in [-0.5, width-0.5), y in
/// [-0.5, height-0.5]. A zero or non-finite direction gives the image centre.
Vec2 PanoramaPixel(int width, int height, const Vec3& worldDirection);
/// The unit world direction of pixel coordinates (x, y) of a width x height panorama (the inverse
/// of PanoramaPixel; y is clamped to the poles).
Vec3 PanoramaDirection(int width, int height, double x, double y);

/// Colour (RGB in [0,1]) of the panorama along a world direction: bilinear between the four
/// nearest pixel centres, wrapping in longitude, clamped in latitude. Black for an invalid
/// panorama; a zero or non-finite direction looks up the image centre.
Vec3 PanoramaColor(const EquirectangularPanorama& panorama, const Vec3& worldDirection);

/// The procedural room seen from `viewpoint` (inside the room), as an RGB8 panorama of
/// width x width/2 pixels (width is raised to at least 2 and made even); one ray per pixel centre,
/// so PanoramaColor at a pixel centre is RoomColor of its direction (to 8 bits). Gives panorama
/// mode a default without external data.
EquirectangularPanorama MakeRoomPanorama(
  const RoomEnvironment& room, const Vec3& viewpoint, int width);
/// The same, for rows [j0, j1) of an allocated, valid RGB8 or RGBA8 `panorama` (alpha set to
/// 255), so that callers may split the rows between threads.
void RenderRoomPanoramaRows(const RoomEnvironment& room, const Vec3& viewpoint,
  EquirectangularPanorama& panorama, int j0, int j1);

/// Where the panorama sits and what the camera sees around the mirror.
struct PanoramaPlacement
{
  /// Rotation of the panorama about world +z, degrees: the panorama's longitude 0 appears at
  /// world longitude `rotation` (positive turns it from +x towards +y).
  double rotation = 0.0;
  /// Colour (RGB in [0,1]) of pixels that do not see the mirror.
  Vec3 backdrop = Vec3(0.5, 0.5, 0.5);
};

/// Colour of the (placed) panorama along a world direction: PanoramaColor of the direction
/// rotated by -placement.rotation about z.
Vec3 PlacedPanoramaColor(const EquirectangularPanorama& panorama,
  const PanoramaPlacement& placement, const Vec3& worldDirection);

/// Fills rows [y0, y1) of `target` (RGBA8, alpha 255) with the camera frame of a panorama at
/// infinity: sub-samples whose ray hits the mirror take PlacedPanoramaColor of the reflected
/// direction (a perfect mirror); the others take placement.backdrop. samples x samples
/// supersampling per pixel (1 to 8), as RenderEnvironmentRows. Rows are independent.
void RenderPanoramaRows(const Projector& projector, const EquirectangularPanorama& panorama,
  const PanoramaPlacement& placement, int samples, const ImageView& target, int y0, int y1);
} // namespace catar

#endif
