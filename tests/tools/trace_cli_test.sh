#!/usr/bin/env bash
# Command-line tests of geotri-trace: the real binary, its exit codes, messages and output files.
#
#   trace_cli_test.sh BINARY TEST_DATA_DIR CASE [CHECK_BINARY]
#
# Each CASE runs in a fresh temporary folder and exits 0 when it passes, 77 when it cannot run (ctest: skipped).
# The cases that read a .gtri back (moved or changed fine mesh, --fine) need a tool that reads .gtri files:
# CHECK_BINARY (geotri-check), when it is built.

set -u

bin=$1
data=$2
case_name=$3
check_bin=${4:-}
program=geotri-trace
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"

tripod=$data/cad/tripod.off   # 24 vertices, 44 faces, closed, genus 0
cross=$data/cad/cross.off     # 40 vertices, 76 faces, closed, genus 0

need_check() {
    if [ -z "$check_bin" ] || [ ! -x "$check_bin" ]; then
        echo "SKIP ($case_name): no tool that reads .gtri files (geotri-check) is built" >&2
        exit 77
    fi
}

# off_edit AWK_BODY FILE: runs AWK_BODY on an OFF file with k (the index among non-blank lines: 1 for OFF, 2 for
# the counts), nv and nf set; blank lines are dropped.
off_edit() {
    awk 'NF == 0 { next } { k++ } k == 2 { nv = $1; nf = $2 } '"$1"' { print }' "$2"
}

# A traced tripod: the coarse mesh is the fine mesh itself, so every coarse vertex is a fine vertex.
trace_tripod() {
    mkdir -p in_meshes out
    cp "$tripod" in_meshes/tripod.off
    run in_meshes/tripod.off in_meshes/tripod.off -o out/g.gtri --quiet
    expect_rc 0
}

# write_trivial_paths CHECKSUM FILE: the edge paths of the tripod traced onto itself: every coarse edge is one fine
# edge. CHECKSUM is the tripod's, as a .gtri of it records it.
write_trivial_paths() {
    awk 'NF == 0 { next } { k++ } k == 2 { nv = $1; nf = $2; next }
         k > 2 + nv && k <= 2 + nv + nf { for (i = 2; i <= 4; i++) { a = $i; b = $(i == 4 ? 2 : i + 1)
             if (a < b) print a, b } }' "$tripod" | sort -n -k1,1 -k2,2 > edges.txt
    local nv
    nv=$(awk 'NF == 0 { next } { k++ } k == 2 { print $1; exit }' "$tripod")
    { echo "geotri-edge-paths 1"; echo "fine $nv $1"; echo "coarse $nv $(wc -l < edges.txt)"
      awk '{ print $1, $2, 2, $1, $2 }' edges.txt; } > "$2"
    rm edges.txt
}

case "$case_name" in

help_lists_every_option)
    run --help
    expect_rc 0
    for option in FINE COARSE --output --paths --json --quiet --threads --version --help; do
        grep -q -- "$option" stdout || fail "--help does not mention $option"
    done
    ;;

version)
    run --version
    expect_rc 0
    grep -q -E '^geotri-trace [0-9]+\.[0-9]+' stdout || fail "no version on stdout"
    ;;

usage_no_arguments)
    run
    expect_usage_error
    ;;

usage_missing_output)
    run "$tripod" "$tripod"
    expect_usage_error
    expect_no_output
    ;;

usage_bad_output_extension)
    run "$tripod" "$tripod" -o out.off
    expect_usage_error
    grep -q "gtri" stderr || fail "message does not say .gtri"
    expect_no_output
    ;;

usage_missing_coarse_file)
    run "$tripod" no_such_coarse.off -o out.gtri
    expect_usage_error
    grep -q "no_such_coarse.off" stderr || fail "message does not name the file"
    expect_no_output
    ;;

usage_bad_threads)
    run "$tripod" "$tripod" -o out.gtri --threads -3
    expect_usage_error
    expect_no_output
    ;;

traces_and_reports)
    run "$cross" "$cross" -o out.gtri
    expect_rc 0
    [ ! -s stdout ] || fail "stdout is not empty without --json"
    head -n 1 out.gtri | grep -q -x "gtri 1" || fail "out.gtri does not start with 'gtri 1'"
    tail -n 1 out.gtri | grep -q -x "end" || fail "out.gtri does not end with 'end'"
    grep -q "propagations" stderr || fail "no propagation count on stderr"
    grep -q "largest move" stderr || fail "no location move on stderr"
    grep -q "valid geodesic triangulation" stderr || fail "no validity summary on stderr"
    grep -q -E "traced in [0-9.]+ s" stderr || fail "no time on stderr"
    grep -q -x "vertices 40" out.gtri || fail "not 40 coarse vertices"
    grep -q -x "faces 76" out.gtri || fail "not 76 coarse faces"
    grep -q -x "edges 114" out.gtri || fail "not 114 coarse edges"
    ;;

