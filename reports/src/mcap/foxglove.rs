//! The Foxglove well-known message types sightline writes (JSON encoding), with
//! the JSON Schemas it registers for them: `schemas/` holds Foxglove's own, as
//! npm `@foxglove/schemas` publishes them (its `jsonschema` export, the version
//! `ci/viewers/package.json` pins, MIT licence), and CI checks that they are
//! equal. Foxglove and Lichtblick recognise them by schema name and draw them
//! without plugins.

use std::borrow::Cow;

use base64::Engine;
use serde::Serialize;

use sightline_engine::trace::{Pose, Vector};

/// `foxglove.SceneUpdate`'s JSON Schema.
pub(crate) const SCENE_UPDATE_SCHEMA: &str = include_str!("schemas/foxglove.SceneUpdate.json");
/// `foxglove.Grid`'s JSON Schema.
pub(crate) const GRID_SCHEMA: &str = include_str!("schemas/foxglove.Grid.json");
/// `foxglove.Log`'s JSON Schema.
pub(crate) const LOG_SCHEMA: &str = include_str!("schemas/foxglove.Log.json");
/// `foxglove.FrameTransforms`' JSON Schema.
pub(crate) const FRAME_TRANSFORMS_SCHEMA: &str = include_str!("schemas/foxglove.FrameTransforms.json");

/// The root of the frame tree, which every entity and grid is drawn in: the
/// scenario's world frame (metres, x east, y north, z up).
pub(crate) const FRAME: &str = "map";

/// A recording time as Foxglove's `time`.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct Time {
    sec: u64,
    nsec: u64,
}

impl Time {
    /// The time `nanos` nanoseconds after 1970-01-01T00:00:00Z.
    pub(crate) fn from_nanos(nanos: u64) -> Self {
        Self {
            sec: nanos / 1_000_000_000,
            nsec: nanos % 1_000_000_000,
        }
    }
}

/// A zero `duration`: an entity that stays until replaced or deleted.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct Forever {
    sec: i64,
    nsec: u32,
}

const FOREVER: Forever = Forever { sec: 0, nsec: 0 };

#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct Vector3 {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) z: f64,
}

#[derive(Debug, Clone, Copy, Serialize)]
struct Quaternion {
    x: f64,
    y: f64,
    z: f64,
    w: f64,
}

/// A position and a heading about z.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct Pose3 {
    position: Vector3,
    orientation: Quaternion,
}

/// `foxglove.FrameTransform`: where frame `child` lies in frame `parent` (the
/// type `/tf`'s JSON, written directly by the recorder, is checked against).
#[cfg(test)]
#[derive(Debug, Clone, Serialize)]
pub(crate) struct FrameTransform {
    timestamp: Time,
    parent_frame_id: String,
    child_frame_id: String,
    translation: Vector3,
    rotation: Quaternion,
}

#[cfg(test)]
impl FrameTransform {
    /// Frame `child` at `pose` in frame `parent`, at `timestamp`.
    pub(crate) fn new(timestamp: Time, parent: impl Into<String>, child: impl Into<String>, pose: Pose3) -> Self {
        Self {
            timestamp,
            parent_frame_id: parent.into(),
            child_frame_id: child.into(),
            translation: pose.position,
            rotation: pose.orientation,
        }
    }
}

/// `foxglove.FrameTransforms`.
#[cfg(test)]
#[derive(Debug, Clone, Serialize)]
pub(crate) struct FrameTransforms {
    pub(crate) transforms: Vec<FrameTransform>,
}

/// Millimetres are plenty for a picture and keep the recording small.
fn mm(value: f64) -> f64 {
    (value * 1000.0).round() / 1000.0
}

impl Pose3 {
    /// At (x, y, z), turned by `heading` radians counter-clockwise about z.
    pub(crate) fn at(x: f64, y: f64, z: f64, heading: f64) -> Self {
        let half = heading / 2.0;
        Self {
            position: Vector3 {
                x: mm(x),
                y: mm(y),
                z: mm(z),
            },
            orientation: Quaternion {
                x: 0.0,
                y: 0.0,
                z: half.sin(),
                w: half.cos(),
            },
        }
    }

    /// A planar pose lifted to height `z`.
    pub(crate) fn planar(pose: Pose, z: f64) -> Self {
        Self::at(pose.translation.x, pose.translation.y, z, pose.rotation.angle())
    }

