#!/usr/bin/env python3
"""Keeps docs/input.md in step with the validator (the reference cannot drift from the code).

    scripts/check_input_reference.py [ROOT]           check (the test suite runs this)
    scripts/check_input_reference.py --write [ROOT]   regenerate the generated tables

Generated from the validator's own tables, between `<!-- BEGIN GENERATED: NAME -->` and
`<!-- END GENERATED -->` markers in docs/input.md:
  keywords         every keyword table `std::array<Named<T>, N> kX` of src/matpoint/io/input/keywords.hpp,
                   with the key(s) that read it (`("key").choice(kX)`);
  particle-fields  kParticleFields of src/matpoint/io/particle_fields.hpp;
  measures         kMeasures of src/matpoint/analysis/measures.hpp.
The check fails when a generated table is stale, when a key of an allowed-key list
`Object(value, {"key", ...})` or a keyword is not mentioned in backticks, and when a table row of
docs/input.md names a key that the validator does not know (a removed or misspelt key).
"""
import os
import re
import sys

BEGIN = "<!-- BEGIN GENERATED: {} (scripts/check_input_reference.py --write) -->"
END = "<!-- END GENERATED -->"


def cpp_strings(text):
    """The concatenated value of adjacent C++ string literals in `text`."""
    return "".join(re.findall(r'"((?:[^"\\]|\\.)*)"', text)).replace('\\"', '"')


def info_table(source, name):
    """[(name, text)] of `inline constexpr std::array<Info, N> NAME{{ {"name", "text" "..."}, ... }};`."""
    body = re.search(name + r"\{\{(.*?)\}\};", source, re.S)
    if not body:
        raise SystemExit(f"check_input_reference.py: no table {name} found")
    rows = []
    for entry in re.findall(r'\{\s*("(?:[^"\\]|\\.)*")\s*,((?:\s*"(?:[^"\\]|\\.)*")+)\s*\}', body.group(1)):
        rows.append((cpp_strings(entry[0]), cpp_strings(entry[1])))
    return rows


def keyword_tables(source):
    """{table: [keywords]} of the Named<T> arrays, in their order."""
    tables = {}
    for name, body in re.findall(r"std::array<Named<[^>]+>,\s*\d+>\s+(k\w+)\s*\{\s*\{(.*?)\}\s*\};", source, re.S):
        tables[name] = re.findall(r'\{"([^"]+)",', body)
    return tables


def validator_source(root):
    """The validator's text: the keyword tables, then the reader's files in a fixed order."""
    folder = os.path.join(root, "src", "matpoint", "io", "input")
    names = ["keywords.hpp", "json_value.hpp", "spec_reader.hpp"] + sorted(
        f for f in os.listdir(folder) if f.startswith("read_") and f.endswith(".cpp"))
    parts = [open(os.path.join(root, "src", "matpoint", "io", "input.cpp")).read()]
    parts += [open(os.path.join(folder, name)).read() for name in names]
    return "\n".join(parts)


# The object that each reading function of the reader (io/input/read_*.cpp) reads (the doc's section names).
SECTIONS = {"read_material": "materials[]", "read_plasticity": "materials[]", "read_shape": "bodies[].shape",
            "read_moving_wall": "boundary_conditions[]", "read_condition": "boundary_conditions[]",
            "read_region": "boundary_conditions[]", "read_normal": "boundary_conditions[]",
            "read_solver": "solver", "read_mapping": "solver", "read_fmpm": "solver.fmpm",
            "read_contact": "contact", "read_contact_law": "contact", "read_checks": "checks[]",
            "read_heat": "heat", "read_thermal_conditions": "heat.conditions[]",
            "read_thermal_contact": "heat", "read_body_temperatures": "heat.body_temperatures[]"}


