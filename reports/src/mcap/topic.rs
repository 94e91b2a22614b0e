//! The topics of a recording (`docs/recording.md` describes each).

/// `sightline.Scenario`, once at time 0: the scenario text and how it was run.
pub const SCENARIO: &str = "/sightline/scenario";
/// `sightline.Outcome`, once per sweep point at the end: its exact metrics.
pub const OUTCOME: &str = "/sightline/outcome";
/// `sightline.Verdict`, once per requirement at the end.
pub const VERDICTS: &str = "/sightline/verdicts";
/// `foxglove.Log`, once per requirement at the end: the verdict in words.
pub const LOG: &str = "/log";
/// `sightline.Signals`, every step: what the step measured.
pub const SIGNALS: &str = "/sightline/signals";
/// `sightline.RequirementSignals`, every step: requirements over the steps so far.
pub const REQUIREMENTS: &str = "/sightline/requirements";
/// `foxglove.SceneUpdate`, once at time 0: roads, occluders, areas, the region.
pub const MAP: &str = "/scene/map";
/// `foxglove.FrameTransforms`, every step: the frame tree, `map` → each agent
/// in the scene → its sensors (and, with every point recorded, the last
/// step's again when a point's scene is cleared).
pub const TRANSFORMS: &str = "/tf";
/// `foxglove.SceneUpdate`, whenever the agents in the scene change: each
/// agent's box and id, locked to its frame.
pub const AGENTS: &str = "/scene/agents";
/// `sightline.Speeds`, every step of a world: each agent's speed.
pub const SPEEDS: &str = "/sightline/speeds";
/// `foxglove.SceneUpdate`, whenever the agents with sensors in the scene
/// change: their sensors' fields of view, each locked to its sensor's frame.
pub const FIELDS_OF_VIEW: &str = "/scene/fields_of_view";
/// `foxglove.Grid`, at the grid rate: fused probability and uncertainty.
pub const FUSED_GRID: &str = "/fusion/grid";
/// `sightline.Packet`, one per V2X packet.
pub const PACKETS: &str = "/v2x/packets";
/// `sightline.SemanticMessage`, one per semantic message an RSU sends the ego.
pub const MESSAGES: &str = "/semantic/messages";
/// `sightline.Arrival`, one per semantic message reaching the ego.
pub const ARRIVALS: &str = "/semantic/arrivals";
/// `sightline.Approach`, one per object coming within d_min of the ego.
pub const APPROACHES: &str = "/semantic/approaches";
/// `sightline.Object`, once per relevant road user of each semantic point at the end.
pub const OBJECTS: &str = "/semantic/objects";

/// `foxglove.SceneUpdate`, every step a cooperating agent is in the scene: what
/// it detected, where it placed it, and where it believes it is.
pub fn detections(agent: &str) -> String {
    format!("/perception/{agent}/detections")
}

/// `foxglove.Grid`, at the grid rate with `record.agent_grids`: a cooperating
/// agent's own grid.
pub fn agent_grid(agent: &str) -> String {
    format!("/perception/{agent}/grid")
}
