#!/usr/bin/env python3
"""Checks that docs/input.md documents every key and keyword the validator accepts.

    scripts/check_input_reference.py [ROOT]

The validator (src/matpoint/io/input.cpp) lists its keys in one place per object, the allowed-key
lists `Object(value, {"key", ...})`, and its keywords in the `Named` tables
`{"keyword", Enum::Value}`. This script reads both from the source and fails, naming each one, when
docs/input.md does not mention it in backticks (`key`, or within a dotted path such as
`solver.fmpm.order`, or as a quoted value `"keyword"`). It runs in the test suite
(tests/cli/input_reference_complete.sh), so the reference cannot fall behind the validator.
"""
import os
import re
import sys


def validator_names(source):
    keys = set()
    for key_list in re.findall(r'Object\([^;]*?\{((?:\s*"[A-Za-z_0-9]+"\s*,?)+)\}\)', source, re.S):
        keys.update(re.findall(r'"([A-Za-z_0-9]+)"', key_list))
    keys.update(re.findall(r'\.(?:optional|required|member|has)\("([A-Za-z_0-9]+)"', source))
    keywords = set(re.findall(r'\{"([a-z_0-9+\-]+)",\s*[A-Z][A-Za-z]*::[A-Za-z0-9]+\}', source))
    return keys, keywords


def documented(name, doc):
    word = re.escape(name)
    in_code = re.search(r'`[^`\n]*(?<![A-Za-z0-9_])' + word + r'(?![A-Za-z0-9_])[^`\n]*`', doc)
    return bool(in_code) or f'"{name}"' in doc


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    source = open(os.path.join(root, "src", "matpoint", "io", "input.cpp")).read()
    doc = open(os.path.join(root, "docs", "input.md")).read()
    keys, keywords = validator_names(source)
    if len(keys) < 30 or len(keywords) < 20:
        print(f"check_input_reference.py: found only {len(keys)} keys and {len(keywords)} keywords in "
              "input.cpp; the patterns above no longer match the validator", file=sys.stderr)
        return 1
    missing = sorted(f"key {k}" for k in keys if not documented(k, doc))
    missing += sorted(f"keyword {k}" for k in keywords if not documented(k, doc))
    for m in missing:
        print(f"docs/input.md does not document the validator's {m}", file=sys.stderr)
    if not missing:
        print(f"docs/input.md documents all {len(keys)} keys and {len(keywords)} keywords of the validator")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
