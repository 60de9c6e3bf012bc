#!/usr/bin/env bash
# Every tracked C++ file as clang-format (.clang-format) would write it; lists the files that are
# not and exits 1. Skipped (77) outside a git checkout or without clang-format.
# To format: git ls-files '*.cpp' '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
format=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$format" ] || ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "check_format: skipped (needs clang-format and a git checkout)"
  exit 77
fi
if report=$(git ls-files -z '*.cpp' '*.h' | xargs -0 "$format" --dry-run --Werror 2>&1); then
  echo "check_format: every tracked C++ file is formatted"
  exit 0
fi
echo "not formatted by $format (.clang-format):"
grep -oE '^[^:]+:[0-9]+:[0-9]+: error' <<<"$report" | cut -d: -f1 | sort -u | sed 's/^/  /'
exit 1