    /// The world frame's origin.
    pub(crate) fn identity() -> Self {
        Self::at(0.0, 0.0, 0.0, 0.0)
    }

    /// Appends the position as serde_json writes a [`Vector3`].
    pub(crate) fn write_translation(&self, out: &mut Vec<u8>) {
        let Vector3 { x, y, z } = self.position;
        write_fields(out, &[(b"x", x), (b"y", y), (b"z", z)]);
    }

    /// Appends the orientation as serde_json writes a quaternion.
    pub(crate) fn write_rotation(&self, out: &mut Vec<u8>) {
        let Quaternion { x, y, z, w } = self.orientation;
        write_fields(out, &[(b"x", x), (b"y", y), (b"z", z), (b"w", w)]);
    }
}

/// Appends an object of number fields (plain keys, no escaping needed) as
/// serde_json writes it: a finite number in its shortest round-trip form.
fn write_fields(out: &mut Vec<u8>, fields: &[(&[u8], f64)]) {
    out.push(b'{');
    for (i, (key, value)) in fields.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        out.push(b'"');
        out.extend_from_slice(key);
        out.extend_from_slice(b"\":");
        // Writing a number into a Vec does not fail.
        let _ = serde_json::to_writer(&mut *out, value);
    }
    out.push(b'}');
}

impl Time {
    /// Appends `{"sec":…,"nsec":…}`, as serde_json writes the time.
    pub(crate) fn write_json(&self, out: &mut Vec<u8>) {
        use std::io::Write as _;
        let _ = write!(out, r#"{{"sec":{},"nsec":{}}}"#, self.sec, self.nsec);
    }
}

/// An RGBA colour, each channel 0–1.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct Color {
    r: f64,
    g: f64,
    b: f64,
    a: f64,
}

impl Color {
    pub(crate) const fn rgba(r: f64, g: f64, b: f64, a: f64) -> Self {
        Self { r, g, b, a }
    }
}

/// `foxglove.CubePrimitive`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Cube {
    pub(crate) pose: Pose3,
    pub(crate) size: Vector3,
    pub(crate) color: Color,
}

/// `foxglove.LineType`.
#[derive(Debug, Clone, Copy)]
pub(crate) enum LineType {
    Strip,
    Loop,
}

impl Serialize for LineType {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u8(match self {
            Self::Strip => 0,
            Self::Loop => 1,
        })
    }
}

/// `foxglove.LinePrimitive`, one colour, points in the frame of `pose`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Line {
    #[serde(rename = "type")]
    kind: LineType,
    pose: Pose3,
    thickness: f64,
    scale_invariant: bool,
    points: Vec<Vector3>,
    color: Color,
    colors: [Color; 0],
    indices: [u32; 0],
}

impl Line {
    /// A line through planar `points` (at z = 0 in the frame of `pose`),
    /// `thickness` metres wide.
    pub(crate) fn new(
        kind: LineType,
        pose: Pose3,
        points: impl IntoIterator<Item = Vector>,
        thickness: f64,
        color: Color,
    ) -> Self {
        Self {
            kind,
            pose,
            thickness,
            scale_invariant: false,
            points: points
                .into_iter()
                .map(|p| Vector3 {
                    x: mm(p.x),
                    y: mm(p.y),
                    z: 0.0,
                })
                .collect(),
            color,
            colors: [],
            indices: [],
        }
    }
}

/// `foxglove.TextPrimitive`: a label that faces the camera, 14 pixels high.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Text {
    pose: Pose3,
    billboard: bool,
    font_size: f64,
    scale_invariant: bool,
    color: Color,
    text: String,
}

impl Text {
    pub(crate) fn label(pose: Pose3, text: impl Into<String>, color: Color) -> Self {
        Self {
            pose,
            billboard: true,
            font_size: 14.0,
            scale_invariant: true,
            color,
            text: text.into(),
        }
    }
}

/// `foxglove.KeyValuePair`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct KeyValue {
    key: &'static str,
    value: String,
}

/// `foxglove.SceneEntity`, drawn until replaced or deleted: in the world frame
/// where it was at `timestamp` ([`new`](Self::new)), or locked to a frame that
/// moves ([`locked`](Self::locked)).
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Entity {
    timestamp: Time,
    frame_id: Cow<'static, str>,
    id: String,
    lifetime: Forever,
    frame_locked: bool,
    metadata: Vec<KeyValue>,
    arrows: [(); 0],
    cubes: Vec<Cube>,
    spheres: [(); 0],
    cylinders: [(); 0],
    lines: Vec<Line>,
    triangles: [(); 0],
    texts: Vec<Text>,
    models: [(); 0],
}

