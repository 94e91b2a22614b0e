"""Writes crossroads.xodr: a four-way junction with sidewalks, buildings on its
corners and a crosswalk, as ASAM OpenDRIVE 1.6, with scenariogeneration 0.16.7
(MPL-2.0; the file it writes is this project's data).

Usage: python generate.py [OUT]   (default: crossroads.xodr beside this script)

The arms are roads 1 (west, 160 m), 2 (south), 3 (east) and 4 (north), 100 m,
each ending at junction 100 (14 m from its centre): one 3.5 m driving
lane each way and a 2 m sidewalk on each side. The west arm approaches on a
S-bend of spirals and arcs (the reference line's other records: lines and, in
the junction, the connecting roads' spirals and arcs). Speed limit 50 km/h
(`<type><speed>`), 30 km/h through the junction. Every driving lane connects to every other arm's outgoing
lane (twelve connecting roads, 101-112). Four buildings stand back from the
corners; a crosswalk crosses the north arm 8 m beyond the junction.
"""

import re
import sys
from pathlib import Path

import numpy as np
from scenariogeneration import xodr

JUNCTION = 100
RADIUS = 14.0  # distance from the junction centre to each arm's end, m
ARM = 100.0


def lanes(width_drive=3.5, width_walk=2.0):
    """One driving lane each way and a sidewalk on each side."""
    section = xodr.LaneSection(0, xodr.standard_lane())
    for add in (section.add_left_lane, section.add_right_lane):
        add(xodr.Lane(lane_type=xodr.LaneType.driving, a=width_drive))
        add(xodr.Lane(lane_type=xodr.LaneType.sidewalk, a=width_walk))
    result = xodr.Lanes()
    result.add_lanesection(section)
    return result


def arm(road_id, geometries):
    plan = xodr.PlanView()
    for geometry in geometries:
        plan.add_geometry(geometry)
    road = xodr.Road(road_id, plan, lanes())
    road.add_type(xodr.RoadType.town, speed=50, speed_unit="km/h")
    return road


def building(object_id, s, t, corners):
    """A building whose outline (u, v corners in its frame) stands at (s, t)."""
    obj = xodr.Object(s=s, t=t, id=str(object_id), Type=xodr.ObjectType.building, name="building", height=12.0)
    outline = xodr.Outline(closed=True)
    for u, v in corners:
        outline.add_corner(xodr.CornerLocal(u, v, 0, 12.0))
    obj.add_outline(outline)
    return obj


def main(out):
    # West arm: an S-bend of spirals and arcs (left, then as much right) that
    # moves it 14 m sideways, then straight; the others straight.
    bend = [
        xodr.Spiral(0.0, 0.02, 20),
        xodr.Arc(0.02, 10),
        xodr.Spiral(0.02, 0.0, 20),
        xodr.Spiral(0.0, -0.02, 20),
        xodr.Arc(-0.02, 10),
        xodr.Spiral(-0.02, 0.0, 20),
    ]
    west = arm(1, bend + [xodr.Line(ARM - 40)])
    south, east, north = (arm(i, [xodr.Line(ARM)]) for i in (2, 3, 4))
    roads = [west, south, east, north]

    creator = xodr.CommonJunctionCreator(id=JUNCTION, name="crossroads", startnum=101)
    for road, angle in zip(roads, (np.pi, 3 * np.pi / 2, 0.0, np.pi / 2)):
        creator.add_incoming_road_circular_geometry(road, RADIUS, angle, "successor")
    for i in range(1, 5):
        for j in range(1, 5):
            if i != j:
                creator.add_connection(i, j, -1, 1)

    # Buildings: 30 m × 24 m blocks in each corner, 6 m back from the sidewalks.
    north.add_object(building(1, 56.0, -13.5, [(0, 0), (30, 0), (30, -24), (0, -24)]))
    north.add_object(building(2, 56.0, 13.5, [(0, 0), (30, 0), (30, 24), (0, 24)]))
    south.add_object(building(3, 56.0, -13.5, [(0, 0), (30, 0), (30, -24), (0, -24)]))
    south.add_object(building(4, 56.0, 13.5, [(0, 0), (30, 0), (30, 24), (0, 24)]))
    # A crosswalk across the north arm, 4 m wide along it, over both driving lanes.
    crosswalk = xodr.Object(s=ARM - 8.0, t=0.0, id="5", Type=xodr.ObjectType.crosswalk, name="crosswalk")
    stripes = xodr.Outline(closed=True)
    for u, v in [(-2.0, -3.5), (2.0, -3.5), (2.0, 3.5), (-2.0, 3.5)]:
        stripes.add_corner(xodr.CornerLocal(u, v, 0, 0))
    crosswalk.add_outline(stripes)
    north.add_object(crosswalk)

    # Through the junction: 30 km/h.
    for road in creator.junction_roads:
        road.add_type(xodr.RoadType.town, speed=30, speed_unit="km/h")

    network = xodr.OpenDrive("crossroads", revMinor="6")
    for road in roads:
        network.add_road(road)
    network.add_junction_creator(creator)
    network.adjust_roads_and_lanes()
    network.write_xml(str(out))
    # scenariogeneration stamps the header with the date; drop it, so that a
    # rerun writes the same bytes.
    text = out.read_text()
    start = text.index(' date="')
    end = text.index('"', start + 7) + 1
    text = text[:start] + text[end:]
    # Its junction creator writes the arcs of the turns as spirals whose
    # curvature changes by a rounding error (1e-16), on which SUMO's netconvert
    # 1.28.0 fails (std::bad_alloc); write them as the arcs they are.
    def arc(match):
        start, end = float(match.group(1)), float(match.group(2))
        return f'<arc curvature="{start!r}"/>' if abs(end - start) < 1e-9 else match.group(0)

    text = re.sub(r'<spiral curvStart="([^"]+)" curvEnd="([^"]+)"/>', arc, text)
    out.write_text(text)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).with_name("crossroads.xodr"))
