#!/usr/bin/env bash
# Tests of examples/Makefile: the pattern rules run the real tools on bundled meshes, in parallel, as a user runs
# them in a folder of their own.
#
#   makefile_test.sh MAKEFILE TOOLS_DIR TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes, 77 when it is skipped (the pictures need
# python3-vtk9 and xvfb-run). ctest registers one test per case.

set -u

makefile=$1
tools=$2
data=$3
case_name=$4
program=make
bin=make
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

pipeline() { make -f "$makefile" GEOTRI_BIN="$tools" "$@" >stdout 2>stderr; rc=$?; }

case "$case_name" in

pipeline_runs_on_every_mesh_in_parallel)
    # Two meshes of two formats, with -j: each goes through decimate, trace, flip, refine, check and overlay.
    cp "$data/classic/bob_small.ply" "$data/cad/tripod.off" .
    pipeline -j2 FACES=100 MINANGLE=20 bob_small.check.txt tripod.check.txt bob_small.refined.vtu tripod.refined.vtu
    expect_rc 0
    for name in bob_small tripod; do
        for suffix in coarse.off traced.gtri flipped.gtri refined.gtri check.txt refined.vtu refined.vtp; do
            [ -s "$name.$suffix" ] || fail "$name.$suffix is not written"
        done
        [ "$(sed -n 1p "$name.check.txt")" = "$name.refined.gtri: valid" ] || fail "$name.check.txt does not say valid"
        "$tools/geotri-check" "$name.refined.gtri" --quiet >/dev/null || fail "$name.refined.gtri is not valid"
    done
    # FACES reaches geotri-decimate; the tripod (genus 0, 44 faces) goes down to 44 at most.
    grep -q '"coarse_faces": 100' bob_small.decimate.json || fail "bob_small is not decimated to FACES=100"
    # Nothing is left to do: a second run makes nothing.
    pipeline -j2 FACES=100 MINANGLE=20 bob_small.check.txt tripod.check.txt
    grep -q "geotri-" stdout && fail "a second run runs the tools again"
    ;;

topology_that_needs_more_faces_goes_as_coarse_as_it_allows)
    # The anchor (genus 4) needs more than 8 faces: the Makefile decimates it as far as its topology allows.
    cp "$data/cad/anchor.off" .
    pipeline FACES=8 anchor.coarse.off
    expect_rc 0
    grep -q "as coarse as it allows" stdout || fail "make does not say that it goes as coarse as it can"
    grep -q '"target_reached": false' anchor.decimate.json || fail "the decimation reached 8 faces"
    ;;

invalid_triangulation_is_a_result_not_a_failure)
    # The joint at the coarsest level its genus allows stays invalid after flipping without the bisections that
    # mend it (docs/algorithms.md, §5): flip and check exit 3, make goes on.
    cp "$data/cad/joint.off" in_joint.off
    pipeline FACES=4 FLIP_OPTIONS="--bisection-rounds 0" in_joint.check.txt
    expect_rc 0
    grep -q "not valid, so it is not refined" stdout || fail "make does not say that it did not refine"
    [ "$(sed -n 1p in_joint.check.txt)" = "in_joint.refined.gtri: INVALID" ] || fail "the check does not say INVALID"
    ;;

upper_case_extensions_are_meshes_too)
    # Meshes straight from CAD systems and scanners are often named Part.STL or Scan.PLY.
    cp "$data/classic/bob_small.ply" Bob.PLY
    pipeline -n
    grep -q "Bob.PLY" stdout || fail "make without a target does not find Bob.PLY"
    pipeline FACES=100 Bob.check.txt
    expect_rc 0
    [ "$(sed -n 1p Bob.check.txt)" = "Bob.refined.gtri: valid" ] || fail "Bob.PLY is not taken through the pipeline"
    ;;

a_failed_check_stops_make_and_leaves_no_partial_file)
    # A broken triangulation is a failure (exit 1 or 2), not an invalid result (exit 3): make stops there.
    cp "$data/classic/bob_small.ply" .
    pipeline FACES=100 bob_small.flipped.gtri
    expect_rc 0
    head -c 100 bob_small.flipped.gtri >broken && mv broken bob_small.flipped.gtri
    pipeline bob_small.check.txt
    [ "$rc" -ne 0 ] || fail "make went on after geotri-check failed"
    grep -q "bob_small.flipped.gtri: line" stderr || fail "geotri-check's error is not shown"
    ls bob_small.refined.gtri* bob_small.check.txt* 2>/dev/null && fail "a refined triangulation or check report is left"
    ;;

missing_tools_are_named)
    cp "$data/cad/tripod.off" .
    make -f "$makefile" GEOTRI_BIN="$PWD/nowhere" tripod.coarse.off >stdout 2>stderr
    rc=$?
    [ "$rc" -ne 0 ] || fail "make succeeded without tools"
    grep -q "no geotri tools in '$PWD/nowhere'" stderr || fail "the error does not name the tools folder"
    [ ! -e tripod.coarse.off ] || fail "a coarse mesh is written without tools"
    ;;

pictures_are_rendered)
    if ! /usr/bin/python3 -c 'import vtk' 2>/dev/null || ! command -v xvfb-run >/dev/null; then
        echo "python3-vtk9 or xvfb-run is missing (scripts/install-deps.sh --render): the pictures are not tested"
        exit 77
    fi
    cp "$data/classic/bob_small.ply" .
    pipeline FACES=100 bob_small.png bob_small.refined.png bob_small.curved.png
    expect_rc 0
    for png in bob_small.png bob_small.refined.png bob_small.curved.png; do
        [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$png is not a PNG"
    done
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
