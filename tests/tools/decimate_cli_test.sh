#!/usr/bin/env bash
# Command-line tests of geotri-decimate: the real binary, its exit codes, messages and output files.
#
#   decimate_cli_test.sh BINARY TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes. ctest registers one test per case.

set -u

bin=$1
data=$2
case_name=$3
program=geotri-decimate
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

bob=$data/classic/bob_small.ply      # 250 vertices, 500 faces, closed, genus 1
tripod=$data/cad/tripod.off          # 24 vertices, 44 faces, genus 0
femur=$data/anatomy/femur_thing157696.stl

# off_counts FILE: "VERTICES FACES" from an OFF header.
off_counts() {
    sed -n 2p "$1" | awk '{ print $1, $2 }'
}

# Every vertex line of the OFF output appears, character for character, among the input's vertex lines (both are
# printed with %.17g, so equal text means equal doubles).
expect_vertices_from() {
    local nv
    nv=$(sed -n 2p "$2" | awk '{ print $1 }')
    sed -n "3,$((nv + 2))p" "$2" | sort -u >coarse_vertices.txt
    local fine_nv
    fine_nv=$(sed -n 2p "$1" | awk '{ print $1 }')
    sed -n "3,$((fine_nv + 2))p" "$1" | sort -u >fine_vertices.txt
    [ -z "$(comm -23 coarse_vertices.txt fine_vertices.txt)" ] || fail "coarse vertices that are not input vertices"
    rm -f coarse_vertices.txt fine_vertices.txt
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in INPUT --output --faces --vertices --ratio --coarsest --paths --no-backoff --json --quiet --threads \
        --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

version)
    run --version
    expect_rc 0
    grep -q -E '^geotri-decimate [0-9]+\.[0-9]+' stdout || fail "no version on stdout"
    ;;

usage_no_arguments)
    run
    expect_usage_error
    ;;

usage_paths_same_as_output)
    run "$bob" -o out.off --faces 60 --paths ./out.off
    expect_usage_error
    grep -q -- "--paths" stderr || fail "message does not name --paths"
    expect_no_output
    ;;

usage_output_is_the_input)
    # By another path too: nothing the user gave is overwritten.
    cp "$tripod" in_t.off
    run in_t.off -o ./in_t.off --faces 20
    expect_usage_error
    grep -q "is the INPUT" stderr || fail "message does not say that -o is the input"
    cmp -s in_t.off "$tripod" || fail "the input changed"
    expect_no_output
    ;;

usage_bad_counts_say_what_is_wanted)
    # Not CLI11's range up to the largest double, and no count beyond what an int index holds.
    run "$tripod" -o out.off --faces 0
    expect_usage_error
    grep -q -- "--faces: 0 is not above 0" stderr || fail "the message does not say that --faces must be above 0"
    run "$tripod" -o out.off --faces 18446744073709551616
    expect_usage_error
    grep -q "is above 2147483647" stderr || fail "the message does not give the largest count"
    run "$tripod" -o out.off --faces 20 --threads 65536
    expect_usage_error
    grep -q -- "--threads: 65536 is above 1024" stderr || fail "the message does not give the most threads"
    run "$tripod" -o out.off --faces 4.5
    expect_usage_error
    grep -q -- "--faces: '4.5' is not a whole number" stderr || fail "the message does not say that --faces is whole"
    expect_no_output
    ;;

paths_that_cannot_be_written_leave_no_coarse_mesh)
    # The coarse mesh and its paths appear together or not at all; an older coarse mesh stays.
    echo "previous" >out.off
    run "$tripod" -o out.off --faces 20 --paths no_such_folder/out.paths
    expect_error_about no_such_folder/out.paths
    [ "$(cat out.off)" = "previous" ] || fail "the coarse mesh was written without its paths"
    # A folder fails only where it is renamed to, after the coarse mesh: it is refused first.
    mkdir in_folder
    run "$tripod" -o out.off --faces 20 --paths in_folder
    expect_error_about in_folder
    [ "$(cat out.off)" = "previous" ] || fail "the coarse mesh was written without its paths (a folder)"
    [ -z "$(ls -A in_folder)" ] || fail "something was written into the folder"
    rm out.off
    expect_no_output
    ;;

