//! EvoGym's `.npz` robots, as its examples save them: `np.savez(path, body, connections)`, a zip
//! archive of two NumPy arrays, `arr_0.npy` (the material grid, rows from the top, usually
//! float64) and `arr_1.npy` (`2 × k` integer pairs of connected cells, each an index into the
//! flattened grid: row × width + column). Read either stored or deflated (`np.savez_compressed`);
//! written stored, with the grid as float64 and the pairs as int64, as EvoGym writes them.
//!
//! The zip archive is the `zip` crate's; the two small arrays are read by [`NpyArray`] here
//! (the `.npy` format is a short header and the raw values).

use super::grid::{MaterialGrid, MAX_ROBOT_SIDE};
use super::materials::Material;
use std::io::{Cursor, Read, Write};
use vsrlab_field::FieldError;

/// Whether `bytes` start like a zip archive (an `.npz` file).
pub fn is_npz(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK\x03\x04")
}

/// Reads an EvoGym `.npz` robot: the grid with exactly the connections the file lists, checked
/// as a robot. Errors name the array (`arr_0`, `arr_1`) and what is wrong.
pub fn robot_from_npz(bytes: &[u8]) -> Result<MaterialGrid, FieldError> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| FieldError::message(format!("not an .npz archive: {e}")))?;
    let body = NpyArray::parse(&entry(&mut archive, "arr_0")?).map_err(|e| e.at("arr_0"))?;
    let pairs = NpyArray::parse(&entry(&mut archive, "arr_1")?).map_err(|e| e.at("arr_1"))?;
    let grid = grid_of(&body).map_err(|e| e.at("arr_0"))?;
    let grid = connected(grid, &pairs).map_err(|e| e.at("arr_1"))?;
    grid.validate_robot().map_err(|e| e.at("arr_0"))?;
    Ok(grid)
}

/// Writes a robot as EvoGym's examples save one: the grid as float64, then every connection as
/// an int64 pair (EvoGym's `get_full_connectivity` order: each cell's right, then lower neighbour).
pub fn robot_to_npz(grid: &MaterialGrid) -> Vec<u8> {
    let (w, h) = (grid.width(), grid.height());
    let cells: Vec<f64> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| f64::from(grid.at(x, y).code()))
        .collect();
    let mut firsts = Vec::new();
    let mut seconds = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as i64;
            if grid.connected_right(x, y) {
                firsts.push(i);
                seconds.push(i + 1);
            }
            if grid.connected_down(x, y) {
                firsts.push(i);
                seconds.push(i + w as i64);
            }
        }
    }
    let k = firsts.len();
    firsts.extend(seconds);
    let mut out = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let stored = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let arrays = [
        (
            "arr_0.npy",
            npy_bytes("<f8", &[h, w], cells.iter().flat_map(|v| v.to_le_bytes())),
        ),
        (
            "arr_1.npy",
            npy_bytes("<i8", &[2, k], firsts.iter().flat_map(|v| v.to_le_bytes())),
        ),
    ];
    for (name, data) in arrays {
        out.start_file(name, stored).expect("writing to memory");
        out.write_all(&data).expect("writing to memory");
    }
    out.finish().expect("writing to memory").into_inner()
}

/// The bytes of entry `name.npy`.
fn entry(archive: &mut zip::ZipArchive<Cursor<&[u8]>>, name: &str) -> Result<Vec<u8>, FieldError> {
    let mut file = archive.by_name(&format!("{name}.npy")).map_err(|_| {
        FieldError::new(
            name,
            "missing: EvoGym saves the body as arr_0 and its connections as arr_1",
        )
    })?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)
        .map_err(|e| FieldError::new(name, format!("cannot be read: {e}")))?;
    Ok(bytes)
}

