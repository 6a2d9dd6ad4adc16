#!/usr/bin/python3
"""Every bundled scenario and crowd file validates against the hand-written JSON Schemas
(scenarios/schema/scenario.schema.json, crowd.schema.json) with Debian's python3-jsonschema.

The files: every *.json under scenarios/, verification/ and examples/ whose "format" is "throng/1"
(a scenario) or "throng-crowd/1" (a crowd file); anything else there (the schemas themselves) is
left alone, and a JSON file there that is neither fails, so a new kind of file is a decision, not a
silent skip. The schemas must themselves be valid Draft 2020-12 schemas. Usage:
    schema_test.py [SOURCE_DIR]       (default: the repository this file is in)
Exit 0 when every file validates; 1 with one line per problem (file, JSON pointer, what was wrong).
"""
import json
import pathlib
import sys

try:
    import jsonschema
except ImportError:
    sys.exit("schema_test: python3-jsonschema is missing: apt-get install python3-jsonschema (scripts/deps.sh)")

SCHEMAS = {"throng/1": "scenario.schema.json", "throng-crowd/1": "crowd.schema.json"}
FOLDERS = ("scenarios", "verification", "examples")


def pointer(path):
    return "/" + "/".join(str(p).replace("~", "~0").replace("/", "~1") for p in path)


def refuse(url):
    raise ValueError(f"{url} is not one of the schemas in scenarios/schema (by $id); nothing is fetched")


def main():
    root = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2]
    schema_dir = root / "scenarios" / "schema"
    validators = {}
    for fmt, name in SCHEMAS.items():
        schema = json.loads((schema_dir / name).read_text())
        cls = jsonschema.validators.validator_for(schema)
        cls.check_schema(schema)  # raises SchemaError on a broken schema
        # Crowd files' points and populations refer to the scenario schema's definitions by a
        # relative reference: resolved against the crowd schema's $id, never fetched.
        store = {}
        for n in SCHEMAS.values():
            s = json.loads((schema_dir / n).read_text())
            store[s["$id"]] = s
        resolver = jsonschema.RefResolver.from_schema(schema, store=store, handlers={"http": refuse, "https": refuse})
        validators[fmt] = cls(schema, resolver=resolver)
    problems, counts = [], {fmt: 0 for fmt in SCHEMAS}
    for folder in FOLDERS:
        base = root / folder
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*.json")):
            if path.parent == schema_dir:
                continue
            rel = path.relative_to(root)
            try:
                doc = json.loads(path.read_text())
            except ValueError as e:
                problems.append(f"{rel}: not JSON: {e}")
                continue
            fmt = doc.get("format") if isinstance(doc, dict) else None
            if fmt not in validators:
                problems.append(f"{rel}: \"format\" is {fmt!r}: expected one of {sorted(SCHEMAS)} "
                                f"(or teach tests/scripts/schema_test.py about this kind of file)")
                continue
            counts[fmt] += 1
            try:
                errors = sorted(validators[fmt].iter_errors(doc), key=lambda e: list(e.absolute_path))
            except jsonschema.exceptions.RefResolutionError as e:
                problems.append(f"{rel}: {SCHEMAS[fmt]} has a $ref that cannot be resolved: {e}")
                continue
            for error in errors:
                problems.append(f"{rel}: {pointer(error.absolute_path)}: {error.message} "
                                f"(schema {SCHEMAS[fmt]}#{pointer(error.absolute_schema_path)})")
    for p in problems:
        print(p)
    print(f"schema_test: {counts['throng/1']} scenarios, {counts['throng-crowd/1']} crowd files; "
          f"{len(problems)} problems")
    if counts["throng/1"] == 0 or counts["throng-crowd/1"] == 0:
        print("schema_test: found no scenario or no crowd file: wrong source directory?")
        return 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
