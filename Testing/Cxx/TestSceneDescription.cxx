// Scene files: the demo scene parses; errors name the key; paths resolve against the scene.
#include "SceneDescription.h"

#include "CalibrationIO.h"
#include "TestCameras.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>

using namespace catar;
using catar_test::Sphere;

namespace
{
const char* kCamera = R"(camera: { image_width: 320, image_height: 240,
  camera_matrix: [300, 0, 159.5, 0, 300, 119.5, 0, 0, 1],
  mirror: { center: [0, 0, 0.2], radius: 0.05 } }
)";
}

TEST(SceneDescription, DemoSceneParses)
{
  const SceneDescription s = DemoScene();
  EXPECT_EQ(s.camera.intrinsics.width, 1328);
  EXPECT_EQ(s.width, 1328);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].type, "box");
  EXPECT_FALSE(s.cullBackFaces); // off unless asked for
  EXPECT_TRUE(s.objects[0].faceColors);
  EXPECT_EQ(s.objects[1].type, "torus");
  EXPECT_EQ(s.background.type, "environment");
  EXPECT_TRUE(s.camera.Validate().empty());
}

// The one demo rig of the tests (TestCameras.h) is the demo calibration file's and the built-in
// demo scene's camera.
TEST(SceneDescription, DemoCamerasAgree)
{
  const CameraModel rig = catar_test::DemoCameraModel();
  CameraModel file;
  std::string error;
  ASSERT_TRUE(LoadCalibration(
    std::string(CATAR_SOURCE_DIR) + "/Data/calibration/demo-camera.yaml", file, error))
    << error;
  // The file, the demo scene's camera and the built-in one (the VTK camera's defaults).
  for (const CameraModel& m : { file, DemoScene().camera, DemoCamera() })
  {
    EXPECT_EQ(m.intrinsics.width, rig.intrinsics.width);
    EXPECT_EQ(m.intrinsics.height, rig.intrinsics.height);
    EXPECT_EQ(m.K(), rig.K());
    EXPECT_TRUE(m.distortion.IsZero());
    EXPECT_EQ(Sphere(m.mirror).center, Sphere(rig.mirror).center);
    EXPECT_EQ(Sphere(m.mirror).radius, Sphere(rig.mirror).radius);
    EXPECT_EQ(m.worldToCamera, rig.worldToCamera);
  }
}

TEST(SceneDescription, ObjectsAndDefaults)
{
  const std::string text = std::string("%YAML:1.0\n---\n") + kCamera + R"(
solver: iterative
cull_back_faces: 1
background: { type: color, color: [0.1, 0.2, 0.3] }
objects:
  - { type: sphere, radius: 0.03, translate: [0.1, 0, 0], color: [1, 0, 0] }
  - { file: meshes/trefoil-knot.ply, scale: 2 }
)";
  SceneDescription s;
  std::string error;
  const std::string data = std::string(CATAR_SOURCE_DIR) + "/Data";
  ASSERT_TRUE(ParseScene(text, data, s, error)) << error;
  EXPECT_EQ(s.solver, SolverType::Iterative);
  EXPECT_TRUE(s.cullBackFaces);
  EXPECT_EQ(s.background.type, "color");
  EXPECT_DOUBLE_EQ(s.background.color.z(), 0.3);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].type, "sphere");
  EXPECT_DOUBLE_EQ(s.objects[0].radius, 0.03);
  EXPECT_EQ(s.objects[1].type, "mesh");
  EXPECT_EQ(s.objects[1].file, data + "/meshes/trefoil-knot.ply");
  EXPECT_EQ(s.objects[1].scale, Vec3(2, 2, 2));
}

