//! What each kind of scenario reads, and the keys `check` refuses because they
//! would change nothing that is simulated or measured.
//!
//! A scenario is one of three kinds, by the section it gives: the field
//! experiment (`field`), a world measuring collective perception
//! (`perception`), or a world running the semantic pipeline (`semantic`). Two
//! passes refuse what a scenario writes without effect:
//! - [`ignored_keys`]: sections and keys its kind never reads (`v2x` in a
//!   collective-perception world), wherever they are written (the setup pass
//!   refuses them); a sweep or `vary` axis that sets one is refused by
//!   [`ignored`];
//! - [`unused`]: keys the settings around them leave without effect in one
//!   configuration (a weight scaling for a rule that weighs nothing, a sensor
//!   model no agent carries). The driver refuses those where every sweep point
//!   agrees, and `vary` refuses a value that would make one.
//!
//! A key is refused when what it configures does not run: its kind never
//! models it, another variant is chosen (a method, a filter, a path-loss model),
//! or nothing uses it (no agent carries a sensor model). A rate of zero is a
//! value, not another model: `speed` of pedestrians generated at 0 per minute
//! is accepted, so that a sweep or a search may reach 0.

use super::context::has;
use crate::model::{
    AgentKind, Experiment, Following, Motion, Odometry, PathLossModel, PoseFilter, RsuSight, Rule, Setup, World,
};
use crate::path::{Path, Segment};
use crate::yaml::{Node, Value};
use Kind::{Field, Perception, Semantic};

/// What a scenario simulates and measures, which decides the keys it reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// The static field experiment of seed 001 (`field`).
    Field,
    /// A world measuring collective perception (`perception`).
    Perception,
    /// A world running the roadside units' semantic pipeline (`semantic`).
    Semantic,
}

impl Kind {
    /// The kind of the scenario `tree`, by the first of `field`, `perception`,
    /// `semantic` it gives; `None` when it gives none (the setup pass says why).
    pub(super) fn of(tree: &Node) -> Option<Self> {
        [
            ("field", Self::Field),
            ("perception", Self::Perception),
            ("semantic", Self::Semantic),
        ]
        .into_iter()
        .find_map(|(section, kind)| tree.get(section).map(|_| kind))
    }

    /// The kind of a compiled configuration.
    pub(super) fn of_setup(setup: &Setup) -> Self {
        match &setup.experiment {
            Experiment::Field(_) => Self::Field,
            Experiment::World(world) if world.perception.is_some() => Self::Perception,
            Experiment::World(_) => Self::Semantic,
        }
    }
}

/// A section or key a kind of scenario never reads: a dotted pattern in which
/// `*` stands for any map key or list index.
struct Ignored {
    kinds: &'static [Kind],
    pattern: &'static str,
    why: &'static str,
}

const WORLDS: &[Kind] = &[Perception, Semantic];

const NOT_A_WORLD: &str = "it belongs to a world, and the scenario simulates the field experiment (`field`); \
                           a scenario simulates one or the other";
const NO_WORLD_RECORDING: &str = "the field experiment has no steps, so `run.mcap` records no grid";
const NO_GRID: &str = "a semantic world fuses no occupancy grid (`grid`, `fusion` and `decision` belong to the \
                       field experiment and to collective perception)";
const NO_SEMANTIC_PIPELINE: &str = "it serves the semantic pipeline's generated traffic and relevance layer, \
                                    which a collective-perception world does not run";

