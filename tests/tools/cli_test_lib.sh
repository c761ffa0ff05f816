# Shared by the *_cli_test.sh scripts; sourced, not run. Before sourcing it, a script sets:
#   program    the tool under test, as it names itself in messages (geotri-flip)
#   bin        the path of its binary
#   case_name  the case to run
# Sourcing makes a fresh temporary folder, removed on exit, and moves into it. A case passes when its script
# exits 0.

work=$(mktemp -d "${TMPDIR:-/tmp}/${program//-/_}_${case_name}.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

# fail MESSAGE: the case fails, with what the tool printed.
fail() {
    echo "FAIL ($case_name): $*" >&2
    for f in stdout stderr; do
        if [ -s "$f" ]; then
            echo "--- $f:" >&2
            head -c 3000 "$f" >&2
        fi
    done
    exit 1
}

# run ARGS...: runs the tool, keeping its exit code in $rc and its output in ./stdout and ./stderr.
run() {
    "$bin" "$@" >stdout 2>stderr
    rc=$?
}

expect_rc() {
    [ "$rc" -eq "$1" ] || fail "exit code $rc, expected $1"
}

# expect_one_error_line PREFIX: exit 1, one line on stderr that starts with PREFIX, nothing on stdout.
expect_one_error_line() {
    expect_rc 1
    [ "$(wc -l <stderr)" -eq 1 ] || fail "stderr is not one line"
    [[ "$(cat stderr)" == "$1"* ]] || fail "stderr does not start with '$1'"
    [ ! -s stdout ] || fail "stdout is not empty"
}

# expect_error_about FILE [PROGRAM]: the one-line error of PROGRAM (default: the tool under test) names FILE first.
expect_error_about() {
    expect_one_error_line "${2:-$program}: error: $1: "
}

# expect_error_mentioning TEXT: the one-line error holds TEXT.
expect_error_mentioning() {
    expect_one_error_line "$program: error: "
    grep -q -F -- "$1" stderr || fail "stderr does not mention '$1'"
}

# expect_usage_error: exit 2, and one line on stderr.
expect_usage_error() {
    expect_rc 2
    [ "$(wc -l <stderr)" -eq 1 ] || fail "stderr is not one line"
    grep -q "^$program: error: " stderr || fail "stderr does not start with '$program: error: '"
}

# expect_no_output: nothing but the inputs (in_*), the logs and the names listed in $keep is left in the folder
# (no output, no temporary file).
expect_no_output() {
    local extra
    extra=$(ls -A | grep -v -x -e stdout -e stderr -e 'in_.*' ${keep:+-e "$keep"})
    [ -z "$extra" ] || fail "files left behind: $extra"
}

# json_value KEY: the value of KEY in the one-line JSON summary on stdout, strings without their quotes.
json_value() {
    sed -n 's/.*"'"$1"'": *\([^,}]*\).*/\1/p' stdout | tr -d '"'
}

# For the scripts that set $tools (the folder of every geotri-* binary) and make their .gtri inputs with the real
# tools:

# check FILE: geotri-check's exit code for FILE (0 valid, 3 invalid).
check() {
    "$tools/geotri-check" "$1" --quiet
}

# make_gtri MESH DECIMATE_OPTIONS...: in_g.gtri, MESH decimated and traced (the fine mesh copied next to it).
make_gtri() {
    local mesh=$1
    shift
    cp "$mesh" "in_$(basename "$mesh")" || fail "cannot copy $mesh"
    "$tools/geotri-decimate" "in_$(basename "$mesh")" -o in_coarse.off "$@" --quiet || fail "geotri-decimate failed"
    "$tools/geotri-trace" "in_$(basename "$mesh")" in_coarse.off -o in_g.gtri --quiet || fail "geotri-trace failed"
}
