#!/bin/bash
# Runs every code block the documentation marks runnable (a line "<!-- runnable -->", or
# "<!-- runnable: needs PATH -->", right before a ```sh block) in README.md and
# Documentation/UserGuide.md, as a reader would from the checkout's root: build/ and Resources/
# there, ../shared/data beside it, IRCADB set to its IRCADb folder as the tutorial asks. A block fails the test on any failing command (bash -e); one
# whose PATH is missing is skipped and said. Every link to a file must be to one in the repository.
#   RunDocBlocks.sh SOURCE_DIR BUILD_DIR DATA_DIR WORK_DIR
set -uo pipefail
source=$(cd "$1" && pwd) build=$(cd "$2" && pwd) data=$3 work=$4
rm -rf "$work"
mkdir -p "$work/repo"
ln -s "$build" "$work/repo/build"
ln -s "$source/Resources" "$work/repo/Resources"
if [ -n "$data" ] && [ -d "$data" ]; then
  mkdir -p "$work/shared"
  ln -s "$(cd "$data" && pwd)" "$work/shared/data"
  # What the tutorial asks its reader to set: where 3D-IRCADb-01 was unzipped.
  export IRCADB="$work/shared/data/ircadb"
fi
# Every link the documentation makes to a file is to one in the repository, and it is there.
for doc in "$source"/README.md "$source"/Documentation/*.md; do
  for target in $(grep -o '](\([^)#]*\))' "$doc" | sed 's/^](//; s/)$//' | grep -v '^[a-z]*://'); do
    resolved=$(cd "$(dirname "$doc")" && realpath -m "$target")
    case "$resolved" in "$source"/*) ;; *) echo "DocumentationBlocks: ${doc#$source/} links outside the repository: $target"; exit 1 ;; esac
    [ -e "$resolved" ] || { echo "DocumentationBlocks: ${doc#$source/} links to a missing file: $target"; exit 1; }
  done
done
ran=0 skipped=0 n=0
for doc in README.md Documentation/UserGuide.md; do
  # Each block as one file: block-N.sh, with its needs in block-N.needs.
  awk -v dir="$work" -v doc="$doc" '
    /^<!-- runnable/ { armed = 1; needs = ""; if (match($0, /needs [^ ]+/)) needs = substr($0, RSTART + 6, RLENGTH - 6); next }
    armed && /^```sh/ { inside = 1; armed = 0; count++; file = dir "/" doc "." count; gsub("/", "_", file); file = dir "/" substr(file, length(dir) + 2);
                        print needs > (file ".needs"); next }
    inside && /^```/ { inside = 0; close(file ".sh"); next }
    inside { print > (file ".sh") }
    { armed = armed && /^[[:space:]]*$/ }' "$source/$doc"
done
for block in "$work"/*.sh; do
  [ -e "$block" ] || continue
  n=$((n + 1))
  name=$(basename "$block" .sh)
  needs=$(cat "${block%.sh}.needs")
  if [ -n "$needs" ] && [ ! -e "$work/repo/$needs" ]; then
    echo "[  SKIPPED ] $name: needs $needs (not here)"
    skipped=$((skipped + 1))
    continue
  fi
  start=$(date +%s)
  if ! (cd "$work/repo" && timeout 900 bash -euo pipefail "$block" > "$work/$name.log" 2>&1); then
    echo "DocumentationBlocks: $name failed:"
    sed 's/^/  | /' "$block"
    echo "  its output, last lines:"
    tail -20 "$work/$name.log" | sed 's/^/  > /'
    exit 1
  fi
  echo "[       OK ] $name ($(( $(date +%s) - start )) s)"
  ran=$((ran + 1))
done
echo "DocumentationBlocks: $ran block(s) ran, $skipped skipped, of $n"
[ "$n" -gt 0 ] || { echo "DocumentationBlocks: no runnable block found"; exit 1; }
[ "$ran" -gt 0 ] || exit 77
rm -rf "$work"