quiet_and_json)
    run "$cross" "$cross" -o out.gtri --quiet --json
    expect_rc 0
    [ ! -s stderr ] || fail "stderr is not empty with --quiet"
    [ "$(wc -l <stdout)" -eq 1 ] || fail "--json is not one line"
    for key in '"valid": true' '"propagations": ' '"largest_location_move": 0' '"faces": 76' '"edges": 114' '"trace_seconds": '; do
        grep -q -F "$key" stdout || fail "--json lacks $key"
    done
    ;;

moved_vertices_are_reported)
    # Every coarse vertex pushed off the surface by scaling the tripod by 1.01 about the origin.
    off_edit 'k > 2 && k <= 2 + nv { printf "%.17g %.17g %.17g\n", $1 * 1.01, $2 * 1.01, $3 * 1.01; next }' \
        "$tripod" >in_scaled.off
    run "$tripod" in_scaled.off -o out.gtri --json
    expect_rc 0
    grep -q -F '"moved_vertices": 24' stdout || fail "not every vertex moved"
    grep -q -E '"largest_location_move": [0-9]' stdout || fail "no largest move"
    grep -q -F '"largest_location_move": 0,' stdout && fail "largest move is 0"
    grep -q "moved onto the fine mesh, the largest by" stderr || fail "the move is not reported on stderr"
    ;;

threads_give_identical_files)
    run "$cross" "$cross" -o t1.gtri --threads 1 --quiet
    expect_rc 0
    run "$cross" "$cross" -o t2.gtri --threads 2 --quiet
    expect_rc 0
    run "$cross" "$cross" -o t4.gtri --threads 4 --quiet
    expect_rc 0
    cmp -s t1.gtri t2.gtri || fail "2 threads differ from 1"
    cmp -s t1.gtri t4.gtri || fail "4 threads differ from 1"
    ;;

fine_path_is_relative_to_the_output)
    trace_tripod
    grep -q -x "fine ../in_meshes/tripod.off" out/g.gtri || fail "the fine path is not ../in_meshes/tripod.off"
    ;;

moved_fine_mesh_is_found)
    need_check
    trace_tripod
    mkdir moved
    mv in_meshes out moved/
    "$check_bin" moved/out/g.gtri --json >stdout 2>stderr
    rc=$?
    [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || fail "geotri-check could not read the moved files (exit $rc)"
    ;;

changed_fine_mesh_is_refused)
    need_check
    trace_tripod
    off_edit 'k == 3 { $1 = $1 + 0.001 }' "$tripod" >in_meshes/tripod.off  # the first vertex moves
    "$check_bin" out/g.gtri >stdout 2>stderr
    rc=$?
    expect_error_about out/g.gtri geotri-check
    grep -q "not the one this file was made on" stderr || fail "message does not say the fine mesh changed"
    ;;

fine_override)
    need_check
    trace_tripod
    mv in_meshes/tripod.off in_elsewhere.off
    "$check_bin" out/g.gtri >stdout 2>stderr
    rc=$?
    expect_error_about out/g.gtri geotri-check
    grep -q -- "--fine" stderr || fail "message does not mention --fine"
    "$check_bin" out/g.gtri --fine in_elsewhere.off >stdout 2>stderr
    rc=$?
    [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || fail "--fine did not find the fine mesh (exit $rc)"
    ;;

error_empty_coarse)
    : >in_empty.off
    run "$tripod" in_empty.off -o out.gtri
    expect_error_about in_empty.off
    expect_no_output
    ;;

error_truncated_coarse)
    head -c 300 "$tripod" >in_cut.off
    run "$tripod" in_cut.off -o out.gtri
    expect_error_about in_cut.off
    expect_no_output
    ;;

error_open_coarse)
    # The tripod without its last face.
    off_edit 'k == 2 { print $1, $2 - 1, $3; next } k == 2 + nv + nf { next }' "$tripod" >in_open.off
    run "$tripod" in_open.off -o out.gtri
    expect_error_about in_open.off
    grep -q "not closed (3 boundary edges)" stderr || fail "message does not say not closed"
    expect_no_output
    ;;

error_open_fine)
    off_edit 'k == 2 { print $1, $2 - 1, $3; next } k == 2 + nv + nf { next }' "$tripod" >in_open.off
    run in_open.off "$tripod" -o out.gtri
    expect_error_about in_open.off
    grep -q "not closed" stderr || fail "message does not say not closed"
    expect_no_output
    ;;

error_nan_coarse)
    off_edit 'k == 3 { $1 = "nan" }' "$tripod" >in_nan.off
    run "$tripod" in_nan.off -o out.gtri
    expect_error_about in_nan.off
    expect_no_output
    ;;

error_huge_coarse_coordinate)
    # Read exactly, but beyond what the geometry can square: refused, naming the coarse mesh.
    off_edit 'k == 3 { $1 = "1e300" }' "$tripod" >in_huge.off
    run "$tripod" in_huge.off -o out.gtri
    expect_error_about in_huge.off
    grep -q "beyond" stderr || fail "the message does not say what is wrong"
    expect_no_output
    ;;

error_index_out_of_range)
    off_edit 'k == 2 + nv + nf { $4 = 99 }' "$tripod" >in_index.off
    run "$tripod" in_index.off -o out.gtri
    expect_error_about in_index.off
    expect_no_output
    ;;

