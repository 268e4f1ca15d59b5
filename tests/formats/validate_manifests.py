#!/usr/bin/env python3
"""Validates cooked manifests against their JSON Schemas (docs/formats/*.schema.json).

usage: validate_manifests.py SCHEMA_DIR MANIFEST...

The schema is picked from each manifest's content: "format" named "specula-level" -> level,
else "flavour" F -> probe-F (probe-distance, probe-lightfield, probe-pem). Prints
"ok: PATH (SCHEMA)" for a manifest that validates, else one "error: PATH (SCHEMA): JSONPATH:
message" line per error. Exit status: 0 all valid, 1 any manifest invalid (or unreadable, or
with no schema), 2 usage errors (wrong arguments, SCHEMA_DIR missing, a schema that cannot be
read or is no valid draft 2020-12 schema).

Python 3 with jsonschema (Debian's python3-jsonschema) and nothing else.
"""
import json
import os
import sys

try:
    from jsonschema import Draft202012Validator
except ImportError:  # pragma: no cover - reported as a usage error
    Draft202012Validator = None

USAGE = "usage: validate_manifests.py SCHEMA_DIR MANIFEST..."


def usage_error(message):
    print("validate_manifests.py: " + message, file=sys.stderr)
    print(USAGE, file=sys.stderr)
    sys.exit(2)


def json_path(path):
    """'$.layers[0].file' from jsonschema's deque of keys and indices."""
    out = "$"
    for key in path:
        if isinstance(key, int):
            out += "[%d]" % key
        else:
            out += "." + str(key)
    return out


def error_order(error):
    """Errors in document order of their paths (indices numerically), then by message."""
    return ([(0, k, "") if isinstance(k, int) else (1, 0, str(k)) for k in error.absolute_path],
            error.message)


def format_name(manifest):
    fmt = manifest.get("format")
    if isinstance(fmt, dict):
        name = fmt.get("name")
        return name if isinstance(name, str) else None
    return fmt if isinstance(fmt, str) else None  # before 2.1 / 1.1: a plain string


def schema_name(manifest):
    """The schema's name for a manifest, or None when nothing in it says which."""
    if not isinstance(manifest, dict):
        return None
    if format_name(manifest) == "specula-level":
        return "level"
    flavour = manifest.get("flavour")
    if isinstance(flavour, str) and flavour:
        return "probe-" + flavour
    return None


class Schemas:
    def __init__(self, folder):
        self.folder = folder
        self.validators = {}

    def validator(self, name):
        """The validator for docs/formats/NAME.schema.json, or None when there is no such file."""
        if name in self.validators:
            return self.validators[name]
        path = os.path.join(self.folder, name + ".schema.json")
        if not os.path.isfile(path):
            self.validators[name] = None
            return None
        try:
            with open(path, encoding="utf-8") as f:
                schema = json.load(f)
            Draft202012Validator.check_schema(schema)
        except (OSError, ValueError) as e:
            usage_error("%s: cannot read the schema: %s" % (path, e))
        except Exception as e:  # jsonschema.SchemaError
            usage_error("%s: not a valid draft 2020-12 schema: %s" % (path, getattr(e, "message", e)))
        self.validators[name] = Draft202012Validator(schema)
        return self.validators[name]


def check(path, schemas):
    """Prints the manifest's result; returns True when it validates."""
    try:
        with open(path, encoding="utf-8") as f:
            manifest = json.load(f)
    except (OSError, ValueError) as e:
        print("error: %s: cannot read it as JSON: %s" % (path, e))
        return False
    name = schema_name(manifest)
    if name is None:
        print("error: %s: no schema: neither \"format\" named specula-level nor a \"flavour\"" % path)
        return False
    validator = schemas.validator(name)
    if validator is None:
        print("error: %s (%s): no such schema in %s" % (path, name, schemas.folder))
        return False
    errors = sorted(validator.iter_errors(manifest), key=error_order)
    if not errors:
        print("ok: %s (%s)" % (path, name))
        return True
    for e in errors:
        print("error: %s (%s): %s: %s" % (path, name, json_path(e.absolute_path), e.message))
    return False


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        if len(argv) >= 2 and argv[1] in ("-h", "--help"):
            print(__doc__.strip())
            return 0
        usage_error("expected a schema folder and at least one manifest")
    if Draft202012Validator is None:
        usage_error("needs the jsonschema module (apt install python3-jsonschema)")
    folder = argv[1]
    if not os.path.isdir(folder):
        usage_error("%s: no such schema folder" % folder)
    schemas = Schemas(folder)
    ok = True
    for path in argv[2:]:
        ok = check(path, schemas) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
