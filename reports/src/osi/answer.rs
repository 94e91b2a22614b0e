//! What sightline reads of a system's `osi3.SensorData`, decoded within a
//! bound: the message types here mirror OSI's with only the fields the
//! protocol reads (same tags, same wire types), so prost skips every other
//! field (sensor views, stationary objects, a header's ids, …) without
//! allocating. The repeated fields it keeps are counted first, by decoding
//! them as empty messages, which take no memory, and refused past
//! [`MAX_OBJECTS`] and [`MAX_CANDIDATES`]: an answer of millions of empty
//! entries (two bytes each) is refused before it becomes millions of structs.

use prost::Message;
use sightline_osi::osi3;

/// The most moving objects one answer may hold.
pub const MAX_OBJECTS: usize = 10_000;

/// The most candidates (classes) one answer may hold, over all its moving objects.
pub const MAX_CANDIDATES: usize = 100_000;

/// `osi3.SensorData`: the step it answers and what it detected.
#[derive(Clone, PartialEq, Message)]
pub(super) struct Answer {
    /// `timestamp`.
    #[prost(message, optional, tag = "2")]
    pub timestamp: Option<osi3::Timestamp>,
    /// `moving_object`.
    #[prost(message, repeated, tag = "13")]
    pub moving_object: Vec<Object>,
}

/// `osi3.DetectedMovingObject`.
#[derive(Clone, PartialEq, Message)]
pub(super) struct Object {
    /// `header`.
    #[prost(message, optional, tag = "1")]
    pub header: Option<Header>,
    /// `base`.
    #[prost(message, optional, tag = "2")]
    pub base: Option<Base>,
    /// `candidate`.
    #[prost(message, repeated, tag = "8")]
    pub candidate: Vec<Candidate>,
}

/// `osi3.DetectedItemHeader`.
#[derive(Clone, Copy, PartialEq, Message)]
pub(super) struct Header {
    /// `existence_probability`.
    #[prost(double, optional, tag = "3")]
    pub existence_probability: Option<f64>,
}

/// `osi3.BaseMoving`.
#[derive(Clone, Copy, PartialEq, Message)]
pub(super) struct Base {
    /// `position`.
    #[prost(message, optional, tag = "2")]
    pub position: Option<osi3::Vector3d>,
}

/// `osi3.DetectedMovingObject.CandidateMovingObject`.
#[derive(Clone, Copy, PartialEq, Message)]
pub(super) struct Candidate {
    /// `probability`.
    #[prost(double, optional, tag = "1")]
    pub probability: Option<f64>,
    /// `type` (`osi3.MovingObject.Type`).
    #[prost(enumeration = "osi3::moving_object::Type", optional, tag = "2")]
    pub r#type: Option<i32>,
    /// `vehicle_classification`.
    #[prost(message, optional, tag = "3")]
    pub vehicle_classification: Option<VehicleClassification>,
}

/// `osi3.MovingObject.VehicleClassification`.
#[derive(Clone, Copy, PartialEq, Message)]
pub(super) struct VehicleClassification {
    /// `type` (`osi3.MovingObject.VehicleClassification.Type`).
    #[prost(
        enumeration = "osi3::moving_object::vehicle_classification::Type",
        optional,
        tag = "1"
    )]
    pub r#type: Option<i32>,
}

/// Any message, read for nothing: a zero-sized type, so a vector of them
/// counts entries without allocating.
#[derive(Clone, Copy, PartialEq, Message)]
struct Skipped {}

/// `osi3.SensorData`'s moving objects, counted.
#[derive(Clone, PartialEq, Message)]
struct ObjectCount {
    #[prost(message, repeated, tag = "13")]
    moving_object: Vec<Skipped>,
}

/// `osi3.SensorData`'s candidates, counted per moving object.
#[derive(Clone, PartialEq, Message)]
struct CandidateCount {
    #[prost(message, repeated, tag = "13")]
    moving_object: Vec<CandidatesOf>,
}

/// One `osi3.DetectedMovingObject`'s candidates, counted.
#[derive(Clone, PartialEq, Message)]
struct CandidatesOf {
    #[prost(message, repeated, tag = "8")]
    candidate: Vec<Skipped>,
}

