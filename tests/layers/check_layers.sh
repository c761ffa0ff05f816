#!/usr/bin/env bash
# Checks that libgeotri's layers depend only downwards: core <- io, core <- check <- ops <- pipeline <- curved
# (pipeline and curved may use io too). Each source under libgeotri/src/LAYER/ may include the private headers
# ("LAYER/name.h") and the public headers (<geotri/name.h>) of its own layer and of the layers below it, never of
# one above. A public header belongs to the layer of the source that implements it (name.cpp), or to the one named
# below.
#
#   tests/layers/check_layers.sh [REPOSITORY_ROOT]
#
# Prints every include that runs upward, one per line, and exits 1 when there is one; 0 otherwise.
set -euo pipefail

root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
src=$root/libgeotri/src
public=$root/libgeotri/include/geotri

# Which layers each layer may use, itself included.
declare -A allowed=(
  [core]="core"
  [io]="core io"
  [check]="core check"
  [ops]="core check ops"
  [pipeline]="core io check ops pipeline"
  [curved]="core io check ops pipeline curved"
)
# Public headers with no source of their own name: the plain data types, and geotri.h, which includes them all.
declare -A header_layer=([mesh_data]=core [edge_paths]=core [geotri]=curved)
for layer in "${!allowed[@]}"; do
  for source in "$src/$layer"/*.cpp; do
    name=$(basename "$source" .cpp)
    header_layer[$name]=$layer
  done
done

upward=0
for layer in "${!allowed[@]}"; do
  for file in "$src/$layer"/*.h "$src/$layer"/*.cpp; do
    [[ -e "$file" ]] || continue
    while IFS= read -r line; do
      used=""
      if [[ "$line" =~ ^#include\ \"([a-z]+)/([a-z_]+)\.h\" ]]; then
        used=${BASH_REMATCH[1]}
      elif [[ "$line" =~ ^#include\ \<geotri/([a-z_]+)\.h\> ]]; then
        header=${BASH_REMATCH[1]}
        if [[ ! -e "$public/$header.h" ]]; then
          continue
        fi
        used=${header_layer[$header]:-}
        if [[ -z "$used" ]]; then
          echo "${file#"$root"/}: <geotri/$header.h> has no layer (no $header.cpp under libgeotri/src, and none named)"
          upward=1
          continue
        fi
      else
        continue
      fi
      if [[ " ${allowed[$layer]} " != *" $used "* ]]; then
        echo "${file#"$root"/}: $layer uses $used: $line"
        upward=1
      fi
    done < "$file"
  done
done

# The public headers, each in its layer, include no public header of a layer above.
for file in "$public"/*.h; do
  name=$(basename "$file" .h)
  layer=${header_layer[$name]:-}
  if [[ -z "$layer" ]]; then
    echo "libgeotri/include/geotri/$name.h: no layer (no $name.cpp under libgeotri/src, and none named)"
    upward=1
    continue
  fi
  while IFS= read -r line; do
    if [[ "$line" =~ ^#include\ \"  ]]; then
      echo "libgeotri/include/geotri/$name.h: a public header includes a private one: $line"
      upward=1
    elif [[ "$line" =~ ^#include\ \<geotri/([a-z_]+)\.h\> ]]; then
      used=${header_layer[${BASH_REMATCH[1]}]:-}
      if [[ -n "$used" && " ${allowed[$layer]} " != *" $used "* ]]; then
        echo "libgeotri/include/geotri/$name.h: $layer uses $used: $line"
        upward=1
      fi
    fi
  done < "$file"
done

if ((upward)); then
  exit 1
fi
echo "libgeotri: every include runs downwards (core <- io, core <- check <- ops <- pipeline <- curved)"
