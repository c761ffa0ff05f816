#!/usr/bin/env bash
# Builds geotri (Release) and computes exact geodesic distances on a mesh with geotri-distance.
#
#   scripts/demo.sh                     the bundled lumbar vertebra (examples/data/lumbar_vertebra.ply)
#   scripts/demo.sh MESH [TARGET]       your own closed triangle mesh (.off .obj .ply .stl); with TARGET (a vertex
#                                       as v:INDEX, or any surface point spec), also the shortest path to it
#
# Distances are measured from vertex 0. The outputs go to out/demo/. Installs missing Debian packages first
# (scripts/install-deps.sh); the build goes to build/, or to $BUILD_DIR.
set -euo pipefail

usage() { sed -n '2,9s/^# \{0,1\}//p' "$0"; }
if [[ "${1:-}" == -h || "${1:-}" == --help ]]; then
  usage
  exit 0
elif (($# > 2)); then
  usage >&2
  exit 2
fi

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if (($# >= 1)); then
  [[ -f "$1" ]] || { echo "demo.sh: error: $1: no such file" >&2; exit 1; }
  mesh=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
  target=${2:-}
else
  mesh=$root/examples/data/lumbar_vertebra.ply
  target=v:13743 # the vertex farthest from vertex 0 along the surface (108.8 mm)
fi

cd "$root"
build_dir=${BUILD_DIR:-build}
out=out/demo
mkdir -p "$out"

scripts/install-deps.sh
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j"$(nproc)" --target geotri-distance

path_args=()
if [[ -n "$target" ]]; then
  path_args=(--path-to "$target" --path-out "$out/path.obj")
else
  rm -f "$out/path.obj" # from an earlier run, and not of this mesh
fi
tool=$build_dir/tools/geotri-distance
[[ -x "$tool" ]] || { echo "demo.sh: error: $tool was not built" >&2; exit 1; }
"$tool" "$mesh" --source v:0 -o "$out/distance.ply" "${path_args[@]}"

echo
echo "Geodesic distance from vertex 0 of $mesh:"
echo "  $root/$out/distance.ply   the mesh with each vertex's distance"
if [[ -n "$target" ]]; then
  echo "  $root/$out/path.obj       the shortest path from vertex 0 to $target"
fi