impl Entity {
    /// An entity in the world frame.
    pub(crate) fn new(timestamp: Time, id: impl Into<String>) -> Self {
        Self::in_frame(timestamp, id, Cow::Borrowed(FRAME), false)
    }

    /// An entity in `frame` that follows it as the frame moves: the viewer
    /// places it with the frame's latest transform (`/tf`) at the time shown.
    pub(crate) fn locked(timestamp: Time, id: impl Into<String>, frame: String) -> Self {
        Self::in_frame(timestamp, id, Cow::Owned(frame), true)
    }

    fn in_frame(timestamp: Time, id: impl Into<String>, frame_id: Cow<'static, str>, frame_locked: bool) -> Self {
        Self {
            timestamp,
            frame_id,
            id: id.into(),
            lifetime: FOREVER,
            frame_locked,
            metadata: Vec::new(),
            arrows: [],
            cubes: Vec::new(),
            spheres: [],
            cylinders: [],
            lines: Vec::new(),
            triangles: [],
            texts: Vec::new(),
            models: [],
        }
    }

    pub(crate) fn meta(mut self, key: &'static str, value: impl ToString) -> Self {
        self.metadata.push(KeyValue {
            key,
            value: value.to_string(),
        });
        self
    }

    pub(crate) fn cube(mut self, cube: Cube) -> Self {
        self.cubes.push(cube);
        self
    }

    pub(crate) fn line(mut self, line: Line) -> Self {
        self.lines.push(line);
        self
    }

    pub(crate) fn text(mut self, text: Text) -> Self {
        self.texts.push(text);
        self
    }
}

/// `foxglove.SceneEntityDeletion` of type ALL: everything earlier on the topic.
#[derive(Debug, Clone, Serialize)]
struct DeleteAll {
    timestamp: Time,
    #[serde(rename = "type")]
    kind: u8,
    id: &'static str,
}

/// `foxglove.SceneUpdate`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct SceneUpdate {
    deletions: Vec<DeleteAll>,
    entities: Vec<Entity>,
}

impl SceneUpdate {
    /// Replaces everything the topic showed before `timestamp` by `entities`.
    pub(crate) fn replace(timestamp: Time, entities: Vec<Entity>) -> Self {
        Self {
            deletions: vec![DeleteAll {
                timestamp,
                kind: 1,
                id: "",
            }],
            entities,
        }
    }
}

/// `foxglove.NumericType` of a grid field.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Numeric {
    Uint8,
    Float32,
}

impl Numeric {
    fn bytes(self) -> u32 {
        match self {
            Self::Uint8 => 1,
            Self::Float32 => 4,
        }
    }
}

impl Serialize for Numeric {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u8(match self {
            Self::Uint8 => 1,
            Self::Float32 => 7,
        })
    }
}

/// `foxglove.PackedElementField`.
#[derive(Debug, Clone, Serialize)]
struct Field {
    name: &'static str,
    offset: u32,
    #[serde(rename = "type")]
    kind: Numeric,
}

#[derive(Debug, Clone, Copy, Serialize)]
struct Vector2 {
    x: f64,
    y: f64,
}

/// `foxglove.Grid`: cells of one numeric type, each cell its fields in order.
/// The recorder writes it with [`write_json`](Self::write_json); its serde
/// encoding is what that is tested against.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Grid {
    #[serde(flatten)]
    head: GridHead,
    /// The cell bytes, written as base64.
    #[serde(serialize_with = "base64_string")]
    data: Vec<u8>,
}

/// What a [`Grid`] holds before its cells.
#[derive(Debug, Clone, Serialize)]
struct GridHead {
    timestamp: Time,
    frame_id: &'static str,
    pose: Pose3,
    column_count: u32,
    cell_size: Vector2,
    row_stride: u32,
    cell_stride: u32,
    fields: Vec<Field>,
}

