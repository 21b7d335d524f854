#!/usr/bin/env bash
# Installs every Debian 12 package deformcd needs to build, test and regenerate its assets.
# Idempotent, and fast when everything is there (one dpkg query, no apt-get).
set -euo pipefail

packages=(
  # toolchain
  g++ cmake ninja-build pkg-config ccache clang-format clang-tidy
  # fuzzing (preset fuzz, scripts/fuzz.sh): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
  # core, io, command line
  libglm-dev libtbb-dev nlohmann-json3-dev libcli11-dev libtinyobjloader-dev
  # OpenGL 4.3 compute, headless through EGL (Mesa's llvmpipe when there is no GPU), windows
  libepoxy-dev libegl-dev libegl1-mesa-dev libgl1-mesa-dri libglfw3-dev xvfb xauth
  # images
  libpng-dev libstb-dev
  # the API reference (the CMake target `docs`, a CI stage): Doxygen over include/deformcd
  doxygen
  # bench --plot
  gnuplot-nox
  # TetGen (AGPL-3, optional target)
  libtet1.5-dev
  # tests, benchmarks, exact oracle, CGAL's data set for the models
  libgtest-dev libgmock-dev libbenchmark-dev libcgal-dev libcgal-demo libeigen3-dev
  # peers of the comparison benchmark (bench_peers)
  libfcl-dev libbullet-dev
  # the Python module (pybind11, for Debian's /usr/bin/python3), its tests and example
  python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib
  # deformcd.study (parameter studies on Dask, results as a DataFrame; Debian 12 has no pyarrow,
  # so CSV), and the test of the module from a venv (python3 -m venv --system-site-packages)
  python3-dask python3-distributed python3-pandas python3-venv
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
# Another apt or dpkg (unattended-upgrades, a second terminal) holds the dpkg lock for a while:
# wait for it, up to 10 minutes, rather than fail at once with exit 100. apt prints "Waiting
# for cache lock" while it waits.
lock_wait=(-o DPkg::Lock::Timeout=600)
echo "install_deps: if another apt or dpkg is running, waiting up to 10 min for its lock"
$SUDO apt-get "${lock_wait[@]}" update -qq
$SUDO apt-get "${lock_wait[@]}" install -y -qq --no-install-recommends "${missing[@]}"
