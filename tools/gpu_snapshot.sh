#!/usr/bin/env bash
# Prepares .gpu/ for a run on a lent GPU machine (see README, "Developing"):
# a snapshot of the committed tree (HEAD, or the working tree with --worktree)
# and Catch2 v2's single header, which that machine lacks.
set -euo pipefail
cd "$(dirname "$0")/.."
rm -rf .gpu && mkdir -p .gpu/src .gpu/include/catch2
if [ "${1:-}" = "--worktree" ]; then
  git ls-files -co --exclude-standard -z | xargs -0 cp --parents -t .gpu/src
else
  git archive HEAD | tar -x -C .gpu/src
fi
cp /usr/include/catch2/catch.hpp .gpu/include/catch2/
du -sh .gpu
