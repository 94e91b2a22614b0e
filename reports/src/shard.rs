//! Shard files: the outcomes `sightline run --shard K/N` simulated, for
//! `sightline merge` to assemble into the run an unsharded `sightline run` gives.
//!
//! A shard file is CBOR (RFC 8949): binary, so every outcome comes back bit for
//! bit (NaN and infinities too, which JSON cannot hold), and self-describing, so
//! a damaged file is an error, not garbage. Its first field, `format`, names the
//! layout; a merge refuses another.

use serde::{Deserialize, Serialize};
use sightline_engine::{Outcome, Unit};

use crate::{Execution, Tool};

/// The layout of a shard file (its `format` field).
pub const SHARD_FORMAT: &str = "sightline-shard/1";

/// One shard's part of one scenario's run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Shard {
    /// [`SHARD_FORMAT`].
    pub format: String,
    /// The tool that simulated it: a merge needs every shard from the same build.
    pub tool: Tool,
    /// The campaign's scenario files, as the user named them, in order.
    pub files: Vec<String>,
    /// This part's scenario file, one of `files`.
    pub file: String,
    /// Every input, the scenario file first, then the files it imports.
    pub inputs: Vec<ShardInput>,
    /// `--seed`, when given.
    pub seed: Option<u64>,
    /// `--record`.
    pub record: bool,
    /// K of `--shard K/N`, from 1.
    pub index: u32,
    /// N of `--shard K/N`.
    pub count: u32,
    /// Where, when and how long this part ran.
    pub execution: Execution,
    /// The units this shard simulated, each with its outcomes.
    pub units: Vec<(Unit, Vec<Outcome>)>,
}

/// An input file and its hash.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardInput {
    /// Its path, as results.json gives it.
    pub path: String,
    /// SHA-256 of its bytes, lowercase hex.
    pub sha256: String,
}

/// Why a shard file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ShardError {
    /// It is not a shard file, or it is damaged (truncated, say).
    #[error("not a sightline shard file, or damaged: {0}")]
    Damaged(String),
    /// It was written in another layout.
    #[error("written as `{0}`; this sightline reads `{SHARD_FORMAT}` (merge with the sightline that wrote it)")]
    Format(String),
}

/// The bytes of `shard`'s file.
pub fn shard_bytes(shard: &Shard) -> Vec<u8> {
    let mut bytes = Vec::new();
    ciborium::into_writer(shard, &mut bytes).expect("writing to memory cannot fail and every outcome is CBOR");
    bytes
}

/// Reads a shard file's bytes.
pub fn read_shard(bytes: &[u8]) -> Result<Shard, ShardError> {
    #[derive(Deserialize)]
    struct Header {
        format: String,
    }
    let damaged = |e: ciborium::de::Error<std::io::Error>| ShardError::Damaged(e.to_string());
    let header: Header = ciborium::from_reader(bytes).map_err(damaged)?;
    if header.format != SHARD_FORMAT {
        return Err(ShardError::Format(header.format));
    }
    ciborium::from_reader(bytes).map_err(damaged)
}
