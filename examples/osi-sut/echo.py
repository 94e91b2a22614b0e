"""A system that detects nothing: it answers every step with an empty
osi3.SensorData. docs/performance.md measures the protocol's cost with it."""

from osi_sut import serve

if __name__ == "__main__":
    serve(lambda views: [])
