#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Debian 12 packages SonarGrid builds and tests with, and only those that are missing.
# Every dependency of the project is listed here and nowhere else.
set -euo pipefail

packages=(
  g++ cmake ninja-build                     # toolchain
  lld                                       # LLVM's linker: links in a fifth of ld.bfd's time
  qt6-base-dev                              # Qt 6 Core/Gui/Widgets/Test/OpenGL/Network
  qt6-serialport-dev                        # Qt 6 SerialPort (the robot link's serial transport)
  libeigen3-dev                             # poses and geometry
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev  # distance transform, PNG
  nlohmann-json3-dev                        # JSON for the CLI and reference maps
  libbz2-dev liblz4-dev libzstd-dev         # ROS bags' chunk compressions (core/sonargrid/io/bag)
  libsqlite3-dev                            # rosbag2's SQLite storage
  libbenchmark-dev                          # Google Benchmark (tests/bench)
  libnlopt-cxx-dev                          # NLopt, the optimisers of sonargrid-cli optimize
  libqt6opengl6-dev                         # Qt 6 OpenGL / OpenGLWidgets (the grid view)
  qt6-svg-dev                               # QSvgGenerator (SVG export of the view)
  qt6-charts-dev                            # Qt Charts (GPL-3.0): the sweep view's plots
  libgl-dev                                 # OpenGL headers for the grid view
  libgl1-mesa-dri                           # Mesa software rendering for the GL tests
  xvfb xauth                                # xvfb-run for the GL tests (ctest label gl)
  clang libclang-rt-14-dev                  # libFuzzer + sanitizer runtimes (.ci/fuzz.sh)
  qemu-user                                 # a CPU without AVX2, emulated (.ci/baseline-cpu.sh)
  pybind11-dev python3-dev python3-numpy    # the Python module, import sonargrid (docs/python.md)
  python3-pytest                            # its test suite (tests/python)
  slurmctld slurmd slurm-client munge       # a one-node Slurm cluster for .ci/slurm.sh
  ccache                                    # compiler cache shared by the CI builds (.ci/build.sh)
  socat                                     # a pty bridged to the virtual robot: the serial test
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi
echo "Installing: ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
