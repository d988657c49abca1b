# Shared set-up of the command-line tests (sourced, not a test: the test glob is *.sh).
# Gives: $matpoint (the binary, first argument), a scratch folder $tmp removed on exit, fail(),
# and $python (Debian's interpreter when present: python3-matplotlib and meshio install there).
set -euo pipefail
matpoint=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
python=python3
[[ -x /usr/bin/python3 ]] && python=/usr/bin/python3
