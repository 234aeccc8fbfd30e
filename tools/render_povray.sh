#!/usr/bin/env bash
# Renders POV-Ray scene files (the scenes program's frame_NNNNN.pov) to PNG next
# to them, with Debian's povray, installing it when missing.
# Usage: tools/render_povray.sh [-w WIDTH] [-h HEIGHT] [-q QUALITY] FILE.pov|DIR ...
#   defaults: 480 x 360, quality 9, antialiasing on; a DIR renders every .pov in it.
set -euo pipefail

width=480 height=360 quality=9
while getopts "w:h:q:" opt; do
  case $opt in
    w) width=$OPTARG ;;
    h) height=$OPTARG ;;
    q) quality=$OPTARG ;;
    *) sed -n '2,6p' "$0" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -eq 0 ]; then
  sed -n '2,6p' "$0" >&2
  exit 2
fi

if ! command -v povray >/dev/null 2>&1; then
  GPUSOLVE_EXTRA_PACKAGES=povray bash "$(dirname "$0")/install_deps.sh"
fi

files=()
for arg in "$@"; do
  if [ -d "$arg" ]; then
    while IFS= read -r f; do files+=("$f"); done < <(find "$arg" -maxdepth 1 -name '*.pov' | sort)
  elif [ -f "$arg" ]; then
    files+=("$arg")
  else
    echo "render_povray: no such file or directory: $arg" >&2
    exit 2
  fi
done
[ ${#files[@]} -gt 0 ] || { echo "render_povray: no .pov files in $*" >&2; exit 2; }

for f in "${files[@]}"; do
  png="${f%.pov}.png"
  # -D: no display window; +A: antialiasing; povray prints its statistics on stderr.
  if ! povray -D +A +Q"$quality" +W"$width" +H"$height" +I"$f" +O"$png" >"${png%.png}.log" 2>&1; then
    echo "render_povray: povray failed on $f; see ${png%.png}.log" >&2
    exit 1
  fi
  rm -f "${png%.png}.log"
  echo "$png"
done