// The output size: one side given, the other keeps the calibration's aspect ratio; a rescale to
// another aspect ratio (which stretches the mirror into an ellipse) is refused unless asked for;
// a uniform one within a pixel of rounding is accepted.
TEST(SceneDescription, OutputSizeKeepsTheAspectRatio)
{
  // kCamera is 320 x 240.
  struct Case
  {
    const char* output;
    int width, height; ///< 0: refused
  };
  const Case cases[] = { { "{ width: 640, height: 480 }", 640, 480 },
    { "{ width: 161, height: 121 }", 161, 121 }, // 161 x 120.75: rounding
    { "{ width: 1000 }", 1000, 750 }, { "{ height: 60 }", 80, 60 },
    { "{ width: 1920, height: 1080 }", 0, 0 }, { "{ width: 320, height: 200 }", 0, 0 },
    { "{ width: 1920, height: 1080, stretch: true }", 1920, 1080 } };
  for (const Case& c : cases)
  {
    SceneDescription s;
    std::string error;
    const bool ok = ParseScene(std::string(kCamera) + "output: " + c.output + "\n", "", s, error);
    if (c.width == 0)
    {
      EXPECT_FALSE(ok) << c.output;
      EXPECT_NE(error.find("stretches the image and the mirror"), std::string::npos) << error;
      EXPECT_NE(error.find("stretch: true"), std::string::npos) << error;
      continue;
    }
    ASSERT_TRUE(ok) << c.output << ": " << error;
    EXPECT_EQ(s.width, c.width) << c.output;
    EXPECT_EQ(s.height, c.height) << c.output;
  }
  SceneDescription s;
  std::string error;
  ASSERT_FALSE(
    ParseScene(std::string(kCamera) + "output: { width: 1920, height: 1080 }\n", "", s, error));
  EXPECT_NE(error.find("1920x1080 rescales the 320x240 calibration by 6 across and 4.5 down"),
    std::string::npos)
    << error;
  EXPECT_NE(error.find("(1920x1440 or 1440x1080)"), std::string::npos) << error;
}

// Plain YAML without OpenCV's header; flags as true/false or 1/0; anything else for a flag is an
// error that names the key.
TEST(SceneDescription, PlainYamlAndFlags)
{
  const std::string text = std::string(kCamera) + R"(
cull_back_faces: true
lighting: { shadows: False }
objects:
  - type: box
    face_colors: yes please
)";
  SceneDescription s;
  std::string error;
  EXPECT_FALSE(ParseScene(text, "", s, error));
  EXPECT_NE(error.find("'face_colors' must be true or false"), std::string::npos) << error;
  std::string good = text;
  good.replace(good.find("yes please"), 10, "0");
  ASSERT_TRUE(ParseScene(good, "", s, error)) << error;
  EXPECT_TRUE(s.cullBackFaces);
  EXPECT_FALSE(s.lighting.shadows);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_FALSE(s.objects[0].faceColors);
  good.replace(good.find("face_colors: 0"), 14, "face_colors: TRUE");
  ASSERT_TRUE(ParseScene(good, "", s, error)) << error;
  EXPECT_TRUE(s.objects[0].faceColors);
}

TEST(SceneDescription, ErrorsNameTheKey)
{
  struct Case
  {
    std::string body;
    std::string expected;
  };
  const std::vector<Case> cases = {
    { "objects: [ { type: teapot } ]", "teapot" },
    { "objects: [ { type: mesh } ]", "file" },
    { "objects: [ { type: box, color: [2, 0, 0] } ]", "color" },
    { "objects: [ { type: box, opacity: 1.5 } ]", "opacity" },
    { "objects: [ { type: box, resolution: 0 } ]", "resolution" },
    { "objects: [ { type: box, size: [1, -1, 1] } ]", "positive" },
    { "objects: [ { type: box, translate: [1, 2] } ]", "translate" },
    { "solver: magic", "solver" },
    { "background: { type: video }", "background" },
    { "objects: { type: box }", "sequence" },
    { "edges: { boundary_tolerance: -1 }", "edges" },
    { "edges: { boundary: 1 }", "boundary" },
    { "edges: 0.5", "edges" },
    { "adaptive: { pixel_tolerance: nan }", "pixel_tolerance" },
    { "adaptive: { pixel_tolerance: -2 }", "adaptive: pixel_tolerance must be pixels" },
    { "adaptive: { tolerance: 1 }", "tolerance" },
  };
  for (const Case& c : cases)
  {
    SceneDescription s;
    std::string error;
    const std::string text = std::string("%YAML:1.0\n---\n") + kCamera + c.body + "\n";
    EXPECT_FALSE(ParseScene(text, "", s, error)) << c.body;
    EXPECT_NE(error.find(c.expected), std::string::npos)
      << "'" << error << "' lacks '" << c.expected << "'";
  }
  SceneDescription s;
  std::string error;
  EXPECT_FALSE(ParseScene("%YAML:1.0\n---\nobjects: []\n", "", s, error));
  EXPECT_NE(error.find("camera"), std::string::npos);
}

