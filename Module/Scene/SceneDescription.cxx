#include "SceneDescription.h"

#include "CalibrationIO.h"
#include "ConfigReader.h"
#include "DemoSceneText.h" // generated: kDemoSceneText
#include "Markers.h"

#include <Eigen/Geometry>

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace catar
{
namespace
{
bool Exists(const std::string& path)
{
  return !path.empty() && std::ifstream(path).good();
}

std::string Join(const std::string& dir, const std::string& path)
{
  return dir.empty() ? path : dir + "/" + path;
}

// The output size against the calibration's: one side given, the other follows the aspect ratio;
// both given, a rescale that is not uniform (to within a pixel) stretches the image and the
// mirror with it, and is refused unless `stretch` asks for it.
void FitOutputToCamera(SceneDescription& scene, const bool given[2], bool stretch)
{
  const double W = scene.camera.intrinsics.width;
  const double H = scene.camera.intrinsics.height;
  if (!(W > 0 && H > 0) || (!given[0] && !given[1]))
  {
    return;
  }
  if (!given[1])
  {
    scene.height = std::max(1, static_cast<int>(std::lround(scene.width * H / W)));
    return;
  }
  if (!given[0])
  {
    scene.width = std::max(1, static_cast<int>(std::lround(scene.height * W / H)));
    return;
  }
  const double w = scene.width, h = scene.height;
  if (stretch || std::abs(h - w * H / W) <= 1.0 || std::abs(w - h * W / H) <= 1.0)
  {
    return;
  }
  char scales[96];
  std::snprintf(scales, sizeof(scales), "%.4g across and %.4g down", w / W, h / H);
  throw fs::ParseError("output: " + std::to_string(scene.width) + "x" +
    std::to_string(scene.height) + " rescales the " + std::to_string(static_cast<int>(W)) + "x" +
    std::to_string(static_cast<int>(H)) + " calibration by " + scales +
    ", which stretches the image and the mirror in it; give the calibration's aspect ratio (" +
    std::to_string(scene.width) + "x" + std::to_string(std::lround(w * H / W)) + " or " +
    std::to_string(std::lround(h * W / H)) + "x" + std::to_string(scene.height) +
    "), one side only, or add 'stretch: true'");
}

// A file named in a scene, found (FindDataFile); a URL, or a name found nowhere, is an error that
// names `key` and the folders looked in. A frame pattern (with '%') is left to its reader.
std::string Resolve(const std::string& baseDir, const std::string& path, const char* key)
{
  if (path.empty())
  {
    return path;
  }
  std::string error;
  std::string found = FindDataFile(baseDir, path, &error);
  if (!error.empty() && path.find('%') == std::string::npos)
  {
    throw fs::ParseError(std::string(key) + ": " + error);
  }
  return found;
}

std::string DirName(const std::string& path)
{
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

Vec3 Vec3Or(const fs::Node& parent, const std::string& key, const Vec3& fallback)
{
  const fs::Node n = parent[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  std::vector<double> v = fs::Numbers(n, key);
  if (v.size() == 1)
  {
    return Vec3::Constant(v[0]);
  }
  if (v.size() != 3)
  {
    throw fs::ParseError("'" + key + "' must have 1 or 3 numbers");
  }
  return Vec3(v[0], v[1], v[2]);
}

Vec3 ColorOr(const fs::Node& parent, const std::string& key, const Vec3& fallback)
{
  Vec3 c = Vec3Or(parent, key, fallback);
  if ((c.array() < 0.0).any() || (c.array() > 1.0).any())
  {
    throw fs::ParseError("'" + key + "' must be RGB in [0, 1]");
  }
  return c;
}

// `remesh: none`, `remesh: { target_area: A }` or `remesh: { pixel_tolerance: P }` (plus
// iterations, feature_angle), starting from `fallback`.
// Key `adaptive: { pixel_tolerance: P }` (at the top or in an object): P, else fallback.
double ReadAdaptive(const fs::Node& adaptive, double fallback)
{
  if (adaptive.empty() || adaptive.isNone())
  {
    return fallback;
  }
  if (!adaptive.isMap())
  {
    throw fs::ParseError("'adaptive' must be a map (pixel_tolerance)");
  }
  try
  {
    fs::CheckKeys(adaptive, { "pixel_tolerance" });
  }
  catch (const fs::ParseError& e)
  {
    throw fs::ParseError(std::string("adaptive: ") + e.what());
  }
  const double p = fs::Number(adaptive, "pixel_tolerance");
  if (!(p >= 0.0 && p <= 1e6))
  {
    throw fs::ParseError("adaptive: pixel_tolerance must be pixels in [0, 1e6] (0: off)");
  }
  return p;
}

SceneRemesh ReadRemesh(const fs::Node& node, const SceneRemesh& fallback)
{
  SceneRemesh r = fallback;
  if (node.empty() || node.isNone())
  {
    return r;
  }
  if (node.isString())
  {
    if (node.text() != "none")
    {
      throw fs::ParseError("'remesh' must be 'none' or a map");
    }
    r.mode = "none";
    return r;
  }
  if (!node.isMap())
  {
    throw fs::ParseError("'remesh' must be 'none' or a map");
  }
  try
  {
    fs::CheckKeys(
      node, { "target_area", "pixel_tolerance", "iterations", "feature_angle", "max_triangles" });
  }
  catch (const fs::ParseError& e)
  {
    throw fs::ParseError(std::string("remesh: ") + e.what());
  }
  const bool area = !node["target_area"].empty();
  const bool pixels = !node["pixel_tolerance"].empty();
  if (area && pixels)
  {
    throw fs::ParseError("remesh: give 'target_area' or 'pixel_tolerance', not both");
  }
  if (area)
  {
    r.mode = "area";
    r.targetArea = fs::Number(node, "target_area");
    if (!(r.targetArea > 0.0) || !std::isfinite(r.targetArea))
    {
      throw fs::ParseError("remesh: 'target_area' must be a positive number (m^2)");
    }
  }
  if (pixels)
  {
    r.mode = "pixels";
    r.pixelTolerance = fs::Number(node, "pixel_tolerance");
    if (!(r.pixelTolerance > 0.0) || !std::isfinite(r.pixelTolerance))
    {
      throw fs::ParseError("remesh: 'pixel_tolerance' must be a positive number (pixels)");
    }
  }
  const double it = fs::Number(node, "iterations", r.iterations);
  if (it < 1 || it > 100 || it != std::floor(it))
  {
    throw fs::ParseError("remesh: 'iterations' must be an integer in [1, 100]");
  }
  r.iterations = static_cast<int>(it);
  r.featureAngle = fs::Number(node, "feature_angle", r.featureAngle);
  if (!(r.featureAngle >= 0.0 && r.featureAngle <= 180.0))
  {
    throw fs::ParseError("remesh: 'feature_angle' must be in [0, 180] degrees");
  }
  r.maxTriangles = fs::Number(node, "max_triangles", r.maxTriangles);
  if (!(r.maxTriangles >= 1 && r.maxTriangles <= 1e9) ||
    r.maxTriangles != std::floor(r.maxTriangles))
  {
    throw fs::ParseError("remesh: 'max_triangles' must be an integer in [1, 1e9]");
  }
  return r;
}

// `keyframes`: a sequence of maps with a `time` and the given keys; calls read(map, time) for
// each, in order, after checking that the times rise.
template<typename Read>
void ReadKeyframes(const fs::Node& node, std::initializer_list<const char*> keys, const Read& read)
{
  if (node.empty() || node.isNone())
  {
    return;
  }
  if (!node.isSeq())
  {
    throw fs::ParseError("'keyframes' must be a sequence of maps");
  }
  double previous = -std::numeric_limits<double>::infinity();
  int i = 0;
  for (const fs::Node& k : node.items())
  {
    const std::string where = "keyframes[" + std::to_string(i++) + "]";
    if (!k.isMap())
    {
      throw fs::ParseError(where + " must be a map");
    }
    try
    {
      fs::CheckKeys(k, keys);
      const double time = fs::Number(k, "time");
      if (!std::isfinite(time) || !(time > previous))
      {
        throw fs::ParseError("'time' must be finite and after the previous keyframe's");
      }
      previous = time;
      read(k, time);
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(where + ": " + e.what());
    }
  }
}

SceneObject ReadObject(
  const fs::Node& node, const std::string& baseDir, int index, const SceneRemesh& defaultRemesh)
{
  std::ostringstream where;
  where << "objects[" << index << "]";
  if (!node.isMap())
  {
    throw fs::ParseError(where.str() + " must be a map");
  }
  try
  {
    fs::CheckKeys(node,
      { "name", "type", "file", "size", "radius", "tube_radius", "height", "resolution",
        "translate", "rotate", "scale", "color", "opacity", "face_colors", "pattern",
        "pattern_size", "texture", "remesh", "adaptive", "material", "keyframes", "id",
        "dictionary" });
    SceneObject o;
    o.type = fs::String(node, "type", "");
    o.file = fs::String(node, "file", "");
    if (o.type.empty())
    {
      o.type = o.file.empty() ? "box" : "mesh";
    }
    if (o.type == "mesh")
    {
      if (o.file.empty())
      {
        throw fs::ParseError("type 'mesh' needs 'file'");
      }
      o.file = Resolve(baseDir, o.file, "file");
    }
    else if (o.type != "box" && o.type != "sphere" && o.type != "torus" && o.type != "cylinder" &&
      o.type != "plane" && o.type != "marker")
    {
      throw fs::ParseError(
        "unknown type '" + o.type + "' (mesh, box, sphere, torus, cylinder, plane, marker)");
    }
    if (o.type != "marker" && (!node["id"].empty() || !node["dictionary"].empty()))
    {
      throw fs::ParseError("'id' and 'dictionary' are keys of a marker");
    }
    o.name = fs::String(node, "name", o.type);
    const fs::Node size = node["size"];
    if (!size.empty() && !size.isNone() && fs::Numbers(size, "size").size() == 2)
    {
      const std::vector<double> xy = fs::Numbers(size, "size"); // a plane's x and y
      o.size = Vec3(xy[0], xy[1], o.size.z());
    }
    else
    {
      o.size = Vec3Or(node, "size", o.size);
    }
    o.radius = fs::Number(node, "radius", o.radius);
    o.tubeRadius = fs::Number(node, "tube_radius", o.tubeRadius);
    o.height = fs::Number(node, "height", o.height);
    const double res = fs::Number(node, "resolution", o.resolution);
    if (res < 1 || res > 4096 || res != std::floor(res))
    {
      throw fs::ParseError("'resolution' must be an integer in [1, 4096]");
    }
    o.resolution = static_cast<int>(res);
    const double triangles = ProceduralTriangles(o.type, o.resolution);
    if (triangles > kMaxObjectTriangles)
    {
      std::ostringstream s;
      s << "'resolution' " << o.resolution << " makes a " << o.type << " of about "
        << static_cast<long long>(triangles) << " triangles, over the limit of "
        << static_cast<long long>(kMaxObjectTriangles);
      throw fs::ParseError(s.str());
    }
    if ((o.size.array() <= 0.0).any() || !(o.radius > 0) || !(o.tubeRadius > 0) || !(o.height > 0))
    {
      throw fs::ParseError("sizes and radii must be positive");
    }
    // Below a nanometre or above a million kilometres the object's own arithmetic (areas,
    // normals, its projection) loses its digits: a size of 1e-300 made a plane of no area.
    const double smallest = std::min({ o.size.minCoeff(), o.radius, o.tubeRadius, o.height });
    const double largest = std::max({ o.size.maxCoeff(), o.radius, o.tubeRadius, o.height });
    if (smallest < 1e-9 || largest > 1e9 || !std::isfinite(largest))
    {
      std::ostringstream s;
      s << "sizes and radii must be between 1e-9 and 1e9 scene units (got "
        << (smallest < 1e-9 ? smallest : largest) << ")";
      throw fs::ParseError(s.str());
    }
    o.translate = Vec3Or(node, "translate", o.translate);
    o.rotate = Vec3Or(node, "rotate", o.rotate);
    o.scale = Vec3Or(node, "scale", o.scale);
    if ((o.scale.array() == 0.0).any())
    {
      throw fs::ParseError("'scale' must not be zero");
    }
    o.color = ColorOr(node, "color", o.color);
    o.opacity = fs::Number(node, "opacity", o.opacity);
    if (!(o.opacity >= 0.0 && o.opacity <= 1.0))
    {
      throw fs::ParseError("'opacity' must be in [0, 1]");
    }
    o.faceColors = fs::Flag(node, "face_colors", o.faceColors);
    o.pattern = fs::String(node, "pattern", o.pattern);
    if (o.pattern != "none" && o.pattern != "checker")
    {
      throw fs::ParseError("'pattern' must be 'none' or 'checker'");
    }
    o.patternSize = fs::Number(node, "pattern_size", o.patternSize);
    if (!(o.patternSize > 0))
    {
      throw fs::ParseError("'pattern_size' must be positive");
    }
    o.texture = fs::String(node, "texture", "");
    if (!o.texture.empty() && o.texture != "checker")
    {
      o.texture = Resolve(baseDir, o.texture, "texture");
    }
    if (o.type == "marker")
    {
      // An ArUco marker (Markers.h): `size` the black square's side, a white margin of one
      // cell around it; white unless a colour is given; textured with its own pattern.
      BoardMarker m;
      const double id = fs::Number(node, "id");
      m.id = id >= 0 && id == std::floor(id) && id < 1e6 ? static_cast<int>(id) : -1;
      m.size = o.size.x();
      MarkerBoard board;
      board.dictionary = fs::String(node, "dictionary", board.dictionary);
      board.markers = { m };
      const std::string problem = ValidateMarkerBoard(board);
      if (!problem.empty() || m.id < 0)
      {
        throw fs::ParseError(
          m.id < 0 ? "'id' must be a non-negative integer" : problem.substr(problem.find(':') + 2));
      }
      if (!node["texture"].empty())
      {
        throw fs::ParseError("a marker is textured with its own pattern: no 'texture'");
      }
      o.markerId = m.id;
      o.markerDictionary = board.dictionary;
      o.texture = "marker";
      if (node["color"].empty())
      {
        o.color = Vec3::Ones();
      }
    }
    o.remesh = ReadRemesh(node["remesh"], defaultRemesh);
    o.adaptiveTolerance = ReadAdaptive(node["adaptive"], -1.0);
    ReadKeyframes(
      node["keyframes"], { "time", "translate", "rotate" }, [&o](const fs::Node& k, double time) {
        Keyframe f;
        f.time = time;
        f.position = Vec3Or(k, "translate", o.translate);
        f.rotation = RotationFromDegrees(Vec3Or(k, "rotate", o.rotate));
        if (!f.position.allFinite() || !f.rotation.coeffs().allFinite())
        {
          throw fs::ParseError("'translate' and 'rotate' must be finite");
        }
        o.keyframes.frames.push_back(f);
      });
    const fs::Node material = node["material"];
    if (!material.empty() && !material.isNone())
    {
      if (!material.isMap())
      {
        throw fs::ParseError("'material' must be a map");
      }
      try
      {
        fs::CheckKeys(
          material, { "ambient", "diffuse", "specular", "specular_power", "specular_color" });
      }
      catch (const fs::ParseError& e)
      {
        throw fs::ParseError(std::string("material: ") + e.what());
      }
      o.ambient = fs::Number(material, "ambient", o.ambient);
      o.diffuse = fs::Number(material, "diffuse", o.diffuse);
      o.specular = fs::Number(material, "specular", o.specular);
      o.specularPower = fs::Number(material, "specular_power", o.specularPower);
      o.specularColor = ColorOr(material, "specular_color", o.specularColor);
      for (double v : { o.ambient, o.diffuse, o.specular })
      {
        if (!(v >= 0.0 && v <= 1.0))
        {
          throw fs::ParseError("material: ambient, diffuse and specular must be in [0, 1]");
        }
      }
      if (!(o.specularPower >= 0.0 && o.specularPower <= 128.0))
      {
        throw fs::ParseError("material: 'specular_power' must be in [0, 128]");
      }
    }
    return o;
  }
  catch (const fs::ParseError& e)
  {
    throw fs::ParseError(where.str() + ": " + e.what());
  }
}

SceneLight ReadLight(const fs::Node& node, int index)
{
  std::ostringstream where;
  where << "lighting.lights[" << index << "]";
  if (!node.isMap())
  {
    throw fs::ParseError(where.str() + " must be a map");
  }
  try
  {
    fs::CheckKeys(node,
      { "type", "position", "focal_point", "cone_angle", "exponent", "color", "ambient",
        "intensity", "attenuation", "keyframes" });
    SceneLight l;
    l.type = fs::String(node, "type", l.type);
    if (l.type != "spot" && l.type != "point" && l.type != "directional")
    {
      throw fs::ParseError("'type' must be spot, point or directional");
    }
    l.position = Vec3Or(node, "position", l.position);
    l.focalPoint = Vec3Or(node, "focal_point", l.focalPoint);
    if (l.type != "point" && (l.position - l.focalPoint).norm() == 0.0)
    {
      throw fs::ParseError("'position' and 'focal_point' must differ");
    }
    l.coneAngle = fs::Number(node, "cone_angle", l.coneAngle);
    if (!(l.coneAngle > 0.0 && l.coneAngle <= 90.0))
    {
      throw fs::ParseError("'cone_angle' must be in (0, 90] degrees");
    }
    l.exponent = fs::Number(node, "exponent", l.exponent);
    if (!(l.exponent >= 0.0 && l.exponent <= 128.0))
    {
      throw fs::ParseError("'exponent' must be in [0, 128]");
    }
    l.color = ColorOr(node, "color", l.color);
    l.ambient = ColorOr(node, "ambient", l.ambient);
    l.intensity = fs::Number(node, "intensity", l.intensity);
    if (!(l.intensity >= 0.0))
    {
      throw fs::ParseError("'intensity' must not be negative");
    }
    l.attenuation = Vec3Or(node, "attenuation", l.attenuation);
    if ((l.attenuation.array() < 0.0).any() || l.attenuation.sum() == 0.0)
    {
      throw fs::ParseError("'attenuation' must be three non-negative numbers, not all zero");
    }
    ReadKeyframes(node["keyframes"], { "time", "position", "focal_point" },
      [&l](const fs::Node& k, double time) {
        SceneLightKeyframe f;
        f.time = time;
        f.position = Vec3Or(k, "position", l.position);
        f.focalPoint = Vec3Or(k, "focal_point", l.focalPoint);
        if (!f.position.allFinite() || !f.focalPoint.allFinite())
        {
          throw fs::ParseError("'position' and 'focal_point' must be finite");
        }
        if (l.type != "point" && (f.position - f.focalPoint).norm() == 0.0)
        {
          throw fs::ParseError("'position' and 'focal_point' must differ");
        }
        l.keyframes.push_back(f);
      });
    return l;
  }
  catch (const fs::ParseError& e)
  {
    throw fs::ParseError(where.str() + ": " + e.what());
  }
}

SceneLighting ReadLighting(const fs::Node& node)
{
  SceneLighting lighting;
  if (node.empty() || node.isNone())
  {
    return lighting;
  }
  if (!node.isMap())
  {
    throw fs::ParseError("'lighting' must be a map");
  }
  try
  {
    fs::CheckKeys(node, { "shading", "shadows", "global_ambient", "lights" });
  }
  catch (const fs::ParseError& e)
  {
    throw fs::ParseError(std::string("lighting: ") + e.what());
  }
  lighting.shading = fs::String(node, "shading", "gouraud");
  if (lighting.shading != "none" && lighting.shading != "flat" && lighting.shading != "gouraud")
  {
    throw fs::ParseError("lighting: 'shading' must be none, flat or gouraud");
  }
  lighting.shadows = fs::Flag(node, "shadows", true);
  lighting.globalAmbient = ColorOr(node, "global_ambient", lighting.globalAmbient);
  const fs::Node lights = node["lights"];
  if (!lights.empty() && !lights.isNone())
  {
    if (!lights.isSeq())
    {
      throw fs::ParseError("lighting: 'lights' must be a sequence");
    }
    int i = 0;
    for (const fs::Node& light : lights.items())
    {
      lighting.lights.push_back(ReadLight(light, i++));
    }
  }
  return lighting;
}

void ReadScene(const fs::Node& root, const std::string& baseDir, SceneDescription& out)
{
  SceneDescription scene;
  if (!root.isMap())
  {
    throw fs::ParseError("a scene must be a map of keys (camera, output, objects, ...)");
  }
  fs::CheckKeys(root,
    { "camera", "output", "solver", "renderer", "reference_samples", "cull_back_faces",
      "visibility", "edges", "adaptive", "antialias", "background", "lighting", "remesh", "objects",
      "trajectory", "sequence", "markers" });
  const fs::Node cam = root["camera"];
  if (cam.isString())
  {
    const std::string path = Resolve(baseDir, cam.text(), "camera");
    scene.calibrationFile = path;
    std::string error;
    if (!LoadCalibration(path, scene.camera, error))
    {
      throw fs::ParseError("camera: " + error);
    }
  }
  else if (cam.isMap())
  {
    try
    {
      fs::ReadCalibration(cam, scene.camera);
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(std::string("camera: ") + e.what());
    }
  }
  else
  {
    throw fs::ParseError("'camera' must name a calibration file or hold a calibration map");
  }
  for (const char* key : { "output", "background", "lighting" })
  {
    const fs::Node n = root[key];
    if (!n.empty() && !n.isNone() && !n.isMap())
    {
      throw fs::ParseError(std::string("'") + key + "' must be a map");
    }
  }
  const fs::Node output = root["output"];
  if (output.isMap())
  {
    try
    {
      fs::CheckKeys(output, { "width", "height", "stretch" });
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(std::string("output: ") + e.what());
    }
    const double w = fs::Number(output, "width", 0);
    const double h = fs::Number(output, "height", 0);
    // Absent: the calibration's size; given, at least 1 (0 was taken silently for "absent").
    const bool given[2] = { !output["width"].empty(), !output["height"].empty() };
    if ((given[0] && !(w >= 1)) || (given[1] && !(h >= 1)) || !(w >= 0 && h >= 0) ||
      w != std::floor(w) || h != std::floor(h))
    {
      throw fs::ParseError("output: width and height must be positive integers");
    }
    if (w > kMaxImageSide || h > kMaxImageSide || w * h > static_cast<double>(kMaxImagePixels))
    {
      throw fs::ParseError("output: width x height is over the limit of " +
        std::to_string(kMaxImageSide) + " pixels a side and " + std::to_string(kMaxImagePixels) +
        " pixels");
    }
    scene.width = static_cast<int>(w);
    scene.height = static_cast<int>(h);
    FitOutputToCamera(scene, given, fs::Flag(output, "stretch", false));
  }
  const std::string solver = fs::String(root, "solver", "auto");
  if (solver == "quartic")
  {
    scene.solver = SolverType::Quartic;
  }
  else if (solver == "iterative")
  {
    scene.solver = SolverType::Iterative;
  }
  else if (solver == "auto")
  {
    scene.solver = SolverType::Automatic;
  }
  else
  {
    throw fs::ParseError("'solver' must be 'auto', 'iterative' or 'quartic'");
  }
  scene.cullBackFaces = fs::Flag(root, "cull_back_faces", false);
  const fs::Node edges = root["edges"];
  if (!edges.empty() && !edges.isNone())
  {
    if (!edges.isMap())
    {
      throw fs::ParseError("'edges' must be a map (boundary_tolerance, adaptive_tolerance)");
    }
    try
    {
      fs::CheckKeys(edges, { "boundary_tolerance", "adaptive_tolerance" });
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(std::string("edges: ") + e.what());
    }
    scene.boundaryTolerance = fs::Number(edges, "boundary_tolerance", scene.boundaryTolerance);
    scene.adaptiveTolerance = fs::Number(edges, "adaptive_tolerance", scene.adaptiveTolerance);
  }
  scene.adaptiveTolerance = ReadAdaptive(root["adaptive"], scene.adaptiveTolerance);
  for (const double t : { scene.boundaryTolerance, scene.adaptiveTolerance })
  {
    if (!(t >= 0.0 && t <= 1e6))
    {
      throw fs::ParseError("edges: tolerances must be pixels in [0, 1e6] (0: off)");
    }
  }
  const fs::Node antialias = root["antialias"];
  if (antialias.isMap())
  {
    try
    {
      fs::CheckKeys(antialias, { "samples" });
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(std::string("antialias: ") + e.what());
    }
    const double n = fs::Number(antialias, "samples");
    if (!(n == 2 || n == 3 || n == 4))
    {
      throw fs::ParseError("antialias: samples (per pixel side) must be 2, 3 or 4");
    }
    scene.antialiasSamples = static_cast<int>(n);
  }
  else
  {
    scene.antialiasSamples = fs::Flag(root, "antialias", false) ? 4 : 0;
  }
  scene.renderer = fs::String(root, "renderer", scene.renderer);
  if (scene.renderer != "fast" && scene.renderer != "reference")
  {
    throw fs::ParseError("'renderer' must be 'fast' or 'reference', not '" + scene.renderer + "'");
  }
  const double referenceSamples = fs::Number(root, "reference_samples", 1.0);
  if (!(referenceSamples >= 1 && referenceSamples <= 8 &&
        referenceSamples == std::floor(referenceSamples)))
  {
    throw fs::ParseError("'reference_samples' must be a whole number from 1 to 8");
  }
  scene.referenceSamples = static_cast<int>(referenceSamples);
  scene.visibility = fs::String(root, "visibility", scene.visibility);
  if (scene.visibility != "painter" && scene.visibility != "depth")
  {
    throw fs::ParseError(
      "'visibility' must be 'painter' or 'depth', not '" + scene.visibility + "'");
  }
  const fs::Node bg = root["background"];
  if (bg.isMap())
  {
    try
    {
      fs::CheckKeys(bg,
        { "type", "color", "image", "samples", "file", "rotation", "backdrop", "match", "fps",
          "start_time" });
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(std::string("background: ") + e.what());
    }
    scene.background.type = fs::String(bg, "type", "environment");
    if (scene.background.type != "environment" && scene.background.type != "panorama" &&
      scene.background.type != "color" && scene.background.type != "image" &&
      scene.background.type != "video")
    {
      throw fs::ParseError(
        "background: 'type' must be environment, panorama, color, image or video");
    }
    scene.background.color = ColorOr(bg, "color", scene.background.color);
    scene.background.image = Resolve(baseDir, fs::String(bg, "image", ""), "background: image");
    if (scene.background.type == "image" && scene.background.image.empty())
    {
      throw fs::ParseError("background: type 'image' needs 'image'");
    }
    const double s = fs::Number(bg, "samples", scene.background.samples);
    if (s < 1 || s > 8 || s != std::floor(s))
    {
      throw fs::ParseError("background: 'samples' must be an integer in [1, 8]");
    }
    scene.background.samples = static_cast<int>(s);
    scene.background.panorama = Resolve(baseDir, fs::String(bg, "file", ""), "background: file");
    scene.background.rotation = fs::Number(bg, "rotation", scene.background.rotation);
    if (!std::isfinite(scene.background.rotation))
    {
      throw fs::ParseError("background: 'rotation' must be a finite number (degrees)");
    }
    scene.background.backdrop = ColorOr(bg, "backdrop", scene.background.backdrop);
    if (scene.background.type == "video")
    {
      scene.background.video = scene.background.panorama;
      scene.background.panorama.clear();
      if (scene.background.video.empty())
      {
        throw fs::ParseError("background: type 'video' needs 'file' (a video or a frame pattern)");
      }
    }
    scene.background.match = fs::String(bg, "match", scene.background.match);
    if (scene.background.match != "index" && scene.background.match != "time")
    {
      throw fs::ParseError("background: 'match' must be 'index' or 'time'");
    }
    scene.background.fps = fs::Number(bg, "fps", 0.0);
    if (!(scene.background.fps >= 0.0 && scene.background.fps <= 1000.0))
    {
      throw fs::ParseError("background: 'fps' must be in (0, 1000] frames a second");
    }
    scene.background.startTime = fs::Number(bg, "start_time", 0.0);
    if (!std::isfinite(scene.background.startTime))
    {
      throw fs::ParseError("background: 'start_time' must be a finite number (seconds)");
    }
  }
  const fs::Node trajectory = root["trajectory"];
  if (!trajectory.empty() && !trajectory.isNone())
  {
    if (!trajectory.isString())
    {
      throw fs::ParseError("'trajectory' must name a file");
    }
    scene.trajectoryFile = Resolve(baseDir, trajectory.text(), "trajectory");
    std::string error;
    if (!LoadTrajectory(scene.trajectoryFile, scene.trajectory, error))
    {
      throw fs::ParseError("trajectory: " + error);
    }
  }
  const fs::Node markers = root["markers"];
  if (!markers.empty() && !markers.isNone())
  {
    if (!markers.isString())
    {
      throw fs::ParseError("'markers' must name a marker board file");
    }
    if (!scene.trajectoryFile.empty())
    {
      throw fs::ParseError(
        "give 'trajectory' or 'markers' (the pose from the frames' markers), not both");
    }
    if (scene.background.type != "video" && scene.background.type != "image")
    {
      throw fs::ParseError("'markers' needs a background of type video or image (the frames "
                           "the markers are found in)");
    }
    scene.markerBoardFile = Resolve(baseDir, markers.text(), "markers");
  }
  const fs::Node sequence = root["sequence"];
  if (!sequence.empty() && !sequence.isNone())
  {
    if (!sequence.isMap())
    {
      throw fs::ParseError("'sequence' must be a map");
    }
    try
    {
      fs::CheckKeys(sequence, { "frames", "fps" });
    }
    catch (const fs::ParseError& e)
    {
      throw fs::ParseError(std::string("sequence: ") + e.what());
    }
    const double frames = fs::Number(sequence, "frames", 1);
    if (!(frames >= 1 && frames <= 10000000 && frames == std::floor(frames)))
    {
      throw fs::ParseError("sequence: 'frames' must be an integer in [1, 10000000]");
    }
    scene.sequence.frames = static_cast<int>(frames);
    scene.sequence.given = true;
    scene.sequence.fps = fs::Number(sequence, "fps", scene.sequence.fps);
    if (!(scene.sequence.fps > 0.0 && scene.sequence.fps <= 1000.0))
    {
      throw fs::ParseError("sequence: 'fps' must be in (0, 1000] frames a second");
    }
  }
  scene.lighting = ReadLighting(root["lighting"]);
  scene.remesh = ReadRemesh(root["remesh"], SceneRemesh());
  const fs::Node objects = root["objects"];
  if (!objects.empty() && !objects.isNone())
  {
    if (!objects.isSeq())
    {
      throw fs::ParseError("'objects' must be a sequence");
    }
    int i = 0;
    for (const fs::Node& object : objects.items())
    {
      scene.objects.push_back(ReadObject(object, baseDir, i++, scene.remesh));
    }
  }
  out = scene;
}

bool ReadRoot(const fs::Node& root, const std::string& what, const std::string& baseDir,
  SceneDescription& scene, std::string& error)
{
  try
  {
    ReadScene(root, baseDir, scene);
    return true;
  }
  catch (const std::exception& e)
  {
    error = what + ": " + e.what();
    return false;
  }
}
} // namespace

void SceneLight::At(double t, Vec3& p, Vec3& focal) const
{
  p = this->position;
  focal = this->focalPoint;
  if (this->keyframes.empty())
  {
    return;
  }
  const auto& k = this->keyframes;
  if (!(t > k.front().time))
  {
    p = k.front().position;
    focal = k.front().focalPoint;
    return;
  }
  if (t >= k.back().time)
  {
    p = k.back().position;
    focal = k.back().focalPoint;
    return;
  }
  std::size_t i = 1;
  while (k[i].time < t)
  {
    ++i;
  }
  const double s = (t - k[i - 1].time) / (k[i].time - k[i - 1].time);
  p = (1.0 - s) * k[i - 1].position + s * k[i].position;
  focal = (1.0 - s) * k[i - 1].focalPoint + s * k[i].focalPoint;
}

std::vector<std::string> SceneDescription::InputFiles() const
{
  std::vector<std::string> files;
  const auto add = [&files](const std::string& f) {
    if (!f.empty())
    {
      files.push_back(f);
    }
  };
  add(this->fileName);
  add(this->calibrationFile);
  for (const SceneObject& o : this->objects)
  {
    add(o.file);
    add(o.texture);
  }
  add(this->background.image);
  add(this->background.panorama);
  add(this->background.video);
  add(this->trajectoryFile);
  add(this->markerBoardFile);
  return files;
}

bool SceneDescription::IsSequence() const
{
  if (!this->trajectory.Empty() || this->background.type == "video" || this->sequence.frames > 1)
  {
    return true;
  }
  for (const SceneObject& o : this->objects)
  {
    if (!o.keyframes.Empty())
    {
      return true;
    }
  }
  for (const SceneLight& l : this->lighting.lights)
  {
    if (!l.keyframes.empty())
    {
      return true;
    }
  }
  return false;
}

double ProceduralTriangles(const std::string& type, int resolution)
{
  // As vtkCatadioptricSceneObjects builds them: a box of res x res squares a face, a sphere of
  // 2 res x res, a torus of res x res / 2 quads, a cylinder of res sides, a plane of res x res.
  const double r = std::max(3, resolution);
  if (type == "box")
  {
    return 12.0 * resolution * resolution;
  }
  if (type == "sphere")
  {
    return 4.0 * r * r;
  }
  if (type == "torus")
  {
    return r * r;
  }
  if (type == "cylinder")
  {
    return 4.0 * r;
  }
  if (type == "plane" || type == "marker")
  {
    return 2.0 * resolution * resolution;
  }
  return 0.0;
}

bool LoadScene(const std::string& path, SceneDescription& scene, std::string& error)
{
  fs::Node root;
  if (!fs::Parse(path, false, path, root, error) ||
    !ReadRoot(root, path, DirName(path), scene, error))
  {
    return false;
  }
  scene.fileName = path;
  return true;
}

bool ParseScene(
  const std::string& text, const std::string& baseDir, SceneDescription& scene, std::string& error)
{
  fs::Node root;
  return fs::Parse(text, true, "scene text", root, error) &&
    ReadRoot(root, "scene text", baseDir, scene, error);
}

const char* DemoSceneText()
{
  // Data/scenes/demo.yaml, embedded when the project is configured (DemoSceneText.h.in).
  return kDemoSceneText;
}

SceneDescription DemoScene()
{
  SceneDescription scene;
  std::string error;
  if (!ParseScene(DemoSceneText(), "", scene, error))
  {
    // The built-in text is fixed; a failure here is a programming error caught by the tests.
    throw std::runtime_error("built-in demo scene: " + error);
  }
  return scene;
}

std::vector<std::string> DataSearchPath()
{
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("CATAR_DATA_PATH"))
  {
    std::stringstream list(env);
    for (std::string dir; std::getline(list, dir, ':');)
    {
      if (!dir.empty())
      {
        dirs.push_back(dir);
      }
    }
  }
  dirs.push_back(InstalledDataDir());
  return dirs;
}

std::string InstalledDataDir()
{
  // Relative to the program or library that holds this code, so that an installed tree that
  // moved (or was installed with --prefix elsewhere) finds its own data; else where the build
  // said it would be installed.
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&InstalledDataDir), &info) && info.dli_fname)
  {
    const std::string dir = DirName(info.dli_fname);
    for (const char* relative : { CATAR_DATA_FROM_BINDIR, CATAR_DATA_FROM_LIBDIR })
    {
      const std::string candidate = dir + "/" + relative;
      char* real = Exists(candidate + "/calibration/demo-camera.yaml")
        ? realpath(candidate.c_str(), nullptr)
        : nullptr;
      if (real)
      {
        std::string found = real; // without the "bin/../" of the relative path
        std::free(real);
        return found;
      }
    }
  }
  return CATAR_INSTALLED_DATA_DIR;
}

