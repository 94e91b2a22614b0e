//! What a semantic run measured (seed 002, section V, and the safety
//! metric).

use serde::{Deserialize, Serialize};

use super::objects::{Category, CloseApproach, ObjectRecord};
use crate::metrics::{Series, quantile};
use sightline_dsl::Metric;

/// Width of the packet-delivery distance bins, metres.
pub const DELIVERY_BIN: f64 = 25.0;

/// Width of the traffic-density bins, objects per km.
pub const DENSITY_BIN: f64 = 10.0;

/// The measurements of one semantic run.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SemanticMetrics {
    /// Independent runs pooled into these measurements.
    pub runs: u32,
    /// Steps with the ego in the scene.
    pub steps: u64,
    /// Simulated seconds with the ego in the scene.
    pub duration: f64,
    /// Vehicles and pedestrians the traffic generator added.
    pub generated: u64,
    /// Anticipation times by the paper's definition, seconds, ascending: for
    /// each object the ego first learned of from an RSU while it could not see
    /// it, the time it first could minus the time the message arrived. (Ours,
    /// per object, is [`ObjectRecord::anticipation`].)
    pub anticipation: Vec<f64>,
    /// Objects learned of while hidden that the ego never saw before the run ended.
    pub never_seen: u64,
    /// [`Self::anticipation`] had the RSUs sent the ETSI baseline's messages
    /// instead, ascending.
    pub baseline_anticipation: Vec<f64>,
    /// Per step with the ego present: objects per km in the scene (`None` in a
    /// world without roads) and objects the ego knew only through an RSU
    /// (summarised by [`Self::contribution_by_density`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contribution: Vec<(Option<f64>, u32)>,
    /// Object-cycles perceived by the RSUs (the ego excluded), in the cycles the
    /// shares count (`semantic.shares_over`).
    pub perceived: u64,
    /// Object-cycles sent to the ego, in the cycles the shares count.
    pub transmitted: u64,
    /// Object-cycles sent with at least one label, in the cycles the shares count.
    pub labelled: u64,
    /// Sent object-cycles by label.
    pub labels: LabelCounts,
    /// Bytes of semantic messages sent.
    pub bytes: u64,
    /// Bytes the ETSI baseline would have sent.
    pub baseline_bytes: u64,
    /// Object-cycles the ETSI baseline would have sent.
    pub baseline_objects: u64,
    /// Semantic messages sent to the ego.
    pub messages: u64,
    /// Semantic messages the ego received.
    pub delivered: u64,
    /// Messages sent and received by RSU–ego distance: entry i covers
    /// [i, i + 1) × `DELIVERY_BIN` metres.
    pub delivery_by_distance: Vec<DeliveryBin>,
    /// Objects coming within d_min of the ego (once per approach).
    pub close_approaches: u64,
    /// Close approaches with no conflict flagged to the ego beforehand.
    pub missed_criticals: u64,
    /// Seconds the ego drove cautiously after a flagged conflict.
    pub cautious_time: f64,
    /// Every close approach, by run, then in order of time.
    pub approaches: Vec<CloseApproach>,
    /// Per pooled run, per step with the ego: (time, objects the ego knew only
    /// through an RSU).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rsu_only: Vec<Series>,
    /// Per pooled run, at each RSU cycle whose message to the ego flags a
    /// conflict: (time, the shortest predicted time to conflict in it).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub time_to_conflict: Vec<Series>,
    /// Every road user relevant to the ego, run by run (in pooled order), each
    /// run's in order of becoming relevant.
    pub objects: Vec<ObjectRecord>,
    /// Where several runs are pooled (`semantic.runs`), the first run's own
    /// measurements: the run a recording of the point records, which
    /// [`simulate_recorded`](crate::simulate_recorded) simulates again to be
    /// checked against these. `None` for one run (these are its own), and in
    /// the runs being pooled.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_run: Option<Box<SemanticMetrics>>,
}

/// Sent object-cycles by label.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct LabelCounts {
    /// NLoS behind a static occluder.
    pub nlos_static: u64,
    /// NLoS behind other road users only.
    pub nlos_dynamic: u64,
    /// Interaction relevance.
    pub relevant: u64,
    /// Dangerous drivers.
    pub speeding: u64,
    /// Predicted conflicts.
    pub conflict: u64,
}