edge_paths_are_written)
    # One line per coarse edge (3F/2 of them), each a path of fine vertices from its first coarse vertex's input
    # vertex to its second's.
    run "$bob" -o out.off --faces 60 --paths out.paths
    expect_rc 0
    read -r nv nf <<<"$(off_counts out.off)"
    head -n 1 out.paths | grep -q -x "geotri-edge-paths 1" || fail "no header line"
    sed -n 3p out.paths | grep -q -x "coarse $nv $((3 * nf / 2))" || fail "not 'coarse $nv $((3 * nf / 2))'"
    [ "$(tail -n +4 out.paths | wc -l)" -eq $((3 * nf / 2)) ] || fail "not one line per coarse edge"
    tail -n +4 out.paths | awk '{ if (NF != $3 + 3 || $3 < 2 || $1 >= $2) exit 1 }' || fail "a malformed edge line"
    ;;

usage_no_target)
    run "$bob" -o out.off
    expect_usage_error
    expect_no_output
    ;;

usage_two_targets)
    run "$bob" -o out.off --faces 100 --coarsest
    expect_usage_error
    expect_no_output
    ;;

usage_bad_ratio)
    run "$bob" -o out.off --ratio 1.5
    expect_usage_error
    run "$bob" -o out.off --ratio 0
    expect_usage_error
    expect_no_output
    ;;

usage_bad_faces)
    run "$bob" -o out.off --faces -3
    expect_usage_error
    run "$bob" -o out.off --faces many
    expect_usage_error
    expect_no_output
    ;;

usage_bad_output_extension)
    run "$bob" -o out.stl --faces 100
    expect_usage_error
    expect_no_output
    ;;

usage_missing_input)
    run no_such_mesh.off -o out.off --faces 100
    expect_usage_error
    grep -q "no_such_mesh.off" stderr || fail "message does not name the file"
    expect_no_output
    ;;

faces_off_exact)
    cp "$tripod" in_tripod.off
    run in_tripod.off -o out.off --faces 20
    expect_rc 0
    [ "$(off_counts out.off)" = "12 20" ] || fail "out.off has $(off_counts out.off), expected 12 vertices, 20 faces"
    grep -q "geotri-decimate: 24 vertices, 44 faces, 1 component -> 12 vertices, 20 faces" stderr ||
        fail "no summary on stderr"
    # The input is not written with %.17g: compare through a round trip of the input itself.
    run in_tripod.off -o full.off --ratio 1
    expect_rc 0
    expect_vertices_from full.off out.off
    ;;

coarsest_genus_one_and_json)
    run "$bob" -o out.obj --coarsest --json --quiet
    expect_rc 0
    [ ! -s stderr ] || fail "--quiet run wrote to stderr"
    [ "$(wc -l <stdout)" -eq 1 ] || fail "--json printed more than one line"
    grep -q '^{.*}$' stdout || fail "--json is not one object"
    for key in '"vertices": 250' '"faces": 500' '"components": 1' '"min_faces": 14' '"coarse_faces": ' \
               '"coarse_vertices": ' '"target_reached": ' '"decimate_seconds": '; do
        grep -q -- "$key" stdout || fail "--json lacks $key"
    done
    nv=$(grep -c '^v ' out.obj)
    nf=$(grep -c '^f ' out.obj)
    # Genus 1: F = 2V.
    [ "$nf" -eq $((2 * nv)) ] || fail "out.obj has $nv vertices and $nf faces: not a torus"
    ;;