/// The material grid of a 2-dimensional array of material codes, not yet connected.
fn grid_of(body: &NpyArray) -> Result<MaterialGrid, FieldError> {
    let &[h, w] = body.shape.as_slice() else {
        return Err(FieldError::message(format!(
            "shape {:?}: expected a 2-dimensional grid",
            body.shape
        )));
    };
    if h == 0 || w == 0 || h > MAX_ROBOT_SIDE || w > MAX_ROBOT_SIDE {
        return Err(FieldError::message(format!(
            "shape ({h}, {w}): a robot is 1 to {MAX_ROBOT_SIDE} cells a side"
        )));
    }
    let cells = body
        .values
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let code = (v.fract() == 0.0 && (0.0..=255.0).contains(&v)).then_some(v as u64);
            code.and_then(Material::from_code).ok_or_else(|| {
                FieldError::message(format!(
                    "cell ({}, {}) = {v}: expected a material code 0-5",
                    i / w,
                    i % w
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(MaterialGrid::unconnected(w, h, cells))
}

/// The grid with the connections of a `2 × k` array of flattened cell indices.
fn connected(mut grid: MaterialGrid, pairs: &NpyArray) -> Result<MaterialGrid, FieldError> {
    let k = match pairs.shape.as_slice() {
        &[2, k] => k,
        &[2] | &[0] => 0,
        other => {
            return Err(FieldError::message(format!(
                "shape {other:?}: expected (2, k) pairs of connected cells"
            )))
        }
    };
    let (w, n) = (grid.width(), grid.width() * grid.height());
    let cell = |v: f64| -> Result<(usize, usize), FieldError> {
        let ok = v.fract() == 0.0 && v >= 0.0 && v < n as f64;
        ok.then(|| (v as usize % w, v as usize / w))
            .ok_or_else(|| FieldError::message(format!("{v} is no cell index: expected 0 to {}", n - 1)))
    };
    for j in 0..k {
        let (a, b) = (cell(pairs.values[j])?, cell(pairs.values[k + j])?);
        grid.connect(a, b)
            .map_err(|e| FieldError::message(format!("pair {j}: {e}")))?;
    }
    Ok(grid)
}

/// A NumPy `.npy` array of numbers, as f64, in C (row-major) order.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// The array's shape.
    pub shape: Vec<usize>,
    /// Every value, row-major.
    pub values: Vec<f64>,
}

impl NpyArray {
    /// Parses format versions 1 to 3 with a little- or big-endian integer, unsigned or float
    /// type of 1 to 8 bytes, in C or Fortran order. Errors say what is wrong.
    pub fn parse(bytes: &[u8]) -> Result<NpyArray, FieldError> {
        let bad = |m: &str| FieldError::message(format!("not a NumPy array: {m}"));
        let rest = bytes.strip_prefix(b"\x93NUMPY").ok_or_else(|| bad("no magic number"))?;
        let (version, rest) = rest.split_at_checked(2).ok_or_else(|| bad("truncated"))?;
        let (header_len, rest) = match version[0] {
            1 => rest
                .split_at_checked(2)
                .map(|(l, r)| (u16::from_le_bytes([l[0], l[1]]) as usize, r)),
            2 | 3 => rest
                .split_at_checked(4)
                .map(|(l, r)| (u32::from_le_bytes([l[0], l[1], l[2], l[3]]) as usize, r)),
            v => return Err(bad(&format!("format version {v}"))),
        }
        .ok_or_else(|| bad("truncated"))?;
        let (header, data) = rest
            .split_at_checked(header_len)
            .ok_or_else(|| bad("truncated header"))?;
        let header = std::str::from_utf8(header).map_err(|_| bad("header is not text"))?;
        let descr = header_value(header, "descr").ok_or_else(|| bad("no 'descr'"))?;
        let fortran = header_value(header, "fortran_order").ok_or_else(|| bad("no 'fortran_order'"))?;
        let shape = parse_shape(header_value(header, "shape").ok_or_else(|| bad("no 'shape'"))?)
            .ok_or_else(|| bad("unreadable 'shape'"))?;
        let kind = ElementType::parse(descr.trim_matches(|c| c == '\'' || c == '"'))
            .ok_or_else(|| FieldError::message(format!("element type {descr}: expected integers or floats")))?;
        let count = shape
            .iter()
            .try_fold(1usize, |a, &d| a.checked_mul(d))
            .ok_or_else(|| bad("shape too large"))?;
        if data.len() != count.saturating_mul(kind.size) {
            return Err(bad(&format!(
                "{} bytes of data for {count} values of {} bytes",
                data.len(),
                kind.size
            )));
        }
        let mut values: Vec<f64> = data.chunks_exact(kind.size).map(|c| kind.value(c)).collect();
        if fortran.trim() == "True" {
            values = c_order(&values, &shape);
        }
        Ok(NpyArray { shape, values })
    }
}

/// The text of `'key': value` in a header dictionary, up to the next key or the end.
fn header_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let start = header.find(&format!("'{key}'"))? + key.len() + 2;
    let rest = header[start..].trim_start().strip_prefix(':')?.trim_start();
    let end = if rest.starts_with('(') {
        rest.find(')')? + 1
    } else {
        rest.find(',').unwrap_or(rest.len())
    };
    Some(rest[..end].trim())
}

/// `(5, 5)`, `(3,)` or `()`.
fn parse_shape(text: &str) -> Option<Vec<usize>> {
    let inner = text.strip_prefix('(')?.strip_suffix(')')?;
    inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().ok())
        .collect()
}

/// Values of a Fortran-order array rearranged into C order.
fn c_order(values: &[f64], shape: &[usize]) -> Vec<f64> {
    let n = values.len();
    let mut out = vec![0.0; n];
    for (f, &v) in values.iter().enumerate() {
        // index digits, first axis fastest
        let (mut rest, mut c, mut stride) = (f, 0, n);
        for &d in shape {
            stride /= d.max(1);
            c += (rest % d.max(1)) * stride;
            rest /= d.max(1);
        }
        out[c] = v;
    }
    out
}

/// A NumPy element type: its kind (`i`, `u`, `f`), size and byte order.
#[derive(Debug, Clone, Copy)]
struct ElementType {
    kind: char,
    size: usize,
    big_endian: bool,
}

impl ElementType {
    fn parse(descr: &str) -> Option<ElementType> {
        let mut chars = descr.chars();
        let order = chars.next()?;
        let kind = chars.next()?;
        let size: usize = chars.as_str().parse().ok()?;
        let ok = matches!((kind, size), ('i' | 'u', 1 | 2 | 4 | 8) | ('f', 4 | 8)) && "<>|=".contains(order);
        ok.then_some(ElementType {
            kind,
            size,
            big_endian: order == '>',
        })
    }

    fn value(self, bytes: &[u8]) -> f64 {
        let mut b = [0u8; 8];
        if self.big_endian {
            b[..self.size]
                .iter_mut()
                .zip(bytes.iter().rev())
                .for_each(|(d, s)| *d = *s);
        } else {
            b[..self.size].copy_from_slice(bytes);
        }
        let sign_extend = |bits: u32| (i64::from_le_bytes(b) << (64 - bits)) >> (64 - bits);
        match (self.kind, self.size) {
            ('f', 8) => f64::from_le_bytes(b),
            ('f', _) => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            ('i', n) => sign_extend(8 * n as u32) as f64,
            _ => u64::from_le_bytes(b) as f64,
        }
    }
}

/// A version 1.0 `.npy` file: header padded with spaces to a multiple of 64 bytes, as NumPy.
fn npy_bytes(descr: &str, shape: &[usize], data: impl Iterator<Item = u8>) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend(data);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A robot EvoGym sampled and saved with `np.savez` (seed 3), and the same compressed.
    const SAVED: &[u8] = include_bytes!("../../../tests/data/evogym_robot.npz");
    const COMPRESSED: &[u8] = include_bytes!("../../../tests/data/evogym_robot_compressed.npz");

    #[test]
    fn evogym_saved_robots_read_stored_or_compressed() {
        let grid = robot_from_npz(SAVED).unwrap();
        assert_eq!(grid.to_rows(), "34300/10300/20212/02040/04443");
        assert_eq!(grid, MaterialGrid::from_rows("34300/10300/20212/02040/04443").unwrap());
        assert_eq!(robot_from_npz(COMPRESSED).unwrap(), grid);
        assert!(is_npz(SAVED) && !is_npz(b"{\"objects\": {}}"));
    }

    /// Our file reads back the same robot and holds the arrays EvoGym's own file holds.
    #[test]
    fn written_robots_round_trip_with_evogym_arrays() {
        let grid = robot_from_npz(SAVED).unwrap();
        let ours = robot_to_npz(&grid);
        assert_eq!(robot_from_npz(&ours).unwrap(), grid);
        let arrays = |bytes: &[u8]| {
            let mut a = zip::ZipArchive::new(Cursor::new(bytes)).unwrap();
            ["arr_0", "arr_1"].map(|n| NpyArray::parse(&entry(&mut a, n).unwrap()).unwrap())
        };
        let (theirs, mine) = (arrays(SAVED), arrays(&ours));
        assert_eq!(mine[0], theirs[0]);
        assert_eq!(mine[1].shape, theirs[1].shape);
        let pairs = |a: &NpyArray| {
            let k = a.shape[1];
            let mut p: Vec<(i64, i64)> = (0..k).map(|j| (a.values[j] as i64, a.values[k + j] as i64)).collect();
            p.sort_unstable();
            p
        };
        assert_eq!(pairs(&mine[1]), pairs(&theirs[1]));
    }

    #[test]
    fn partial_connections_are_kept() {
        // "33" with its one connection left out: two cells, each a separate piece
        let grid = MaterialGrid::unconnected(2, 1, vec![Material::HorizontalActuator; 2]);
        let bytes = robot_to_npz(&grid);
        let err = robot_from_npz(&bytes).unwrap_err();
        assert!(
            err.to_string().starts_with("arr_0"),
            "an unconnected robot is refused: {err}"
        );
        let mut one = grid.clone();
        one.connect((0, 0), (1, 0)).unwrap();
        assert_eq!(robot_from_npz(&robot_to_npz(&one)).unwrap(), one);
    }

    #[test]
    fn bad_files_name_the_array() {
        let grid = MaterialGrid::from_rows("33").unwrap();
        let write = |arrays: &[(&str, Vec<u8>)]| {
            let mut out = zip::ZipWriter::new(Cursor::new(Vec::new()));
            for (name, data) in arrays {
                out.start_file(*name, zip::write::SimpleFileOptions::default()).unwrap();
                out.write_all(data).unwrap();
            }
            out.finish().unwrap().into_inner()
        };
        let body = npy_bytes("<f8", &[1, 2], [3.0f64, 3.0].iter().flat_map(|v| v.to_le_bytes()));
        let pairs = npy_bytes("<i8", &[2, 1], [0i64, 1].iter().flat_map(|v| v.to_le_bytes()));
        assert_eq!(
            robot_from_npz(&write(&[("arr_0.npy", body.clone()), ("arr_1.npy", pairs.clone())])).unwrap(),
            grid
        );
        let cases = [
            (write(&[("arr_0.npy", body.clone())]), "arr_1: missing"),
            (
                write(&[
                    (
                        "arr_0.npy",
                        npy_bytes("<f8", &[2], [3.0f64, 7.0].iter().flat_map(|v| v.to_le_bytes())),
                    ),
                    ("arr_1.npy", pairs.clone()),
                ]),
                "arr_0: shape [2]",
            ),
            (
                write(&[
                    (
                        "arr_0.npy",
                        npy_bytes("<f8", &[1, 2], [3.0f64, 9.0].iter().flat_map(|v| v.to_le_bytes())),
                    ),
                    ("arr_1.npy", pairs.clone()),
                ]),
                "arr_0: cell (0, 1) = 9",
            ),
            (
                write(&[
                    ("arr_0.npy", body.clone()),
                    (
                        "arr_1.npy",
                        npy_bytes("<i8", &[2, 1], [0i64, 7].iter().flat_map(|v| v.to_le_bytes())),
                    ),
                ]),
                "arr_1: 7 is no cell index",
            ),
            (
                write(&[("arr_0.npy", b"\x93NUMPY\x01\x00".to_vec()), ("arr_1.npy", pairs)]),
                "arr_0: not a NumPy array",
            ),
            (b"PK\x03\x04 not really".to_vec(), "not an .npz archive"),
        ];
        for (bytes, expected) in cases {
            let err = robot_from_npz(&bytes).unwrap_err().to_string();
            assert!(err.starts_with(expected), "{err} (expected {expected})");
        }
    }

    #[test]
    fn npy_headers_of_other_types_and_orders_read() {
        let a = NpyArray::parse(&npy_bytes(
            ">i2",
            &[2, 3],
            [1i16, 2, 3, -4, 5, 6].iter().flat_map(|v| v.to_be_bytes()),
        ))
        .unwrap();
        assert_eq!(a.values, [1.0, 2.0, 3.0, -4.0, 5.0, 6.0]);
        let mut fortran = npy_bytes("|u1", &[2, 3], [1u8, 4, 2, 5, 3, 6].into_iter());
        let at = fortran.windows(5).position(|w| w == b"False").unwrap();
        fortran.splice(at..at + 5, b"True ".iter().copied());
        let f = NpyArray::parse(&fortran).unwrap();
        assert_eq!(f.values, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        assert!(NpyArray::parse(&npy_bytes("<c16", &[1], [0u8; 16].into_iter())).is_err());
    }
}
