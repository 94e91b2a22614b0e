"""The system side of sightline's protocol for a system under test, version 1
(docs/osi-sut.md): length-delimited OSI messages over standard input and
output. A system imports this, gives `serve` a function from one step's
`osi3.SensorView`s to its detected objects, and runs.
"""

import os
import struct
import sys

from osi3.osi_sensordata_pb2 import SensorData
from osi3.osi_sensorview_pb2 import SensorView

PROTOCOL = "sightline-osi-sut/1"
MAX_MESSAGE = 16 << 20


def read_message(stream):
    """The next message, or None when sightline closed the input."""
    prefix = stream.read(4)
    if len(prefix) == 0:
        return None
    if len(prefix) < 4:
        raise EOFError("input ended inside a length prefix")
    (length,) = struct.unpack("<I", prefix)
    if length > MAX_MESSAGE:
        raise ValueError(f"a message of {length} bytes, above the protocol's limit")
    message = stream.read(length)
    if len(message) < length:
        raise EOFError("input ended inside a message")
    return message


def write_message(stream, message):
    stream.write(struct.pack("<I", len(message)))
    stream.write(message)
    stream.flush()


def serve(perceive):
    """Answers every step: `perceive(views)` returns the detected objects as
    (x, y, existence_probability, (osi_type, vehicle_type)) tuples in the
    host's frame; the class is one candidate of probability 1, `vehicle_type`
    (an osi3.MovingObject.VehicleClassification.Type) None but for a vehicle."""
    if os.environ.get("SIGHTLINE_SUT_PROTOCOL") != PROTOCOL:
        sys.exit(f"this system speaks {PROTOCOL}; sightline announced {os.environ.get('SIGHTLINE_SUT_PROTOCOL')}")
    count = int(os.environ["SIGHTLINE_SUT_VIEWS"])
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    write_message(stdout, PROTOCOL.encode())
    while True:
        first = read_message(stdin)
        if first is None:
            return
        views = [first] + [read_message(stdin) for _ in range(count - 1)]
        parsed = []
        for raw in views:
            view = SensorView()
            view.ParseFromString(raw)
            parsed.append(view)
        data = SensorData()
        data.timestamp.CopyFrom(parsed[0].timestamp)
        for x, y, existence, (kind, vehicle) in perceive(parsed):
            detected = data.moving_object.add()
            detected.header.existence_probability = existence
            detected.base.position.x = x
            detected.base.position.y = y
            detected.base.position.z = 0.0
            candidate = detected.candidate.add()
            candidate.probability = 1.0
            candidate.type = kind
            if vehicle is not None:
                candidate.vehicle_classification.type = vehicle
        write_message(stdout, data.SerializeToString())