vertices_ply_output)
    run "$femur" -o out.ply --vertices 50 --quiet --json
    expect_rc 0
    grep -a -q "^property double x$" out.ply || fail "the PLY does not hold doubles"
    grep -a -q "^element vertex 50$" out.ply || fail "not 50 vertices"
    grep -q '"target_reached": true' stdout || fail "target not reached"
    ;;

unreachable_target_says_so)
    run "$bob" -o out.off --faces 4
    expect_rc 0
    grep -q "not reached" stderr || fail "no word that the target was not reached"
    ;;

unreachable_target_is_traced_and_no_backoff_skips_that)
    # bob's coarsest mesh (18 faces) tangles too little to back off from: the same mesh either way.
    run "$bob" -o out.off --faces 4 --json
    expect_rc 0
    [ "$(json_value backed_off)" = false ] || fail "backed off from bob's coarsest mesh"
    [ "$(json_value faces_where_topology_stops)" = 18 ] || fail "not traced where the topology stops"
    [ "$(json_value tangled_where_topology_stops)" -gt 0 ] || fail "no tangles counted"
    grep -q "traced there" stderr || fail "no word of the tracing on stderr"
    mv out.off traced.off
    run "$bob" -o out.off --faces 4 --json --no-backoff
    expect_rc 0
    [ -z "$(json_value faces_where_topology_stops)" ] || fail "traced with --no-backoff"
    cmp -s out.off traced.off || fail "another mesh with --no-backoff"
    ;;

error_empty_file)
    : >in_empty.off
    run in_empty.off -o out.off --faces 10
    expect_error_about in_empty.off
    expect_no_output
    ;;

error_truncated_ply)
    head -c 5000 "$bob" >in_cut.ply
    run in_cut.ply -o out.off --faces 10
    expect_error_about in_cut.ply
    grep -q "truncated" stderr || fail "message does not say truncated"
    expect_no_output
    ;;

error_open_mesh)
    printf 'OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n' >in_open.off
    run in_open.off -o out.off --faces 2
    expect_error_about in_open.off
    grep -q "not closed (3 boundary edges)" stderr || fail "message does not count the boundary edges"
    expect_no_output
    ;;

error_non_manifold)
    # Two tetrahedra glued along the edge 0-1.
    printf 'OFF\n6 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 -1 0\n0 0 -1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n3 0 4 1\n3 0 1 5\n3 1 4 5\n3 0 5 4\n' >in_fin.off
    run in_fin.off -o out.off --faces 4
    expect_error_about in_fin.off
    grep -q "non-manifold" stderr || fail "message does not say non-manifold"
    expect_no_output
    ;;

error_nan_coordinate)
    printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 nan 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n' >in_nan.off
    run in_nan.off -o out.off --faces 4
    expect_error_about in_nan.off
    grep -q "vertex 2" stderr || fail "message does not name vertex 2"
    expect_no_output
    ;;

error_index_out_of_range)
    printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 4\n3 0 3 2\n' >in_index.off
    run in_index.off -o out.off --faces 4
    expect_error_about in_index.off
    grep -q "face 2" stderr || fail "message does not name face 2"
    expect_no_output
    ;;

error_unwritable_output)
    run "$bob" -o no_such_folder/out.off --faces 100
    expect_error_about no_such_folder/out.off
    expect_no_output
    ;;

failure_keeps_the_old_output)
    echo "previous" >out.off
    printf 'OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n' >in_open.off
    run in_open.off -o out.off --faces 2
    expect_rc 1
    [ "$(cat out.off)" = "previous" ] || fail "a failed run changed the existing output"
    rm out.off
    expect_no_output
    ;;

success_replaces_the_old_output_whole)
    head -c 100000 /dev/zero | tr '\0' 'x' >out.off
    run "$tripod" -o out.off --faces 20 --quiet
    expect_rc 0
    [ "$(off_counts out.off)" = "12 20" ] || fail "out.off has $(off_counts out.off)"
    grep -q x out.off && fail "old content left in the output"
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
