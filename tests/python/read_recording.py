"""Reads a sightline recording with the official Python MCAP reader and prints
what the end-to-end test checks, as JSON: the header, the chunk compression,
every channel (schema name and encodings, message count) and the attachments,
plus any message that does not decode as its schema says.

Usage: python read_recording.py RUN.mcap
"""

import base64
import collections
import json
import sys

from mcap.reader import make_reader


def problems_of(schema_name, message):
    """What is wrong with one decoded message, as far as this script checks."""
    if schema_name == "foxglove.Grid":
        data = base64.b64decode(message["data"])
        stride = message["row_stride"]
        if stride != message["column_count"] * message["cell_stride"]:
            return ["row_stride is not column_count * cell_stride"]
        if stride == 0 or len(data) % stride != 0:
            return [f"{len(data)} bytes of data are not whole rows of {stride}"]
        if message["frame_id"] != "map":
            return ["a grid outside the map frame"]
    elif schema_name == "foxglove.SceneUpdate":
        for entity in message["entities"]:
            # In the world frame, or locked to a frame /tf moves (an agent's
            # box, a sensor's field of view).
            if entity["frame_id"] != "map" and not entity["frame_locked"]:
                return ["an entity outside the map frame and not locked to it"]
    return []


def main(path):
    with open(path, "rb") as stream:
        reader = make_reader(stream, validate_crcs=True)
        header = reader.get_header()
        summary = reader.get_summary()
        counts = collections.Counter()
        channels = {}
        problems = []
        for schema, channel, message in reader.iter_messages():
            counts[channel.topic] += 1
            channels[channel.topic] = {
                "schema": schema.name,
                "schema_encoding": schema.encoding,
                "message_encoding": channel.message_encoding,
            }
            decoded = json.loads(message.data)
            problems += [f"{channel.topic}: {p}" for p in problems_of(schema.name, decoded)]
        for topic, channel in channels.items():
            channel["count"] = counts[topic]
        result = {
            "library": header.library,
            "profile": header.profile,
            "compression": sorted({c.compression for c in summary.chunk_indexes}),
            "channels": channels,
            "attachments": sorted(a.name for a in reader.iter_attachments()),
            "problems": problems,
        }
    print(json.dumps(result, sort_keys=True))


if __name__ == "__main__":
    main(sys.argv[1])