def keys_reading(source, table):
    """The input keys (with their object) whose value is read with `.choice(table)`."""
    variables = dict(
        (var, key) for var, key in re.findall(r'\b(\w+)\s*=\s*\w+\.(?:optional|required|member)\("(\w+)"', source))
    keys = []
    for match in re.finditer(r'(?:\b(\w+)\.(?:optional|required)\("(\w+)"\)|\b(\w+))\.choice\(' + table + r"\)",
                             source):
        functions = list(re.finditer(r"\n(?:  )?(?:static )?[\w:<>]+ (?:SpecReader::)?(read_\w+)\(", source[: match.start()]))
        if not functions:
            continue
        body = source[functions[-1].start() : match.start()]
        local = dict(re.findall(r'\b(\w+)\s*=\s*\w+\.(?:optional|required|member)\("(\w+)"', body))
        owner = match.group(1)
        key = match.group(2) or local.get(match.group(3)) or variables.get(match.group(3))
        if not key:
            continue
        path = SECTIONS.get(functions[-1].group(1), functions[-1].group(1))
        sub = re.search(r"Object " + owner + r'\((?:\w+\.(?:optional|required)\("(\w+)"\)|(\w+),)', body) if owner else None
        sub_key = (sub.group(1) or local.get(sub.group(2))) if sub else None
        if sub_key and not path.endswith(sub_key):  # `const Object mls(s.optional("mls"), ...)`
            path += "." + sub_key
        path += "." + key
        if path not in keys:
            keys.append(path)
    return keys


def escape(text):
    return text.replace("|", "\\|")


def generated_blocks(root):
    read = lambda *p: open(os.path.join(root, *p)).read()
    validator = validator_source(root)
    blocks = {}
    lines = ["| Key | Accepted keywords | Table (io/input/keywords.hpp) |", "|---|---|---|"]
    for table, words in keyword_tables(validator).items():
        keys = ", ".join(f"`{k}`" for k in keys_reading(validator, table)) or "?"
        lines.append(f"| {keys} | " + ", ".join(f'`"{w}"`' for w in words) + f" | `{table}` |")
    blocks["keywords"] = lines
    lines = ["| Name | Content |", "|---|---|"]
    for name, text in info_table(read("src", "matpoint", "io", "particle_fields.hpp"), "kParticleFields"):
        lines.append(f"| `{name}` | {escape(text)} |")
    blocks["particle-fields"] = lines
    lines = ["| Measure | Meaning |", "|---|---|"]
    for name, text in info_table(read("src", "matpoint", "analysis", "measures.hpp"), "kMeasures"):
        lines.append(f"| `{name}` | {escape(text)}. |")
    blocks["measures"] = lines
    return blocks


def with_blocks(doc, blocks):
    """doc with every generated block replaced; raises if a marker pair is missing."""
    for name, lines in blocks.items():
        pattern = re.compile(re.escape(BEGIN.format(name)) + r".*?" + re.escape(END), re.S)
        if not pattern.search(doc):
            raise SystemExit(f"check_input_reference.py: docs/input.md has no block '{BEGIN.format(name)}'")
        doc = pattern.sub(lambda _: "\n".join([BEGIN.format(name)] + lines + [END]), doc)
    return doc


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


def problems(root, doc):
    source = validator_source(root)
    keys, keywords = validator_names(source)
    if len(keys) < 30 or len(keywords) < 20:
        return [f"found only {len(keys)} keys and {len(keywords)} keywords in io/input*; the patterns of "
                "scripts/check_input_reference.py no longer match the validator"]
    out = [f"docs/input.md does not document the validator's key {k}" for k in sorted(keys) if not documented(k, doc)]
    out += [f"docs/input.md does not document the validator's keyword {k}"
            for k in sorted(keywords) if not documented(k, doc)]
    hand_written = re.sub(r"<!-- BEGIN GENERATED.*?" + re.escape(END), "", doc, flags=re.S)
    for row in re.findall(r"^\| `([^`]+)` \|", hand_written, re.M):
        known = row.strip('"') in keywords if row.startswith('"') else row.split(".")[-1] in keys
        if not known:
            out.append(f"docs/input.md has a row for `{row}`, which the validator does not read")
    return out


def main(argv):
    write = "--write" in argv
    args = [a for a in argv[1:] if a != "--write"]
    root = args[0] if args else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = os.path.join(root, "docs", "input.md")
    doc = open(path).read()
    fresh = with_blocks(doc, generated_blocks(root))
    if write:
        if fresh != doc:
            open(path, "w").write(fresh)
        doc = fresh
    found = problems(root, doc)
    if fresh != doc:
        found.append("the generated tables of docs/input.md are stale: run scripts/check_input_reference.py --write")
    for p in found:
        print(p, file=sys.stderr)
    if not found:
        print("docs/input.md documents every key and keyword of the validator; its generated tables are current")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
