#!/usr/bin/env bash
# Installs the Debian packages CatadioptricAR needs (ParaView 5.11's SDK with its VTK 9.2, CGAL,
# Eigen, OpenCV, OpenMesh, GoogleTest, Google Benchmark, Embree, yaml-cpp, OpenGV, Ceres, CLI11,
# Xvfb; help2man for the manual pages; clang-format and clang-tidy; for the tests, Python's
# numpy, PIL, yaml and jsonschema, and POV-Ray, the independent renderer of Testing/Independent).
#   scripts/install-deps.sh               install (runs apt-get update first)
#   scripts/install-deps.sh --if-missing  do nothing when everything is already installed
# Never install libvtk9-dev or python3-vtk9: they conflict with paraview-dev.
set -euo pipefail
packages=(build-essential cmake git pkg-config clang-format clang-tidy
  paraview paraview-dev python3-paraview qtbase5-dev qttools5-dev libqt5svg5-dev
  libqt5opengl5-dev qtxmlpatterns5-dev-tools libqt5x11extras5-dev
  libcgal-dev libeigen3-dev libopencv-dev libopencv-contrib-dev libopenmesh-dev libgtest-dev
  libbenchmark-dev libembree-dev libyaml-cpp-dev zlib1g-dev liblzma-dev xvfb xauth
  libdouble-conversion-dev liblz4-dev libutfcpp-dev libopenmpi-dev libglew-dev
  libopengv-dev libceres-dev libcli11-dev help2man povray
  python3-numpy python3-pil python3-yaml python3-jsonschema)
if [[ "${1:-}" == "--if-missing" ]]; then
  missing=0
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing=1
  done
  [[ $missing == 0 ]] && exit 0
fi
sudo=""
if [[ $(id -u) != 0 ]]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update
$sudo apt-get install -y --no-install-recommends "${packages[@]}"
