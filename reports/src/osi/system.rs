//! The protocol between sightline and a system under test, version 1
//! (docs/osi-sut.md): length-delimited OSI messages over the system's standard
//! input and output.
//!
//! - Framing: each message is a 4-byte little-endian length, then that many
//!   bytes (OSI's binary trace framing). A length above [`MAX_MESSAGE`] is an
//!   error, read before anything is allocated.
//! - Version: the system is started with [`PROTOCOL_ENV`] set to [`PROTOCOL`]
//!   and [`VIEWS_ENV`] to the number of views it gets per step; its first
//!   message is the text [`PROTOCOL`], which sightline checks.
//! - Each step the served agent is among the cooperating agents, sightline
//!   writes one `osi3.SensorView` per served sensor ([`sensor_views`]), then
//!   reads one `osi3.SensorData` ([`detections`]) whose timestamp is the
//!   views'; its moving objects, with their existence probability, their
//!   position in the host's frame and their class, are what it detected.
//! - After the last step sightline closes the system's input; the system
//!   exits with status 0.

use std::io::{self, Read};

use prost::Message;
use sightline_dsl::{Agent, AgentKind};
use sightline_engine::outcome::Detection;
use sightline_engine::trace::WorldStep;
use sightline_osi::osi3;

use super::answer::{self, AnswerError};
pub use super::answer::{MAX_CANDIDATES, MAX_OBJECTS, decoded_bound};
use super::reported_class::reported_class;
use super::views::{ground_truth, sensor_view};

/// The protocol's name and version, the system's first message.
pub const PROTOCOL: &str = "sightline-osi-sut/1";

/// The environment variable that tells the system the protocol's version.
pub const PROTOCOL_ENV: &str = "SIGHTLINE_SUT_PROTOCOL";

/// The environment variable that tells the system how many `SensorView`s
/// each step brings (one per served sensor).
pub const VIEWS_ENV: &str = "SIGHTLINE_SUT_VIEWS";

/// The most characters of a wrong version announcement an error shows.
pub const VERSION_SHOWN: usize = 64;

/// The largest message either side may send, bytes (16 MiB).
pub const MAX_MESSAGE: u32 = 16 << 20;

