#!/usr/bin/env bash
# docs/input.md documents every key and keyword the validator accepts (issue 8: the reference and
# the validator cannot drift apart). The check reads both; see scripts/check_input_reference.py.
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
root=$2
"$python" "$root/scripts/check_input_reference.py" "$root" || fail "docs/input.md is behind the validator (above)"
