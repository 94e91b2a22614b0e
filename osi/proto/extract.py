"""Writes the descriptor set sightline compiles OSI from (osi/proto/osi3.fds).

ASAM publishes OSI's .proto files in its source repository; the published
packages carry them compiled. The official Python bindings, PyPI's
osi-python, embed in each `osi3/*_pb2.py` module the FileDescriptorProto that
protoc made of the release's .proto file. This script gathers those of
`osi3/osi_sensordata.proto` and of every file it imports (SensorData imports
SensorView, which imports GroundTruth: every message sightline reads or
writes), dependencies first, as `protoc --include_imports
--descriptor_set_out` writes them, and prints the FileDescriptorSet's bytes.

    target/osi-python/bin/python osi/proto/extract.py > osi/proto/osi3.fds

with the venv of ci/tools.sh (osi-python pinned there). The test
`the_descriptors_are_the_official_bindings` (tests/e2e/osi.rs) runs it and
compares its output with the vendored file.
"""

import sys

from google.protobuf import descriptor_pb2
from osi3 import osi_sensordata_pb2


def closure(root):
    """The file `root` and every file it imports, dependencies first."""
    order, seen = [], set()

    def visit(file):
        if file.name in seen:
            return
        seen.add(file.name)
        for dependency in file.dependencies:
            visit(dependency)
        order.append(file)

    visit(root)
    return order


def main():
    descriptors = descriptor_pb2.FileDescriptorSet()
    for file in closure(osi_sensordata_pb2.DESCRIPTOR):
        file.CopyToProto(descriptors.file.add())
    sys.stdout.buffer.write(descriptors.SerializeToString(deterministic=True))


if __name__ == "__main__":
    main()
