#!/usr/bin/env python3
"""Checks every request and reply of `stopscan serve` journals against protocol.schema.json.

Usage: check_protocol_schema.py JOURNAL...   (exit status 1 on the first message that does
not match, naming the journal, its line and the schema's complaint).
"""
import json
import pathlib
import sys

import jsonschema

schema = json.loads((pathlib.Path(__file__).parent / "protocol.schema.json").read_text())
jsonschema.Draft202012Validator.check_schema(schema)
defs = schema["$defs"]


def validator(name):
    return jsonschema.Draft202012Validator({"$ref": f"#/$defs/{name}", "$defs": defs})


requests, replies = validator("request"), validator("reply")
checked = 0
for path in sys.argv[1:]:
    lines = pathlib.Path(path).read_text().splitlines()
    for number, line in enumerate(lines[1:], start=2):
        step = json.loads(line)
        for kind, v, message in (("request", requests, step["request"]), ("reply", replies, step["reply"])):
            errors = sorted(v.iter_errors(message), key=lambda e: e.path)
            if errors:
                print(f"{path}, line {number}: the {kind} does not match the schema: {errors[0].message}")
                sys.exit(1)
            checked += 1
print(f"{checked} messages match protocol.schema.json")
