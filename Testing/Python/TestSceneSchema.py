"""Every shipped scene (Data/scenes) and the built-in demo satisfy Documentation/scene.schema.json;
scenes the reader refuses for a wrong key, type or value are refused by the schema too. Scenes and
calibrations, shipped and written, are standard YAML (PyYAML reads them; OpenCV's `%YAML:1.0`
first line is not standard).

Usage: TestSceneSchema.py SOURCE_DIR RENDER_PROGRAM"""
import glob
import json
import os
import subprocess
import sys
import tempfile

import jsonschema
import yaml

source, program = sys.argv[1], sys.argv[2]
with open(os.path.join(source, "Documentation", "scene.schema.json")) as f:
    schema = json.load(f)
jsonschema.Draft7Validator.check_schema(schema)
validator = jsonschema.Draft7Validator(schema)


class PlainLoader(yaml.SafeLoader):
    """PyYAML's safe loader, plus OpenCV's `!!opencv-matrix` tag (a map: rows, cols, dt, data)."""


PlainLoader.add_constructor("tag:yaml.org,2002:opencv-matrix",
                            lambda loader, node: loader.construct_mapping(node, deep=True))


def load(text):
    # Standard YAML, as any parser reads it: OpenCV's "%YAML:1.0" first line is not accepted.
    return yaml.load(text, Loader=PlainLoader)


passed = failed = 0
scenes = sorted(glob.glob(os.path.join(source, "Data", "scenes", "*.yaml")))
demo = subprocess.run([program, "--print-demo-scene"], check=True, capture_output=True).stdout
cases = [(path, open(path).read()) for path in scenes] + [("built-in demo", demo.decode())]
assert len(cases) >= 5, cases
for name, text in cases:
    errors = list(validator.iter_errors(load(text)))
    if errors:
        failed += 1
        print(f"FAIL {name}: " + "; ".join(e.message for e in errors))
    else:
        passed += 1
        print(f"ok   {name}")

bad = {
    "unknown key": "camera: c.yaml\ncolour: [1, 0, 0]\n",
    "object key misspelt": "camera: c.yaml\nobjects:\n  - { type: box, colour: [1, 0, 0] }\n",
    "solver": "camera: c.yaml\nsolver: magic\n",
    "opacity range": "camera: c.yaml\nobjects:\n  - { type: box, opacity: 1.5 }\n",
    "antialias samples": "camera: c.yaml\nantialias: { samples: 8 }\n",
    "no camera": "objects: []\n",
}
for name, text in bad.items():
    if list(validator.iter_errors(load(text))):
        passed += 1
        print(f"ok   refused: {name}")
    else:
        failed += 1
        print(f"FAIL accepted: {name}")

# Shipped calibrations and a calibration the project writes are standard YAML too.
calibrations = sorted(glob.glob(os.path.join(source, "Data", "calibration", "*.yaml")))
assert calibrations, "no calibration in Data/calibration"
with tempfile.TemporaryDirectory() as folder:
    import catadioptricar as car
    written = os.path.join(folder, "written-camera.yaml")
    assert car.vtkCatadioptricCamera().Save(written), written
    for path in calibrations + [written]:
        try:
            camera = load(open(path).read())
            assert camera["camera_matrix"]["rows"] == 3 and camera["image_width"] > 0, camera
            passed += 1
            print(f"ok   plain YAML: {os.path.basename(path)}")
        except Exception as e:  # noqa: BLE001 - any failure to read is the failure reported
            failed += 1
            print(f"FAIL {os.path.basename(path)}: {e}")

print(f"scene schema: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
