"""Reads a sightline OSI trace (osi.mcap) with ASAM's Python tools and prints
what the end-to-end test checks (tests/e2e/osi.rs), as JSON:

- `metadata`, `schemas`, `channels`, `chunks`: the file as the official MCAP
  reader sees it (its summary, CRCs validated);
- `readers`: messages per topic and type as ASAM's OSI trace reader
  (asam-osi-utilities' MultiTraceReader) reads them, once decoding with the
  official bindings' classes (`precompiled`) and once with the descriptors the
  trace embeds (`mcap-contained`);
- `round_trip`: every message parsed by the official bindings (osi-python),
  its unknown fields discarded and serialized again: the bytes must be those
  sightline wrote (so every field is one the bindings know, with the same
  value); `problems` lists each message that differs or whose publish time is
  not its OSI timestamp;
- `visibility`: per SensorView topic, the first message's road users with the
  identifiers of their `sightline.visibility` reference, as the bindings read
  them.

Usage: python read_osi.py OSI.mcap
"""

import collections
import json
import sys
from pathlib import Path

from mcap.reader import make_reader
from osi3.osi_groundtruth_pb2 import GroundTruth
from osi3.osi_sensorview_pb2 import SensorView
from osi_utilities.tracefile.readers.multi import MultiTraceReader

CLASSES = {"osi3.GroundTruth": GroundTruth, "osi3.SensorView": SensorView}


def summary_of(path):
    """The file's metadata, schemas, channels and chunks, read with mcap."""
    with open(path, "rb") as stream:
        reader = make_reader(stream, validate_crcs=True)
        summary = reader.get_summary()
        metadata = [{"name": m.name, "data": dict(m.metadata)} for m in reader.iter_metadata()]
        counts = summary.statistics.channel_message_counts
        schemas = {
            s.name: {"encoding": s.encoding, "data": s.data.hex()} for s in summary.schemas.values()
        }
        channels = {
            c.topic: {
                "schema": summary.schemas[c.schema_id].name,
                "message_encoding": c.message_encoding,
                "metadata": dict(c.metadata),
                "count": counts.get(c.id, 0),
            }
            for c in summary.channels.values()
        }
        chunks = {
            "count": len(summary.chunk_indexes),
            "compressions": sorted({c.compression for c in summary.chunk_indexes}),
            "messages": summary.statistics.message_count,
        }
    return metadata, schemas, channels, chunks


def read_with_osi_utilities(path, mode):
    """Messages per topic and OSI type as ASAM's trace reader decodes them."""
    reader = MultiTraceReader(decoder_mode=mode, skip_incompatible_messages=False)
    if not reader.open(Path(path)):
        raise SystemExit(f"asam-osi-utilities could not open {path}")
    counts = collections.Counter()
    try:
        for result in reader:
            if result.message is None:
                raise SystemExit(f"{mode}: a message on {result.channel_name} did not decode: {result.error_message}")
            counts[f"{result.channel_name} {type(result.message).__name__}"] += 1
    finally:
        reader.close()
    return dict(counts)


def visibility_of(view):
    """Each road user of a SensorView with its visibility identifiers."""
    return {
        str(o.id.value): [list(r.identifier) for r in o.source_reference if r.type == "sightline.visibility"]
        for o in view.global_ground_truth.moving_object
    }


def round_trip(path):
    """Problems of the official bindings' parse and re-serialization, and
    the first SensorView of each topic's visibility."""
    problems, visibility, checked = [], {}, 0
    with open(path, "rb") as stream:
        for schema, channel, message in make_reader(stream).iter_messages():
            parsed = CLASSES[schema.name].FromString(message.data)
            parsed.DiscardUnknownFields()
            where = f"{channel.topic} at {message.log_time} ns"
            if parsed.SerializeToString() != message.data:
                problems.append(f"{where}: the bindings' serialization differs from sightline's bytes")
            stamp = parsed.timestamp.seconds * 1_000_000_000 + parsed.timestamp.nanos
            if not (message.publish_time == message.log_time == stamp):
                problems.append(f"{where}: publish time {message.publish_time}, OSI timestamp {stamp}")
            if schema.name == "osi3.SensorView" and channel.topic not in visibility:
                visibility[channel.topic] = visibility_of(parsed)
            checked += 1
    return {"checked": checked, "problems": problems}, visibility


def main(path):
    metadata, schemas, channels, chunks = summary_of(path)
    checked, visibility = round_trip(path)
    print(
        json.dumps(
            {
                "metadata": metadata,
                "schemas": schemas,
                "channels": channels,
                "chunks": chunks,
                "readers": {mode: read_with_osi_utilities(path, mode) for mode in ("precompiled", "mcap-contained")},
                "round_trip": checked,
                "visibility": visibility,
            },
            indent=1,
            sort_keys=True,
        )
    )


if __name__ == "__main__":
    main(sys.argv[1])