/// Packet delivery in one distance bin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct DeliveryBin {
    /// Messages sent.
    pub sent: u64,
    /// Messages received.
    pub received: u64,
}

/// The contribution in one density bin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DensityRow {
    /// Lower edge of the bin, objects per km.
    pub from: f64,
    /// Steps in the bin.
    pub steps: usize,
    /// Median objects known only through an RSU.
    pub median: f64,
    /// Mean objects known only through an RSU.
    pub mean: f64,
}

impl SemanticMetrics {
    /// Adds the measurements of another independent run: counts and durations
    /// add up, samples join, so every ratio and quantile is over the pooled runs.
    pub fn pool(&mut self, other: SemanticMetrics) {
        // Destructured so that a new field cannot be forgotten here.
        let SemanticMetrics {
            runs,
            steps,
            duration,
            generated,
            anticipation,
            never_seen,
            baseline_anticipation,
            contribution,
            perceived,
            transmitted,
            labelled,
            labels,
            bytes,
            baseline_bytes,
            baseline_objects,
            messages,
            delivered,
            delivery_by_distance,
            close_approaches,
            missed_criticals,
            cautious_time,
            approaches,
            rsu_only,
            time_to_conflict,
            objects,
            first_run: _,
        } = other;
        self.runs += runs;
        self.steps += steps;
        self.duration += duration;
        self.generated += generated;
        self.anticipation.extend(anticipation);
        self.anticipation.sort_by(f64::total_cmp);
        self.never_seen += never_seen;
        self.baseline_anticipation.extend(baseline_anticipation);
        self.baseline_anticipation.sort_by(f64::total_cmp);
        self.contribution.extend(contribution);
        self.perceived += perceived;
        self.transmitted += transmitted;
        self.labelled += labelled;
        self.labels.nlos_static += labels.nlos_static;
        self.labels.nlos_dynamic += labels.nlos_dynamic;
        self.labels.relevant += labels.relevant;
        self.labels.speeding += labels.speeding;
        self.labels.conflict += labels.conflict;
        self.bytes += bytes;
        self.baseline_bytes += baseline_bytes;
        self.baseline_objects += baseline_objects;
        self.messages += messages;
        self.delivered += delivered;
        if self.delivery_by_distance.len() < delivery_by_distance.len() {
            self.delivery_by_distance
                .resize(delivery_by_distance.len(), DeliveryBin::default());
        }
        for (mine, theirs) in self.delivery_by_distance.iter_mut().zip(delivery_by_distance) {
            mine.sent += theirs.sent;
            mine.received += theirs.received;
        }
        self.close_approaches += close_approaches;
        self.missed_criticals += missed_criticals;
        self.cautious_time += cautious_time;
        self.approaches.extend(approaches);
        self.rsu_only.extend(rsu_only);
        self.time_to_conflict.extend(time_to_conflict);
        self.objects.extend(objects);
    }

    /// Our anticipation times ([`ObjectRecord::anticipation`]) of the objects
    /// that have one, seconds, ascending.
    pub fn object_anticipation(&self) -> Vec<f64> {
        self.ascending(ObjectRecord::anticipation)
    }

    /// [`Self::object_anticipation`] over the ETSI baseline's messages.
    pub fn baseline_object_anticipation(&self) -> Vec<f64> {
        self.ascending(ObjectRecord::baseline_anticipation)
    }

    /// The values of `of` over the objects that have one, ascending.
    fn ascending(&self, of: fn(&ObjectRecord) -> Option<f64>) -> Vec<f64> {
        let mut times: Vec<f64> = self.objects.iter().filter_map(of).collect();
        times.sort_by(f64::total_cmp);
        times
    }

    /// The relevant objects in `category`, over the pooled runs.
    pub fn objects_in(&self, category: Category) -> u64 {
        self.objects.iter().filter(|o| o.category == category).count() as u64
    }

