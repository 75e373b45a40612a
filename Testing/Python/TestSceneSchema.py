"""Every shipped scene (Data/scenes) and the built-in demo satisfy Documentation/scene.schema.json;
scenes the reader refuses for a wrong key, type or value are refused by the schema too.

Usage: TestSceneSchema.py SOURCE_DIR RENDER_PROGRAM"""
import glob
import json
import os
import subprocess
import sys

import jsonschema
import yaml

source, program = sys.argv[1], sys.argv[2]
with open(os.path.join(source, "Documentation", "scene.schema.json")) as f:
    schema = json.load(f)
jsonschema.Draft7Validator.check_schema(schema)
validator = jsonschema.Draft7Validator(schema)


def load(text):
    # OpenCV's "%YAML:1.0" first line (optional in scene files) is not YAML 1.1's directive.
    lines = text.splitlines()
    if lines and lines[0].startswith("%YAML"):
        lines = lines[1:]
    return yaml.safe_load("\n".join(lines))


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

print(f"scene schema: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
