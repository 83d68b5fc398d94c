"""Reads an MCAP file with an independent reader (the `mcap` package from PyPI) and prints
what it finds as one JSON object: for each topic its schema's name and encoding, the message
encoding and the number of messages (counted by iterating, not from the summary), the
summary's own counts, the metadata records, every message's log time, and every message
decoded. With jsonschema installed, every message is validated against its channel's schema.

Usage: python3 read_mcap.py FILE
"""

import json
import sys

from mcap.reader import make_reader


def main(path):
    out = {"topics": {}, "metadata": {}, "summary_counts": {}, "errors": []}
    try:
        import jsonschema
    except ImportError:  # the caller decides whether that is allowed
        jsonschema = None
    out["validated"] = jsonschema is not None
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        for cid, channel in summary.channels.items():
            schema = summary.schemas[channel.schema_id]
            out["topics"][channel.topic] = {
                "schema": schema.name,
                "schema_encoding": schema.encoding,
                "message_encoding": channel.message_encoding,
                "count": 0,
                "log_times": [],
                "messages": [],
            }
            out["summary_counts"][channel.topic] = summary.statistics.channel_message_counts.get(cid, 0)
        for record in reader.iter_metadata():
            out["metadata"][record.name] = dict(record.metadata)
        validators = {}
        for schema, channel, message in reader.iter_messages(log_time_order=True):
            topic = out["topics"][channel.topic]
            topic["count"] += 1
            topic["log_times"].append(message.log_time)
            data = json.loads(message.data)
            topic["messages"].append(data)
            if jsonschema is not None:
                if schema.id not in validators:
                    validators[schema.id] = jsonschema.Draft202012Validator(json.loads(schema.data))
                for e in validators[schema.id].iter_errors(data):
                    out["errors"].append(f"{channel.topic}: {e.message}")
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1])