    /// The value of `metric`, or `None` where it is not defined for this run:
    /// where it is not a semantic metric or its population
    /// ([`Self::sample_size`]) is empty (no close approaches, no relevant
    /// object: a count per run over nobody is no figure, not 0).
    pub fn value(&self, metric: Metric) -> Option<f64> {
        if self.sample_size(metric)? == 0 {
            return None;
        }
        let ratio = |num: u64, den: u64| (den > 0).then(|| num as f64 / den as f64);
        let rate = |bytes: u64| (self.duration > 0.0).then(|| bytes as f64 / self.duration);
        match metric {
            Metric::AnticipationMedian => quantile(&self.anticipation, 0.5),
            Metric::AnticipationP95 => quantile(&self.anticipation, 0.95),
            Metric::InfrastructureContribution => (!self.contribution.is_empty()).then(|| {
                self.contribution.iter().map(|&(_, n)| f64::from(n)).sum::<f64>() / self.contribution.len() as f64
            }),
            Metric::TransmittedShare => ratio(self.transmitted, self.perceived),
            Metric::LabelledShare => ratio(self.labelled, self.perceived),
            Metric::ChannelLoad => rate(self.bytes),
            Metric::BaselineChannelLoad => rate(self.baseline_bytes),
            Metric::PacketDeliveryRatio => ratio(self.delivered, self.messages),
            Metric::MissedCriticals => Some(self.missed_criticals as f64 / f64::from(self.runs.max(1))),
            Metric::ObjectAnticipationMedian => quantile(&self.object_anticipation(), 0.5),
            Metric::ObjectAnticipationP95 => quantile(&self.object_anticipation(), 0.95),
            Metric::ObjectsWarnedBeforeSeen => Some(self.per_run(Category::WarnedBeforeSeen)),
            Metric::ObjectsWarnedNeverSeen => Some(self.per_run(Category::WarnedNeverSeen)),
            Metric::ObjectsSeenFirst => Some(self.per_run(Category::SeenFirst)),
            Metric::ObjectsNeverKnown => Some(self.per_run(Category::NeverKnown)),
            Metric::BaselineAnticipationMedian => quantile(&self.baseline_anticipation, 0.5),
            Metric::BaselineAnticipationP95 => quantile(&self.baseline_anticipation, 0.95),
            Metric::BaselineObjectAnticipationMedian => quantile(&self.baseline_object_anticipation(), 0.5),
            Metric::BaselineObjectAnticipationP95 => quantile(&self.baseline_object_anticipation(), 0.95),
            Metric::MinTtc => self.criticality(|o| o.min_ttc).reduce(f64::min),
            Metric::MinPet => self.criticality(|o| o.pet).reduce(f64::min),
            Metric::MaxDrac => self.criticality(|o| o.max_drac).reduce(f64::max),
            _ => None,
        }
    }

    /// The number of samples `metric` is computed over ([`Metric::population`]),
    /// or `None` where a semantic world does not measure it.
    pub fn sample_size(&self, metric: Metric) -> Option<u64> {
        Some(match metric {
            Metric::AnticipationMedian | Metric::AnticipationP95 => self.anticipation.len() as u64,
            Metric::InfrastructureContribution => self.contribution.len() as u64,
            Metric::TransmittedShare | Metric::LabelledShare => self.perceived,
            Metric::ChannelLoad | Metric::BaselineChannelLoad => self.steps,
            Metric::PacketDeliveryRatio => self.messages,
            Metric::MissedCriticals => self.close_approaches,
            Metric::ObjectAnticipationMedian | Metric::ObjectAnticipationP95 => {
                self.objects.iter().filter(|o| o.anticipation().is_some()).count() as u64
            }
            Metric::ObjectsWarnedBeforeSeen
            | Metric::ObjectsWarnedNeverSeen
            | Metric::ObjectsSeenFirst
            | Metric::ObjectsNeverKnown => self.objects.len() as u64,
            Metric::BaselineAnticipationMedian | Metric::BaselineAnticipationP95 => {
                self.baseline_anticipation.len() as u64
            }
            Metric::BaselineObjectAnticipationMedian | Metric::BaselineObjectAnticipationP95 => {
                self.objects
                    .iter()
                    .filter(|o| o.baseline_anticipation().is_some())
                    .count() as u64
            }
            Metric::MinTtc => self.criticality(|o| o.min_ttc).count() as u64,
            Metric::MinPet => self.criticality(|o| o.pet).count() as u64,
            Metric::MaxDrac => self.criticality(|o| o.max_drac).count() as u64,
            _ => return None,
        })
    }

