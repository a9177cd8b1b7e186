#!/usr/bin/env python3
"""The other half of ChecksSchema.* in checks_test.cpp: with the Python jsonschema package, the
example checks section (tests/golden/cls/checks.json) satisfies $defs/checks of
stylesheets/profile.schema.json, a built-in profile with that section satisfies the whole schema,
and every example of checks_invalid_examples.json (which checks_test.cpp checks cls::parse_checks
refuses) is refused by the schema too. Exit 77 (skip) without jsonschema."""
import copy
import json
import pathlib
import sys

root = pathlib.Path(sys.argv[1])
try:
    import jsonschema
except ImportError:
    print("python3-jsonschema not installed: skipped")
    sys.exit(77)

schema = json.loads((root / "stylesheets" / "profile.schema.json").read_text())
checks_schema = {"$schema": schema["$schema"], "$ref": "#/$defs/checks", "$defs": schema["$defs"]}
checks = jsonschema.Draft202012Validator(checks_schema)
whole = jsonschema.Draft202012Validator(schema)
example = json.loads((root / "tests" / "golden" / "cls" / "checks.json").read_text())
failures = 0
for error in checks.iter_errors(example):
    failures += 1
    print(f"example: {error.message}")
profile = json.loads((root / "stylesheets" / "linuxcnc" / "profile.json").read_text())
profile["checks"] = example
for error in whole.iter_errors(profile):
    failures += 1
    print(f"profile with checks: {error.message}")


def parent_of(doc, path):
    parts = path.strip("/").split("/")
    for p in parts[:-1]:
        doc = doc[int(p)] if isinstance(doc, list) else doc[p]
    key = parts[-1]
    return doc, (int(key) if isinstance(doc, list) else key)


examples = json.loads((root / "tests" / "unit" / "cls" / "checks_invalid_examples.json").read_text())
for ex in examples:
    doc = copy.deepcopy(example)
    if "replace" in ex:
        doc = ex["replace"]
    for path, value in ex.get("set", {}).items():
        parent, key = parent_of(doc, path)
        parent[key] = value
    for path in ex.get("remove", []):
        parent, key = parent_of(doc, path)
        del parent[key]
    if checks.is_valid(doc):
        failures += 1
        print(f"schema accepts invalid example: {ex['name']}")
print(f"{len(examples)} invalid examples checked, {failures} failures")
sys.exit(1 if failures else 0)