// `edges` and `adaptive` set the projection's per-frame tessellation tolerances.
TEST(SceneDescription, EdgesAndAdaptive)
{
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(ParseScene(std::string(kCamera), "", s, error)) << error;
  EXPECT_EQ(s.boundaryTolerance, 0.25);
  EXPECT_EQ(s.adaptiveTolerance, 0.0);
  ASSERT_TRUE(
    ParseScene(std::string(kCamera) + "edges: { boundary_tolerance: 0, adaptive_tolerance: 0.5 }\n",
      "", s, error))
    << error;
  EXPECT_EQ(s.boundaryTolerance, 0.0);
  EXPECT_EQ(s.adaptiveTolerance, 0.5);
  ASSERT_TRUE(
    ParseScene(std::string(kCamera) + "adaptive: { pixel_tolerance: 0.3 }\n", "", s, error))
    << error;
  EXPECT_EQ(s.adaptiveTolerance, 0.3);
  // Per object: its own, else unset (-1: the scene's).
  ASSERT_TRUE(ParseScene(std::string(kCamera) +
      "adaptive: { pixel_tolerance: 2 }\nobjects:\n  - { type: box }\n"
      "  - { type: sphere, adaptive: { pixel_tolerance: 0.25 } }\n",
    "", s, error))
    << error;
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.adaptiveTolerance, 2.0);
  EXPECT_EQ(s.objects[0].adaptiveTolerance, -1.0);
  EXPECT_EQ(s.objects[1].adaptiveTolerance, 0.25);
  for (const char* bad : { "objects:\n  - { adaptive: { pixel_tolerance: -1 } }\n",
         "objects:\n  - { adaptive: 0.5 }\n", "objects:\n  - { adaptive: { tolerance: 1 } }\n" })
  {
    EXPECT_FALSE(ParseScene(std::string(kCamera) + bad, "", s, error)) << bad;
    EXPECT_NE(error.find("adaptive"), std::string::npos) << error;
  }
}

TEST(SceneDescription, Renderer)
{
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(ParseScene(std::string(kCamera), "", s, error)) << error;
  EXPECT_EQ(s.renderer, "fast");
  ASSERT_TRUE(
    ParseScene(std::string(kCamera) + "renderer: reference\nreference_samples: 3\n", "", s, error))
    << error;
  EXPECT_EQ(s.renderer, "reference");
  EXPECT_EQ(s.referenceSamples, 3);
  for (const char* bad :
    { "renderer: exact\n", "reference_samples: 9\n", "reference_samples: 1.5\n" })
  {
    EXPECT_FALSE(ParseScene(std::string(kCamera) + bad, "", s, error)) << bad;
    EXPECT_NE(error.find(bad[0] == 'r' && bad[2] == 'n' ? "renderer" : "reference_samples"),
      std::string::npos)
      << error;
  }
}

