//! What the models idealise, as data: each model declares its simplifications
//! beside its code, and [`idealisations`] lists those that applied to a run, for
//! the report's "Assumptions and limitations".
//!
//! A model's own simplifications apply whenever it runs; a model option (a
//! pose filter, a fusion method, a path-loss model …) adds those of its choice
//! ([`ModelOption::idealisations`]), so a run lists what its settings assumed,
//! not everything the tool could assume.

use serde::Serialize;
use sightline_dsl::{
    ErrorModel, Experiment, Following, FusionMethod, ImportKind, LabelledBy, OdometryModel, PathLossModel, PoseFilter,
    RiskScope, RsuSight, Rule, Scenario, Setup, ShareCycles, SourceCombination, SwitchMeasure, WeightScaling,
};

use crate::{field, fusion, semantic, v2x, world};

/// A simplification a model makes, stated for an assessor: what the model
/// takes as given that the real system does not guarantee.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub struct Idealisation {
    /// A stable id, `model.what` (`sight.one-ray`).
    pub id: &'static str,
    /// The simplification and what it means for a verdict, in a sentence or two.
    pub text: &'static str,
}

/// A choice among a model's variants that a scenario makes: a value of one of
/// the language's enumerations that select how something is modelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelOption {
    /// `localization.filter`.
    PoseFilter(PoseFilter),
    /// `localization.odometry.model` (a Kalman filter's).
    OdometryModel(OdometryModel),
    /// `fusion.method`.
    FusionMethod(FusionMethod),
    /// `fusion.weights`.
    WeightScaling(WeightScaling),
    /// `fusion.sources`.
    SourceCombination(SourceCombination),
    /// `fusion.switch.measure`.
    SwitchMeasure(SwitchMeasure),
    /// `field.masses.error_model`.
    ErrorModel(ErrorModel),
    /// `v2x.channel.model`.
    PathLossModel(PathLossModel),
    /// `driving.following`.
    Following(Following),
    /// `semantic.risk_for`.
    RiskScope(RiskScope),
    /// `semantic.rsu_sight`.
    RsuSight(RsuSight),
    /// `semantic.shares_over` and `semantic.contribution_over`.
    ShareCycles(ShareCycles),
    /// `semantic.labelled_by`.
    LabelledBy(LabelledBy),
}

impl ModelOption {
    /// The idealisations choosing this option adds to its model's own; empty
    /// when the option idealises nothing more (each model says so explicitly).
    pub fn idealisations(self) -> &'static [Idealisation] {
        match self {
            Self::PoseFilter(filter) => world::localization_idealisations(filter),
            Self::OdometryModel(model) => world::odometry_idealisations(model),
            Self::FusionMethod(method) => fusion::method_idealisations(method),
            // The weighted rules' parameters change how evidence is weighed, not
            // what is assumed of it: the method's entry covers them.
            Self::WeightScaling(WeightScaling::SumToOne | WeightScaling::MeanOne | WeightScaling::NearestOne)
            | Self::SourceCombination(SourceCombination::AllAtOnce | SourceCombination::Pairwise)
            | Self::SwitchMeasure(SwitchMeasure::Difference | SwitchMeasure::Ratio) => &[],
            Self::ErrorModel(model) => field::error_model_idealisations(model),
            Self::PathLossModel(model) => v2x::path_loss_idealisations(model),
            Self::Following(following) => world::following_idealisations(following),
            Self::RsuSight(sight) => semantic::rsu_sight_idealisations(sight),
            // Which objects are predicted, which cycles are counted and which
            // labels make an object labelled are choices of what is measured,
            // not simplifications of the world.
            Self::RiskScope(RiskScope::Relevant | RiskScope::All)
            | Self::ShareCycles(ShareCycles::EgoInRange | ShareCycles::All)
            | Self::LabelledBy(LabelledBy::Any | LabelledBy::Critical) => &[],
        }
    }
}

/// What driving a system under test over its protocol takes as given (the
/// CLI drives it; the engine's `system` judges it).
const SYSTEM_UNDER_TEST: [Idealisation; 3] = [
    Idealisation {
        id: "system.synchronous",
        text: "The system under test is stepped synchronously: the simulated world waits for its answer, so the \
               time it takes to compute counts in no latency; `sut_latency` counts simulated steps only, and a \
               system too slow for real time passes as long as it answers within `step_timeout`.",
    },
    Idealisation {
        id: "system.lossless",
        text: "Its input is what the served sensors have in view, as exact ground truth with sightline's \
               visibility (osi3.SensorView), delivered whole and on time at every step: no sensor noise, no \
               dropped or late frames, and no V2X link in between.",
    },
    Idealisation {
        id: "system.centre-match",
        text: "Its detections are judged by their centres alone, matched one to one within the gate, nearest \
               first (not an optimal assignment): size, heading, velocity and class are not judged.",
    },
];