bool IsUrl(const std::string& name)
{
  // scheme "://" (RFC 3986: a letter, then letters, digits, '+', '-', '.').
  const std::size_t colon = name.find("://");
  if (colon == std::string::npos || colon == 0 ||
    !std::isalpha(static_cast<unsigned char>(name[0])))
  {
    return false;
  }
  return std::all_of(name.begin(), name.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
  });
}

std::string FindDataFile(const std::string& baseDir, const std::string& path, std::string* error)
{
  if (error)
  {
    error->clear();
  }
  if (IsUrl(path))
  {
    if (error)
    {
      *error =
        "'" + path + "' is a URL; files are read from disk only: download it and name the file";
    }
    return path;
  }
  if (path.empty() || path[0] == '/')
  {
    if (error && !path.empty() && !Exists(path))
    {
      *error = "'" + path + "' not found";
    }
    return path;
  }
  std::string local = Join(baseDir, path);
  if (Exists(local))
  {
    return local;
  }
  const std::vector<std::string> searchPath = DataSearchPath();
  for (const std::string& dir : searchPath)
  {
    if (Exists(Join(dir, path)))
    {
      return Join(dir, path);
    }
  }
  if (error)
  {
    // Where it was looked for, in order, each folder said once.
    std::string looked = "'" + (baseDir.empty() ? std::string(".") : baseDir) + "' (" +
      (baseDir.empty() ? "the working folder" : "the scene's folder") + ")";
    const char* env = std::getenv("CATAR_DATA_PATH");
    for (std::size_t i = 0; i < searchPath.size(); ++i)
    {
      const bool installed = i + 1 == searchPath.size();
      looked += ", '" + searchPath[i] + "' (" +
        (installed ? "the installed data" : "CATAR_DATA_PATH") + ")";
    }
    if (!env || !*env)
    {
      looked += "; CATAR_DATA_PATH is not set";
    }
    *error = "'" + path + "' not found; looked in " + looked;
  }
  return local;
}

} // namespace catar
