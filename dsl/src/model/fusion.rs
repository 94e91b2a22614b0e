//! Fusion rules and the decision rule.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A fusion rule and the name tables show for it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fusion {
    /// Name in tables (`Baseline`, `Proposed`); defaults to the method name.
    pub label: String,
    /// The rule.
    pub rule: Rule,
}

/// Fusion methods as named in scenario files.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FusionMethod {
    /// Bayesian log-odds occupancy fusion of each source's pignistic probability.
    Bayes,
    /// The standard Dempster rule of combination (seed 001, eq. 1).
    #[default]
    Dempster,
    /// The distance-weighted Dempster rule (seed 001, §III-B) on every cell.
    DistanceWeighted,
    /// The standard rule where the sources' distances are close, the distance-weighted
    /// rule where they are far apart (seed 001, §IV-B).
    Hybrid,
}

impl FusionMethod {
    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Bayes => "bayes",
            Self::Dempster => "dempster",
            Self::DistanceWeighted => "distance_weighted",
            Self::Hybrid => "hybrid",
        }
    }
}

/// A compiled fusion rule with exactly the parameters it uses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rule {
    /// See [`FusionMethod::Bayes`].
    Bayes,
    /// See [`FusionMethod::Dempster`].
    Dempster,
    /// See [`FusionMethod::DistanceWeighted`].
    DistanceWeighted(Weighting),
    /// See [`FusionMethod::Hybrid`].
    Hybrid {
        /// The weighted rule used where distances differ.
        weighting: Weighting,
        /// When distances count as different.
        switch: Switch,
    },
}

impl Rule {
    /// The method this rule implements.
    pub fn method(&self) -> FusionMethod {
        match self {
            Self::Bayes => FusionMethod::Bayes,
            Self::Dempster => FusionMethod::Dempster,
            Self::DistanceWeighted(_) => FusionMethod::DistanceWeighted,
            Self::Hybrid { .. } => FusionMethod::Hybrid,
        }
    }

    /// Whether the rule produces evidential masses (and so a conflict signal).
    pub fn is_evidential(&self) -> bool {
        !matches!(self, Self::Bayes)
    }
}

/// The parameters of the distance-weighted rule the paper leaves open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub struct Weighting {
    /// How the weights 1/dᵢ are scaled.
    pub scaling: WeightScaling,
    /// How more than two sources combine.
    pub sources: SourceCombination,
}

/// How reliability weights wᵢ ∝ 1/dᵢ are scaled before the power transform mᵢ^wᵢ.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WeightScaling {
    /// As the paper writes it: wᵢ = (1/dᵢ) / Σⱼ(1/dⱼ), so the weights sum to 1.
    /// Equal distances give wᵢ = 1/n, which flattens every source.
    #[default]
    SumToOne,
    /// wᵢ = n·(1/dᵢ) / Σⱼ(1/dⱼ): weights average 1; nearer sources are sharpened
    /// (w > 1), farther ones flattened. Equal distances give the standard rule with
    /// `all_at_once` (or two sources), not with `pairwise`.
    MeanOne,
    /// wᵢ = min_j dⱼ / dᵢ: the nearest source keeps its mass (w = 1), farther
    /// ones are flattened. Equal distances give the standard rule with
    /// `all_at_once` (or two sources), not with `pairwise`.
    NearestOne,
}

/// How the two-source weighted rule extends to n sources (the paper writes only two).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SourceCombination {
    /// Weights are computed over all n sources of the cell, each source is
    /// transformed once, and the transformed sources are combined with the
    /// (associative) standard rule. For n = 2 this is the paper's rule.
    #[default]
    AllAtOnce,
    /// Sources are folded pairwise in sensor order with the paper's two-source
    /// rule; a fused result carries the reliability 1/d₁ + 1/d₂ of its inputs.
    /// Not associative: the result depends on the order of the sensors.
    Pairwise,
}

/// When the hybrid rule switches from the standard to the weighted rule.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Switch {
    /// How the sources' distances are compared.
    pub measure: SwitchMeasure,
    /// The weighted rule is used when the measure exceeds this threshold.
    pub threshold: f64,
}

/// How the hybrid switch compares the distances of a cell's sources.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SwitchMeasure {
    /// max dᵢ − min dᵢ, metres.
    #[default]
    Difference,
    /// max dᵢ / min dᵢ, dimensionless (≥ 1).
    Ratio,
}

/// The decision rule of seed 001: a cell takes the state of its largest mass
/// p_max when `rule` holds at θ, and stays undecided otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Decision {
    /// Which of the paper's two statements of the rule.
    pub rule: DecisionRule,
    /// θ.
    pub threshold: f64,
}

/// The two statements of seed 001's decision rule (p_others: the sum of the
/// other two masses).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DecisionRule {
    /// p_max − p_others ≥ θ, the formula of §IV-C, to which §IV-E refers its
    /// Table III. With masses summing to 1: p_max ≥ (1 + θ)/2.
    #[default]
    Margin,
    /// p_max > θ: "the probability of one of the states exceeds the threshold"
    /// (§IV-A); Table III counts cells whose vector "does not exceed the
    /// threshold θ in any component" (§IV-E).
    Exceeds,
}