/// What is wrong with what a system sent.
#[derive(Debug, thiserror::Error)]
pub enum ProtocolError {
    /// Reading its output failed.
    #[error("failed to read its output: {0}")]
    Io(#[from] io::Error),
    /// Its output ended inside a message.
    #[error("its output ended inside a message ({got} of {expected} bytes)")]
    Truncated {
        /// Bytes announced.
        expected: u32,
        /// Bytes read.
        got: usize,
    },
    /// A length prefix above [`MAX_MESSAGE`].
    #[error("a message of {0} bytes announced, above the protocol's limit of {MAX_MESSAGE} bytes")]
    TooLong(u32),
    /// Its first message is not this protocol's name and version.
    #[error("it announced `{found}`, and sightline speaks `{PROTOCOL}`")]
    Version {
        /// What it announced: lossy UTF-8, at most [`VERSION_SHOWN`]
        /// characters, then `…` if there is more, escaped as Rust's debug
        /// format escapes a string (control characters and terminal escapes
        /// are `\n`, `\u{1b}`, …).
        found: String,
    },
    /// A message that is not an `osi3.SensorData`.
    #[error("its message is not an osi3.SensorData: {0}")]
    Decode(#[from] prost::DecodeError),
    /// A `SensorData` with more entries than a bound of the protocol.
    #[error("its osi3.SensorData holds {count} {what}, above the protocol's limit of {limit}")]
    TooMany {
        /// What it holds too many of.
        what: &'static str,
        /// How many.
        count: usize,
        /// The bound ([`MAX_OBJECTS`], [`MAX_CANDIDATES`]).
        limit: usize,
    },
    /// A `SensorData` that breaks the protocol.
    #[error("its osi3.SensorData {0}")]
    Content(String),
}

/// `message` with its length prefix.
pub fn frame(message: &[u8]) -> Vec<u8> {
    let mut framed = Vec::with_capacity(message.len() + 4);
    framed.extend_from_slice(&(message.len() as u32).to_le_bytes());
    framed.extend_from_slice(message);
    framed
}

/// The next message of `input`; `None` when it ends before a message begins.
pub fn read_frame(input: &mut impl Read) -> Result<Option<Vec<u8>>, ProtocolError> {
    let mut prefix = [0u8; 4];
    let mut got = 0;
    while got < 4 {
        match input.read(&mut prefix[got..]) {
            Ok(0) if got == 0 => return Ok(None),
            Ok(0) => return Err(ProtocolError::Truncated { expected: 4, got }),
            Ok(n) => got += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e.into()),
        }
    }
    let length = u32::from_le_bytes(prefix);
    if length > MAX_MESSAGE {
        return Err(ProtocolError::TooLong(length));
    }
    let mut message = Vec::new();
    let read = input.take(u64::from(length)).read_to_end(&mut message)?;
    if read < length as usize {
        return Err(ProtocolError::Truncated {
            expected: length,
            got: read,
        });
    }
    Ok(Some(message))
}

/// Checks the system's first message, its protocol's name and version.
pub fn check_version(message: &[u8]) -> Result<(), ProtocolError> {
    if message == PROTOCOL.as_bytes() {
        return Ok(());
    }
    let text = String::from_utf8_lossy(&message[..message.len().min(4 * VERSION_SHOWN)]);
    let mut found: String = text
        .chars()
        .take(VERSION_SHOWN)
        .collect::<String>()
        .escape_debug()
        .collect();
    if text.chars().nth(VERSION_SHOWN).is_some() || message.len() > 4 * VERSION_SHOWN {
        found.push('…');
    }
    Err(ProtocolError::Version { found })
}

/// What `sensors` of agent `host` have in view at `step`, each view framed
/// and in sensor order (the ground truth's host vehicle is `host`); empty when
/// `host` does not cooperate at this step.
pub fn sensor_views(agents: &[Agent], step: &WorldStep<'_>, host: usize, sensors: &[usize]) -> Vec<u8> {
    let Some(cooperator) = step.cooperators.iter().find(|c| c.agent == host) else {
        return Vec::new();
    };
    let Some(agent) = agents.get(host) else {
        return Vec::new();
    };
    let truth = ground_truth(agents, step.agents, step.time, Some(host));
    let vehicle = agent.kind != AgentKind::Rsu;
    let mut bytes = Vec::new();
    for &index in sensors {
        if let Some(sensor) = agent.sensors.get(index) {
            let view = sensor_view(
                &truth,
                (host, vehicle),
                (index, sensor),
                cooperator.observation.sighted(),
            );
            bytes.extend(frame(&view.encode_to_vec()));
        }
    }
    bytes
}

/// The detections of a system's `osi3.SensorData` answering the step at
/// `time`: its moving objects whose existence probability is at least
/// `min_existence`, in the host's frame, each with the class it reports.
/// Only what the protocol reads is decoded, and at most [`MAX_OBJECTS`]
/// moving objects and [`MAX_CANDIDATES`] candidates.
pub fn detections(message: &[u8], time: f64, min_existence: f64) -> Result<Vec<Detection>, ProtocolError> {
    let data = answer::decode(message).map_err(|error| match error {
        AnswerError::Decode(error) => ProtocolError::Decode(error),
        AnswerError::TooMany(what, count, limit) => ProtocolError::TooMany { what, count, limit },
    })?;
    let expected = super::views::timestamp(time);
    if data.timestamp != Some(expected) {
        let shown = |t: Option<osi3::Timestamp>| {
            t.map_or("none".to_string(), |t| {
                format!("{}.{:09} s", t.seconds.unwrap_or(0), t.nanos.unwrap_or(0))
            })
        };
        return Err(ProtocolError::Content(format!(
            "has the timestamp {}, and answers the step at {}: each step's answer carries its views' timestamp",
            shown(data.timestamp),
            shown(Some(expected))
        )));
    }
    let mut detections = Vec::with_capacity(data.moving_object.len());
    for (i, object) in data.moving_object.iter().enumerate() {
        let existence = object.header.as_ref().and_then(|h| h.existence_probability);
        let Some(existence) = existence.filter(|p| (0.0..=1.0).contains(p)) else {
            return Err(ProtocolError::Content(format!(
                "moving object {i} has no existence probability from 0 to 1 (header.existence_probability)"
            )));
        };
        let position = object.base.as_ref().and_then(|b| b.position);
        let Some((x, y)) = position
            .and_then(|p| p.x.zip(p.y))
            .filter(|(x, y)| x.is_finite() && y.is_finite())
        else {
            return Err(ProtocolError::Content(format!(
                "moving object {i} has no finite position (base.position.x and y)"
            )));
        };
        let class = reported_class(i, object).map_err(ProtocolError::Content)?;
        if existence >= min_existence {
            detections.push(Detection { x, y, class });
        }
    }
    Ok(detections)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_reads_back_and_an_end_between_messages_is_none() {
        let mut bytes = frame(b"abc");
        bytes.extend(frame(b""));
        let mut input = bytes.as_slice();
        assert_eq!(read_frame(&mut input).unwrap(), Some(b"abc".to_vec()));
        assert_eq!(read_frame(&mut input).unwrap(), Some(Vec::new()));
        assert!(read_frame(&mut input).unwrap().is_none());
    }

    #[test]
    fn a_length_over_the_limit_is_refused_before_reading_it() {
        let bytes = (MAX_MESSAGE + 1).to_le_bytes();
        let error = read_frame(&mut bytes.as_slice()).unwrap_err();
        assert!(
            matches!(error, ProtocolError::TooLong(n) if n == MAX_MESSAGE + 1),
            "{error}"
        );
    }

    #[test]
    fn a_message_cut_short_is_truncated() {
        let mut bytes = frame(b"abcdef");
        bytes.truncate(7);
        let error = read_frame(&mut bytes.as_slice()).unwrap_err();
        assert!(
            matches!(error, ProtocolError::Truncated { expected: 6, got: 3 }),
            "{error}"
        );
        let error = read_frame(&mut [1u8, 0].as_slice()).unwrap_err();
        assert!(
            matches!(error, ProtocolError::Truncated { expected: 4, got: 2 }),
            "{error}"
        );
    }

    #[test]
    fn another_version_is_refused_by_name() {
        assert!(check_version(PROTOCOL.as_bytes()).is_ok());
        let error = check_version(b"sightline-osi-sut/2").unwrap_err();
        assert_eq!(
            error.to_string(),
            "it announced `sightline-osi-sut/2`, and sightline speaks `sightline-osi-sut/1`"
        );
    }

    #[test]
    fn a_wrong_version_is_shown_escaped_and_bounded() {
        let shown = |message: &[u8]| match check_version(message).unwrap_err() {
            ProtocolError::Version { found } => found,
            error => panic!("{error}"),
        };
        assert_eq!(shown(b"sightline-osi-sut/1\n"), r"sightline-osi-sut/1\n");
        assert_eq!(shown(b"\x1b[2J\x07\r\xff"), "\\u{1b}[2J\\u{7}\\r\u{fffd}");
        let long = "v".repeat(VERSION_SHOWN + 1);
        assert_eq!(shown(long.as_bytes()), "v".repeat(VERSION_SHOWN) + "…");
        assert_eq!(shown(&long.as_bytes()[1..]), "v".repeat(VERSION_SHOWN));
        let error = check_version(b"a\nb").unwrap_err().to_string();
        assert_eq!(error.lines().count(), 1, "{error}");
    }

    fn object(existence: Option<f64>, x: f64, y: f64) -> osi3::DetectedMovingObject {
        osi3::DetectedMovingObject {
            header: Some(osi3::DetectedItemHeader {
                existence_probability: existence,
                ..Default::default()
            }),
            base: Some(osi3::BaseMoving {
                position: Some(osi3::Vector3d {
                    x: Some(x),
                    y: Some(y),
                    z: Some(0.0),
                }),
                ..Default::default()
            }),
            ..Default::default()
        }
    }

    fn data(time: f64, objects: Vec<osi3::DetectedMovingObject>) -> Vec<u8> {
        osi3::SensorData {
            timestamp: Some(crate::osi::views::timestamp(time)),
            moving_object: objects,
            ..Default::default()
        }
        .encode_to_vec()
    }

    #[test]
    fn detections_below_the_existence_threshold_are_not_judged() {
        let message = data(1.5, vec![object(Some(0.9), 3.0, -1.0), object(Some(0.2), 9.0, 9.0)]);
        assert_eq!(
            detections(&message, 1.5, 0.5).unwrap(),
            vec![Detection {
                x: 3.0,
                y: -1.0,
                class: None
            }]
        );
    }

    #[test]
    fn an_answer_to_another_step_or_without_existence_is_out_of_protocol() {
        let message = data(1.4, vec![]);
        let error = detections(&message, 1.5, 0.5).unwrap_err();
        assert!(error.to_string().contains("timestamp 1.400000000 s"), "{error}");
        let message = data(1.5, vec![object(None, 1.0, 1.0)]);
        let error = detections(&message, 1.5, 0.5).unwrap_err();
        assert!(error.to_string().contains("existence probability"), "{error}");
        assert!(matches!(
            detections(b"\xff\xff", 1.5, 0.5),
            Err(ProtocolError::Decode(_))
        ));
    }

    #[test]
    fn each_detection_carries_its_class_and_an_ambiguous_one_is_out_of_protocol() {
        use osi3::detected_moving_object::CandidateMovingObject;
        let pedestrian = |probability| CandidateMovingObject {
            probability: Some(probability),
            r#type: Some(osi3::moving_object::Type::Pedestrian as i32),
            ..Default::default()
        };
        let mut walker = object(Some(0.9), 3.0, -1.0);
        walker.candidate = vec![pedestrian(0.8)];
        let message = data(1.5, vec![walker.clone(), object(Some(0.9), 9.0, 9.0)]);
        let classes: Vec<_> = (detections(&message, 1.5, 0.5).unwrap().iter())
            .map(|d| d.class)
            .collect();
        assert_eq!(classes, [Some(AgentKind::Pedestrian), None]);
        // Checked below the existence threshold too, as the rest of an object.
        walker.candidate.push(pedestrian(0.8));
        walker.header.as_mut().unwrap().existence_probability = Some(0.1);
        let error = detections(&data(1.5, vec![walker]), 1.5, 0.5).unwrap_err();
        assert!(
            error.to_string().contains("moving object 0 has two most probable"),
            "{error}"
        );
    }
}
