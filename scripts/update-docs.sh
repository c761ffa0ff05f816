#!/usr/bin/env bash
# Puts each tool's --help into docs/tools.md (between its "<!-- help TOOL -->" and "<!-- end help -->" lines) and
# makes the man pages docs/man/TOOL.1 from the same text: the section's heading and paragraphs, then the help.
#
#   scripts/update-docs.sh TOOLS_DIR            rewrite docs/tools.md and docs/man/*.1
#   scripts/update-docs.sh --check TOOLS_DIR    change nothing; exit 1 when they are out of date, or when a section
#                                               of docs/tools.md names an option that its tool does not have
#
# TOOLS_DIR is the folder of the built geotri-* tools (build/tools).
set -euo pipefail

check=false
if [[ "${1:-}" == --check ]]; then
  check=true
  shift
fi
if (($# != 1)) || [[ ! -d "$1" ]]; then
  sed -n '2,9s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
tools=$(cd "$1" && pwd)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
doc=$root/docs/tools.md
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

mapfile -t names < <(sed -n 's/^<!-- help \(geotri-[a-z]*\) -->$/\1/p' "$doc")
((${#names[@]} > 0)) || { echo "update-docs.sh: error: $doc has no help blocks" >&2; exit 1; }

# The section of docs/tools.md about TOOL, from its heading to the next one, without the help block.
section() {
  awk -v tool="$1" '
    /^## / { inside = index($0, "## " tool ":") == 1; if (inside) print; next }
    inside && /^<!-- help / { skipping = 1 }
    inside && !skipping { print }
    inside && /^<!-- end help -->/ { skipping = 0 }' "$doc"
}

# docs/tools.md with every help block filled in from the tools.
for name in "${names[@]}"; do
  [[ -x "$tools/$name" ]] || { echo "update-docs.sh: error: $tools/$name is not built" >&2; exit 1; }
  "$tools/$name" --help >"$work/$name.help"
done
awk -v dir="$work" '
  /^<!-- help geotri-[a-z]* -->$/ {
    print; name = $3; print "```text"
    while ((getline line < (dir "/" name ".help")) > 0) print line
    print "```"; skipping = 1; next }
  /^<!-- end help -->$/ { skipping = 0 }
  !skipping { print }' "$doc" >"$work/tools.md"

# One man page per tool: NAME from the heading, DESCRIPTION from the paragraphs, then the help verbatim.
mkdir -p "$work/man"
version=$("$tools/${names[0]}" --version | awk '{ print $2 }')
for name in "${names[@]}"; do
  section "$name" >"$work/$name.section"
  summary=$(sed -n '1s/^## [^:]*: //p' "$work/$name.section")
  {
    echo ".TH ${name^^} 1 \"\" \"geotri $version\" \"geotri manual\""
    echo ".SH NAME"
    echo "$name \\- $summary"
    echo ".SH DESCRIPTION"
    # Paragraphs; roff needs backslashes doubled and lines that start with a dot or quote escaped.
    sed '1d' "$work/$name.section" | sed 's/`//g; s/\\/\\e/g; s/^\([.'"'"']\)/\\\&\1/; s/^$/.PP/' | sed '/./,$!d'
    echo ".SH USAGE AND OPTIONS"
    echo ".nf"
    sed 's/\\/\\e/g; s/^\([.'"'"']\)/\\\&\1/' "$work/$name.help"
    echo ".fi"
    echo ".SH SEE ALSO"
    printf '%s\n' "${names[@]}" | grep -vx "$name" | sed 's/$/(1)/' | paste -sd, - | sed 's/,/, /g'
  } >"$work/man/$name.1"
done

# Every option that a section names must be one of its tool's.
status=0
for name in "${names[@]}"; do
  for option in $(grep -o -- '--[a-z][a-z-]*' "$work/$name.section" | sort -u); do
    grep -q -- "$option\b" "$work/$name.help" ||
      { echo "update-docs.sh: docs/tools.md: the section on $name names $option, which $name does not have" >&2; status=1; }
  done
done

if $check; then
  cmp -s "$work/tools.md" "$doc" ||
    { echo "update-docs.sh: docs/tools.md is out of date with the tools' --help (run scripts/update-docs.sh)" >&2; status=1; }
  for name in "${names[@]}"; do
    cmp -s "$work/man/$name.1" "$root/docs/man/$name.1" ||
      { echo "update-docs.sh: docs/man/$name.1 is out of date (run scripts/update-docs.sh)" >&2; status=1; }
  done
  exit $status
fi
cp "$work/tools.md" "$doc"
mkdir -p "$root/docs/man"
cp "$work/man/"*.1 "$root/docs/man/"
echo "update-docs.sh: wrote docs/tools.md and docs/man/ (${#names[@]} tools)"
exit $status
