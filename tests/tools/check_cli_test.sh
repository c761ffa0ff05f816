#!/usr/bin/env bash
# Command-line tests of geotri-check: the real binary, its exit codes (0 valid, 3 invalid, 1 bad input, 2 usage),
# its report and its --json summary. The .gtri inputs are made by the real geotri-decimate and geotri-trace.
#
#   check_cli_test.sh TOOLS_DIR TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes. ctest registers one test per case.

set -u

tools=$1
data=$2
case_name=$3
bin=$tools/geotri-check
program=geotri-check
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

tripod=$data/cad/tripod.off   # 24 vertices, 44 faces, genus 0: its coarsest G (a tetrahedron) is valid
cross=$data/cad/cross.off     # 40 vertices, 76 faces, genus 0

# make_coarsest_gtri MESH OUT: the coarsest G of MESH, traced, in OUT (with the fine mesh copied next to it).
make_coarsest_gtri() {
    cp "$1" "in_$(basename "$1")" || fail "cannot copy $1"
    "$tools/geotri-decimate" "in_$(basename "$1")" -o in_coarse.off --coarsest --quiet || fail "geotri-decimate failed"
    "$tools/geotri-trace" "in_$(basename "$1")" in_coarse.off -o "$2" --quiet || fail "geotri-trace failed"
}

# turn_over IN OUT: the same G with every coarse face turned over (its three vertex indices reversed).
turn_over() {
    awk '/^faces /{inside=1; print; next} /^edges /{inside=0} inside && NF==3 {print $3, $2, $1; next} {print}' \
        "$1" >"$2"
}

# json_field FILE KEY: the value of KEY in the JSON object on the first line of FILE (exits 1 if it does not parse).
json_field() {
    python3 -c 'import json,sys; d=json.loads(open(sys.argv[1]).readline()); print(json.dumps(d[sys.argv[2]]))' "$1" "$2"
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in IN --fine --json --quiet --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

version)
    run --version
    expect_rc 0
    grep -q -E '^geotri-check [0-9]+\.[0-9]+' stdout || fail "no version on stdout"
    ;;

usage_no_arguments)
    run
    expect_usage_error
    ;;

usage_missing_file)
    run no_such.gtri
    expect_usage_error
    grep -q "no_such.gtri" stderr || fail "message does not name the file"
    ;;

usage_missing_fine_override)
    make_coarsest_gtri "$tripod" in_g.gtri
    run in_g.gtri --fine no_such_mesh.off
    expect_usage_error
    ;;

usage_unknown_option)
    make_coarsest_gtri "$tripod" in_g.gtri
    run in_g.gtri --frobnicate
    expect_usage_error
    ;;

valid_exits_zero)
    make_coarsest_gtri "$tripod" in_g.gtri
    run in_g.gtri
    expect_rc 0
    head -n 1 stdout | grep -q "in_g.gtri: valid" || fail "report does not say valid"
    for c in 1 2 3 4; do
        grep -q "condition $c (.*): ok" stdout || fail "condition $c not reported ok"
    done
    grep -q "4 vertices, 6 edges, 4 faces, 1 component, genus 0" stdout || fail "wrong counts"
    grep -q "fine mesh: 24 vertices, 44 faces, 1 component, genus 0" stdout || fail "wrong counts of T"
    grep -q "violations:" stdout && fail "a valid G lists violations"
    ;;

valid_json_parses)
    make_coarsest_gtri "$cross" in_g.gtri
    run in_g.gtri --json
    expect_rc 0
    [ "$(wc -l <stdout)" -eq 1 ] || fail "--json is not one line"
    [ "$(json_field stdout valid)" = "true" ] || fail "valid is not true"
    for key in condition_1 condition_2 condition_3 condition_4; do
        [ "$(json_field stdout $key)" = "0" ] || fail "$key is not 0"
    done
    [ "$(json_field stdout vertices)" = "4" ] || fail "vertices is not 4"
    [ "$(json_field stdout faces)" = "4" ] || fail "faces is not 4"
    [ "$(json_field stdout genus)" = "0" ] || fail "genus is not 0"
    [ "$(json_field stdout fine_genus)" = "0" ] || fail "fine_genus is not 0"
    for key in min_corner_angle_deg max_corner_angle_deg min_edge_length mean_edge_length max_edge_length \
               patch_area fine_area; do
        json_field stdout $key >/dev/null || fail "no $key"
    done
    python3 - stdout <<'EOF' || fail "summary figures are inconsistent"
import json, sys
d = json.loads(open(sys.argv[1]).readline())
assert 0 < d["min_corner_angle_deg"] <= d["max_corner_angle_deg"] < 360
assert 0 < d["min_edge_length"] <= d["mean_edge_length"] <= d["max_edge_length"]
assert abs(d["patch_area"] - d["fine_area"]) <= 1e-9 * d["fine_area"]
EOF
    ;;

invalid_exits_three)
    make_coarsest_gtri "$tripod" in_g.gtri
    turn_over in_g.gtri in_turned.gtri
    run in_turned.gtri
    expect_rc 3
    head -n 1 stdout | grep -q "in_turned.gtri: INVALID" || fail "report does not say INVALID"
    grep -q "condition 2 (.*): 4 violations" stdout || fail "condition 2 does not count the 4 vertices"
    grep -q "^  \[2\] coarse vertex 0: .*wind 2 times" stdout || fail "coarse vertex 0 is not named"
    grep -q "{vertices 0; edges " stdout || fail "the offending elements are not listed"
    ;;

invalid_json_counts)
    make_coarsest_gtri "$tripod" in_g.gtri
    turn_over in_g.gtri in_turned.gtri
    run in_turned.gtri --json
    expect_rc 3
    [ "$(json_field stdout valid)" = "false" ] || fail "valid is not false"
    [ "$(json_field stdout condition_2)" = "4" ] || fail "condition_2 is not 4"
    [ "$(json_field stdout condition_1)" = "0" ] || fail "condition_1 is not 0"
    ;;

quiet_prints_nothing)
    make_coarsest_gtri "$tripod" in_g.gtri
    turn_over in_g.gtri in_turned.gtri
    run in_turned.gtri --quiet
    expect_rc 3
    [ ! -s stdout ] || fail "stdout is not empty"
    [ ! -s stderr ] || fail "stderr is not empty"
    run in_g.gtri --quiet
    expect_rc 0
    [ ! -s stdout ] && [ ! -s stderr ] || fail "output under --quiet"
    ;;

fine_override_finds_a_moved_mesh)
    make_coarsest_gtri "$tripod" in_g.gtri
    mkdir elsewhere && mv in_g.gtri elsewhere/
    run elsewhere/in_g.gtri
    expect_error_mentioning "elsewhere/in_g.gtri"
    run elsewhere/in_g.gtri --fine in_tripod.off
    expect_rc 0
    ;;

error_wrong_fine_mesh)
    make_coarsest_gtri "$tripod" in_g.gtri
    cp "$cross" in_other.off
    run in_g.gtri --fine in_other.off
    expect_error_mentioning "in_"
    ;;

error_empty_file)
    : >in_empty.gtri
    run in_empty.gtri
    expect_error_mentioning "in_empty.gtri"
    ;;

error_truncated_file)
    make_coarsest_gtri "$tripod" in_g.gtri
    head -c 300 in_g.gtri >in_cut.gtri
    run in_cut.gtri
    expect_error_mentioning "in_cut.gtri"
    ;;

error_not_a_gtri)
    cp "$tripod" in_mesh.gtri
    run in_mesh.gtri
    expect_error_mentioning "in_mesh.gtri"
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
