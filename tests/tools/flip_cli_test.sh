#!/usr/bin/env bash
# Command-line tests of geotri-flip: the real binary, its exit codes (0 valid output, 3 written but invalid, 1 bad
# input, 2 usage), its summary and its output. The .gtri inputs are made by the real geotri-decimate and
# geotri-trace, and the outputs are judged by the real geotri-check.
#
#   flip_cli_test.sh TOOLS_DIR TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes. ctest registers one test per case.

set -u

tools=$1
data=$2
case_name=$3
bin=$tools/geotri-flip
program=geotri-flip
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

tripod=$data/cad/tripod.off                  # genus 0: its coarsest G (a tetrahedron) is valid
femur=$data/anatomy/femur_thing157696.stl    # at 320 faces, its traced G is invalid and flips make it valid
anchor=$data/cad/anchor.off                  # genus 4: at 320 faces, untangling needs fork splits too; at its
                                             # coarsest, traced by shortest geodesics, it is left invalid
joint=$data/cad/joint.off                    # at its coarsest, traced by shortest geodesics, only the last resorts
                                             # of untangling make it valid

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in IN --output --criterion --thorough --fine --json --quiet --threads --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

version)
    run --version
    expect_rc 0
    grep -q -E '^geotri-flip [0-9]+\.[0-9]+' stdout || fail "no version on stdout"
    ;;

usage_no_arguments)
    run
    expect_usage_error
    ;;

usage_missing_output)
    make_gtri "$tripod" --coarsest
    run in_g.gtri
    expect_usage_error
    expect_no_output
    ;;

usage_bad_output_extension)
    make_gtri "$tripod" --coarsest
    run in_g.gtri -o out.off
    expect_usage_error
    grep -q "gtri" stderr || fail "message does not say .gtri"
    expect_no_output
    ;;

usage_bad_criterion)
    make_gtri "$tripod" --coarsest
    run in_g.gtri -o out.gtri --criterion delaunay
    expect_usage_error
    grep -q "criterion" stderr || fail "message does not name --criterion"
    expect_no_output
    ;;

usage_missing_input_file)
    run in_nothing.gtri -o out.gtri
    expect_usage_error
    grep -q "in_nothing.gtri" stderr || fail "message does not name the file"
    expect_no_output
    ;;

usage_output_is_the_input)
    make_gtri "$tripod" --faces 20
    cp in_g.gtri in_before.gtri
    run in_g.gtri -o ./in_g.gtri
    expect_usage_error
    grep -q "is the IN" stderr || fail "message does not say that -o is the input"
    cmp -s in_g.gtri in_before.gtri || fail "the input changed"
    expect_no_output
    ;;

valid_g_stays_valid)
    make_gtri "$tripod" --faces 20
    check in_g.gtri || fail "the traced tripod is not valid to begin with"
    run in_g.gtri -o out.gtri
    expect_rc 0
    [ ! -s stdout ] || fail "stdout is not empty without --json"
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    grep -q "corner angles before: min" stderr || fail "no angles before on stderr"
    grep -q "corner angles after:  min" stderr || fail "no angles after on stderr"
    grep -q "after: valid" stderr || fail "stderr does not say valid"
    ;;

untangles_an_invalid_g)
    make_gtri "$femur" --faces 320
    check in_g.gtri && fail "the traced femur is valid: this case needs an invalid one"
    run in_g.gtri -o out.gtri --json --quiet
    expect_rc 0
    [ ! -s stderr ] || fail "stderr is not empty with --quiet"
    [ "$(json_value valid_before)" = "false" ] || fail "valid_before is not false"
    [ "$(json_value valid)" = "true" ] || fail "valid is not true"
    [ "$(json_value untangle_flips)" -gt 0 ] || fail "no untangle flips counted"
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    ;;

json_summary_and_angles)
    make_gtri "$tripod" --faces 20
    run in_g.gtri -o out.gtri --json --quiet
    expect_rc 0
    [ "$(wc -l <stdout)" -eq 1 ] || fail "the JSON summary is not one line"
    for key in valid_before valid improve_flips untangle_flips refused_bad_corner refused_leaves_region \
               min_corner_angle_deg_before min_corner_angle_deg mean_corner_angle_deg max_corner_angle_deg; do
        grep -q "\"$key\"" stdout || fail "no $key in the summary"
    done
    awk -v a="$(json_value min_corner_angle_deg_before)" -v b="$(json_value min_corner_angle_deg)" \
        'BEGIN { exit !(b >= a) }' || fail "the minimum corner angle went down"
    ;;