/// Every section and key a kind never reads, in the order they are reported.
const IGNORED: &[Ignored] = &[
    // The field experiment has no world.
    Ignored {
        kinds: &[Field],
        pattern: "time",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "traces",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "roads",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "occluders",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "sensor_models",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "agents",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "localization",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "perception",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "traffic",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "crosswalks",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "interaction_areas",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "driving",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "v2x",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "semantic",
        why: NOT_A_WORLD,
    },
    Ignored {
        kinds: &[Field],
        pattern: "record.grid_rate",
        why: NO_WORLD_RECORDING,
    },
    Ignored {
        kinds: &[Field],
        pattern: "record.agent_grids",
        why: NO_WORLD_RECORDING,
    },
    // Collective perception: no radio yet, no generated traffic, no semantic pipeline.
    Ignored {
        kinds: &[Perception],
        pattern: "v2x",
        why: "a collective-perception world does not model the radio yet: every cooperating agent's grid \
              reaches the ego at the step it is observed, complete and without delay (issue 16 will model it)",
    },
    Ignored {
        kinds: &[Perception],
        pattern: "semantic",
        why: "a world measures `perception` or `semantic`, not both: split it into two scenarios",
    },
    Ignored {
        kinds: &[Perception],
        pattern: "traffic",
        why: "background traffic is generated in semantic worlds only; a collective-perception world moves \
              the agents it declares",
    },
    Ignored {
        kinds: &[Perception],
        pattern: "crosswalks",
        why: NO_SEMANTIC_PIPELINE,
    },
    Ignored {
        kinds: &[Perception],
        pattern: "interaction_areas",
        why: NO_SEMANTIC_PIPELINE,
    },
    Ignored {
        kinds: &[Perception],
        pattern: "traces.junction_areas",
        why: NO_SEMANTIC_PIPELINE,
    },
    Ignored {
        kinds: &[Perception],
        pattern: "sensor_models.*.velocity_noise",
        why: "an occupancy grid holds no speeds: collective perception measures none",
    },
    // The semantic pipeline: no occupancy grid, no self-localization, no free space.
    Ignored {
        kinds: &[Semantic],
        pattern: "grid",
        why: NO_GRID,
    },
    Ignored {
        kinds: &[Semantic],
        pattern: "fusion",
        why: NO_GRID,
    },
    Ignored {
        kinds: &[Semantic],
        pattern: "decision",
        why: NO_GRID,
    },
    Ignored {
        kinds: &[Semantic],
        pattern: "record.grid_rate",
        why: "a semantic world fuses no grid, so `run.mcap` records none",
    },
    Ignored {
        kinds: &[Semantic],
        pattern: "record.agent_grids",
        why: "a semantic world fuses no grid, so `run.mcap` records none",
    },
    Ignored {
        kinds: &[Semantic],
        pattern: "localization",
        why: "a semantic world does not model self-localization: the ego and the roadside units know their \
              own poses exactly",
    },
    Ignored {
        kinds: &[Semantic],
        pattern: "sensor_models.*.ray_spacing_deg",
        why: "a semantic world carves no free space: a sensor sees an object along one ray to its centre",
    },
    // Every world is flat.
    Ignored {
        kinds: WORLDS,
        pattern: "occluders.*.height",
        why: "sight and radio are computed in the plane (a 2-D world), so an occluder's height changes nothing",
    },
];

/// Whether the dotted `pattern` (with `*` for any key or index) is a prefix of `path`.
fn covers(pattern: &str, path: &[Segment]) -> bool {
    let parts: Vec<&str> = pattern.split('.').collect();
    parts.len() <= path.len()
        && parts.iter().zip(path).all(|(part, segment)| match segment {
            _ if *part == "*" => true,
            Segment::Key(key) => key == part,
            Segment::Index(_) => false,
        })
}

/// Why a scenario of `kind` never reads the setting at `path`: the setting or
/// a section holding it is one its kind ignores. `None` when it may read it.
pub(super) fn ignored(kind: Kind, path: &Path) -> Option<&'static str> {
    IGNORED
        .iter()
        .find(|rule| rule.kinds.contains(&kind) && covers(rule.pattern, path.segments()))
        .map(|rule| rule.why)
}

