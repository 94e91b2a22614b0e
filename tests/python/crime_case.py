"""CommonRoad's criticality package (commonroad-crime) on one two-road-user case.

Usage: python crime_case.py CASE.json

The case (written by tests/e2e/criticality.rs, which runs sightline on the same scene):

    {"dt": 0.1, "steps": 12, "proximity": 50,
     "ego":   {"x": 0, "y": 0, "heading_deg": 0, "speed": 10, "length": 4.5, "width": 1.8},
     "other": {"x": 40, "y": 0, "heading_deg": 0, "speed": 4, "length": 4.5, "width": 1.8},
     "measures": ["ttc", "ttc_star", "a_long_req", "pet"]}

Both road users move at constant velocity along straight lines, one step of
`dt` seconds at a time, steps 0 .. steps - 1 being sightline's run. The script
builds the CommonRoad scenario, runs the measures asked for and prints one
JSON object on stdout:

- "ttc": the least of CRIME's TTC (lane-based, constant acceleration:
  headway along the lanelet over the speed difference) over the run's steps
  with the centres closer than `proximity`; the ego and the other on one
  lanelet along the ego's heading, as wide as 4 m plus the wider of the two.
- "ttc_star": the least of CRIME's TTC* over the same steps: the first time
  step at which the ego's oriented box collides with the other's occupancy,
  both following their trajectories, extended past the run (HORIZON seconds)
  so that a collision after its end is found. Each road user on its own
  lanelet along its heading, 4 m wider than it, so that the ego stays on the
  road (TTC* collides with the road boundary too).
- "a_long_req": the most negative of CRIME's required longitudinal
  acceleration (Jansson's a_long,req with constant acceleration, which the
  review calls DRAC) over the same steps, on the lanelet of "ttc".
- "pet": CRIME's PET at step 0 over the run's trajectories: the conflict
  area is the intersection of the two lanelets (each exactly as wide as its
  road user, so that it is the intersection of their swept footprints),
  both lanelets marked as at an intersection (CRIME measures PET only there).

A value CRIME reports as infinite (no collision, no conflict area) is null.
"""

import json
import logging
import math
import sys

import numpy as np
from commonroad.geometry.shape import Rectangle
from commonroad.prediction.prediction import TrajectoryPrediction
from commonroad.scenario.intersection import Intersection, IntersectionIncomingElement
from commonroad.scenario.lanelet import Lanelet, LaneletNetwork, LaneletType
from commonroad.scenario.obstacle import DynamicObstacle, ObstacleType
from commonroad.scenario.scenario import Scenario, ScenarioID, Tag
from commonroad.scenario.state import CustomState, InitialState
from commonroad.scenario.trajectory import Trajectory
from commonroad_crime.data_structure.configuration import CriMeConfiguration
from commonroad_crime.measure.acceleration.a_long_req import ALongReq
from commonroad_crime.measure.time.pet import PET
from commonroad_crime.measure.time.ttc import TTC
from commonroad_crime.measure.time.ttc_star import TTCStar

EGO, OTHER = 1, 2
EGO_LANE, OTHER_LANE = 101, 102
# Seconds the trajectories go on past the run for TTC*; metres of road
# before and after them.
HORIZON = 30.0
ROAD_MARGIN = 50.0


def unit(deg):
    rad = math.radians(deg)
    return np.array([math.cos(rad), math.sin(rad)])


def position(user, t):
    return np.array([user["x"], user["y"]]) + unit(user["heading_deg"]) * user["speed"] * t


def lanelet(lanelet_id, user, width, duration, types):
    """A straight lanelet along the road user's heading, covering its way
    over `duration` seconds with a margin at both ends, `width` wide."""
    direction = unit(user["heading_deg"])
    left = np.array([-direction[1], direction[0]])
    start = position(user, 0) - direction * ROAD_MARGIN
    end = position(user, duration) + direction * ROAD_MARGIN
    centre = np.array([start + (end - start) * i / 10 for i in range(11)])
    return Lanelet(
        centre + left * width / 2,
        centre,
        centre - left * width / 2,
        lanelet_id,
        lanelet_type=set(types),
    )


