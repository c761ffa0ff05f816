#!/usr/bin/env bash
# Command-line tests of geotri-refine: the real binary, its exit codes (0 valid output, 3 written but invalid, 1 bad
# input, 2 usage), its summary and its output. The .gtri inputs are made by the real geotri-decimate, geotri-trace
# and geotri-flip, and the outputs are judged by the real geotri-check.
#
#   refine_cli_test.sh TOOLS_DIR TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes. ctest registers one test per case.

set -u

tools=$1
data=$2
case_name=$3
bin=$tools/geotri-refine
program=geotri-refine
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

tripod=$data/cad/tripod.off        # genus 0: its coarse G at 20 faces is valid
bob=$data/classic/bob_small.ply    # genus 1: its G at 100 faces is valid

# make_valid_gtri MESH DECIMATE_OPTIONS...: in_g.gtri, MESH decimated, traced and made valid by geotri-flip.
make_valid_gtri() {
    make_gtri "$@"
    "$tools/geotri-flip" in_g.gtri -o in_flipped.gtri --quiet || fail "geotri-flip did not make G valid"
    mv in_flipped.gtri in_g.gtri
}

# attempts_run: how many refinements of the input the --json summary on stdout lists.
attempts_run() {
    python3 -c 'import json, sys; print(len(json.load(open("stdout"))["attempts"]))'
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in IN --output --max-length --faces --min-angle --max-new-vertices --no-flip --fine --json --quiet \
                  --threads --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

usage_no_target)
    make_valid_gtri "$tripod" --faces 20
    run in_g.gtri -o out.gtri
    expect_usage_error
    grep -q -- "--min-angle" stderr || fail "the message does not name the options"
    expect_no_output
    ;;

usage_angle_out_of_range)
    make_valid_gtri "$tripod" --faces 20
    run in_g.gtri -o out.gtri --min-angle 50
    expect_usage_error
    expect_no_output
    ;;

usage_nan_angle)
    # A usage error, not a failure blamed on the input.
    make_valid_gtri "$tripod" --faces 20
    run in_g.gtri -o out.gtri --min-angle nan
    expect_usage_error
    grep -q -- "--min-angle: 'nan' is not a number" stderr || fail "the message does not say what is wrong"
    expect_no_output
    ;;

usage_output_is_the_input)
    make_valid_gtri "$tripod" --faces 20
    cp in_g.gtri in_before.gtri
    run in_g.gtri -o in_g.gtri --faces 40
    expect_usage_error
    grep -q "is the IN" stderr || fail "message does not say that -o is the input"
    cmp -s in_g.gtri in_before.gtri || fail "the input changed"
    expect_no_output
    ;;

usage_bad_output_extension)
    make_valid_gtri "$tripod" --faces 20
    run in_g.gtri -o out.off --faces 40
    expect_usage_error
    expect_no_output
    ;;

face_target_is_reached)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.gtri --faces 300 --json
    expect_rc 0
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    faces=$(json_value faces)
    [ "$faces" -ge 300 ] && [ "$faces" -le 309 ] || fail "$faces faces, expected 300 to 309"
    ;;

max_length_is_reached)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.gtri --max-length 0.5 --json
    expect_rc 0
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) <= 0.5 else 1)' "$(json_value longest_edge)" ||
        fail "longest edge $(json_value longest_edge) is above 0.5"
    [ "$(json_value bisection_target_reached)" = true ] || fail "bisection_target_reached is not true"
    ;;

unreachable_bisection_target_is_said)
    # No split may make an edge shorter than a tenth of T's mean edge: the bound stops bisection, which says so.
    make_valid_gtri "$tripod" --faces 20
    run in_g.gtri -o out.gtri --max-length 1e-12 --json
    expect_rc 0
    [ "$(json_value bisection_target_reached)" = false ] || fail "bisection_target_reached is not false"
    run in_g.gtri -o out.gtri --max-length 1e-12
    expect_rc 0
    grep -q -- "--max-length 1e-12 not reached: the longest edge is" stderr || fail "stderr does not say so"
    run in_g.gtri -o out.gtri --faces 100000000
    grep -q -- "--faces 100000000 not reached" stderr || fail "stderr does not say that --faces was not reached"
    ;;

min_angle_is_reached)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.gtri --min-angle 30 --json
    expect_rc 0
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    [ "$(json_value small_corners_left)" = "0" ] || fail "corners below 30 degrees are left"
    [ "$(attempts_run)" = 1 ] || fail "refined again where the first attempt reached the angle"
    python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) >= 30 else 1)' "$(json_value min_corner_angle_deg)" ||
        fail "min corner angle $(json_value min_corner_angle_deg) is below 30"
    ;;

vertex_cap_is_the_option)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o out.gtri --min-angle 30 --max-new-vertices 3 --json
    expect_rc 0
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    [ "$(json_value vertex_cap_reached)" = "true" ] || fail "the cap of 3 new vertices was not reached"
    [ "$(attempts_run)" = 1 ] || fail "refined again after stopping at the cap"
    faces=$(json_value faces)
    [ "$faces" -le 106 ] || fail "$faces faces from 100 with at most 3 new vertices"
    grep -q -- "--max-new-vertices" stderr || fail "the summary does not say which option raises the cap"
    run in_g.gtri -o out.gtri --min-angle 30 --max-new-vertices 0
    expect_usage_error
    ;;

same_output_twice)
    make_valid_gtri "$bob" --faces 100
    run in_g.gtri -o one.gtri --min-angle 25 --quiet
    expect_rc 0
    run in_g.gtri -o two.gtri --min-angle 25 --quiet --threads 1
    expect_rc 0
    cmp -s one.gtri two.gtri || fail "two runs wrote different files"
    ;;

error_invalid_input_g)
    make_valid_gtri "$bob" --faces 100
    # Turn every coarse face over: G is no longer valid, and refinement refuses it.
    awk '/^faces /{inside=1; print; next} /^edges /{inside=0} inside && NF==3 {print $3, $2, $1; next} {print}' \
        in_g.gtri >in_turned.gtri
    run in_turned.gtri -o out.gtri --faces 200
    expect_error_mentioning "not valid"
    expect_no_output
    ;;

error_truncated_gtri)
    make_valid_gtri "$tripod" --faces 20
    head -c 200 in_g.gtri >in_cut.gtri
    run in_cut.gtri -o out.gtri --faces 40
    expect_error_mentioning "in_cut.gtri"
    expect_no_output
    ;;

failure_keeps_the_old_output)
    make_valid_gtri "$tripod" --faces 20
    echo "old" >in_out.gtri
    : >in_empty.gtri
    run in_empty.gtri -o in_out.gtri --faces 40
    expect_rc 1
    [ "$(cat in_out.gtri)" = "old" ] || fail "the old output was changed"
    expect_no_output
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
