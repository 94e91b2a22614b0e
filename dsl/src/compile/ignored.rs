//! The sections and keys each kind of scenario never reads (`v2x` in the
//! field experiment, `v2x.messages` in a semantic world), refused wherever they
//! are written: [`ignored_keys`] for the setup pass, [`ignored`] for a sweep or
//! `vary` axis that sets one.

use super::kind::Kind::{self, Field, Joint, Perception, Semantic};
use crate::path::{Path, Segment};
use crate::yaml::{Node, Value};

/// A section or key a kind of scenario never reads: a dotted pattern in which
/// `*` stands for any map key or list index.
struct Ignored {
    kinds: &'static [Kind],
    pattern: &'static str,
    why: &'static str,
}

const WORLDS: &[Kind] = &[Perception, Semantic, Joint];

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
        pattern: "map",
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
        pattern: "areas",
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
    // Collective perception: no generated traffic, no semantic pipeline (with
    // `semantic`, the scenario is a joint world, which reads them).
    Ignored {
        kinds: &[Perception],
        pattern: "traffic",
        why: "background traffic is generated where the semantic pipeline runs (`semantic`); a \
              collective-perception world moves the agents it declares",
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
        pattern: "areas",
        why: "areas select road users of per-object checks, which judge the semantic pipeline's records, or the \
              object-steps a system under test is judged on, and the scenario has neither",
    },
    Ignored {
        kinds: &[Perception],
        pattern: "traces.junction_areas",
        why: NO_SEMANTIC_PIPELINE,
    },
    Ignored {
        kinds: &[Perception],
        pattern: "map.junction_areas",
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
        pattern: "v2x.messages",
        why: "it configures the messages of collective perception; the semantic pipeline sends its own \
              (the RSUs' semantic messages, the ego's plan, connected road users' states)",
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
/// inside one already listed is not listed again. A perception world `driven`
/// by a system under test reads `areas`: its metrics (`sut_*`) select
/// object-steps and detections by them.
pub(super) fn ignored_keys(tree: &Node, kind: Kind, driven: bool) -> Vec<(Path, &'static str)> {
    let driven = driven && kind == Perception;
    let mut found: Vec<(Path, &'static str)> = Vec::new();
    let rules = IGNORED.iter().filter(|rule| !(driven && rule.pattern == "areas"));
    for rule in rules.filter(|rule| rule.kinds.contains(&kind)) {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn path(dotted: &str) -> Path {
        Path::parse_dotted(dotted).unwrap()
    }

    #[test]
    fn a_section_covers_the_settings_inside_it() {
        assert!(ignored(Field, &path("v2x.channel.tx_power_dbm")).is_some());
        assert!(ignored(Field, &path("v2x")).is_some());
        assert!(ignored(Semantic, &path("v2x.latency")).is_none());
        assert!(ignored(Perception, &path("v2x.latency")).is_none());
        assert!(ignored(Semantic, &path("v2x.messages.rate_hz")).is_some());
        assert!(ignored(Semantic, &path("sensor_models.lidar.ray_spacing_deg")).is_some());
        assert!(ignored(Semantic, &path("sensor_models.lidar.range")).is_none());
        // A mapping that holds an ignored key is not ignored as a whole.
        assert!(ignored(Perception, &path("sensor_models.lidar")).is_none());
    }
}
