#!/bin/sh
# cli-calls.sh: no two files of src/ call each other in a circle, directly
# or through others (docs/design.md, "Modules and dependencies"), read from
# the objects of this build by scripts/call-cycles; and the tool sees a
# circle where there is one: two objects made here, each calling the other.
set -eu
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
build=${GRANMPM_BUILDDIR:-$src}
"$src/scripts/call-cycles" "$build"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/src/a"
printf 'int b(int);\nint a(int x) { return x > 0 ? b(x - 1) : 0; }\n' > "$work/a.c"
printf 'int a(int);\nint b(int x) { return x > 0 ? a(x - 1) : 1; }\n' > "$work/b.c"
cc -c -o "$work/src/a/a.o" "$work/a.c"
cc -c -o "$work/src/a/b.o" "$work/b.c"
if out=$("$src/scripts/call-cycles" "$work"); then
  echo "cli-calls: a circle of two files was not found: $out"
  exit 1
fi
echo "a circle of two files is found: $out"