TEST(SceneDescription, Antialias)
{
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(ParseScene(std::string(kCamera), "", s, error)) << error;
  EXPECT_EQ(s.antialiasSamples, 0);
  ASSERT_TRUE(ParseScene(std::string(kCamera) + "antialias: true\n", "", s, error)) << error;
  EXPECT_EQ(s.antialiasSamples, 4);
  ASSERT_TRUE(ParseScene(std::string(kCamera) + "antialias: { samples: 2 }\n", "", s, error))
    << error;
  EXPECT_EQ(s.antialiasSamples, 2);
  ASSERT_TRUE(ParseScene(std::string(kCamera) + "antialias: false\n", "", s, error)) << error;
  EXPECT_EQ(s.antialiasSamples, 0);
  for (const char* bad :
    { "antialias: maybe\n", "antialias: { samples: 8 }\n", "antialias: { sample: 2 }\n" })
  {
    EXPECT_FALSE(ParseScene(std::string(kCamera) + bad, "", s, error)) << bad;
    EXPECT_NE(error.find("antialias"), std::string::npos) << error;
  }
}

TEST(SceneDescription, CalibrationFileRelativeToTheScene)
{
  const std::string dir = ::testing::TempDir();
  const std::string calib = dir + "/catar_scene_calib.yaml";
  std::ofstream(calib) << "%YAML:1.0\n---\nimage_width: 64\nimage_height: 48\n"
                          "camera_matrix: [60, 0, 31.5, 0, 60, 23.5, 0, 0, 1]\n"
                          "mirror: { center: [0, 0, 0.2], radius: 0.05 }\n";
  const std::string scenePath = dir + "/catar_scene.yaml";
  std::ofstream(scenePath) << "%YAML:1.0\n---\ncamera: catar_scene_calib.yaml\n";
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(LoadScene(scenePath, s, error)) << error;
  EXPECT_EQ(s.camera.intrinsics.width, 64);
  std::remove(calib.c_str());
  std::remove(scenePath.c_str());
}

// The data search path: a relative name is looked for in the scene's folder, then in each folder
// of CATAR_DATA_PATH in order, then in the installed data; the first that has it wins.
TEST(SceneDescription, DataSearchPathOrder)
{
  const std::string root = ::testing::TempDir() + "/catar_data_path";
  for (const char* sub : { "", "/scene", "/first", "/first/meshes", "/second", "/second/meshes" })
  {
    const std::string dir = root + sub;
    ASSERT_TRUE(mkdir(dir.c_str(), 0755) == 0 || errno == EEXIST) << dir;
  }
  std::ofstream(root + "/second/meshes/both.ply") << "second\n";
  std::ofstream(root + "/first/meshes/both.ply") << "first\n";
  std::ofstream(root + "/second/meshes/only-second.ply") << "second\n";
  std::ofstream(root + "/scene/meshes.ply") << "scene\n";
  const std::string scene = root + "/scene";
  ASSERT_EQ(setenv("CATAR_DATA_PATH", (root + "/first::" + root + "/second").c_str(), 1), 0);
  EXPECT_EQ(FindDataFile(scene, "meshes/both.ply"), root + "/first/meshes/both.ply");
  EXPECT_EQ(FindDataFile(scene, "meshes/only-second.ply"), root + "/second/meshes/only-second.ply");
  EXPECT_EQ(FindDataFile(scene, "meshes.ply"), scene + "/meshes.ply");
  // Absent everywhere: the scene's folder (whose reader then names the missing file); absolute
  // names are kept.
  EXPECT_EQ(FindDataFile(scene, "meshes/none.ply"), scene + "/meshes/none.ply");
  EXPECT_EQ(FindDataFile(scene, "/abs/none.ply"), "/abs/none.ply");
  const std::vector<std::string> path = DataSearchPath();
  ASSERT_EQ(path.size(), 3u); // the empty entry of '::' is skipped
  EXPECT_EQ(path[0], root + "/first");
  EXPECT_EQ(path[1], root + "/second");
  EXPECT_EQ(path[2], InstalledDataDir());
  // A scene's mesh through the path.
  std::ofstream(scene + "/s.yaml")
    << kCamera << "objects:\n  - { type: mesh, file: meshes/only-second.ply }\n";
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(LoadScene(scene + "/s.yaml", s, error)) << error;
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].file, root + "/second/meshes/only-second.ply");

  // Found nowhere: "not found" and every folder looked in, in order; the scene's key first.
  std::string notFound;
  FindDataFile(scene, "meshes/none.ply", &notFound);
  const std::string expected = "'meshes/none.ply' not found; looked in '" + scene +
    "' (the scene's folder), '" + root + "/first' (CATAR_DATA_PATH), '" + root +
    "/second' (CATAR_DATA_PATH), '" + InstalledDataDir() + "' (the installed data)";
  EXPECT_EQ(notFound, expected);
  std::string found;
  FindDataFile(scene, "meshes/both.ply", &found);
  EXPECT_EQ(found, "");
  std::ofstream(scene + "/missing.yaml")
    << kCamera << "objects:\n  - { type: box }\n  - { type: mesh, file: meshes/none.ply }\n";
  EXPECT_FALSE(LoadScene(scene + "/missing.yaml", s, error));
  EXPECT_NE(error.find("objects[1]: file: " + expected), std::string::npos) << error;
  for (const std::string key : { "texture", "trajectory" })
  {
    std::ofstream(scene + "/missing.yaml")
      << kCamera
      << (key == "texture" ? "objects:\n  - { type: box, texture: none.png }\n"
                           : "trajectory: none.csv\n");
    EXPECT_FALSE(LoadScene(scene + "/missing.yaml", s, error));
    EXPECT_NE(error.find(key + ": 'none."), std::string::npos) << error;
    EXPECT_NE(error.find("not found; looked in"), std::string::npos) << error;
  }
  unsetenv("CATAR_DATA_PATH");
  EXPECT_EQ(DataSearchPath().size(), 1u);
  FindDataFile(scene, "meshes/none.ply", &notFound);
  EXPECT_NE(notFound.find("CATAR_DATA_PATH is not set"), std::string::npos) << notFound;
}