    /// A criticality measure `of` the relevant objects that have one, in order.
    fn criticality(&self, of: fn(&ObjectRecord) -> Option<f64>) -> impl Iterator<Item = f64> + '_ {
        self.objects.iter().filter_map(of)
    }

    /// The relevant objects in `category` per pooled run.
    fn per_run(&self, category: Category) -> f64 {
        self.objects_in(category) as f64 / f64::from(self.runs.max(1))
    }

    /// The contribution by density bin, densest last, empty bins left out (all of
    /// them where the density is undefined).
    pub fn contribution_by_density(&self) -> Vec<DensityRow> {
        let mut bins: std::collections::BTreeMap<i64, Vec<f64>> = std::collections::BTreeMap::new();
        for &(density, count) in &self.contribution {
            let Some(density) = density else { continue };
            bins.entry((density / DENSITY_BIN).floor() as i64)
                .or_default()
                .push(f64::from(count));
        }
        bins.into_iter()
            .map(|(bin, mut counts)| {
                counts.sort_by(f64::total_cmp);
                DensityRow {
                    from: bin as f64 * DENSITY_BIN,
                    steps: counts.len(),
                    median: quantile(&counts, 0.5).expect("a bin holds a step"),
                    mean: counts.iter().sum::<f64>() / counts.len() as f64,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contribution_bins_by_density() {
        let metrics = SemanticMetrics {
            contribution: vec![
                (Some(12.0), 4),
                (Some(18.0), 6),
                (Some(15.0), 5),
                (Some(44.0), 12),
                (None, 3),
            ],
            ..Default::default()
        };
        let rows = metrics.contribution_by_density();
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].from, rows[0].steps, rows[0].median), (10.0, 3, 5.0));
        assert_eq!((rows[1].from, rows[1].median), (40.0, 12.0));
        assert_eq!(metrics.value(Metric::InfrastructureContribution), Some(6.0));
    }

    #[test]
    fn pooled_runs_add_counts_and_join_samples() {
        let mut first = SemanticMetrics {
            runs: 1,
            duration: 10.0,
            anticipation: vec![1.0, 3.0],
            perceived: 10,
            transmitted: 4,
            bytes: 1000,
            delivery_by_distance: vec![DeliveryBin { sent: 2, received: 2 }],
            steps: 100,
            close_approaches: 2,
            missed_criticals: 1,
            ..Default::default()
        };
        let second = SemanticMetrics {
            runs: 1,
            duration: 30.0,
            anticipation: vec![2.0],
            perceived: 30,
            transmitted: 6,
            bytes: 1000,
            delivery_by_distance: vec![
                DeliveryBin { sent: 1, received: 0 },
                DeliveryBin { sent: 1, received: 1 },
            ],
            steps: 300,
            close_approaches: 3,
            missed_criticals: 2,
            ..Default::default()
        };
        first.pool(second);
        assert_eq!(first.runs, 2);
        assert_eq!(first.anticipation, [1.0, 2.0, 3.0]);
        assert_eq!(first.value(Metric::AnticipationMedian), Some(2.0));
        // (4 + 6) / (10 + 30), not the mean of 0.4 and 0.2.
        assert_eq!(first.value(Metric::TransmittedShare), Some(0.25));
        assert_eq!(first.value(Metric::ChannelLoad), Some(50.0));
        // Three over two runs.
        assert_eq!(first.value(Metric::MissedCriticals), Some(1.5));
        assert_eq!(
            first.delivery_by_distance,
            [
                DeliveryBin { sent: 3, received: 2 },
                DeliveryBin { sent: 1, received: 1 }
            ]
        );
    }

    #[test]
    fn a_metric_over_nobody_has_no_value() {
        // Two pooled runs with no close approach and no relevant object: the
        // counts per run are over nobody, so they are no figure (not 0).
        let metrics = SemanticMetrics {
            runs: 2,
            duration: 20.0,
            steps: 200,
            ..Default::default()
        };
        for metric in [
            Metric::MissedCriticals,
            Metric::ObjectsWarnedBeforeSeen,
            Metric::ObjectsWarnedNeverSeen,
            Metric::ObjectsSeenFirst,
            Metric::ObjectsNeverKnown,
        ] {
            assert_eq!(
                (metrics.value(metric), metrics.sample_size(metric)),
                (None, Some(0)),
                "{metric:?}"
            );
        }
        // One close approach, missed in neither run: 0 per run, over n = 1.
        let one = SemanticMetrics {
            close_approaches: 1,
            ..metrics
        };
        assert_eq!(one.value(Metric::MissedCriticals), Some(0.0));
    }
}
