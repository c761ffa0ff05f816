#!/usr/bin/env bash
# Runs the propagation benchmark on generated meshes (spheres, a torus, a cube, a flat grid) and shared real ones,
# and prints a Markdown table on stdout.
#
#   bench/run.sh [--no-cgal] [--repeat N] [--keep-windows]
#
# Builds geotri-bench-propagation in Release (with CGAL when libcgal-dev is installed: scripts/install-deps.sh
# --bench). The shared real meshes are read from ../shared/data, or from $GEOTRI_SHARED_DATA; those that are
# missing are skipped with a note on stderr. Times are CPU seconds, the median of --repeat runs (default 3).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
build_dir=${BUILD_DIR:-build}
data=${GEOTRI_SHARED_DATA:-../shared/data}

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j"$(nproc)" --target geotri-bench-propagation >/dev/null
bench=$build_dir/bench/geotri-bench-propagation

meshes=(gen:icosphere:100k gen:torus:100k gen:cube:100k gen:grid:100k gen:noisy-sphere:100k
        gen:icosphere:400k)
for file in classic/lucy_100k.ply classic/bunny_closed_cgal.off anatomy/brain_conte69_32k_lh.ply \
            anatomy/lumbar_spine_L2-L5_mean.ply cad/turbineblade.ply; do
  if [[ -f "$data/$file" ]]; then
    meshes+=("$data/$file")
  else
    echo "bench/run.sh: skipping $file: not found under $data" >&2
  fi
done

# The 1M-face sphere comes last: it takes the longest, and with --keep-windows its windows need about 12 GB,
# more on the way as their storage grows; a machine without that much memory must still get the other rows.
meshes+=(gen:icosphere:1M)

header=()
failed=0
for mesh in "${meshes[@]}"; do
  if "$bench" "${header[@]}" "$@" "$mesh"; then
    header=(--no-header)
  else
    echo "bench/run.sh: $mesh: the benchmark failed (exit $?), going on" >&2
    failed=1
  fi
done
exit "$failed"