// A URL is not a relative path: it is refused by name, not looked for in the scene's folder.
TEST(SceneDescription, UrlsAreRefused)
{
  for (const char* url : { "https://example.org/bunny.ply", "http://host/a.png",
         "file:///tmp/a.ply", "s3://bucket/a.ply", "git+ssh://h/a.ply" })
  {
    EXPECT_TRUE(IsUrl(url)) << url;
    std::string error;
    EXPECT_EQ(FindDataFile("/tmp", url, &error), url);
    EXPECT_NE(error.find("is a URL"), std::string::npos) << url << ": " << error;
    SceneDescription s;
    EXPECT_FALSE(
      ParseScene(std::string(kCamera) + "objects:\n  - { type: mesh, file: '" + url + "' }\n",
        "/tmp", s, error));
    EXPECT_NE(error.find("file: '" + std::string(url) + "' is a URL"), std::string::npos) << error;
  }
  for (const char* name : { "a.ply", "meshes/x://y.ply", "1http://a", "://a", "c:/a.ply" })
  {
    EXPECT_FALSE(IsUrl(name)) << name;
  }
}

TEST(SceneDescription, LightingAndMaterials)
{
  const std::string text = std::string("%YAML:1.0\n---\n") + kCamera + R"(
lighting:
  shading: flat
  shadows: 0
  global_ambient: [0.1, 0.1, 0.1]
  lights:
    - { type: spot, position: [0, 0, 2], focal_point: [0, 0, 0], cone_angle: 25, exponent: 3,
        color: [1, 0, 0], intensity: 0.5 }
    - { type: directional, position: [1, 1, 1] }
objects:
  - { type: box, material: { ambient: 0.1, diffuse: 0.7, specular: 0.9, specular_power: 64 } }
)";
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(ParseScene(text, "", s, error)) << error;
  EXPECT_EQ(s.lighting.shading, "flat");
  EXPECT_FALSE(s.lighting.shadows);
  ASSERT_EQ(s.lighting.lights.size(), 2u);
  EXPECT_EQ(s.lighting.lights[0].type, "spot");
  EXPECT_DOUBLE_EQ(s.lighting.lights[0].coneAngle, 25);
  EXPECT_DOUBLE_EQ(s.lighting.lights[0].intensity, 0.5);
  EXPECT_EQ(s.lighting.lights[1].type, "directional");
  EXPECT_DOUBLE_EQ(s.objects[0].specularPower, 64);
  EXPECT_DOUBLE_EQ(s.objects[0].diffuse, 0.7);
  // Without a lighting section a scene is unlit.
  SceneDescription plain;
  ASSERT_TRUE(ParseScene(std::string("%YAML:1.0\n---\n") + kCamera, "", plain, error)) << error;
  EXPECT_EQ(plain.lighting.shading, "none");

  const std::vector<std::pair<std::string, std::string>> bad = {
    { "lighting: { shading: phong }", "shading" },
    { "lighting: { lights: [ { type: laser } ] }", "lights[0]" },
    { "lighting: { lights: [ { cone_angle: 120 } ] }", "cone_angle" },
    { "lighting: { lights: [ { position: [0, 0, 0], focal_point: [0, 0, 0] } ] }", "differ" },
    { "lighting: { lights: [ { attenuation: [0, 0, 0] } ] }", "attenuation" },
    { "objects: [ { type: box, material: { diffuse: 2 } } ]", "material" },
    { "objects: [ { type: box, material: { specular_power: 500 } } ]", "specular_power" },
  };
  for (const auto& c : bad)
  {
    SceneDescription t;
    EXPECT_FALSE(
      ParseScene(std::string("%YAML:1.0\n---\n") + kCamera + c.first + "\n", "", t, error))
      << c.first;
    EXPECT_NE(error.find(c.second), std::string::npos)
      << "'" << error << "' lacks '" << c.second << "'";
  }
}

