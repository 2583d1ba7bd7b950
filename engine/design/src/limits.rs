//! The most hpr-mc reads of any file it is given, stated once, and the one reader that keeps
//! to it.
//!
//! A file handed to hpr-mc may be anything: `/dev/zero`, a log of several gigabytes named by
//! mistake, a ZIP that inflates a thousandfold. Every input is therefore read through
//! [`read_limited`], which stops one byte past the limit and refuses the file with the limit
//! in the message, and the document inside an OpenRocket ZIP or gzip stream is inflated no
//! further than [`MAX_ORK_DOCUMENT_BYTES`]. The limits are far above any real file of each
//! kind (the largest bundled thrust curve is a few kilobytes, an OpenRocket file with every
//! simulation's data a few megabytes), and low enough that what is read fits in memory with
//! room for the structures built from it.

use std::io::Read;
use std::path::Path;

/// One mebibyte, bytes.
const MIB: u64 = 1 << 20;

/// A design file (JSON or OpenRocket `.ork`, as stored on disk), bytes: 64 MiB.
pub const MAX_DESIGN_FILE_BYTES: u64 = 64 * MIB;

/// The XML document inside an OpenRocket file once inflated from its ZIP or gzip stream,
/// bytes: 64 MiB (OpenRocket's own files, simulation data included, are a few MiB).
pub const MAX_ORK_DOCUMENT_BYTES: u64 = 64 * MIB;

/// How deeply the elements of an OpenRocket document may nest: 100 (OpenRocket's deepest,
/// a part inside an inner tube inside a body tube of a stage, is about 12).
pub const MAX_ORK_DEPTH: usize = 100;

/// How many XML nodes (elements, text, comments) an OpenRocket document may hold: 4,000,000
/// (a design with every simulation's data saved holds some tens of thousands).
pub const MAX_ORK_NODES: u32 = 4_000_000;

/// A table beside a design (a drag curve's or an airfoil's CSV), bytes: 16 MiB.
pub const MAX_TABLE_FILE_BYTES: u64 = 16 * MIB;

/// A motor file (`.eng`, `.rse`), bytes: 16 MiB (some 700,000 samples of a RASP curve).
pub const MAX_MOTOR_FILE_BYTES: u64 = 16 * MIB;

/// A radiosonde sounding (the University of Wyoming's text listing), bytes: 16 MiB.
pub const MAX_SOUNDING_FILE_BYTES: u64 = 16 * MIB;

/// A scenario file (TOML), bytes: 4 MiB.
pub const MAX_SCENARIO_FILE_BYTES: u64 = 4 * MIB;

/// A size in the words the limits are stated in: `16 MiB`, `1500 bytes`.
pub fn size_text(bytes: u64) -> String {
    if bytes >= MIB && bytes.is_multiple_of(MIB) {
        format!("{} MiB", bytes / MIB)
    } else {
        format!("{bytes} bytes")
    }
}

/// The rule a file larger than `limit` breaks, for a `what` (`a motor file`).
pub fn too_large(what: &str, limit: u64) -> String {
    format!(
        "it is larger than {}, the most hpr-mc reads for {what}",
        size_text(limit)
    )
}

/// The whole of the file at `path`, if it holds at most `limit` bytes; `what` names the kind
/// of file in the error (`a motor file`). A directory is refused as one (not "no such
/// file"), and a file that never ends (`/dev/zero`) or is too large is refused after
/// `limit + 1` bytes with [`std::io::ErrorKind::FileTooLarge`] and the rule in the message.
pub fn read_limited(path: &Path, limit: u64, what: &str) -> std::io::Result<Vec<u8>> {
    if path.is_dir() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::IsADirectory,
            format!("it is a directory, not {what}"),
        ));
    }
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            too_large(what, limit),
        ));
    }
    Ok(bytes)
}

/// [`read_limited`] as UTF-8 text (a byte-order mark at the start is dropped).
pub fn read_text_limited(path: &Path, limit: u64, what: &str) -> std::io::Result<String> {
    let bytes = read_limited(path, limit, what)?;
    let text = String::from_utf8(bytes).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("it is not UTF-8 text ({e})"),
        )
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_owned(),
        None => text,
    })
}

/// At most `limit` bytes from `reader` as UTF-8 text: `Err(None)` past the limit,
/// `Err(Some(e))` for a read error or text that is not UTF-8.
pub fn read_to_string_limited(
    reader: impl Read,
    limit: u64,
) -> Result<String, Option<std::io::Error>> {
    let mut bytes = Vec::new();
    reader
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(Some)?;
    if bytes.len() as u64 > limit {
        return Err(None);
    }
    String::from_utf8(bytes).map_err(|e| {
        Some(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text ({e})"),
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_that_never_ends_is_refused_after_the_limit_with_the_rule() {
        let e = read_limited(Path::new("/dev/zero"), 1000, "a motor file").unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::FileTooLarge);
        assert_eq!(
            e.to_string(),
            "it is larger than 1000 bytes, the most hpr-mc reads for a motor file"
        );
    }

    #[test]
    fn a_file_at_the_limit_is_read_whole_and_one_byte_more_is_refused() {
        let dir = std::env::temp_dir().join(format!("hpr-limits-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("f.txt");
        std::fs::write(&path, vec![b'a'; 64]).unwrap();
        assert_eq!(read_limited(&path, 64, "x").unwrap().len(), 64);
        assert!(read_limited(&path, 63, "x").is_err());
        let e = read_limited(&dir, 64, "a design").unwrap_err();
        assert_eq!(e.to_string(), "it is a directory, not a design");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn sizes_read_in_mebibytes_when_whole() {
        assert_eq!(size_text(MAX_MOTOR_FILE_BYTES), "16 MiB");
        assert_eq!(size_text(1500), "1500 bytes");
    }
}
