#!/usr/bin/env bash
# docs/input.md documents every key and keyword the validator accepts, names no key it does not, and its
# tables generated from the validator's own tables (keywords, particle fields, measures) are current
# (issue 8: the reference and the validator cannot drift apart); see scripts/check_input_reference.py.
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
root=$2
"$python" "$root/scripts/check_input_reference.py" "$root" || fail "docs/input.md is behind the validator (above)"
