#!/usr/bin/env bash
# Command-line tests of geotri-distance: the real binary, its exit codes, messages and output files.
#
#   distance_cli_test.sh BINARY TEST_DATA_DIR CASE
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes. ctest registers one test per case.

set -u

bin=$1
data=$2
case_name=$3
program=geotri-distance
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

bob=$data/classic/bob_small.ply      # 250 vertices, 500 faces, closed, genus 1
tripod=$data/cad/tripod.off          # 24 vertices, 44 faces
femur=$data/anatomy/femur_thing157696.stl

# A flat 5 x 4 grid of unit squares in the plane z = 0 (open mesh): geodesic distances are Euclidean there.
write_grid() {
    {
        echo "OFF"
        echo "30 40 0"
        for j in 0 1 2 3 4; do
            for i in 0 1 2 3 4 5; do echo "$i $j 0"; done
        done
        for j in 0 1 2 3; do
            for i in 0 1 2 3 4; do
                a=$((j * 6 + i))
                echo "3 $a $((a + 1)) $((a + 7))"
                echo "3 $a $((a + 7)) $((a + 6))"
            done
        done
    } >"$1"
}

# check_lines FILE COUNT: FILE has COUNT lines, each a number or inf.
check_lines() {
    [ "$(wc -l <"$1")" -eq "$2" ] || fail "$1 has $(wc -l <"$1") lines, expected $2"
    grep -v -q -E '^(inf|-?[0-9.]+(e[-+]?[0-9]+)?)$' "$1" && fail "$1 has a line that is not a number"
    return 0
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in MESH --source --stop --max-distance --output --path-to --path-out --json --quiet --threads \
                  --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

version)
    run --version
    expect_rc 0
    grep -q -E '^geotri-distance [0-9]+\.[0-9]+' stdout || fail "no version on stdout"
    ;;

usage_no_arguments)
    run
    expect_usage_error
    ;;

usage_missing_source)
    run "$bob" -o out.txt
    expect_usage_error
    grep -q -- "--source" stderr || fail "message does not name --source"
    expect_no_output
    ;;

usage_missing_output)
    run "$bob" --source v:0
    expect_usage_error
    ;;

usage_bad_spec)
    run "$bob" --source x:3 -o out.txt
    expect_usage_error
    grep -q "x:3" stderr || fail "message does not show the bad spec"
    expect_no_output
    ;;

usage_bad_output_extension)
    run "$bob" --source v:0 -o out.xyz
    expect_usage_error
    expect_no_output
    ;;

usage_missing_mesh_file)
    run no_such_mesh.off --source v:0 -o out.txt
    expect_usage_error
    grep -q "no_such_mesh.off" stderr || fail "message does not name the file"
    expect_no_output
    ;;

usage_path_to_without_path_out)
    run "$bob" --source v:0 -o out.txt --path-to v:3
    expect_usage_error
    expect_no_output
    ;;

usage_bad_threads)
    run "$bob" --source v:0 -o out.txt --threads -2
    expect_usage_error
    ;;

usage_nan_max_distance)
    # A usage error, not a failure blamed on the mesh.
    run "$bob" --source v:0 -o out.txt --max-distance nan
    expect_usage_error
    grep -q -- "--max-distance: 'nan' is not a number" stderr || fail "the message does not say what is wrong"
    expect_no_output
    ;;

usage_outputs_are_the_mesh)
    cp "$tripod" in_t.off
    run in_t.off --source v:0 -o out.txt --path-to v:5 --path-out in_t.obj
    expect_rc 0  # another file: a different extension
    rm out.txt in_t.obj
    cp "$bob" in_b.ply
    run in_b.ply --source v:0 -o ./in_b.ply
    expect_usage_error
    grep -q "is the MESH" stderr || fail "message does not say that -o is the mesh"
    cmp -s in_b.ply "$bob" || fail "the mesh changed"
    expect_no_output
    ;;

path_that_cannot_be_written_leaves_no_distances)
    echo "previous" >out.txt
    run "$tripod" --source v:0 -o out.txt --path-to v:5 --path-out no_such_folder/path.obj
    expect_error_about no_such_folder/path.obj
    [ "$(cat out.txt)" = "previous" ] || fail "the distances were written without the path"
    rm out.txt
    expect_no_output
    ;;

