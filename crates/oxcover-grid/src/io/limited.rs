//! Reading whole files with a size limit, checked before and while reading:
//! a file larger than the limit, or a device or pipe that never ends (a map
//! that is a link to `/dev/zero`), is refused with a clear error instead of
//! filling memory.

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

/// The whole file at `path`, refused (`InvalidData`) when it holds more
/// than `limit` bytes.
///
/// # Errors
/// The open or read error, or `InvalidData` naming the limit.
pub fn read_limited(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let file = std::fs::File::open(path)?;
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
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// [`read_limited`] as UTF-8 text.
///
/// # Errors
/// As [`read_limited`], or `InvalidData` for text that is not UTF-8.
pub fn read_limited_string(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_limited(path, limit)?)
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
}
