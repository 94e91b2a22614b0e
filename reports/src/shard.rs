//! Shard files: the outcomes `sightline run --shard K/N` simulated, for
//! `sightline merge` to assemble into the run an unsharded `sightline run` gives.
//!
//! A shard file is sealed: two header lines, then the payload.
//!
//! ```text
//! sightline-shard/3\n              the layout (SHARD_FORMAT)
//! <SHA-256 of the payload>\n       64 lowercase hex digits
//! <payload>                        the Shard as CBOR (RFC 8949)
//! ```
//!
//! [`read_shard`] checks the digest over the exact payload bytes before it
//! decodes anything, so any damaged byte (in the header or the payload) is
//! refused, never read as other outcomes. The payload is CBOR so that every
//! outcome comes back bit for bit (NaN and infinities too, which JSON cannot
//! hold).

use serde::{Deserialize, Serialize};
use sightline_engine::{Outcome, Unit};

use crate::{Execution, Tool, sha256_hex};

/// The layout of a shard file: its first line.
pub const SHARD_FORMAT: &str = "sightline-shard/3";

/// The length of the digest line: 64 hex digits and a newline.
const DIGEST_LINE: usize = 65;

/// One shard's part of one scenario's run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Shard {
    /// The campaign it belongs to ([`campaign_id`]): the same in every shard
    /// of one `run --shard` campaign.
    pub campaign: String,
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

/// The id of a campaign: the SHA-256 (lowercase hex) of the CBOR encoding of
/// what defines its work: the tool build, each scenario file's inputs (its
/// path as given and SHA-256, then its imports'), `--seed`, `--record` and N.
/// Every shard of a campaign computes it alike, without coordination.
pub fn campaign_id(tool: &Tool, inputs: &[Vec<ShardInput>], seed: Option<u64>, record: bool, count: u32) -> String {
    #[derive(Serialize)]
    struct Campaign<'a> {
        tool: &'a Tool,
        inputs: &'a [Vec<ShardInput>],
        seed: Option<u64>,
        record: bool,
        count: u32,
    }
    let campaign = Campaign {
        tool,
        inputs,
        seed,
        record,
        count,
    };
    let mut bytes = Vec::new();
    ciborium::into_writer(&campaign, &mut bytes).expect("writing strings and numbers to memory cannot fail");
    sha256_hex(&bytes)
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
    /// It does not start as a shard file does.
    #[error("not a sightline shard file (its first line is not `{SHARD_FORMAT}`)")]
    NotShard,
    /// It was written in another layout.
    #[error(
        "written as `{0}`; this sightline reads `{SHARD_FORMAT}` (merge with the sightline that wrote it, or run the shards again with this one)"
    )]
    Format(String),
    /// Its payload does not have the SHA-256 its header records: a byte of
    /// either is damaged, or the file is truncated.
    #[error("damaged or truncated: the SHA-256 of its payload is {actual}, and its header records `{recorded}`")]
    Damaged {
        /// The payload's digest.
        actual: String,
        /// The header's digest line, as far as it is text.
        recorded: String,
    },
    /// The payload is intact but does not decode as a shard: written by a
    /// defective sightline.
    #[error("its payload is intact but does not decode: {0}")]
    Payload(String),
}

/// The bytes of `shard`'s file: the header lines, then the payload.
pub fn shard_bytes(shard: &Shard) -> Vec<u8> {
    let mut payload = Vec::new();
    ciborium::into_writer(shard, &mut payload).expect("writing to memory cannot fail and every outcome is CBOR");
    let mut bytes = format!("{SHARD_FORMAT}\n{}\n", sha256_hex(&payload)).into_bytes();
    bytes.append(&mut payload);
    bytes
}

/// Reads a shard file's bytes, checking the seal before decoding anything.
pub fn read_shard(bytes: &[u8]) -> Result<Shard, ShardError> {
    let Some(sealed) = bytes
        .strip_prefix(SHARD_FORMAT.as_bytes())
        .and_then(|rest| rest.strip_prefix(b"\n"))
    else {
        return Err(other_format(bytes));
    };
    let (recorded, payload) = sealed.split_at(DIGEST_LINE.min(sealed.len()));
    let actual = sha256_hex(payload);
    if recorded != format!("{actual}\n").as_bytes() {
        let line = recorded.strip_suffix(b"\n").unwrap_or(recorded);
        return Err(ShardError::Damaged {
            actual,
            recorded: String::from_utf8_lossy(line).escape_debug().to_string(),
        });
    }
    ciborium::from_reader(payload).map_err(|e| ShardError::Payload(e.to_string()))
}

/// Why `bytes`, which do not start with this layout's line, are refused: a
/// shard of another layout (a later one's first line, or the first layout's
/// CBOR map with its `format` field), or not a shard at all.
fn other_format(bytes: &[u8]) -> ShardError {
    #[derive(Deserialize)]
    struct Unsealed {
        format: String,
    }
    let start = &bytes[..bytes.len().min(DIGEST_LINE)];
    let line = start.split(|&b| b == b'\n').next().unwrap_or_default();
    if let Some(line) = std::str::from_utf8(line)
        .ok()
        .filter(|l| l.starts_with("sightline-shard/"))
    {
        return ShardError::Format(line.escape_debug().to_string());
    }
    match ciborium::from_reader::<Unsealed, _>(bytes) {
        Ok(unsealed) if unsealed.format.starts_with("sightline-shard/") => ShardError::Format(unsealed.format),
        _ => ShardError::NotShard,
    }
}