usage_unknown_option)
    run "$bob" --source v:0 -o out.txt --frobnicate
    expect_usage_error
    ;;

source_after_positional_is_not_swallowed)
    # --source takes one value per occurrence: the mesh after it stays the positional argument.
    run --source v:0 "$bob" -o out.txt --quiet
    expect_rc 0
    check_lines out.txt 250
    ;;

flat_grid_is_euclidean)
    write_grid in_grid.off
    run in_grid.off --source v:0 -o out.txt --quiet
    expect_rc 0
    [ ! -s stderr ] || fail "--quiet run wrote to stderr"
    check_lines out.txt 30
    awk 'BEGIN { bad = 0 }
         { v = NR - 1; x = v % 6; y = int(v / 6); d = sqrt(x * x + y * y);
           if ($1 == "inf" || ($1 - d) > 1e-12 * (1 + d) || (d - $1) > 1e-12 * (1 + d)) {
               print "vertex " v ": " $1 " != " d; bad = 1 } }
         END { exit bad }' out.txt >mismatch || fail "distances differ from Euclidean: $(head -3 mismatch)"
    ;;

bob_txt_output)
    run "$bob" --source v:0 -o out.txt
    expect_rc 0
    check_lines out.txt 250
    [ "$(head -1 out.txt)" = "0" ] || fail "the source's distance is $(head -1 out.txt), not 0"
    grep -q inf out.txt && fail "a closed connected mesh has unreachable vertices"
    grep -q "geotri-distance: 250 vertices, 500 faces" stderr || fail "no summary on stderr"
    ;;

several_sources_and_edge_and_face_points)
    # Face 0 of bob_small.ply is (197, 38, 37).
    run "$bob" --source v:0 --source f:10:0.25,0.25,0.5 --source e:38,197:0.5 -o out.txt --quiet
    expect_rc 0
    check_lines out.txt 250
    [ "$(head -1 out.txt)" = "0" ] || fail "the first source's distance is not 0"
    ;;

ply_output_has_distance_property)
    run "$tripod" --source v:3 -o out.ply --quiet
    expect_rc 0
    grep -a -q "^property double distance$" out.ply || fail "no distance property in the PLY header"
    grep -a -q "^element vertex 24$" out.ply || fail "wrong vertex count"
    grep -a -q "^element face 44$" out.ply || fail "wrong face count"
    header=$(grep -a -b -m1 "^end_header$" out.ply | cut -d: -f1)
    size=$(stat -c %s out.ply)
    expected=$((header + 11 + 24 * 32 + 44 * 13))
    [ "$size" -eq "$expected" ] || fail "out.ply has $size bytes, expected $expected"
    ;;

stl_input)
    [ -f "$femur" ] || fail "missing $femur"
    run "$femur" --source v:0 -o out.txt --quiet
    expect_rc 0
    check_lines out.txt 1776
    ;;

max_distance_leaves_far_vertices_infinite)
    run "$bob" --source v:0 --max-distance 0.3 -o out.txt --quiet
    expect_rc 0
    check_lines out.txt 250
    grep -q inf out.txt || fail "no vertex beyond --max-distance"
    awk '$1 != "inf" && $1 > 0.3 { exit 1 }' out.txt || fail "a finite distance beyond --max-distance"
    ;;

stop_points_settle_their_distance)
    run "$bob" --source v:0 -o full.txt --quiet
    expect_rc 0
    run "$bob" --source v:0 --stop v:5 --stop v:9 -o out.txt --quiet
    expect_rc 0
    check_lines out.txt 250
    for v in 5 9; do
        [ "$(sed -n "$((v + 1))p" out.txt)" = "$(sed -n "$((v + 1))p" full.txt)" ] ||
            fail "stop vertex $v: $(sed -n "$((v + 1))p" out.txt) != $(sed -n "$((v + 1))p" full.txt)"
    done
    ;;

