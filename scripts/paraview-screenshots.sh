#!/usr/bin/env bash
# Regenerates the ParaView screenshots of Documentation/images (paraview-*.png): starts the
# ParaView GUI on a virtual X server with a script that builds a pipeline through the plugin of
# ./build, and photographs the window. Needs, besides the build: xvfb, xdotool, x11-apps (xwd) and
# imagemagick (apt-get install xvfb xdotool x11-apps imagemagick); they are not needed to build or
# test the project.
#   scripts/paraview-screenshots.sh [OUTPUT_FOLDER]   (default Documentation/images)
set -euo pipefail
cd "$(dirname "$0")/.."
out="$(realpath "${1:-Documentation/images}")"
plugin="$(realpath build/lib/paraview-5.11/plugins/CatadioptricAR/CatadioptricAR.so)"
source_dir="$(pwd)"
for tool in paraview xvfb-run xdotool xwd convert; do
  command -v "$tool" > /dev/null || { echo "paraview-screenshots: $tool is missing" >&2; exit 1; }
done
[ -f "$plugin" ] || { echo "paraview-screenshots: build the plugin first ($plugin)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# One picture: $1 the GUI script, $2 the PNG. A fresh settings folder without the welcome dialog;
# the window is photographed 25 s after ParaView starts (it has run the script by then).
shoot() {
  cat > "$work/shoot.sh" << SHOOT
#!/usr/bin/env bash
export HOME="$work/home"
rm -rf "\$HOME" && mkdir -p "\$HOME/.config/ParaView"
echo '{ "settings": { "GeneralSettings": { "ShowWelcomeDialog": 0 } } }' \\
  > "\$HOME/.config/ParaView/ParaView-UserSettings.json"
paraview --script="$1" > "$work/paraview.log" 2>&1 &
pv=\$!
sleep 25
window=\$(xdotool search --onlyvisible --name '^ParaView 5' | tail -1)
xdotool windowmove "\$window" 0 0 windowsize --sync "\$window" 1440 900
sleep 6
xwd -root -silent | convert xwd:- -crop 1440x900+0+0 +repage "$2"
kill \$pv
SHOOT
  chmod +x "$work/shoot.sh"
  VTK_SMP_BACKEND_IN_USE=STDThread xvfb-run -a -s "-screen 0 1600x1000x24" "$work/shoot.sh"
  echo "paraview-screenshots: wrote $2"
}

shots="${2:-all}"

# 1. First Apply: a sphere through the demo camera's mirror, every proxy with its defaults (no
# calibration file), over the synthesised room; the projection's panel shows the camera's groups.
cat > "$work/first-apply.py" << PY
from paraview.simple import *
LoadPlugin("$plugin", remote=False)
from paraview.simple import *
ball = Sphere(Center=[0.06, -0.32, 0.92], Radius=0.06, ThetaResolution=32, PhiResolution=16)
projection = CatadioptricProjection(Input=ball)
sort = CatadioptricPainterSort(Input=projection)
frame = CatadioptricEnvironment()
compositor = CatadioptricCompositor(Input=[sort], Frame=frame, Textures=[])
compositor.Color = [1.0, 0.55, 0.1]
view = GetActiveViewOrCreate("RenderView")
Hide(ball, view)
Show(compositor, view)
view.InteractionMode = "2D"
ResetCamera(view)
SetActiveSource(projection)
Render(view)
PY
[ "$shots" = scene ] || shoot "$work/first-apply.py" "$out/paraview-first-apply.png"

# 2. The demo scene opened as a file (the scene reader, whose first output is the frame it
# renders) and the rig: the scene's objects, the camera, its frustum and the mirror part it sees,
# in world coordinates. (A second view for the frame is left out: assigning a view to a layout
# from the GUI's Python did not return under xvfb.)
cat > "$work/scene-and-rig.py" << PY
from paraview.simple import *
LoadPlugin("$plugin", remote=False)
from paraview.simple import *
scene = CatadioptricARSceneReader(FileName="$source_dir/Data/scenes/demo.yaml")
rig = CatadioptricRig(CalibrationFileName="$source_dir/Data/calibration/demo-camera.yaml")
rig.FrustumLength = 0.3
world = GetActiveViewOrCreate("RenderView")
objects = Show(OutputPort(scene, 1), world)
ColorBy(objects, ("CELLS", "Colors"))
objects.MapScalars = 0
parts = Show(rig, world)
ColorBy(parts, ("CELLS", "RigPart"))
parts.LineWidth = 2.0
parts.PointSize = 10.0
parts.RenderPointsAsSpheres = 1
world.CameraPosition = [0.9, -1.1, 1.45]
world.CameraFocalPoint = [0.0, -0.05, 0.9]
world.CameraViewUp = [0.0, 0.0, 1.0]
world.OrientationAxesVisibility = 1
SetActiveSource(rig)
Render(world)
PY
shoot "$work/scene-and-rig.py" "$out/paraview-scene-and-rig.png"
