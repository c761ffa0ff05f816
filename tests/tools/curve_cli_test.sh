#!/usr/bin/env bash
# Command-line tests of geotri-curve: the real binary, its exit codes (0 every element certified, 3 written with some
# not, 1 bad input, 2 usage), its summary and its files. The .gtri inputs are made by the real geotri-decimate,
# geotri-trace and geotri-flip; the files are read back by gmsh, meshio and VTK (check_curved_mesh.py), clients that
# nobody here wrote, when they are installed (the cases that need them exit 77, skipped, otherwise).
#
#   curve_cli_test.sh TOOLS_DIR TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes. ctest registers one test per case.

set -u

tools=$1
data=$2
case_name=$3
bin=$tools/geotri-curve
program=geotri-curve
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

bob=$data/classic/bob_small.ply  # genus 1: its G at 100 faces is valid once flipped
checker="$(dirname "${BASH_SOURCE[0]}")/check_curved_mesh.py"

# make_valid_gtri MESH DECIMATE_OPTIONS...: in_g.gtri, MESH decimated, traced and made valid by geotri-flip.
make_valid_gtri() {
    make_gtri "$@"
    "$tools/geotri-flip" in_g.gtri -o in_flipped.gtri --quiet || fail "geotri-flip did not make G valid"
    mv in_flipped.gtri in_g.gtri
}

# independent_check FILE ORDER [MIN_QUALITY]: gmsh, meshio and VTK read FILE; a missing client skips the case.
independent_check() {
    /usr/bin/python3 "$checker" "$@" >check.log 2>&1
    local status=$?
    if [ "$status" -eq 77 ]; then
        cat check.log >&2
        exit 77
    fi
    [ "$status" -eq 0 ] || fail "the independent check of $1 failed: $(cat check.log)"
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in IN --output --order --tolerance --min-quality --max-rounds --no-adapt --gtri-out --msh-version \
                  --bezier --fine --json --quiet --threads --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

usage_bad_output_extension)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.obj
    expect_usage_error
    expect_no_output
    ;;

usage_order_out_of_range)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.msh --order 9
    expect_usage_error
    expect_no_output
    ;;

usage_bezier_needs_vtu)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.msh --bezier
    expect_usage_error
    expect_no_output
    ;;

error_invalid_input_g)
    # bob traced at 60 faces, not flipped: its geodesics cross, and no element can stand for a patch that is not one.
    make_gtri "$bob" --faces 60
    check in_g.gtri && fail "the traced G was expected to be invalid"
    run in_g.gtri -o out.msh
    expect_error_about in_g.gtri
    grep -q "geotri-flip" stderr || fail "the message does not say how to make G valid"
    expect_no_output
    ;;

orders_2_3_4_are_certified_and_gmsh_agrees)
    make_valid_gtri "$bob" --faces 100
    for order in 2 3 4; do
        run in_g.gtri -o "out$order.msh" --order "$order" --json --quiet
        expect_rc 0
        [ "$(json_value failing)" = 0 ] || fail "order $order: elements left uncertified"
        [ "$(json_value order)" = "$order" ] || fail "order $order: the summary gives order $(json_value order)"
        [ "$(json_value certified_plane)" = "$(json_value elements)" ] || fail "order $order: not all certified"
        independent_check "out$order.msh" "$order" 0.1
    done
    ;;

msh_2_2_and_vtu_are_read_back)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.msh --msh-version 2.2 --quiet
    expect_rc 0
    head -2 out.msh | grep -q "^2.2 0 8$" || fail "out.msh is not MSH 2.2"
    independent_check out.msh 3 0.1
    run in_g.gtri -o out.vtu --quiet
    expect_rc 0
    independent_check out.vtu 3
    ;;

mfem_and_bezier_vtu_are_the_msh_elements)
    # The MFEM mesh, read by MFEM's numbering of H1 degrees of freedom, and the Bezier cells, evaluated by VTK, give
    # node by node the elements that gmsh reads from the MSH file of the same G.
    make_valid_gtri "$bob" --faces 100
    for order in 2 3 4; do
        run in_g.gtri -o "out$order.msh" --order "$order" --gtri-out "g$order.gtri" --quiet
        expect_rc 0
        for output in "out$order.mesh" "lagrange$order.vtu"; do
            run "g$order.gtri" -o "$output" --order "$order" --no-adapt --quiet
            expect_rc 0
        done
        run "g$order.gtri" -o "bezier$order.vtu" --order "$order" --no-adapt --bezier --quiet
        expect_rc 0
        independent_check "out$order.mesh" "$order" "out$order.msh"
        independent_check "bezier$order.vtu" "$order" "lagrange$order.vtu"
    done
    ;;

no_adapt_writes_the_uncertified_and_exits_three)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.msh --tolerance 1e-6 --no-adapt --json
    expect_rc 3
    [ -s out.msh ] || fail "out.msh was not written"
    grep -q "not certified" stderr || fail "stderr does not say which elements are not certified"
    # --json names each failing element, one of G's faces, with a distance bound beyond the tolerance.
    /usr/bin/python3 - <<'PY' || fail "--json does not list the failing elements: $(cat stdout)"
import json
summary = json.load(open("stdout"))
failing = summary["failing_elements"]
assert summary["failing"] > 0 and len(failing) == summary["failing"]
assert all(0 <= f["face"] < summary["elements"] and f["distance"] > 1e-6 for f in failing)
PY
    ;;

refined_g_is_written_and_valid)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.msh --gtri-out out.gtri --json --quiet
    expect_rc 0
    check out.gtri || fail "the refined G is not valid"
    [ "$(json_value splits)" -gt 0 ] || fail "nothing was refined"
    faces=$("$tools/geotri-check" out.gtri --json --quiet | sed -n 's/.*"faces": *\([0-9]*\).*/\1/p')
    [ "$faces" = "$(json_value elements)" ] || fail "the refined G has $faces faces, the mesh $(json_value elements) elements"
    ;;

same_output_for_any_thread_count)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o one.msh --threads 1 --quiet
    expect_rc 0
    run in_g.gtri -o three.msh --threads 3 --quiet
    expect_rc 0
    cmp -s one.msh three.msh || fail "the files differ between 1 and 3 threads"
    ;;

*)
    fail "no such case"
    ;;
esac
