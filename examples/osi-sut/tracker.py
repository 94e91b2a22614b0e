"""A simple tracker under test: it tracks every road user its sensors have at
least partly in sight (sightline's `sightline.visibility` annotation), coasts
a track for up to 0.3 s after it was last seen, predicting it at constant
velocity, and reports positions on its 0.5 m map cells (the centre of the
cell a track is in) with the class the ground truth gives. It runs with sightline's protocol (osi_sut.py)."""

import math

from osi_sut import serve

COAST = 0.3
CELL = 0.5


def host_pose(view):
    truth = view.global_ground_truth
    for obj in truth.moving_object:
        if obj.id.value == view.host_vehicle_id.value:
            return obj.base.position.x, obj.base.position.y, obj.base.orientation.yaw
    return 0.0, 0.0, 0.0


def visible_fraction(obj):
    """The share of the object in sight, or None when no sensor has it in range."""
    for reference in obj.source_reference:
        if reference.type == "sightline.visibility":
            return float(reference.identifier[1])
    return None


def seen(views, keep):
    """Road users in sight of any view that `keep(fraction)` accepts: id → object."""
    found = {}
    for view in views:
        for obj in view.global_ground_truth.moving_object:
            fraction = visible_fraction(obj)
            if fraction is not None and fraction > 0 and keep(fraction):
                found[obj.id.value] = obj
    return found


class Tracker:
    def __init__(self, keep=lambda fraction: True):
        self.keep = keep
        self.tracks = {}

    def __call__(self, views):
        now = views[0].timestamp.seconds + views[0].timestamp.nanos * 1e-9
        for ident, obj in seen(views, self.keep).items():
            base = obj.base
            vehicle = obj.vehicle_classification.type if obj.HasField("vehicle_classification") else None
            kind = (obj.type, vehicle)
            self.tracks[ident] = (now, base.position.x, base.position.y, base.velocity.x, base.velocity.y, kind)
        hx, hy, yaw = host_pose(views[0])
        cos, sin = math.cos(yaw), math.sin(yaw)
        detections = []
        for ident in sorted(self.tracks):
            t, x, y, vx, vy, kind = self.tracks[ident]
            age = now - t
            if age > COAST + 1e-9:
                del self.tracks[ident]
                continue
            px, py = x + vx * age - hx, y + vy * age - hy
            existence = 0.95 if age == 0 else 0.7
            qx, qy = (math.floor(v / CELL) * CELL + CELL / 2 for v in (px, py))
            detections.append((cos * qx + sin * qy, -sin * qx + cos * qy, existence, kind))
        return detections


if __name__ == "__main__":
    serve(Tracker())