impl Grid {
    /// A grid of `columns` columns of square `cell`-metre cells whose corner is at
    /// `corner` in the world frame, each cell holding `names` (in order) of type
    /// `kind`; `data` holds the cells row by row, little-endian.
    pub(crate) fn new(
        timestamp: Time,
        corner: [f64; 2],
        cell: f64,
        columns: u32,
        names: &[&'static str],
        kind: Numeric,
        data: Vec<u8>,
    ) -> Self {
        let cell_stride = kind.bytes() * names.len() as u32;
        let head = GridHead {
            timestamp,
            frame_id: FRAME,
            pose: Pose3::at(corner[0], corner[1], 0.0, 0.0),
            column_count: columns,
            cell_size: Vector2 { x: cell, y: cell },
            row_stride: cell_stride * columns,
            cell_stride,
            fields: names
                .iter()
                .zip(0u32..)
                .map(|(&name, i)| Field {
                    name,
                    offset: i * kind.bytes(),
                    kind,
                })
                .collect(),
        };
        Self { head, data }
    }

    /// A grid of no cell with the fields `names` of type `kind`: what a grid
    /// topic shows once its point is over. Its row stride is one cell's, so
    /// that a viewer reading the row count as bytes over row stride reads 0
    /// rows, not 0 / 0.
    pub(crate) fn cleared(timestamp: Time, names: &[&'static str], kind: Numeric) -> Self {
        let mut grid = Self::new(timestamp, [0.0, 0.0], 1.0, 0, names, kind, Vec::new());
        grid.head.row_stride = grid.head.cell_stride;
        grid
    }

    /// How many bytes its cells hold.
    pub(crate) fn data_len(&self) -> usize {
        self.data.len()
    }

    /// Appends the grid as serde_json writes it, its cells' base64 encoded
    /// straight into `out` (serde_json would build the string, then check
    /// each of its bytes for escaping, which base64 never needs).
    pub(crate) fn write_json(&self, out: &mut Vec<u8>) -> serde_json::Result<()> {
        serde_json::to_writer(&mut *out, &self.head)?;
        out.pop(); // the head's closing brace
        out.extend_from_slice(br#","data":""#);
        let start = out.len();
        // A vector holds at most isize::MAX bytes: its base64 length fits a usize.
        let len = base64::encoded_len(self.data.len(), true).expect("base64 of a vector's bytes fits a usize");
        out.resize(start + len, 0);
        let written = base64::engine::general_purpose::STANDARD
            .encode_slice(&self.data, &mut out[start..])
            .expect("the buffer holds the encoded length");
        out.truncate(start + written);
        out.extend_from_slice(br#""}"#);
        Ok(())
    }
}

/// Bytes as JSON gives them in a Foxglove message: a base64 string.
fn base64_string<S: serde::Serializer>(data: &impl AsRef<[u8]>, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(&base64::engine::general_purpose::STANDARD.encode(data))
}

/// `foxglove.LogLevel`.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Level {
    Info,
    Warning,
    Error,
}

impl Serialize for Level {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u8(match self {
            Self::Info => 2,
            Self::Warning => 3,
            Self::Error => 4,
        })
    }
}

/// `foxglove.Log`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Log {
    timestamp: Time,
    level: Level,
    message: String,
    name: &'static str,
    file: String,
    line: u32,
}

impl Log {
    /// A line from sightline about `file` (line `line`).
    pub(crate) fn new(timestamp: Time, level: Level, message: String, file: String, line: usize) -> Self {
        Self {
            timestamp,
            level,
            message,
            name: "sightline",
            file,
            line: u32::try_from(line).unwrap_or(u32::MAX),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid written directly is byte for byte serde_json's, for cells of
    /// every length modulo 3 (base64's padding), none, and all 256 byte values.
    #[test]
    fn a_grid_written_directly_is_serde_jsons() {
        for len in [0, 1, 2, 3, 4, 5, 256, 1_000, 4_097] {
            let data: Vec<u8> = (0..len).map(|i| (i * 7 % 256) as u8).collect();
            let grid = Grid::new(
                Time::from_nanos(1_700_000_000_123_456_789),
                [-12.5, 3.25],
                0.5,
                7,
                &["probability", "uncertainty"],
                Numeric::Float32,
                data,
            );
            let mut out = b"prefix".to_vec();
            grid.write_json(&mut out).unwrap();
            let expected = serde_json::to_vec(&grid).unwrap();
            assert_eq!(
                String::from_utf8(out[6..].to_vec()),
                String::from_utf8(expected),
                "{len} bytes"
            );
        }
    }
}
