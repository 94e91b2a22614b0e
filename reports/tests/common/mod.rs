//! Scenarios shared by the integration tests.

/// A small junction: an ego, a cooperating car and an RSU, 6 s at 10 Hz, fused
/// by Bayes and by Dempster (one shared-data group of two points).
pub const WORLD: &str = "sightline: 1
name: t
time: { duration: 6, step: 0.1 }
grid: { origin: [-50, -50], size: [100, 100], cell: 0.5 }
roads:
  - { id: ring, roundabout: { center: [0, 0], radius: 10 }, speed_limit: 6 }
  - { id: arm_in, polyline: [[-1.75, 45], [-1.75, 10.3]], speed_limit: 12 }
  - { id: east_out, polyline: [[10.3, -1.75], [45, -1.75]], speed_limit: 12 }
occluders:
  - { id: block, polygon: [[15, 15], [40, 15], [40, 40], [15, 40]] }
sensor_models:
  lidar: { range: 40 }
agents:
  - { id: ego, kind: car, route: [arm_in, ring, east_out], speed: { target: 8 }, connected: true, sensors: [lidar] }
  - { id: cav, kind: car, route: [arm_in, ring, east_out], start: { offset: 20 }, speed: { target: 8 }, connected: true, sensors: [lidar] }
  - { id: rsu, kind: rsu, position: [12, 12], sensors: [lidar], connected: true }
  - { id: walker, kind: pedestrian, path: [[-8, 20], [8, 20]], speed: { target: 1.4 } }
perception: { ego: ego }
sweep: { fusion: [{ method: bayes }, { method: dempster }] }
requirements:
  - { id: REC, text: recall, check: { metric: occupied_recall, at_least: 0.5 } }
  - { id: MASS, text: masses, check: { invariant: mass_function } }
record: { point: 1, grid_rate: 2, agent_grids: true }
";
