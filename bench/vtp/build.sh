#!/bin/bash
# Builds bench/vtp/vtp_bench.cpp against VTP's sources, with VTP's tie bug fixed, to time VTP and libgeodesic on
# the same machine in the same run (bench/vtp/README.md). VTP is not part of geotri: its sources are fetched by
# you, e.g. `git clone https://github.com/YipengQin/VTP_source_code` (MIT licence).
#
#     bench/vtp/build.sh VTP_SOURCE_DIR [OUTPUT]      (OUTPUT defaults to build/vtp-bench)
set -euo pipefail

if [[ $# -lt 1 || ! -f "$1/geodesic_algorithm_exact.h" ]]; then
    echo "usage: bench/vtp/build.sh VTP_SOURCE_DIR [OUTPUT]: a folder with VTP's geodesic_algorithm_exact.h" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
output=${2:-build/vtp-bench}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$1"/*.h "$work"/

# Its vertex queue is a std::set ordered by distance alone, so a vertex whose distance equals another's is never
# queued: order ties by vertex id (VTP's published figures assume this order).
python3 - "$work/geodesic_mesh_elements.h" <<'PY'
import sys
path = sys.argv[1]
text = open(path).read()
old = "return (x->geodesic_distance() < y->geodesic_distance());"
new = ("return x->geodesic_distance() != y->geodesic_distance() ? "
       "x->geodesic_distance() < y->geodesic_distance() : x->id() < y->id();")
if text.count(old) != 1:
    sys.exit(f"{path}: the queue's comparison is not the one expected; is this VTP's source?")
open(path, "w").write(text.replace(old, new))
PY

# Names of MSVC's runtime that its headers use.
cat > "$work/posix_shim.h" <<'H'
#include <cstdio>
#include <cstring>
#include <memory>
#define sscanf_s sscanf
H
mkdir -p "$(dirname "$output")"
g++ -O3 -DNDEBUG -std=c++17 -w -include "$work/posix_shim.h" -I"$work" "$here/vtp_bench.cpp" -o "$output"
echo "built $output"