/// Every key of `tree` that a scenario of `kind` never reads, with why; a key
/// inside one already listed is not listed again.
pub(super) fn ignored_keys(tree: &Node, kind: Kind) -> Vec<(Path, &'static str)> {
    let mut found: Vec<(Path, &'static str)> = Vec::new();
    for rule in IGNORED.iter().filter(|rule| rule.kinds.contains(&kind)) {
        let parts: Vec<&str> = rule.pattern.split('.').collect();
        for path in expand(tree, Path::root(), &parts) {
            if !found
                .iter()
                .any(|(outer, _)| path.segments().starts_with(outer.segments()))
            {
                found.push((path, rule.why));
            }
        }
    }
    found
}

/// The paths in `node` (at `at`) that the pattern `parts` matches.
fn expand(node: &Node, at: Path, parts: &[&str]) -> Vec<Path> {
    let Some((first, rest)) = parts.split_first() else {
        return vec![at];
    };
    match &node.value {
        Value::Map(entries) => entries
            .iter()
            .filter(|(key, _)| *first == "*" || key.name == *first)
            .flat_map(|(key, child)| expand(child, at.key(&key.name), rest))
            .collect(),
        Value::Seq(items) if *first == "*" => items
            .iter()
            .enumerate()
            .flat_map(|(i, child)| expand(child, at.index(i), rest))
            .collect(),
        _ => Vec::new(),
    }
}

/// The keys of the configuration `tree`, compiled into `setup`, that the
/// settings around them leave without effect, each with why. Only keys the
/// file gives count: a default is not a claim.
pub(super) fn unused(tree: &Node, setup: &Setup) -> Vec<(Path, String)> {
    let mut found = Unused {
        tree,
        found: Vec::new(),
    };
    if let Some(occupancy) = &setup.occupancy {
        let fusion = Path::root().key("fusion");
        let method = occupancy.fusion.rule.method().name();
        if !matches!(occupancy.fusion.rule, Rule::DistanceWeighted(_) | Rule::Hybrid { .. }) {
            for key in ["weights", "sources"] {
                found.check(fusion.key(key), || {
                    format!("only the distance-weighted rules weigh sources, and the scenario fuses with `{method}`")
                });
            }
        }
        if !matches!(occupancy.fusion.rule, Rule::Hybrid { .. }) {
            found.check(fusion.key("switch"), || {
                format!("only the `hybrid` rule switches, and the scenario fuses with `{method}`")
            });
        }
    }
    if let Experiment::World(world) = &setup.experiment {
        found.world(world);
    }
    found.found
}

/// Why agent `i` of `world`, a roadside unit, changes nothing: it is not part
/// of the ground truth, so it counts only if it shares its grid (collective
/// perception) or assists the ego (the semantic pipeline). `None` for any other
/// agent, and for a roadside unit that does either.
fn idle_roadside_unit(world: &World, i: usize) -> Option<String> {
    let agent = &world.agents[i];
    if agent.kind != AgentKind::Rsu {
        return None;
    }
    let id = &agent.id;
    if let Some(perception) = &world.perception {
        let shares = agent.connected && !agent.sensors.is_empty();
        return (perception.ego != i && !shares).then(|| {
            format!(
                "roadside unit `{id}` is not part of the ground truth, and shares nothing unless it is \
                 `connected: true` with sensors"
            )
        });
    }
    let semantic = world.semantic.as_ref()?;
    (!semantic.rsus.contains(&i)).then(|| {
        format!(
            "roadside unit `{id}` is not in `semantic.rsus`, so it does not assist the ego, and it is not part of \
             the ground truth"
        )
    })
}

/// What [`unused`] collects.
struct Unused<'a> {
    tree: &'a Node,
    found: Vec<(Path, String)>,
}