def obstacle(obstacle_id, user, dt, steps):
    """The road user moving at constant velocity for `steps` steps of `dt`."""
    heading = math.radians(user["heading_deg"])
    shape = Rectangle(user["length"], user["width"])

    def state(k, kind):
        return kind(
            time_step=k,
            position=position(user, k * dt),
            orientation=heading,
            velocity=user["speed"],
            acceleration=0.0,
            yaw_rate=0.0,
            slip_angle=0.0,
        )

    trajectory = Trajectory(1, [state(k, CustomState) for k in range(1, steps)])
    return DynamicObstacle(
        obstacle_id,
        ObstacleType.CAR,
        shape,
        state(0, InitialState),
        TrajectoryPrediction(trajectory, shape),
    )


def scenario(case, steps, lanes):
    """The scene over `steps` steps, on `lanes` (lanelets built by `lanelet`)."""
    dt = case["dt"]
    sce = Scenario(dt, ScenarioID(country_id="ZAM", map_name="Sightline", map_id=1))
    network = LaneletNetwork()
    for lane in lanes:
        network.add_lanelet(lane)
    sce.add_objects(network)
    sce.add_objects(obstacle(EGO, case["ego"], dt, steps))
    sce.add_objects(obstacle(OTHER, case["other"], dt, steps))
    sce.assign_obstacles_to_lanelets(time_steps=list(range(steps)), use_center_only=True)
    return sce


def measure(sce, kind):
    config = CriMeConfiguration()
    config.update(ego_id=EGO, sce=sce)
    return kind(config)


def finite(value):
    return None if value is None or math.isinf(value) or math.isnan(value) else float(value)


def over_the_run(case, sce, kind):
    """CRIME's `kind` at every step of the run with the centres closer than
    the proximity, finite values only."""
    crime = measure(sce, kind)
    values = []
    for k in range(case["steps"]):
        t = k * case["dt"]
        apart = np.linalg.norm(position(case["other"], t) - position(case["ego"], t))
        if apart >= case["proximity"]:
            continue
        # TTC*'s compute takes the time step first, the others the vehicle.
        if kind is TTCStar:
            value = finite(crime.compute(k, OTHER, verbose=False))
        else:
            value = finite(crime.compute(OTHER, k, verbose=False))
        if value is not None:
            values.append(value)
    return values


def main():
    logging.disable(logging.CRITICAL)
    with open(sys.argv[1]) as f:
        case = json.load(f)
    dt, steps = case["dt"], case["steps"]
    duration = (steps - 1) * dt
    ego, other = case["ego"], case["other"]
    out = {}
    measures = case["measures"]
    if "ttc" in measures or "a_long_req" in measures:
        width = max(ego["width"], other["width"]) + 4.0
        sce = scenario(case, steps, [lanelet(EGO_LANE, ego, width, duration, [LaneletType.URBAN])])
        if "ttc" in measures:
            out["ttc"] = min(over_the_run(case, sce, TTC), default=None)
        if "a_long_req" in measures:
            out["a_long_req"] = min(over_the_run(case, sce, ALongReq), default=None)
    if "ttc_star" in measures:
        extended = steps + round(HORIZON / dt)
        lanes = [
            lanelet(EGO_LANE, ego, ego["width"] + 4.0, HORIZON + duration, [LaneletType.URBAN]),
            lanelet(OTHER_LANE, other, other["width"] + 4.0, HORIZON + duration, [LaneletType.URBAN]),
        ]
        sce = scenario(case, extended, lanes)
        out["ttc_star"] = min(over_the_run(case, sce, TTCStar), default=None)
    if "pet" in measures:
        crossing = [LaneletType.INTERSECTION]
        lanes = [
            lanelet(EGO_LANE, ego, ego["width"], duration, crossing),
            lanelet(OTHER_LANE, other, other["width"], duration, crossing),
        ]
        sce = scenario(case, steps, lanes)
        sce.tags = {Tag.INTERSECTION}
        incoming = IntersectionIncomingElement(1, incoming_lanelets={EGO_LANE})
        sce.lanelet_network.add_intersection(Intersection(1, [incoming]))
        out["pet"] = finite(measure(sce, PET).compute(OTHER, 0, verbose=False))
    json.dump(out, sys.stdout)
    print()


if __name__ == "__main__":
    main()