/// Why an answer was not decoded.
#[derive(Debug)]
pub(super) enum AnswerError {
    /// The bytes are no `osi3.SensorData`.
    Decode(prost::DecodeError),
    /// More entries than a bound: what, how many, the bound.
    TooMany(&'static str, usize, usize),
}

impl From<prost::DecodeError> for AnswerError {
    fn from(error: prost::DecodeError) -> Self {
        Self::Decode(error)
    }
}

/// `message` decoded, its moving objects and candidates within the bounds.
/// What it holds in memory beyond `message` is at most [`MAX_OBJECTS`]
/// objects and [`MAX_CANDIDATES`] candidates ([`decoded_bound`]).
pub(super) fn decode(message: &[u8]) -> Result<Answer, AnswerError> {
    // An entry takes two bytes at least: an answer too short to hold more
    // than a bound needs no count against it.
    let may_exceed = |limit: usize| message.len() / 2 > limit;
    if may_exceed(MAX_OBJECTS) {
        let objects = ObjectCount::decode(message)?.moving_object.len();
        if objects > MAX_OBJECTS {
            return Err(AnswerError::TooMany("moving objects", objects, MAX_OBJECTS));
        }
        // Candidates are an object's: none without one.
        if objects > 0 && may_exceed(MAX_CANDIDATES) {
            let counted = CandidateCount::decode(message)?;
            let candidates = counted.moving_object.iter().map(|o| o.candidate.len()).sum();
            if candidates > MAX_CANDIDATES {
                return Err(AnswerError::TooMany("candidates", candidates, MAX_CANDIDATES));
            }
        }
    }
    Ok(Answer::decode(message)?)
}

/// The bytes the decoded structs of an answer at both bounds take, at most
/// twice their size (a vector grown by doubling).
pub const fn decoded_bound() -> usize {
    2 * (MAX_OBJECTS * size_of::<Object>() + MAX_CANDIDATES * size_of::<Candidate>())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_counting_messages_take_no_memory_per_entry() {
        assert_eq!(size_of::<Skipped>(), 0);
        // The documented figure (docs/limits.md, docs/osi-sut.md: 8.2 MB).
        assert!(decoded_bound() <= 8_200_000, "{}", decoded_bound());
    }

    /// `count` empty entries of field `tag` (2 bytes each: key, length 0).
    fn empty_entries(tag: u8, count: usize) -> Vec<u8> {
        [tag << 3 | 2, 0].repeat(count)
    }

    #[test]
    fn entries_past_the_bounds_are_refused_by_count() {
        let error = decode(&empty_entries(13, MAX_OBJECTS + 1)).unwrap_err();
        assert!(
            matches!(error, AnswerError::TooMany("moving objects", n, MAX_OBJECTS) if n == MAX_OBJECTS + 1),
            "{error:?}"
        );
        assert_eq!(
            decode(&empty_entries(13, MAX_OBJECTS)).unwrap().moving_object.len(),
            MAX_OBJECTS
        );
        // One object of many candidates.
        let message = CandidateCount {
            moving_object: vec![CandidatesOf {
                candidate: vec![Skipped {}; MAX_CANDIDATES + 1],
            }],
        };
        let error = decode(&message.encode_to_vec()).unwrap_err();
        assert!(
            matches!(error, AnswerError::TooMany("candidates", n, MAX_CANDIDATES) if n == MAX_CANDIDATES + 1),
            "{error:?}"
        );
    }

    #[test]
    fn fields_sightline_does_not_read_are_skipped_and_what_it_reads_matches_osi() {
        // Millions of empty sensor views (8) and stationary objects (11):
        // nothing to allocate, nothing to count.
        let mut message = empty_entries(8, 1 << 20);
        message.extend(empty_entries(11, 1 << 20));
        let full = osi3::SensorData {
            timestamp: Some(osi3::Timestamp {
                seconds: Some(1),
                nanos: Some(500_000_000),
            }),
            moving_object: vec![osi3::DetectedMovingObject {
                header: Some(osi3::DetectedItemHeader {
                    existence_probability: Some(0.75),
                    tracking_id: Some(osi3::Identifier { value: Some(4) }),
                    ..Default::default()
                }),
                base: Some(osi3::BaseMoving {
                    position: Some(osi3::Vector3d {
                        x: Some(3.0),
                        y: Some(-1.0),
                        z: Some(0.0),
                    }),
                    ..Default::default()
                }),
                candidate: vec![osi3::detected_moving_object::CandidateMovingObject {
                    probability: Some(0.5),
                    r#type: Some(osi3::moving_object::Type::Vehicle as i32),
                    vehicle_classification: Some(osi3::moving_object::VehicleClassification {
                        r#type: Some(osi3::moving_object::vehicle_classification::Type::Bus as i32),
                        has_trailer: Some(true),
                        ..Default::default()
                    }),
                    ..Default::default()
                }],
                ..Default::default()
            }],
            ..Default::default()
        };
        message.extend(full.encode_to_vec());
        let answer = decode(&message).unwrap();
        assert_eq!(answer.timestamp, full.timestamp);
        let [object] = answer.moving_object.as_slice() else {
            panic!("{answer:?}")
        };
        assert_eq!(object.header.unwrap().existence_probability, Some(0.75));
        assert_eq!(
            object.base.unwrap().position,
            full.moving_object[0].base.as_ref().unwrap().position
        );
        let candidate = object.candidate[0];
        assert_eq!(
            (candidate.probability, candidate.r#type),
            (Some(0.5), Some(osi3::moving_object::Type::Vehicle as i32))
        );
        assert_eq!(
            candidate.vehicle_classification.unwrap().r#type,
            Some(osi3::moving_object::vehicle_classification::Type::Bus as i32)
        );
    }
}
