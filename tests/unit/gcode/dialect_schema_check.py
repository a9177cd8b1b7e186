#!/usr/bin/env python3
"""The other half of DialectTest.SchemaAndValidationAgree: with the Python jsonschema package
(when it is installed), every built-in dialect.json satisfies stylesheets/dialect.schema.json,
and every example of invalid_examples.json (which dialect_test.cpp checks load_dialect refuses)
is refused by the schema too. Exit 77 (skip) without jsonschema."""
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

schema = json.loads((root / "stylesheets" / "dialect.schema.json").read_text())
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
failures = 0
dialects = 0
for folder in sorted((root / "stylesheets").iterdir()):
    if (folder / "dialect.json").exists():
        dialects += 1
        errors = list(validator.iter_errors(json.loads((folder / "dialect.json").read_text())))
        for e in errors[:3]:
            failures += 1
            print(f"{folder.name}: {'/'.join(map(str, e.path))}: {e.message}")


def pointer(doc, path):
    parts = path.strip("/").split("/")
    for p in parts[:-1]:
        doc = doc[int(p)] if isinstance(doc, list) else doc[p]
    return doc, parts[-1]


valid = json.loads((root / "stylesheets" / "linuxcnc" / "dialect.json").read_text())
examples = json.loads((root / "tests" / "unit" / "gcode" / "invalid_examples.json").read_text())
for example in examples:
    doc = copy.deepcopy(valid)
    for path, value in example.get("set", {}).items():
        parent, key = pointer(doc, path)
        if isinstance(parent, list):
            parent[int(key)] = value
        else:
            parent[key] = value
    for path in example.get("remove", []):
        parent, key = pointer(doc, path)
        del parent[key]
    if validator.is_valid(doc):
        failures += 1
        print(f"schema accepts invalid example: {example['name']}")
print(f"{dialects} dialects and {len(examples)} invalid examples checked, {failures} failures")
sys.exit(1 if failures or dialects == 0 else 0)
