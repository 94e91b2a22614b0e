//! What each kind of scenario reads: the kind itself, and the keys `check`
//! refuses because the settings around them leave them without effect.
//!
//! A scenario is one of four kinds, by the sections it gives: the field
//! experiment (`field`), a world measuring collective perception
//! (`perception`), a world running the semantic pipeline (`semantic`), or a
//! joint world running both on one scene (`perception` and `semantic`). Two
//! passes refuse what a scenario writes without effect: the keys its kind never
//! reads ([`super::ignored`]), and [`unused`]: keys the settings around them
//! leave without effect in one configuration (a weight scaling for a rule that
//! weighs nothing, a sensor model no agent carries). The driver refuses those
//! where every sweep point agrees, and `vary` refuses a value that would make
//! one.
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
use crate::path::Path;
use crate::yaml::{Node, Value};

/// What a scenario simulates and measures, which decides the keys it reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// The static field experiment of seed 001 (`field`).
    Field,
    /// A world measuring collective perception (`perception`).
    Perception,
    /// A world running the roadside units' semantic pipeline (`semantic`).
    Semantic,
    /// A world running collective perception and the semantic pipeline
    /// together, on one scene (`perception` and `semantic`).
    Joint,
}

impl Kind {
    /// The kind of the scenario `tree`: the field experiment if it gives
    /// `field`, else a world by which of `perception` and `semantic` it gives;
    /// `None` when it gives none (the setup pass says why).
    pub(super) fn of(tree: &Node) -> Option<Self> {
        if tree.get("field").is_some() {
            return Some(Self::Field);
        }
        match (tree.get("perception").is_some(), tree.get("semantic").is_some()) {
            (true, true) => Some(Self::Joint),
            (true, false) => Some(Self::Perception),
            (false, true) => Some(Self::Semantic),
            (false, false) => None,
        }
    }

