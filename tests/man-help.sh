#!/bin/sh
# man-help.sh: the manual page (docs/granmpm.1.in) keeps step with the usage:
# every command that `granmpm --help` lists has its section (.SS) there, and
# every option that `granmpm --help` or `granmpm constitutive --help` lists
# is named there. A command or option added to the usage without the page
# fails here.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
page=$srcdir/docs/granmpm.1.in
tmp=$(mktemp -d "${TMPDIR:-/tmp}/man-help.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT
fails=0

# the page as text: \- is -, font changes and zero-width marks dropped
sed -e 's/\\-/-/g' -e 's/\\f[BIRP]//g' -e 's/\\&//g' -e 's/\\(en/-/g' "$page" > "$tmp/page" ||
  exit 99
"$GRANMPM" --help > "$tmp/help" && "$GRANMPM" constitutive --help > "$tmp/chelp" ||
  { echo "FAIL: granmpm --help or granmpm constitutive --help"; exit 1; }

# commands: the first word of the lines of "commands:" indented by two spaces
cmds=$(awk '/^commands:/ { on = 1; next } on && /^$/ { on = 0 } on && /^  [a-z]/ { print $1 }' \
  "$tmp/help" | sort -u)
for c in $cmds; do
  grep -q "^\.SS \"$c[ \"]" "$tmp/page" ||
    { echo "FAIL: command '$c' (granmpm --help) has no .SS section in docs/granmpm.1.in"; fails=$((fails + 1)); }
done
opts=$(cat "$tmp/help" "$tmp/chelp" | grep -o -e '--[a-z][a-z0-9-]*' | sort -u)
for o in $opts; do
  grep -q -e "$o\([^a-z0-9-]\|\$\)" "$tmp/page" ||
    { echo "FAIL: option '$o' (--help) is not in docs/granmpm.1.in"; fails=$((fails + 1)); }
done

# the usage was read: the seven commands and the options of their lines
ncmd=$(echo $cmds | wc -w) nopt=$(echo $opts | wc -w)
echo "$ncmd commands, $nopt options of the usage checked against docs/granmpm.1.in"
[ "$ncmd" -ge 7 ] && [ "$nopt" -ge 30 ] ||
  { echo "FAIL: too few commands or options read from --help (the format changed?)"; fails=$((fails + 1)); }
[ "$fails" -eq 0 ]