TEST(SceneDescription, RemeshDefaultsAndOverrides)
{
  const std::string text = std::string("%YAML:1.0\n---\n") + kCamera + R"(
remesh: { target_area: 2.0e-5, feature_angle: 45 }
objects:
  - { type: box }
  - { type: box, remesh: { pixel_tolerance: 0.25, iterations: 5 } }
  - { type: box, remesh: none }
)";
  SceneDescription s;
  std::string error;
  ASSERT_TRUE(ParseScene(text, "", s, error)) << error;
  EXPECT_EQ(s.remesh.mode, "area");
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(s.objects[0].remesh.mode, "area");
  EXPECT_DOUBLE_EQ(s.objects[0].remesh.targetArea, 2.0e-5);
  EXPECT_DOUBLE_EQ(s.objects[0].remesh.featureAngle, 45.0);
  EXPECT_EQ(s.objects[1].remesh.mode, "pixels");
  EXPECT_DOUBLE_EQ(s.objects[1].remesh.pixelTolerance, 0.25);
  EXPECT_EQ(s.objects[1].remesh.iterations, 5);
  EXPECT_EQ(s.objects[2].remesh.mode, "none");
  // Without a remesh key, nothing is remeshed.
  SceneDescription plain;
  ASSERT_TRUE(ParseScene(
    std::string("%YAML:1.0\n---\n") + kCamera + "objects: [ { type: box } ]\n", "", plain, error))
    << error;
  EXPECT_EQ(plain.objects[0].remesh.mode, "none");
  // Errors name the key.
  for (const auto& bad : { std::make_pair("remesh: { target_area: -1 }", "target_area"),
         std::make_pair("remesh: { pixel_tolerance: 0 }", "pixel_tolerance"),
         std::make_pair("remesh: { target_area: 1e-5, pixel_tolerance: 1 }", "not both"),
         std::make_pair("remesh: sometimes", "remesh"),
         std::make_pair("remesh: { target_area: 1e-5, iterations: 0 }", "iterations") })
  {
    SceneDescription r;
    EXPECT_FALSE(
      ParseScene(std::string("%YAML:1.0\n---\n") + kCamera + bad.first + "\n", "", r, error));
    EXPECT_NE(error.find(bad.second), std::string::npos) << error;
  }
}