error_coarse_on_another_mesh)
    # The cross's vertices land on the tripod somewhere, but two of them may land on one point, or all on one
    # component: either way the tripod traced with a coarse mesh from elsewhere must work or fail cleanly.
    run "$tripod" "$cross" -o out.gtri
    if [ "$rc" -ne 0 ]; then
        expect_error_about "$cross"
        expect_no_output
    fi
    ;;

error_coarse_of_another_genus)
    # A tetrahedron on Bob, who has a handle: no G with that connectivity can ever be valid, so trace refuses it.
    # Its corners are four of the vertices of Bob's coarsest decimation, made by the geotri-decimate built beside.
    decimate=$(dirname "$bin")/geotri-decimate
    if [ ! -x "$decimate" ]; then
        echo "SKIP ($case_name): no geotri-decimate beside $bin" >&2
        exit 77
    fi
    cp "$data/classic/bob_small.ply" in_bob.ply
    "$decimate" in_bob.ply -o in_coarsest.off --coarsest --quiet || fail "geotri-decimate failed"
    awk 'NR == 1 { print; print "4 4 0" } NR == 3 || NR == 6 || NR == 9 || NR == 11 { print }
         END { print "3 0 1 2"; print "3 0 2 3"; print "3 0 3 1"; print "3 1 3 2" }' in_coarsest.off >in_tetrahedron.off
    run in_bob.ply in_tetrahedron.off -o out.gtri
    expect_error_about in_tetrahedron.off
    grep -q "genus 0 but the fine mesh has genus 1" stderr || fail "stderr does not name the two genera"
    expect_no_output
    ;;

edge_paths_are_used)
    trace_tripod
    write_trivial_paths "$(sed -n 's/^fine_checksum //p' out/g.gtri)" in_tripod.paths
    run in_meshes/tripod.off in_meshes/tripod.off --paths in_tripod.paths -o out/p.gtri --json
    expect_rc 0
    [ "$(json_value class_geodesics_differing)" = 0 ] || fail "one fine edge is its own class geodesic"
    [ "$(json_value class_geodesics_kept)" = false ] || fail "class geodesics kept on a valid G"
    grep -q "decimation's class" stderr || fail "no class summary on stderr"
    ;;

error_edge_paths_of_another_mesh)
    trace_tripod
    write_trivial_paths 0123456789abcdef in_tripod.paths
    rm -f out/g.gtri
    run in_meshes/tripod.off in_meshes/tripod.off --paths in_tripod.paths -o out/g.gtri
    expect_error_about in_tripod.paths
    grep -q "another fine mesh" stderr || fail "message does not say another fine mesh"
    [ -z "$(ls -A out)" ] || fail "files left in out/: $(ls -A out)"
    ;;

error_edge_path_through_a_coarse_vertex)
    # The path of the first face's first edge (i, j) detours through the face's third corner k, a coarse vertex.
    trace_tripod
    write_trivial_paths "$(sed -n 's/^fine_checksum //p' out/g.gtri)" in_trivial.paths
    read -r i j k <<<"$(awk 'NF == 0 { next } { n++ } n == 2 { nv = $1 } n == 3 + nv { print $2, $3, $4; exit }' \
                           "$tripod")"
    a=$((i < j ? i : j)) b=$((i < j ? j : i))
    awk -v a="$a" -v b="$b" -v k="$k" '$1 == a && $2 == b && NF == 5 { print a, b, 3, a, k, b; next } { print }' \
        in_trivial.paths >in_tripod.paths
    rm -f out/g.gtri
    run in_meshes/tripod.off in_meshes/tripod.off --paths in_tripod.paths -o out/g.gtri
    expect_error_about in_tripod.paths
    grep -q "the path of coarse edge ($a, $b) passes through coarse vertex $k" stderr ||
        fail "message does not name the edge and the coarse vertex"
    grep -q straighten stderr && fail "the message names an internal function"
    [ -z "$(ls -A out)" ] || fail "files left in out/: $(ls -A out)"
    ;;

error_truncated_edge_paths)
    trace_tripod
    write_trivial_paths "$(sed -n 's/^fine_checksum //p' out/g.gtri)" in_full.paths
    head -n 10 in_full.paths > in_tripod.paths
    rm -f out/g.gtri
    run in_meshes/tripod.off in_meshes/tripod.off --paths in_tripod.paths -o out/g.gtri
    expect_error_about in_tripod.paths
    grep -q "truncated" stderr || fail "message does not say truncated"
    ;;

error_unwritable_output)
    run "$tripod" "$tripod" -o no_such_folder/out.gtri
    expect_error_about no_such_folder/out.gtri
    expect_no_output
    ;;

failure_keeps_the_old_output)
    echo "previous" >out.gtri
    : >in_empty.off
    run "$tripod" in_empty.off -o out.gtri
    expect_rc 1
    [ "$(cat out.gtri)" = "previous" ] || fail "a failed run changed the existing output"
    rm out.gtri
    expect_no_output
    ;;

*)
    fail "unknown case"
    ;;
esac
exit 0
