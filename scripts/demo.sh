#!/usr/bin/env bash
# Builds geotri (Release) and runs the whole pipeline on a mesh with examples/Makefile: geotri-decimate (320 faces,
# or as coarse as the topology allows when it needs more), geotri-trace, geotri-flip, geotri-refine (to a minimum
# corner angle of 25 degrees), geotri-check, geotri-overlay and the pictures (examples/render.py); then
# geotri-distance for the exact geodesic distance from vertex 0.
#
#   scripts/demo.sh                     the bundled lumbar vertebra (examples/data/lumbar_vertebra.ply)
#   scripts/demo.sh MESH [TARGET]       your own closed triangle mesh (.off .obj .ply .stl); with TARGET (a vertex
#                                       as v:INDEX, or any surface point spec), also the shortest path to it
#
# The outputs go to out/demo/ (out/demo/NAME/ for your own mesh NAME.ext), named NAME.*: the list is printed at
# the end. An invalid triangulation is a result, not an error: it is reported. Installs missing Debian packages
# first (scripts/install-deps.sh --render); the build goes to build/, or to $BUILD_DIR.
set -euo pipefail

usage() { sed -n '2,13s/^# \{0,1\}//p' "$0"; }
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
  name=lumbar_vertebra
  out=out/demo
  target=v:13743 # the vertex farthest from vertex 0 along the surface (108.8 mm)
fi

cd "$root"
build_dir=${BUILD_DIR:-build}
mkdir -p "$out"

scripts/install-deps.sh --render
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j"$(nproc)" \
  --target geotri-decimate geotri-trace geotri-flip geotri-refine geotri-check geotri-overlay geotri-distance \
  geotri-curve
tools=$(cd "$build_dir/tools" && pwd)

# The Makefile works on the meshes in the folder where it runs: the mesh goes there as a link.
ln -sf "$mesh" "$out/$(basename "$mesh")"
echo && echo "== The pipeline (examples/Makefile)"
make -f "$root/examples/Makefile" -C "$out" GEOTRI_BIN="$tools" "$name.png" "$name.refined.png" "$name.check.txt" \
  "$name.curved.png" "$name.curved.msh"
verdict=$(sed -n '1s/^[^:]*: //p' "$out/$name.check.txt")

echo && echo "== Geodesic distance from vertex 0"
path_args=()
if [[ -n "$target" ]]; then
  path_args=(--path-to "$target" --path-out "$out/$name.path.obj")
else
  rm -f "$out/$name.path.obj" # from an earlier run, and not of this mesh
fi
"$tools/geotri-distance" "$mesh" --source v:0 -o "$out/$name.distance.ply" "${path_args[@]}"

cat <<END

Done: $mesh
The geodesic triangulation is $verdict (geotri-check's full report: $name.check.txt).
Outputs in $root/$out/:
  $name.png                    coarse mesh, traced geodesics, flipped triangulation coloured by patch
  $name.refined.png            the refined triangulation
  $name.curved.png             certified curved P3 elements, by min J / max J, beside their patches
  $name.curved.msh, .vtu       the curved elements for gmsh and solvers, and for ParaView
  $name.coarse.off             the decimated mesh ($name.coarse.paths: its edges on the mesh, for trace)
  $name.traced.gtri            its edges traced as geodesics (coarse mesh, vertex locations, polylines)
  $name.flipped.gtri           after geotri-flip
  $name.refined.gtri           after geotri-refine: the final geodesic triangulation
  $name.STEP.vtu and .vtp      T cut along the geodesics of each step (cell data patch, colour), the geodesics
  $name.distance.ply           the mesh with each vertex's geodesic distance from vertex 0
END
if [[ -n "$target" ]]; then
  echo "  $name.path.obj               the shortest path from vertex 0 to $target"
fi
echo
echo "Open them in ParaView (apt install paraview): paraview $root/$out/$name.refined.vtu $root/$out/$name.refined.vtp"