impl Unused<'_> {
    /// Lists `path` with `why()` when the file gives it.
    fn check(&mut self, path: Path, why: impl FnOnce() -> String) {
        if has(self.tree, &path) {
            self.found.push((path, why()));
        }
    }

    fn world(&mut self, world: &World) {
        let root = Path::root();
        let moving_cooperator = world.perception.as_ref().is_some_and(|p| {
            p.cooperating
                .iter()
                .any(|&i| !matches!(world.agents[i].motion, Motion::Fixed { .. }))
        });
        if world.perception.is_some() && !moving_cooperator {
            self.check(root.key("localization"), || {
                "every cooperating agent is a roadside unit, whose pose is surveyed: nobody localizes".into()
            });
        } else if world.localization.filter == PoseFilter::None {
            for key in ["process_position_sigma", "process_heading_sigma_deg", "odometry"] {
                self.check(root.key("localization").key(key), || {
                    "`filter: none` takes each measurement as it is, without the Kalman filter's motion model".into()
                });
            }
        } else if world.localization.odometry == Odometry::Exact {
            let odometry = root.key("localization").key("odometry");
            for key in ["speed_sigma", "speed_bias", "yaw_rate_sigma_deg", "yaw_rate_bias_deg"] {
                self.check(odometry.key(key), || {
                    "`model: exact` predicts with the agent's exact motion: no reading has noise or bias".into()
                });
            }
        }
        if world.driving.following == Following::None {
            let why = || "vehicles ignore each other (`following: none`), so no car-following model runs".to_string();
            for key in ["headway", "min_gap", "deceleration"] {
                self.check(root.key("driving").key(key), why);
            }
            if world.semantic.is_some() {
                self.check(root.key("semantic").key("caution").key("headway"), why);
            }
        }
        let traces = root.key("traces");
        if !has(self.tree, &traces.key("poly")) {
            self.check(traces.key("occluder_types"), || {
                "it selects polygons of `traces.poly`, and there is none".into()
            });
        }
        if !has(self.tree, &traces.key("net")) {
            self.check(traces.key("junction_areas"), || {
                "junctions come from `traces.net`, and there is none".into()
            });
        }
        self.agents(world);
        self.sensor_models(world);
        if let Some(semantic) = &world.semantic {
            if matches!(world.agents[semantic.ego].motion, Motion::Trace { .. }) {
                for key in ["headway", "speed_factor"] {
                    self.check(root.key("semantic").key("caution").key(key), || {
                        "the ego replays its trace, so caution cannot slow it down".into()
                    });
                }
            }
            self.v2x(world);
        }
    }

    /// The declared agents (imported ones follow them in `world.agents`).
    fn agents(&mut self, world: &World) {
        let declared = &world.agents[..world.agents.len() - world.imported];
        let list = Path::root().key("agents");
        for (i, agent) in declared.iter().enumerate() {
            let at = list.index(i);
            let id = &agent.id;
            if let Some(why) = idle_roadside_unit(world, i) {
                self.found.push((at, why));
                continue;
            }
            if agent.kind != AgentKind::Rsu {
                self.check(at.key("heading_deg"), || {
                    "only a roadside unit stands at a heading; a moving agent heads along its way".into()
                });
            } else {
                for key in ["start", "speed"] {
                    self.check(at.key(key), || "a roadside unit stands still".into());
                }
            }
            if matches!(agent.kind, AgentKind::Pedestrian | AgentKind::Rsu) {
                self.check(at.key("lane"), || "only vehicles keep to a lane of a road".into());
            }
            if agent.kind == AgentKind::Pedestrian {
                self.check(at.key("speed").key("limit_factor"), || {
                    "a pedestrian's path has no speed limit".into()
                });
            }
            if world.perception.as_ref().is_some_and(|p| p.ego != i) {
                if !agent.connected && !agent.sensors.is_empty() {
                    self.check(at.key("sensors"), || {
                        format!("`{id}` is not `connected: true`: only the ego and agents that share see for the ego")
                    });
                }
                if agent.connected && agent.sensors.is_empty() {
                    self.check(at.key("connected"), || {
                        format!("`{id}` has no sensors, and a connected agent shares what it perceives")
                    });
                }
            }
            if let Some(semantic) = &world.semantic {
                if agent.kind == AgentKind::Rsu {
                    self.check(at.key("connected"), || {
                        "a roadside unit reaches the ego through the semantic pipeline; `connected` applies to road \
                         users, which send the ego their own state"
                            .into()
                    });
                    self.check(at.key("size"), || {
                        "a roadside unit is not part of the ground truth, and in a semantic world it reports no \
                         footprint of its own"
                            .into()
                    });
                } else if i != semantic.ego && !agent.sensors.is_empty() {
                    self.check(at.key("sensors"), || {
                        "in a semantic world only the ego's and the roadside units' sensors perceive".into()
                    });
                }
            }
        }
    }

    /// Sensor models no agent carries, and the keys of those only an agent that
    /// ignores them carries.
    fn sensor_models(&mut self, world: &World) {
        let Some(Value::Map(models)) = self.tree.get("sensor_models").map(|n| &n.value) else {
            return;
        };
        let declared = &world.agents[..world.agents.len() - world.imported];
        for (key, _) in models {
            let at = Path::root().key("sensor_models").key(&key.name);
            let carriers: Vec<usize> = declared
                .iter()
                .enumerate()
                .filter(|(_, agent)| agent.sensors.iter().any(|s| s.model == key.name))
                .map(|(i, _)| i)
                .collect();
            if carriers.is_empty() {
                self.found
                    .push((at, format!("no agent carries sensor model `{}`", key.name)));
                continue;
            }
            let Some(semantic) = &world.semantic else { continue };
            let by_ego = carriers.contains(&semantic.ego);
            let by_rsu = carriers.iter().any(|i| semantic.rsus.contains(i));
            if !by_rsu {
                for key in [
                    "detection_probability",
                    "position_noise",
                    "size_noise",
                    "velocity_noise",
                ] {
                    self.check(at.key(key), || {
                        "no roadside unit carries this model, and the ego of a semantic world sees what is in view \
                         and in line of sight, exactly"
                            .into()
                    });
                }
            }
            if !by_ego && semantic.rsu_sight == RsuSight::Range {
                self.check(at.key("fov_deg"), || {
                    "a roadside unit with `rsu_sight: range` perceives all around, within range".into()
                });
                self.check(at.key("mount").key("yaw_deg"), || {
                    "a roadside unit with `rsu_sight: range` perceives all around, within range".into()
                });
            }
        }
    }

    fn v2x(&mut self, world: &World) {
        let v2x = Path::root().key("v2x");
        let channel = v2x.key("channel");
        match world.v2x.channel.model {
            PathLossModel::Ideal => {
                for key in [
                    "tx_power_dbm",
                    "shadowing_sigma_db",
                    "nlos_shadowing_sigma_db",
                    "device_loss_db",
                    "sensitivity_dbm",
                    "carrier_ghz",
                    "vehicle_antenna_m",
                    "rsu_antenna_m",
                ] {
                    self.check(channel.key(key), || "every packet arrives under `model: ideal`".into());
                }
            }
            PathLossModel::Tr36885Highway => {
                self.check(channel.key("nlos_shadowing_sigma_db"), || {
                    "the freeway model treats every link as line of sight".into()
                });
                for key in ["vehicle_antenna_m", "rsu_antenna_m"] {
                    self.check(channel.key(key), || {
                        "the freeway model's path loss ignores antenna heights".into()
                    });
                }
            }
            PathLossModel::Tr36885Urban => {}
        }
        let generated = world.traffic.as_ref().is_some_and(|t| t.vehicles.is_some());
        if !generated && world.imported == 0 {
            self.check(v2x.key("penetration"), || {
                "it draws which generated (`traffic.vehicles`) and imported (`traces`) vehicles are connected, and \
                 there are none"
                    .into()
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(dotted: &str) -> Path {
        Path::parse_dotted(dotted).unwrap()
    }

    #[test]
    fn a_section_covers_the_settings_inside_it() {
        assert!(ignored(Perception, &path("v2x.channel.tx_power_dbm")).is_some());
        assert!(ignored(Perception, &path("v2x")).is_some());
        assert!(ignored(Semantic, &path("v2x.latency")).is_none());
        assert!(ignored(Semantic, &path("sensor_models.lidar.ray_spacing_deg")).is_some());
        assert!(ignored(Semantic, &path("sensor_models.lidar.range")).is_none());
        // A mapping that holds an ignored key is not ignored as a whole.
        assert!(ignored(Perception, &path("sensor_models.lidar")).is_none());
    }
}
