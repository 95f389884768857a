//! Reading whole files with a size limit, checked before and while reading:
//! a file larger than the limit, or a device or pipe that never ends (a map
//! that is a link to `/dev/zero`), is refused with a clear error instead of
//! filling memory. The readers that know their format check a file's
//! first bytes ([`HEAD_BYTES`]) before reading on ([`read_limited_after`]):
//! a link to `/dev/zero` named `map.pgm` is refused after 64 bytes, not
//! after the 1 GiB cap.

use std::io::Read as _;
use std::path::Path;

/// Most bytes read for a map image or a MovingAI map (1 GiB).
pub const MAX_MAP_BYTES: u64 = 1 << 30;
/// Most bytes read for a map yaml (1 MiB).
pub const MAX_YAML_BYTES: u64 = 1 << 20;
/// Most bytes read for a path file (1 GiB).
pub const MAX_PATH_BYTES: u64 = 1 << 30;
/// Most bytes read for a RON description (world, camera, profile, robot)
/// or a camera pose list (64 MiB).
pub const MAX_TEXT_BYTES: u64 = 64 << 20;

/// How many of a file's first bytes a format check sees.
pub const HEAD_BYTES: usize = 64;

/// The whole file at `path`, refused (`InvalidData`) when it holds more
/// than `limit` bytes.
///
/// # Errors
/// The open or read error, or `InvalidData` naming the limit.
pub fn read_limited(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    read_limited_after(path, limit, |_| Ok(()))
}

/// [`read_limited`], after `check` has accepted the file's first
/// [`HEAD_BYTES`] bytes (fewer if the file is shorter): a file of the wrong
/// format is refused before the rest is read.
///
/// # Errors
/// As [`read_limited`], or `InvalidData` with `check`'s message.
pub fn read_limited_after(
    path: &Path,
    limit: u64,
    check: impl FnOnce(&[u8]) -> Result<(), String>,
) -> std::io::Result<Vec<u8>> {
    let mut file = std::fs::File::open(path)?;
    let too_large = || {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "larger than {}, the most read for this kind of file",
                size(limit)
            ),
        )
    };
    if file
        .metadata()
        .is_ok_and(|m| m.is_file() && m.len() > limit)
    {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    (&mut file)
        .take((HEAD_BYTES as u64).min(limit + 1))
        .read_to_end(&mut bytes)?;
    check(&bytes).map_err(|m| std::io::Error::new(std::io::ErrorKind::InvalidData, m))?;
    file.take(limit + 1 - bytes.len() as u64)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Accepts the first bytes of a text file: no NUL byte, and UTF-8 (a
/// character cut off at the end of `head` aside).
///
/// # Errors
/// What the bytes are instead.
pub fn text_head(head: &[u8]) -> Result<(), String> {
    if let Some(i) = head.iter().position(|&b| b == 0) {
        return Err(format!("not a text file (byte {i} is NUL)"));
    }
    match std::str::from_utf8(head) {
        Err(e) if e.error_len().is_some() => {
            Err(format!("not UTF-8 text (byte {} is not)", e.valid_up_to()))
        }
        _ => Ok(()),
    }
}

/// The first bytes of a file for a message: up to 8, in hex.
#[must_use]
pub fn hex_head(head: &[u8]) -> String {
    head.iter()
        .take(8)
        .map(|b| format!("{b:02x}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// [`read_limited`] as UTF-8 text, its first bytes checked by [`text_head`].
///
/// # Errors
/// As [`read_limited`], or `InvalidData` for text that is not UTF-8.
pub fn read_limited_string(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_limited_after(path, limit, text_head)?)
        .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8 text"))
}

fn size(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{} GiB", bytes >> 30)
    } else if bytes >= 1 << 20 {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endless_and_large_files_are_refused() {
        let zero = Path::new("/dev/zero");
        if zero.exists() {
            let e = read_limited(zero, 1000).unwrap_err();
            assert!(e.to_string().contains("larger than 1000 bytes"), "{e}");
        }
        let dir = std::env::temp_dir().join(format!("oxcover-limited-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("f.txt");
        std::fs::write(&f, "hello").unwrap();
        assert_eq!(read_limited_string(&f, 5).unwrap(), "hello");
        assert!(read_limited(&f, 4).is_err());
    }

    #[test]
    fn a_wrong_format_is_refused_from_its_first_bytes() {
        let zero = Path::new("/dev/zero");
        if zero.exists() {
            // The check sees 64 bytes; the cap (1 TiB here) is never reached.
            let e = read_limited_string(zero, 1 << 40).unwrap_err();
            assert!(e.to_string().contains("byte 0 is NUL"), "{e}");
        }
        assert!(text_head(b"x: 1\n").is_ok());
        assert!(
            text_head(&[b'a', 0xC3]).is_ok(),
            "a character cut at the end"
        );
        assert!(
            text_head(&[b'a', 0xFF, b'b'])
                .unwrap_err()
                .contains("byte 1")
        );
        assert_eq!(hex_head(&[0, 0xAB, 7]), "00 ab 07");
    }
}
