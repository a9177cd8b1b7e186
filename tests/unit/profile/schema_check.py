#!/usr/bin/env python3
"""The other half of SchemaAndValidationAgree: with the Python jsonschema package (when it is
installed), the built-in profiles satisfy stylesheets/profile.schema.json, every example of
invalid_examples.json (which profile_test.cpp checks the C++ validation refuses) is refused by
the schema too, and every example of valid_examples.json (which the C++ validation accepts) is
accepted. Exit 77 (skip) without jsonschema."""
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
validator = jsonschema.Draft202012Validator(schema)
failures = 0
for folder in sorted((root / "stylesheets").iterdir()):
    if (folder / "profile.json").exists():
        errors = list(validator.iter_errors(json.loads((folder / "profile.json").read_text())))
        if errors:
            failures += 1
            print(f"{folder.name}: {errors[0].message}")

def pointer(doc, path):
    parts = path.strip("/").split("/")
    for p in parts[:-1]:
        doc = doc[p]
    return doc, parts[-1]

valid = json.loads((root / "stylesheets" / "linuxcnc" / "profile.json").read_text())

def applied(example):
    doc = copy.deepcopy(valid)
    for path, value in example.get("set", {}).items():
        parent, key = pointer(doc, path)
        parent[key] = value
    for path in example.get("remove", []):
        parent, key = pointer(doc, path)
        del parent[key]
    return doc

examples = json.loads((root / "tests" / "unit" / "profile" / "invalid_examples.json").read_text())
for example in examples:
    if validator.is_valid(applied(example)):
        failures += 1
        print(f"schema accepts invalid example: {example['name']}")
good = json.loads((root / "tests" / "unit" / "profile" / "valid_examples.json").read_text())
for example in good:
    errors = list(validator.iter_errors(applied(example)))
    if errors:
        failures += 1
        print(f"schema refuses valid example: {example['name']}: {errors[0].message}")
print(f"{len(examples)} invalid and {len(good)} valid examples checked, {failures} failures")
sys.exit(1 if failures else 0)
