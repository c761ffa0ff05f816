#!/usr/bin/env bash
# Command-line tests of geotri-overlay: the real binary, its exit codes, messages and output files.
#
#   overlay_cli_test.sh OVERLAY TRACE DECIMATE TEST_DATA_DIR CASE
#
# The .gtri inputs are made by the real geotri-trace (and geotri-decimate). Each CASE runs in a fresh temporary
# folder and exits 0 when it passes. ctest registers one test per case.

set -u

bin=$1
trace=$2
decimate=$3
data=$4
case_name=$5
program=geotri-overlay
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

bob=$data/classic/bob_small.ply      # 250 vertices, 500 faces, closed, genus 1

# The unit cube, each side split into two triangles, some along the diagonal that the tetrahedron of alternate
# corners (0,0,0), (1,1,0), (1,0,1), (0,1,1) uses and some along the other one. Its geodesics are the six side
# diagonals, so G is valid and each patch (a corner of the cube and three half sides) has area 1.5.
write_cube_and_tetrahedron() {
    cat >in_cube.off <<'EOF'
OFF
8 12 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
3 0 2 1
3 0 3 2
3 4 5 6
3 4 6 7
3 0 1 5
3 0 5 4
3 3 7 6
3 3 6 2
3 1 2 5
3 2 6 5
3 0 4 3
3 4 7 3
EOF
    cat >in_tet.off <<'EOF'
OFF
4 4 0
0 0 0
1 1 0
1 0 1
0 1 1
3 0 1 2
3 0 3 1
3 0 2 3
3 1 3 2
EOF
    "$trace" in_cube.off in_tet.off -o in_tet.gtri --quiet || fail "geotri-trace failed"
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in --output --curves --fine --quiet --json --threads --version; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

version)
    run --version
    expect_rc 0
    grep -q -E '[0-9]+\.[0-9]+' stdout || fail "no version number"
    ;;

usage_no_arguments)
    run
    expect_usage_error
    ;;

usage_missing_output)
    write_cube_and_tetrahedron
    run in_tet.gtri
    expect_usage_error
    expect_no_output
    ;;

usage_bad_output_extension)
    write_cube_and_tetrahedron
    run in_tet.gtri -o out.stl
    expect_usage_error
    expect_no_output
    ;;

usage_bad_curves_extension)
    write_cube_and_tetrahedron
    run in_tet.gtri -o out.vtu --curves curves.ply
    expect_usage_error
    expect_no_output
    ;;

usage_missing_input_file)
    run no_such.gtri -o out.vtu
    expect_usage_error
    expect_no_output
    ;;

cube_tetrahedron_is_valid)
    write_cube_and_tetrahedron
    run in_tet.gtri -o out.vtu --json
    expect_rc 0
    [ "$(wc -l <stdout)" -eq 1 ] || fail "the JSON summary is not one line"
    [ "$(json_value valid)" = "true" ] || fail "G is valid, the overlay says otherwise"
    [ "$(json_value good_patches)" = "4" ] || fail "expected 4 good patches"
    [ "$(json_value bad_patches)" = "0" ] || fail "expected no bad patch"
    [ "$(json_value regions)" = "4" ] || fail "expected 4 regions"
    [ "$(json_value colours)" = "4" ] || fail "four mutually adjacent patches need four colours"
    [ "$(json_value fine_area)" = "6" ] || fail "the cube's area is 6"
    awk -v e="$(json_value relative_area_error)" 'BEGIN { exit !(e < 1e-9) }' || fail "patch areas do not add up"
    grep -q '^geotri-overlay: .* 4 of 4 patches are disks' stderr || fail "no patch summary on stderr"
    ;;

writes_every_format)
    write_cube_and_tetrahedron
    for ext in vtu ply obj; do
        run in_tet.gtri -o "out.$ext" --quiet
        expect_rc 0
        [ -s "out.$ext" ] || fail "no out.$ext"
    done
    grep -q 'Name="patch"' out.vtu || fail ".vtu has no patch array"
    grep -q 'Name="fine_face"' out.vtu || fail ".vtu has no fine_face array"
    grep -q 'Name="colour"' out.vtu || fail ".vtu has no colour array"
    grep -q '^property uchar red$' out.ply || fail ".ply has no face colours"
    [ "$(grep -c '^g patch_' out.obj)" -eq 4 ] || fail ".obj has not 4 patch groups"
    # Every triangle of the .ply, and every patch's triangles in the .obj, add up to the 6 sides' area.
    faces=$(sed -n 's/^element face //p' out.ply)
    [ "$(grep -c '^f ' out.obj)" -eq "$faces" ] || fail ".obj and .ply differ in triangle count"
    for ext in vtp vtk obj; do
        run in_tet.gtri -o out.vtu --curves "curves.$ext" --quiet
        expect_rc 0
        [ -s "curves.$ext" ] || fail "no curves.$ext"
    done
    grep -q 'Name="edge"' curves.vtp || fail ".vtp has no edge array"
    grep -q '^LINES 6 ' curves.vtk || fail ".vtk does not hold 6 polylines"
    [ "$(grep -c '^l ' curves.obj)" -eq 6 ] || fail ".obj does not hold 6 polylines"
    [ "$(grep -c '^o edge_' curves.obj)" -eq 6 ] || fail ".obj does not name the 6 edges"
    ;;