/// What reading a world's map from an OpenDRIVE file (`map`; the reader is
/// `sightline_dsl::import::opendrive`) takes as given.
const OPENDRIVE_MAP: [Idealisation; 3] = [
    Idealisation {
        id: "map.flat",
        text: "The OpenDRIVE map is read flat: elevation, superelevation and the heights of lanes and objects are \
               dropped, so every road, building and line of sight lies in one plane, and a crest or a dip that \
               would hide a road user does not.",
    },
    Idealisation {
        id: "map.lane-centre",
        text: "Vehicles on the map keep to their lane's centreline (sampled at most 1 m apart, within 1 cm of a \
               curve) and never change lanes; the map's road marks, signals, priorities and access rules are not \
               read.",
    },
    Idealisation {
        id: "map.speed-limit",
        text: "A lane's speed limit is the lowest that applies anywhere along it (its own <speed>, else its \
               road's <type><speed>), or `map.speed_limit` where the map gives none.",
    },
];

/// The idealisations that applied to a run of `scenario`: at every sweep
/// point, those of the models it runs and of the options it chooses, then
/// those of the imported map. Each is listed once, in the order of the first
/// point that needs it.
pub fn idealisations(scenario: &Scenario) -> Vec<Idealisation> {
    let mut listed: Vec<Idealisation> = Vec::new();
    for point in &scenario.points {
        for idealisation in of_setup(&point.setup) {
            if !listed.contains(&idealisation) {
                listed.push(idealisation);
            }
        }
    }
    if scenario
        .imports
        .iter()
        .any(|import| import.kind == ImportKind::OpenDrive)
    {
        listed.extend(OPENDRIVE_MAP);
    }
    if scenario.system_under_test.is_some() {
        listed.extend(SYSTEM_UNDER_TEST);
    }
    listed
}

/// The idealisations of one configuration: its models', then its options'.
fn of_setup(setup: &Setup) -> Vec<Idealisation> {
    let mut listed = match &setup.experiment {
        Experiment::Field(_) => field::IDEALISATIONS.to_vec(),
        // A joint world runs both models: the grid's, then the pipeline's.
        Experiment::World(w) => {
            let mut listed = w
                .perception
                .as_ref()
                .map_or_else(Vec::new, |perception| world::idealisations(w, perception));
            for idealisation in w.semantic.iter().flat_map(|s| semantic::idealisations(w, s)) {
                if !listed.contains(&idealisation) {
                    listed.push(idealisation);
                }
            }
            listed
        }
    };
    for option in options(setup) {
        listed.extend_from_slice(option.idealisations());
    }
    listed
}

/// The model options a configuration chooses, in pipeline order.
fn options(setup: &Setup) -> Vec<ModelOption> {
    let mut options = Vec::new();
    match &setup.experiment {
        Experiment::Field(field) => options.push(ModelOption::ErrorModel(field.masses.error_model)),
        Experiment::World(world) => {
            if world.drives_vehicles() {
                options.push(ModelOption::Following(world.driving.following));
            }
            // Exact measurements make the estimate the true pose: no filter runs
            // in effect, and `localization.exact` says so.
            if world.perception.is_some() && !world.localization.is_exact() {
                let localization = &world.localization;
                options.push(ModelOption::PoseFilter(localization.filter));
                if localization.filter == PoseFilter::Kalman {
                    options.push(ModelOption::OdometryModel(localization.odometry.model()));
                }
            }
            if let Some(semantic) = &world.semantic {
                options.extend([
                    ModelOption::RsuSight(semantic.rsu_sight),
                    ModelOption::RiskScope(semantic.risk_for),
                    ModelOption::ShareCycles(semantic.shares_over),
                    ModelOption::ShareCycles(semantic.contribution_over),
                    ModelOption::LabelledBy(semantic.labelled_by),
                    ModelOption::PathLossModel(world.v2x.channel.model),
                ]);
            }
        }
    }
    if let Some(occupancy) = &setup.occupancy {
        let rule = occupancy.fusion.rule;
        options.push(ModelOption::FusionMethod(rule.method()));
        if let Rule::DistanceWeighted(weighting) | Rule::Hybrid { weighting, .. } = rule {
            options.push(ModelOption::WeightScaling(weighting.scaling));
            options.push(ModelOption::SourceCombination(weighting.sources));
        }
        if let Rule::Hybrid { switch, .. } = rule {
            options.push(ModelOption::SwitchMeasure(switch.measure));
        }
    }
    options
}
