#!/usr/bin/env bash
# Installs the Debian packages that geotri needs to build and test, and only those that are missing.
#
#   scripts/install-deps.sh            compiler, CMake, Eigen, OpenMesh, GoogleTest, CLI11, and the independent readers
#                                      that the tests check curved elements with: gmsh, meshio and VTK for Python
#   scripts/install-deps.sh --bench    the same, plus CGAL for the benchmarks
#   scripts/install-deps.sh --render   the same, plus VTK's Python bindings and Xvfb for examples/render.py
#
# Runs apt-get (update, then install) only when something is missing: as root, or through sudo otherwise.
set -euo pipefail

packages=(cmake g++ make libeigen3-dev libopenmesh-dev libgtest-dev libcli11-dev
          gmsh python3-gmsh python3-meshio python3-vtk9)

for arg in "$@"; do
  case "$arg" in
    --bench) packages+=(libcgal-dev) ;;
    --render) packages+=(python3-vtk9 xvfb xauth libgl1-mesa-dri) ;;
    -h | --help)
      sed -n '2,9s/^# \{0,1\}//p' "$0"
      exit 0
      ;;
    *)
      echo "install-deps.sh: error: unknown argument '$arg' (try --help)" >&2
      exit 2
      ;;
  esac
done

if ! command -v dpkg-query >/dev/null 2>&1; then
  echo "install-deps.sh: error: dpkg-query not found; this script knows Debian and Ubuntu only." >&2
  echo "Install by hand: ${packages[*]}" >&2
  exit 1
fi

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
  [[ "$status" == installed ]] || missing+=("$package")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps.sh: all dependencies are installed"
  exit 0
fi

if ((EUID == 0)); then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps.sh: error: missing ${missing[*]}, and neither root nor sudo is available to install them" >&2
  exit 1
fi

echo "install-deps.sh: installing ${missing[*]}"
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
