//! The length fields inside a record, checked before the `mcap` crate parses
//! it: that crate allocates a string or byte field by its declared length
//! before it finds the field overruns its record, so one damaged length in a
//! small file could ask for gigabytes (found by fuzzing, issue 15). Layouts
//! follow the MCAP specification, record by record.

/// One field of a record, in order.
#[derive(Clone, Copy)]
enum Field {
    /// A fixed number of bytes.
    Fixed(usize),
    /// A string or byte array with a `u32` length prefix.
    Prefixed,
    /// A map of strings to strings: a `u32` byte length, then prefixed pairs.
    StringMap,
    /// A byte array with a `u64` length prefix.
    Long,
}

use Field::{Fixed, Long, Prefixed, StringMap};

/// The fields of the records whose parsing allocates by a declared length,
/// up to the last such field; `None` for the others.
fn layout(opcode: u8) -> Option<&'static [Field]> {
    Some(match opcode {
        0x01 => &[Prefixed, Prefixed],                      // Header
        0x03 => &[Fixed(2), Prefixed, Prefixed, Prefixed],  // Schema
        0x04 => &[Fixed(4), Prefixed, Prefixed, StringMap], // Channel
        0x06 => &[Fixed(28), Prefixed, Long],               // Chunk
        0x07 => &[Fixed(2), Prefixed],                      // Message Index
        0x08 => &[Fixed(32), Prefixed, Fixed(8), Prefixed], // Chunk Index
        0x09 => &[Fixed(16), Prefixed, Prefixed, Long],     // Attachment
        0x0A => &[Fixed(40), Prefixed, Prefixed],           // Attachment Index
        0x0B => &[Fixed(42), Prefixed],                     // Statistics
        0x0C => &[Prefixed, StringMap],                     // Metadata
        0x0D => &[Fixed(16), Prefixed],                     // Metadata Index
        _ => return None,
    })
}

/// Whether every length field of a record of `opcode` fits in its `data`;
/// otherwise, what overruns.
pub(super) fn check(opcode: u8, data: &[u8]) -> Result<(), String> {
    let Some(fields) = layout(opcode) else { return Ok(()) };
    let mut rest = data;
    for field in fields {
        rest = match *field {
            Fixed(n) => rest.get(n..),
            Prefixed => prefixed(rest),
            StringMap => prefixed(rest).and_then(|after| {
                let mut map = &rest[4..rest.len() - after.len()];
                while !map.is_empty() {
                    map = prefixed(map)?;
                }
                Some(after)
            }),
            Long => rest.get(..8).and_then(|len| {
                let len = u64::from_le_bytes(len.try_into().expect("8 bytes"));
                rest.get(8..).and_then(|after| after.get(usize::try_from(len).ok()?..))
            }),
        }
        .ok_or_else(|| format!("a length field of a record with opcode {opcode:#04x} overruns the record"))?;
    }
    Ok(())
}

/// The bytes after a `u32`-prefixed field at the start of `data`.
fn prefixed(data: &[u8]) -> Option<&[u8]> {
    let len = u32::from_le_bytes(data.get(..4)?.try_into().expect("4 bytes"));
    data.get(4..)?.get(usize::try_from(len).ok()?..)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(s: &str) -> Vec<u8> {
        let mut bytes = (s.len() as u32).to_le_bytes().to_vec();
        bytes.extend_from_slice(s.as_bytes());
        bytes
    }

    fn channel(topic_len: Option<u32>, key_len: Option<u32>) -> Vec<u8> {
        let mut data = vec![1, 0, 0, 0];
        let mut topic = string("/t");
        if let Some(len) = topic_len {
            topic[..4].copy_from_slice(&len.to_le_bytes());
        }
        data.extend(topic);
        data.extend(string("json"));
        let mut pair = string("k");
        if let Some(len) = key_len {
            pair[..4].copy_from_slice(&len.to_le_bytes());
        }
        pair.extend(string("v"));
        data.extend((pair.len() as u32).to_le_bytes());
        data.extend(pair);
        data
    }

    #[test]
    fn a_whole_channel_passes_and_a_length_past_its_end_is_refused() {
        assert_eq!(check(0x04, &channel(None, None)), Ok(()));
        assert!(check(0x04, &channel(Some(2_667_577_362), None)).is_err());
        assert!(
            check(0x04, &channel(None, Some(1 << 31))).is_err(),
            "a key inside the metadata map"
        );
        let whole = channel(None, None);
        assert!(check(0x04, &whole[..whole.len() - 1]).is_err(), "truncated");
    }

    #[test]
    fn an_attachment_longer_than_its_record_is_refused() {
        let mut data = vec![0; 16];
        data.extend(string("a.yaml"));
        data.extend(string("text/yaml"));
        data.extend(3u64.to_le_bytes());
        data.extend(b"abc");
        data.extend([0; 4]);
        assert_eq!(check(0x09, &data), Ok(()));
        let at = data.len() - 4 - 3 - 8;
        data[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
        assert!(check(0x09, &data).is_err());
    }

    #[test]
    fn records_without_length_fields_pass() {
        assert_eq!(check(0x05, &[0; 3]), Ok(()));
    }
}