path_obj_and_json)
    run "$bob" --source v:0 -o out.txt --path-to v:120 --path-out path.obj --json --quiet
    expect_rc 0
    [ "$(wc -l <stdout)" -eq 1 ] || fail "--json printed more than one line"
    for key in '"vertices": 250' '"faces": 500' '"sources": 1' '"max_finite_distance": ' '"load_seconds": ' \
               '"propagation_seconds": ' '"windows_created": ' '"path_length": '; do
        grep -q -- "$key" stdout || fail "--json lacks $key"
    done
    grep -q '^{.*}$' stdout || fail "--json is not one object"
    points=$(grep -c '^v ' path.obj)
    [ "$points" -ge 2 ] || fail "path.obj has $points points"
    grep -q "^l 1 .* $points\$" path.obj || fail "path.obj has no polyline through every point"
    # The path's length equals the target's distance.
    length=$(sed -e 's/.*"path_length": \([^,}]*\).*/\1/' stdout)
    distance=$(sed -n 121p out.txt)
    awk -v a="$length" -v b="$distance" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-9 * (1 + b)) }' ||
        fail "path length $length != distance $distance"
    ;;

path_vtk)
    run "$tripod" --source v:0 -o out.txt --path-to v:20 --path-out path.vtk --quiet
    expect_rc 0
    head -1 path.vtk | grep -q "^# vtk DataFile Version" || fail "not a legacy VTK file"
    grep -q "^DATASET POLYDATA$" path.vtk || fail "not polydata"
    n=$(sed -n 's/^POINTS \([0-9]*\) double$/\1/p' path.vtk)
    [ -n "$n" ] && [ "$n" -ge 2 ] || fail "bad POINTS line"
    grep -q "^LINES 1 $((n + 1))$" path.vtk || fail "bad LINES line"
    ;;

error_empty_file)
    : >in_empty.off
    run in_empty.off --source v:0 -o out.txt
    expect_error_about in_empty.off
    grep -q "empty" stderr || fail "message does not say empty"
    expect_no_output
    ;;

error_truncated_ply)
    head -c 5000 "$bob" >in_cut.ply
    run in_cut.ply --source v:0 -o out.ply
    expect_error_about in_cut.ply
    grep -q "truncated" stderr || fail "message does not say truncated"
    expect_no_output
    ;;

error_truncated_stl)
    head -c 100000 "$femur" >in_cut.stl
    run in_cut.stl --source v:0 -o out.txt
    expect_error_about in_cut.stl
    grep -q "truncated" stderr || fail "message does not say truncated"
    expect_no_output
    ;;

error_nan_coordinate)
    printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 nan 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n' >in_nan.off
    run in_nan.off --source v:0 -o out.txt
    expect_error_about in_nan.off
    grep -q "vertex 2" stderr || fail "message does not name vertex 2"
    expect_no_output
    ;;

error_index_out_of_range)
    printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 4\n3 0 3 2\n' >in_index.off
    run in_index.off --source v:0 -o out.txt
    expect_error_about in_index.off
    grep -q "face 2" stderr || fail "message does not name face 2"
    expect_no_output
    ;;

error_non_triangle)
    printf 'OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n4 0 1 3 2\n' >in_quad.off
    run in_quad.off --source v:0 -o out.txt
    expect_error_about in_quad.off
    grep -q "face 1 has 4 vertices" stderr || fail "message does not name the quad"
    expect_no_output
    ;;

error_non_manifold)
    # Three triangles on the edge 0-1.
    printf 'OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n' >in_fin.off
    run in_fin.off --source v:0 -o out.txt
    expect_error_about in_fin.off
    expect_no_output
    ;;

error_source_out_of_range)
    run "$bob" --source v:250 -o out.txt
    expect_rc 1
    [ "$(wc -l <stderr)" -eq 1 ] || fail "stderr is not one line"
    grep -q "^geotri-distance: error: --source v:250: " stderr || fail "message does not name the source"
    expect_no_output
    ;;

error_unwritable_output)
    run "$bob" --source v:0 -o no_such_folder/out.txt
    expect_error_about no_such_folder/out.txt
    expect_no_output
    ;;

failure_keeps_the_old_output)
    echo "previous" >out.txt
    : >in_empty.off
    run in_empty.off --source v:0 -o out.txt
    expect_rc 1
    [ "$(cat out.txt)" = "previous" ] || fail "a failed run changed the existing output"
    rm out.txt
    expect_no_output
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
