#!/usr/bin/env bash
# Builds geotri (Release) and runs every test.
#
#   scripts/test.sh [CTEST_ARGS...]     e.g. scripts/test.sh -R ExactGeodesic, or scripts/test.sh -LE install
#
# Installs missing Debian packages first (scripts/install-deps.sh). The build goes to build/, or to $BUILD_DIR.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
build_dir=${BUILD_DIR:-build}

scripts/install-deps.sh
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j"$(nproc)"
cd "$build_dir"
ctest --output-on-failure "$@"