    /// The kind of a compiled configuration.
    pub(super) fn of_setup(setup: &Setup) -> Self {
        match &setup.experiment {
            Experiment::Field(_) => Self::Field,
            Experiment::World(world) => match (&world.perception, &world.semantic) {
                (Some(_), Some(_)) => Self::Joint,
                (Some(_), None) => Self::Perception,
                (None, _) => Self::Semantic,
            },
        }
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
    match &setup.experiment {
        Experiment::World(world) => found.world(world),
        Experiment::Field(_) => {
            // Sensors laid out on the grid move with it: every distance stays.
            let root = Path::root();
            if !has(tree, &root.key("field").key("sensors").key("layout").key("positions")) {
                found.check(root.key("grid").key("origin"), || {
                    "the sensors are laid out on the grid (`regular`, `random`), so moving the grid moves them \
                     with it and no distance changes; `positions` places them in the grid's frame"
                        .into()
                });
            }
        }
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
    let shares = world
        .perception
        .as_ref()
        .map(|p| p.ego == i || (agent.connected && !agent.sensors.is_empty()));
    let assists = world.semantic.as_ref().map(|s| s.rsus.contains(&i));
    match (shares, assists) {
        (Some(false), None) => Some(format!(
            "roadside unit `{id}` is not part of the ground truth, and shares nothing unless it is \
             `connected: true` with sensors"
        )),
        (None, Some(false)) => Some(format!(
            "roadside unit `{id}` is not in `semantic.rsus`, so it does not assist the ego, and it is not part of \
             the ground truth"
        )),
        (Some(false), Some(false)) => Some(format!(
            "roadside unit `{id}` is not part of the ground truth, shares no grid (it is not `connected: true` \
             with sensors) and does not assist the ego (it is not in `semantic.rsus`)"
        )),
        _ => None,
    }
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
        } else if world.localization.is_exact() {
            for key in [
                "filter",
                "process_position_sigma",
                "process_heading_sigma_deg",
                "odometry",
            ] {
                self.check(root.key("localization").key(key), || {
                    "`position_sigma` and `heading_sigma_deg` are 0: every estimate is the true pose, whatever the \
                     filter and its odometry"
                        .into()
                });
            }
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
        if !world.drives_vehicles() {
            for key in ["following", "headway", "min_gap", "deceleration"] {
                self.check(root.key("driving").key(key), || {
                    "no vehicle drives by the model: each one replays its trace or stands still".into()
                });
            }
        } else if world.driving.following == Following::None {
            let why = || "vehicles ignore each other (`following: none`), so no car-following model runs".to_string();
            for key in ["headway", "min_gap", "deceleration"] {
                self.check(root.key("driving").key(key), why);
            }
            if world.semantic.is_some() {
                self.check(root.key("semantic").key("caution").key("headway"), why);
            }
        }
        let traces = root.key("traces");
        // A configuration names its network and additional files itself.
        let config = has(self.tree, &traces.key("sumocfg"));
        if !config && !has(self.tree, &traces.key("poly")) {
            self.check(traces.key("occluder_types"), || {
                "it selects polygons of `traces.poly`, and there is none".into()
            });
        }
        if !config && !has(self.tree, &traces.key("net")) {
            self.check(traces.key("junction_areas"), || {
                "junctions come from `traces.net`, and there is none".into()
            });
        }
        self.agents(world);
        self.sensor_models(world);
        if let Some(semantic) = &world.semantic
            && matches!(world.agents[semantic.ego].motion, Motion::Trace { .. })
        {
            for key in ["headway", "speed_factor"] {
                self.check(root.key("semantic").key("caution").key(key), || {
                    "the ego replays its trace, so caution cannot slow it down".into()
                });
            }
        }
        if let Some(semantic) = &world.semantic {
            let vehicles = world.traffic.as_ref().is_some_and(|t| t.vehicles.is_some())
                || (world.agents.iter().enumerate()).any(|(i, a)| i != semantic.ego && a.kind.is_vehicle());
            if !vehicles {
                for key in ["hypotheses", "overspeed"] {
                    self.check(root.key("semantic").key(key), || {
                        "only vehicles are predicted at speed hypotheses and judged for speeding, and no vehicle \
                         but the ego can occur (no `traffic.vehicles`, every other agent a pedestrian or a roadside \
                         unit)"
                            .into()
                    });
                }
                if world.crosswalks.is_empty() {
                    let why = || {
                        "no conflict can be predicted: no vehicle but the ego can occur, and no crosswalk (where \
                         pedestrians are predicted) is declared or imported"
                            .to_string()
                    };
                    self.check(root.key("semantic").key("risk_for"), why);
                    self.check(root.key("semantic").key("caution"), why);
                    // The horizon also makes a pedestrian heading for an
                    // interaction area relevant.
                    if world.interaction_areas.is_empty() {
                        self.check(root.key("semantic").key("horizon"), || {
                            "no conflict can be predicted nor area approached: no vehicle but the ego can occur, \
                             and no crosswalk or interaction area is declared or imported"
                                .into()
                        });
                    }
                }
            }
        }
        if world.semantic.is_some() || world.perception.as_ref().is_some_and(|p| p.messages.is_some()) {
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
            // The engine lets an agent in at the first step within a millionth
            // of a step of its start time.
            let last = world.steps.saturating_sub(1) as f64 * world.step;
            if let Motion::Along { start_time, .. } = agent.motion
                && start_time > last + 1e-6 * world.step
            {
                self.check(at.key("start").key("time"), || {
                    format!(
                        "`{id}` would start at {start_time} s, after the run's last step at {} s: it never enters",
                        (last * 1e9).round() / 1e9
                    )
                });
            }
            if matches!(agent.kind, AgentKind::Pedestrian | AgentKind::Rsu) {
                self.check(at.key("lane"), || "only vehicles keep to a lane of a road".into());
            }
            if agent.kind == AgentKind::Pedestrian {
                self.check(at.key("speed").key("limit_factor"), || {
                    "a pedestrian's path has no speed limit".into()
                });
            }
            // A roadside unit in `semantic.rsus` perceives for the pipeline.
            let assists = world.semantic.as_ref().is_some_and(|s| s.rsus.contains(&i));
            if world.perception.as_ref().is_some_and(|p| p.ego != i) {
                if !agent.connected && !agent.sensors.is_empty() && !assists {
                    self.check(at.key("sensors"), || {
                        format!("`{id}` is not `connected: true`: only the ego and agents that share see for the ego")
                    });
                }
                // A connected road user of a joint world sends the ego its own
                // state (the semantic pipeline's radio), sensors or not.
                let sends = world.is_joint() && agent.kind != AgentKind::Rsu;
                if agent.connected && agent.sensors.is_empty() && !sends {
                    self.check(at.key("connected"), || {
                        format!("`{id}` has no sensors, and a connected agent shares what it perceives")
                    });
                }
            }
            let cooperates = world.perception.as_ref().is_some_and(|p| p.cooperating.contains(&i));
            if world.is_joint() && agent.kind == AgentKind::Rsu && !cooperates {
                self.check(at.key("size"), || {
                    format!(
                        "roadside unit `{id}` is not part of the ground truth, and shares no grid in which to \
                         report a footprint of its own"
                    )
                });
            }
            // In a joint world, collective perception's rules above say which
            // agents' sensors and connections count.
            if let Some(semantic) = world.semantic.as_ref().filter(|_| !world.is_joint()) {
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
            // In a joint world, the cooperating agents' grids read a model too.
            let by_cooperator = world
                .perception
                .as_ref()
                .is_some_and(|p| carriers.iter().any(|i| p.cooperating.contains(i)));
            if by_cooperator {
                if !by_rsu {
                    self.check(at.key("velocity_noise"), || {
                        "no roadside unit of the pipeline carries this model, the ego's own sight in the pipeline \
                         is exact, and an occupancy grid holds no speeds"
                            .into()
                    });
                }
                continue;
            }
            if world.perception.is_some() {
                self.check(at.key("ray_spacing_deg"), || {
                    "no cooperating agent carries this model, so it carves no free space in a grid".into()
                });
            }
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

    /// The radio's keys; in a joint world the semantic pipeline's radio
    /// reads every one `v2x.penetration` aside, which `joint` refuses.
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
            PathLossModel::Tr37885Urban => {
                for key in ["vehicle_antenna_m", "rsu_antenna_m"] {
                    self.check(channel.key(key), || {
                        "TR 37.885's urban V2V path loss ignores antenna heights".into()
                    });
                }
            }
            PathLossModel::Tr36885Urban => {}
        }
        let urban = matches!(
            world.v2x.channel.model,
            PathLossModel::Tr36885Urban | PathLossModel::Tr37885Urban
        );
        if urban && world.occluders.is_empty() {
            self.check(channel.key("nlos_shadowing_sigma_db"), || {
                "only a building blocks a link, and there is none (declared or imported): every link is line of \
                 sight"
                    .into()
            });
        }
        if let Some(semantic) = &world.semantic
            && world.perception.is_none()
            && semantic.rsus.iter().all(|&i| world.agents[i].antenna_m.is_some())
        {
            self.check(channel.key("rsu_antenna_m"), || {
                "every roadside unit has its own antenna height (a SUMO point of interest's `height`)".into()
            });
        }
        if world.is_joint() {
            return;
        }
        if let Some(perception) = &world.perception {
            if !perception
                .cooperating
                .iter()
                .any(|&a| world.agents[a].kind == AgentKind::Rsu)
            {
                self.check(channel.key("rsu_antenna_m"), || {
                    "no roadside unit cooperates, so every message goes between vehicles' antennas".into()
                });
            }
            return;
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
