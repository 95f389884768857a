//! CDR (XCDR1) messages as ROS 2 puts them on the wire and in bags: a
//! four-byte encapsulation header (`00 01` little endian, `00 00` big
//! endian, then two option bytes), then the fields, each aligned to its
//! size from the end of the header. The field coding is `cdr-encoding`'s.

use byteorder::{BigEndian, LittleEndian};
use serde::{Serialize, de::DeserializeOwned};

/// Encapsulation header of plain CDR, little endian.
const CDR_LE: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// `value` as a CDR message, little endian, with its encapsulation header.
///
/// # Errors
/// A message `cdr-encoding` cannot encode (not one of ours).
pub fn encode<T: Serialize>(value: &T) -> Result<Vec<u8>, String> {
    let body = cdr_encoding::to_vec::<T, LittleEndian>(value).map_err(|e| e.to_string())?;
    let mut out = Vec::with_capacity(body.len() + 4);
    out.extend_from_slice(&CDR_LE);
    out.extend_from_slice(&body);
    Ok(out)
}

/// Decodes a CDR message of either byte order.
///
/// # Errors
/// One line saying what was wrong: no header, an unknown representation
/// (only plain CDR, `00 00` or `00 01`, is read), or the fields'
/// decoding error (too short, a bad boolean or string).
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, String> {
    if bytes.len() < 4 {
        return Err(format!(
            "{} bytes, shorter than the 4-byte CDR encapsulation header",
            bytes.len()
        ));
    }
    let body = &bytes[4..];
    let decoded = match [bytes[0], bytes[1]] {
        [0x00, 0x01] => cdr_encoding::from_bytes::<T, LittleEndian>(body),
        [0x00, 0x00] => cdr_encoding::from_bytes::<T, BigEndian>(body),
        other => {
            return Err(format!(
                "CDR representation {:02x} {:02x}, expected plain CDR (00 00 or 00 01)",
                other[0], other[1]
            ));
        }
    };
    decoded
        .map(|(value, _)| value)
        .map_err(|e| format!("CDR decoding failed: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msgs::{Header, OccupancyGrid, Odometry, Path, PoseStamped, Time};

    #[test]
    fn header_bytes_are_as_ros_writes_them() {
        let header = Header {
            stamp: Time { sec: 1, nanosec: 2 },
            frame_id: "map".into(),
        };
        let bytes = encode(&header).expect("encode");
        // header, sec, nanosec, string length 4 ("map\0"), "map\0".
        assert_eq!(
            bytes,
            [
                0, 1, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 4, 0, 0, 0, b'm', b'a', b'p', 0
            ]
        );
        assert_eq!(decode::<Header>(&bytes).expect("decode"), header);
    }

    #[test]
    fn messages_round_trip_and_float64_is_aligned_to_eight() {
        let path = Path {
            header: Header::default(),
            poses: vec![PoseStamped::default(); 3],
        };
        assert_eq!(decode::<Path>(&encode(&path).expect("e")).expect("d"), path);
        let odom = Odometry::default();
        assert_eq!(
            decode::<Odometry>(&encode(&odom).expect("e")).expect("d"),
            odom
        );
        let mut grid = OccupancyGrid {
            data: vec![-1, 0, 100],
            ..OccupancyGrid::default()
        };
        grid.info.origin.position.x = 1.5;
        let bytes = encode(&grid).expect("e");
        assert_eq!(decode::<OccupancyGrid>(&bytes).expect("d"), grid);
        // Header: stamp 8 + string length 4 + "\0" = 13, padded to 16 for
        // the load time (16..24); resolution, width, height to 36; the
        // origin's x is a float64, aligned to 40.
        let x = f64::from_le_bytes(bytes[4 + 40..4 + 48].try_into().expect("8"));
        assert_eq!(x, 1.5);
    }

    #[test]
    fn bad_messages_are_one_line_errors() {
        assert!(decode::<Header>(&[0, 1]).unwrap_err().contains("shorter"));
        assert!(
            decode::<Header>(&[0, 7, 0, 0])
                .unwrap_err()
                .contains("representation")
        );
        let mut bytes = encode(&OccupancyGrid::default()).expect("e");
        bytes.truncate(bytes.len() - 3);
        assert!(
            decode::<OccupancyGrid>(&bytes)
                .unwrap_err()
                .contains("CDR decoding failed")
        );
    }
}
