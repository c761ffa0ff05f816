#!/usr/bin/env bash
# Builds geotri (Release) and runs the whole pipeline on a mesh: geotri-decimate (320 faces, or as coarse as the
# topology allows when it needs more), geotri-trace, geotri-flip, geotri-refine (to a minimum corner angle of 25
# degrees), geotri-check and geotri-overlay; and geotri-distance for the exact geodesic distance from vertex 0.
#
#   scripts/demo.sh                     the bundled lumbar vertebra (examples/data/lumbar_vertebra.ply)
#   scripts/demo.sh MESH [TARGET]       your own closed triangle mesh (.off .obj .ply .stl); with TARGET (a vertex
#                                       as v:INDEX, or any surface point spec), also the shortest path to it
#
# The outputs go to out/demo/ (out/demo/NAME/ for your own mesh NAME.ext): coarse.off, traced.gtri, flipped.gtri,
# triangulation.gtri, check.txt, overlay.vtu, geodesics.vtp, distance.ply (and path.obj). An invalid triangulation
# is a result, not an error: it is reported. Installs missing Debian packages first (scripts/install-deps.sh); the
# build goes to build/, or to $BUILD_DIR.
set -euo pipefail

usage() { sed -n '2,14s/^# \{0,1\}//p' "$0"; }
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
  name=$(basename "${mesh%.*}")
  out=out/demo/$name
  target=${2:-}
else
  mesh=$root/examples/data/lumbar_vertebra.ply
  out=out/demo
  target=v:13743 # the vertex farthest from vertex 0 along the surface (108.8 mm)
fi
faces=320
min_angle=25

cd "$root"
build_dir=${BUILD_DIR:-build}
mkdir -p "$out"

scripts/install-deps.sh
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j"$(nproc)" \
  --target geotri-decimate geotri-trace geotri-flip geotri-refine geotri-check geotri-overlay geotri-distance
tools=$build_dir/tools

step() { echo && echo "== $*"; }

step "Decimating to $faces faces"
summary=$("$tools/geotri-decimate" "$mesh" -o "$out/coarse.off" --faces "$faces" --json)
min_faces=$(grep -o '"min_faces": *[0-9]*' <<<"$summary" | grep -o '[0-9]*$')
if ((min_faces > faces)); then
  step "The topology needs at least $min_faces faces: decimating as far as it allows"
  "$tools/geotri-decimate" "$mesh" -o "$out/coarse.off" --coarsest
fi

step "Tracing every coarse edge as an exact geodesic"
"$tools/geotri-trace" "$mesh" "$out/coarse.off" -o "$out/traced.gtri"

step "Flipping: untangle, then towards geodesic Delaunay"
flip=0
"$tools/geotri-flip" "$out/traced.gtri" -o "$out/flipped.gtri" || flip=$?
if ((flip == 0)); then
  step "Refining to a minimum corner angle of $min_angle degrees"
  "$tools/geotri-refine" "$out/flipped.gtri" -o "$out/triangulation.gtri" --min-angle "$min_angle"
elif ((flip == 3)); then
  step "Flips could not make it valid: no refinement"
  cp "$out/flipped.gtri" "$out/triangulation.gtri"
else
  echo "demo.sh: error: geotri-flip failed (exit code $flip)" >&2
  exit 1
fi

step "Checking the geodesic triangulation (full report in $out/check.txt)"
check=0
"$tools/geotri-check" "$out/triangulation.gtri" >"$out/check.txt" || check=$?
if ((check == 0)); then
  verdict="valid"
elif ((check == 3)); then
  verdict="INVALID (flips do not untangle every triangulation yet; check.txt lists the violations)"
else
  echo "demo.sh: error: geotri-check failed (exit code $check)" >&2
  exit 1
fi
sed -n '1,9p' "$out/check.txt" # the summary, before the list of violations

step "Cutting the mesh along the geodesics"
"$tools/geotri-overlay" "$out/triangulation.gtri" -o "$out/overlay.vtu" --curves "$out/geodesics.vtp"

step "Geodesic distance from vertex 0"
path_args=()
if [[ -n "$target" ]]; then
  path_args=(--path-to "$target" --path-out "$out/path.obj")
else
  rm -f "$out/path.obj" # from an earlier run, and not of this mesh
fi
"$tools/geotri-distance" "$mesh" --source v:0 -o "$out/distance.ply" "${path_args[@]}"

cat <<EOF

Done: $mesh
The geodesic triangulation is $verdict.
Outputs in $root/$out/:
  coarse.off           the decimated mesh
  traced.gtri          its edges traced as geodesics (coarse mesh, vertex locations, geodesic polylines)
  flipped.gtri         after geotri-flip
  triangulation.gtri   the final geodesic triangulation, refined
  check.txt            geotri-check's report
  overlay.vtu          the mesh cut along the geodesics; colour by the cell data "patch" or "colour"
  geodesics.vtp        the geodesics, one polyline per coarse edge
  distance.ply         the mesh with each vertex's geodesic distance from vertex 0
EOF
if [[ -n "$target" ]]; then
  echo "  path.obj             the shortest path from vertex 0 to $target"
fi
echo
echo "Open them with ParaView (apt install paraview): paraview $root/$out/overlay.vtu $root/$out/geodesics.vtp"
