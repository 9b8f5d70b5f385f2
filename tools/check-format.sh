#!/bin/sh
# Checks that every C++ file in the tree is formatted by .clang-format (docs/style.md), with
# Debian bookworm's clang-format 14: other versions format some constructs differently, so the
# check insists on 14 rather than reporting spurious differences.
#   tools/check-format.sh          list the files that differ, exit 1 if any
#   tools/check-format.sh --fix    rewrite them in place
set -eu
cd "$(dirname "$0")/.."
format=${CLANG_FORMAT:-clang-format}
version=$("$format" --version 2>/dev/null || true)
case "$version" in
  *"version 14."*) ;;
  *) echo "check-format: needs clang-format 14 (Debian's clang-format package); found: ${version:-none}" >&2
     exit 2 ;;
esac
files=$(git ls-files '*.cpp' '*.hpp' '*.h')
if [ "${1:-}" = "--fix" ]; then
  # shellcheck disable=SC2086
  "$format" -i $files
  exit 0
fi
unformatted=""
for f in $files; do
  "$format" --dry-run --Werror "$f" >/dev/null 2>&1 || unformatted="$unformatted $f"
done
if [ -n "$unformatted" ]; then
  echo "check-format: not formatted by .clang-format (run tools/check-format.sh --fix):" >&2
  for f in $unformatted; do echo "  $f" >&2; done
  exit 1
fi
echo "check-format: $(echo "$files" | wc -w) files formatted"
