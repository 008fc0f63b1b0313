#!/usr/bin/env bash
# Installs every Debian 12 package VesselTouch needs to build, test and run (idempotent: does
# nothing when all are installed). Never installs libvtk9-dev or python3-vtk9: they conflict with
# python3-paraview, and the plugin builds against ParaView's bundled VTK 9.2.
set -euo pipefail

packages=(
  # tool chain
  build-essential cmake pkg-config git clang libclang-rt-14-dev clang-format ccache
  # the host: ParaView 5.11 with its bundled VTK 9.2, and what its CMake package looks for
  paraview paraview-dev python3-paraview
  libboost-dev libutfcpp-dev libexpat1-dev libeigen3-dev libfreetype-dev libgl2ps-dev libglew-dev
  libgl-dev libjpeg-dev liblz4-dev liblzma-dev libxml2-dev libnetcdf-dev libpng-dev libtheora-dev
  libtiff-dev libx11-dev zlib1g-dev libdouble-conversion-dev libgdal-dev libopenmpi-dev
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  # the parallel server (mpiexec -np N pvserver) for the client/server mode and its tests
  openmpi-bin
  # Qt5 for the plugin's GUI parts
  qtbase5-dev libqt5svg5-dev libqt5x11extras5-dev libqt5opengl5-dev qttools5-dev
  qttools5-dev-tools qtxmlpatterns5-dev-tools
  # ITK 5.2 (GDCM for DICOM) and hidapi
  libinsighttoolkit5-dev libgdcm-tools libhidapi-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth imagemagick xdotool
  python3-numpy python3-matplotlib python3-skimage
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages are installed"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  SUDO="sudo"
fi
echo "install-deps: installing ${#missing[@]} package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