length_criterion)
    make_gtri "$tripod" --faces 20
    run in_g.gtri -o out.gtri --criterion length --json --quiet
    expect_rc 0
    [ "$(json_value criterion)" = "length" ] || fail "criterion is not length"
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    ;;

threads_give_identical_files)
    # Untangling tries its moves a batch per thread at a time, and improving evaluates flips in parallel.
    for mesh in "$femur" "$anchor"; do
        make_gtri "$mesh" --faces 320
        "$bin" in_g.gtri -o one.gtri --threads 1 --quiet --json >one.json
        for threads in 2 3; do
            "$bin" in_g.gtri -o more.gtri --threads $threads --quiet --json >more.json
            cmp -s one.gtri more.gtri || fail "$(basename "$mesh"): 1 and $threads threads give different files"
            # All but the times and the output's name.
            figures() { sed -e 's/"[a-z_]*seconds": [0-9.e+-]*//g' -e 's/"output": "[a-z]*.gtri"//' "$1"; }
            diff <(figures one.json) <(figures more.json) >/dev/null ||
                fail "$(basename "$mesh"): 1 and $threads threads give different summaries"
        done
    done
    grep -q '"untangle_fork_splits": [1-9]' one.json || fail "the anchor is untangled without fork splits"
    ;;

still_invalid_exits_three_and_is_written)
    # The anchor at the coarsest level its genus allows: untangling gets stuck, with too many violations left for its
    # last resorts, and without the bisections that go on from there and mend it (docs/algorithms.md, §5).
    make_gtri "$anchor" --coarsest
    run in_g.gtri -o out.gtri --bisection-rounds 0
    expect_rc 3
    [ -s out.gtri ] || fail "out.gtri is not written"
    grep -q "still invalid" stderr || fail "stderr does not say that the output is still invalid"
    grep -q "more faces" stderr || fail "stderr does not suggest a coarse mesh with more faces"
    check out.gtri
    [ $? -eq 3 ] || fail "geotri-check does not find out.gtri invalid"
    ;;

last_resorts_mend_the_joint_by_default)
    # Stuck after every other move, the joint at its coarsest is mended by a collapse judged after untangling what
    # it leaves, which runs by default, within the last resorts' budget (1e8 windows); --thorough 0 leaves it
    # invalid without the bisections that come after the last resorts, and its last resorts (pairs of flips, wider
    # moves) do less work.
    make_gtri "$joint" --coarsest
    run in_g.gtri -o out.gtri --json --quiet
    expect_rc 0
    [ "$(json_value last_resorts_tried)" = "true" ] || fail "last_resorts_tried is not true"
    thorough_work=$(json_value thorough_windows)
    [ "$thorough_work" -gt 0 ] || fail "no work counted for the last resorts"
    [ "$(json_value thorough_budget_spent)" = "false" ] || fail "the budget is spent on the joint"
    check out.gtri || fail "geotri-check finds out.gtri invalid"
    run in_g.gtri -o plain.gtri --thorough 0 --bisection-rounds 0 --json --quiet
    expect_rc 3
    [ "$(json_value thorough_windows)" -lt "$thorough_work" ] ||
        fail "--thorough 0 counts as much work for the last resorts as level 2"
    ;;

error_empty_gtri)
    : >in_empty.gtri
    run in_empty.gtri -o out.gtri
    expect_error_mentioning "in_empty.gtri"
    expect_no_output
    ;;

error_truncated_gtri)
    make_gtri "$tripod" --coarsest
    head -c 200 in_g.gtri >in_cut.gtri
    run in_cut.gtri -o out.gtri
    expect_error_mentioning "in_cut.gtri"
    expect_no_output
    ;;

error_unwritable_output)
    make_gtri "$tripod" --coarsest
    run in_g.gtri -o no_such_folder/out.gtri
    expect_error_mentioning "no_such_folder/out.gtri"
    expect_no_output
    ;;

failure_keeps_the_old_output)
    make_gtri "$tripod" --coarsest
    echo "old" >in_out.gtri
    : >in_empty.gtri
    run in_empty.gtri -o in_out.gtri
    expect_rc 1
    [ "$(cat in_out.gtri)" = "old" ] || fail "the old output was changed"
    expect_no_output
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