quiet_prints_nothing)
    write_cube_and_tetrahedron
    run in_tet.gtri -o out.vtu --quiet
    expect_rc 0
    [ ! -s stdout ] && [ ! -s stderr ] || fail "--quiet printed something"
    ;;

fine_override)
    write_cube_and_tetrahedron
    mkdir moved
    mv in_cube.off moved/cube.off
    run in_tet.gtri -o out.vtu
    expect_rc 1
    rm -f stdout stderr
    run in_tet.gtri -o out.vtu --fine moved/cube.off --json
    expect_rc 0
    [ "$(json_value valid)" = "true" ] || fail "the overlay with --fine is not valid"
    rm -rf moved out.vtu
    ;;

reversed_coarse_mesh_makes_every_patch_bad)
    # The same tetrahedron with its faces turned inwards: each path has the wrong patch on its left.
    write_cube_and_tetrahedron
    sed -i 's/^3 \([0-9]\) \([0-9]\) \([0-9]\)$/3 \1 \3 \2/' in_tet.off
    "$trace" in_cube.off in_tet.off -o in_tet.gtri --quiet || fail "geotri-trace failed"
    run in_tet.gtri -o out.vtu --json
    expect_rc 0
    [ "$(json_value bad_patches)" = "4" ] || fail "expected 4 bad patches"
    [ "$(json_value valid)" = "false" ] || fail "a reversed G is not valid"
    grep -q "4 bad patches (coarse faces): 0 1 2 3" stderr || fail "bad patches are not named"
    ;;

invalid_g_is_reported_and_written)
    # bob (genus 1) decimated to the coarsest torus and traced: whatever its validity, the overlay is written, its
    # pieces cover T, and the summary counts what it found.
    "$decimate" "$bob" -o in_coarse.off --coarsest --quiet || fail "geotri-decimate failed"
    "$trace" "$bob" in_coarse.off -o in_bob.gtri --quiet || fail "geotri-trace failed"
    run in_bob.gtri -o out.ply --curves curves.vtk --json
    expect_rc 0
    [ -s out.ply ] && [ -s curves.vtk ] || fail "outputs missing"
    bad=$(json_value bad_patches)
    good=$(json_value good_patches)
    faces=$(json_value coarse_faces)
    [ $((bad + good)) -eq "$faces" ] || fail "good and bad patches do not add up to the coarse faces"
    if [ "$bad" -gt 0 ]; then
        grep -q "bad patches (coarse faces):" stderr || fail "bad patches are not named"
        [ "$(json_value valid)" = "false" ] || fail "bad patches but valid"
    fi
    ;;

error_empty_gtri)
    : >in_empty.gtri
    run in_empty.gtri -o out.vtu
    expect_error_about in_empty.gtri
    expect_no_output
    ;;

error_truncated_gtri)
    write_cube_and_tetrahedron
    head -c $(($(wc -c <in_tet.gtri) / 2)) in_tet.gtri >in_half.gtri
    run in_half.gtri -o out.vtu
    expect_error_about in_half.gtri
    expect_no_output
    ;;

error_unwritable_output)
    write_cube_and_tetrahedron
    run in_tet.gtri -o no_such_folder/out.vtu
    expect_error_about no_such_folder/out.vtu
    expect_no_output
    ;;

usage_output_is_the_fine_mesh_or_the_other_output)
    # The fine mesh that the .gtri names is an input too, and it must stay whole: the .gtri holds its checksum.
    write_cube_and_tetrahedron
    "$decimate" in_cube.off -o in_cube.obj --ratio 1 --quiet || fail "geotri-decimate failed"
    "$trace" in_cube.obj in_tet.off -o in_obj.gtri --quiet || fail "geotri-trace failed"
    cp in_cube.obj in_cube_before.obj
    run in_obj.gtri -o ./in_cube.obj
    expect_usage_error
    grep -q "is the fine mesh" stderr || fail "message does not say that -o is the fine mesh"
    cmp -s in_cube.obj in_cube_before.obj || fail "the fine mesh changed"
    run in_tet.gtri -o out.obj --curves out.obj
    expect_usage_error
    grep -q "name the same file" stderr || fail "message does not say that both outputs are one file"
    expect_no_output
    ;;

curves_that_cannot_be_written_leave_no_overlay)
    write_cube_and_tetrahedron
    echo "previous" >out.vtu
    run in_tet.gtri -o out.vtu --curves no_such_folder/out.vtp
    expect_error_about no_such_folder/out.vtp
    [ "$(cat out.vtu)" = "previous" ] || fail "the overlay was written without its curves"
    rm out.vtu
    expect_no_output
    ;;

failure_keeps_the_old_output)
    echo "previous" >out.vtu
    : >in_empty.gtri
    run in_empty.gtri -o out.vtu
    expect_rc 1
    [ "$(cat out.vtu)" = "previous" ] || fail "a failed run changed the existing output"
    rm out.vtu
    expect_no_output
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
