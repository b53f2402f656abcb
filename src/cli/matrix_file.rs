//! Named matrices and name lists written as `.json`, `.npz` (numpy: a zip of `.npy` files,
//! format 1.0, `<f8` row-major and `<U` strings) or `.mat` (MATLAB level 5: doubles column-major,
//! name lists as 1 × k cell arrays of char rows). The same keys in all three.

use std::io::Write;

/// One entry of the file.
#[derive(Clone, Debug)]
pub enum Value {
    /// A `rows × cols` matrix, row-major values.
    Matrix(usize, usize, Vec<f64>),
    /// A vector (numpy shape `(k,)`, MATLAB `k × 1`).
    Vector(Vec<f64>),
    /// A scalar.
    Scalar(f64),
    /// A list of names.
    Names(Vec<String>),
}

/// Entries in file order.
pub type Entries = Vec<(&'static str, Value)>;

/// The JSON text: matrices as arrays of rows.
pub fn json(entries: &Entries) -> String {
    let num = |x: f64| {
        if x.is_finite() {
            serde_json::json!(x)
        } else {
            serde_json::Value::Null
        }
    };
    let mut map = serde_json::Map::new();
    for (k, v) in entries {
        let val = match v {
            Value::Matrix(r, c, xs) => serde_json::Value::Array(
                (0..*r)
                    .map(|i| {
                        serde_json::Value::Array((0..*c).map(|j| num(xs[i * c + j])).collect())
                    })
                    .collect(),
            ),
            Value::Vector(xs) => serde_json::Value::Array(xs.iter().map(|&x| num(x)).collect()),
            Value::Scalar(x) => num(*x),
            Value::Names(ns) => serde_json::json!(ns),
        };
        map.insert((*k).to_string(), val);
    }
    let mut s = serde_json::to_string_pretty(&serde_json::Value::Object(map)).unwrap_or_default();
    s.push('\n');
    s
}

fn npy(v: &Value) -> Vec<u8> {
    let (descr, shape, data): (String, String, Vec<u8>) = match v {
        Value::Matrix(r, c, xs) => (
            "<f8".into(),
            format!("({r}, {c})"),
            xs.iter().flat_map(|x| x.to_le_bytes()).collect(),
        ),
        Value::Vector(xs) => (
            "<f8".into(),
            format!("({},)", xs.len()),
            xs.iter().flat_map(|x| x.to_le_bytes()).collect(),
        ),
        Value::Scalar(x) => ("<f8".into(), "()".into(), x.to_le_bytes().to_vec()),
        Value::Names(ns) => {
            let w = ns
                .iter()
                .map(|n| n.chars().count())
                .max()
                .unwrap_or(0)
                .max(1);
            let mut data = Vec::new();
            for n in ns {
                let mut k = 0;
                for ch in n.chars() {
                    data.extend_from_slice(&(ch as u32).to_le_bytes());
                    k += 1;
                }
                data.resize(data.len() + 4 * (w - k), 0);
            }
            (format!("<U{w}"), format!("({},)", ns.len()), data)
        }
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    // magic (6) + version (2) + length (2) + header, padded with spaces to a multiple of 64
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(
        &u16::try_from(header.len())
            .unwrap_or(u16::MAX)
            .to_le_bytes(),
    );
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(&data);
    out
}

/// The `.npz` bytes (stored, deterministic).
///
/// # Errors
/// A message if the zip cannot be written.
pub fn npz(entries: &Entries) -> Result<Vec<u8>, String> {
    let mut zw = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .last_modified_time(zip::DateTime::default());
    for (k, v) in entries {
        zw.start_file(format!("{k}.npy"), opts)
            .map_err(|e| e.to_string())?;
        zw.write_all(&npy(v)).map_err(|e| e.to_string())?;
    }
    Ok(zw.finish().map_err(|e| e.to_string())?.into_inner())
}

const MI_INT8: u32 = 1;
const MI_UINT16: u32 = 4;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_DOUBLE: u32 = 9;
const MI_MATRIX: u32 = 14;
const MX_CELL: u32 = 1;
const MX_CHAR: u32 = 4;
const MX_DOUBLE: u32 = 6;

/// A data element: tag, bytes, padding to 8.
fn element(kind: u32, bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len() + 16);
    out.extend_from_slice(&kind.to_le_bytes());
    out.extend_from_slice(&u32::try_from(bytes.len()).unwrap_or(u32::MAX).to_le_bytes());
    out.extend_from_slice(bytes);
    out.resize(out.len().div_ceil(8) * 8, 0);
    out
}

/// A `miMATRIX` of class `class`, dimensions `dims`, name and body elements.
fn matrix(class: u32, dims: &[usize], name: &str, body: &[Vec<u8>]) -> Vec<u8> {
    let mut inner = element(
        MI_UINT32,
        &[class.to_le_bytes(), 0u32.to_le_bytes()].concat(),
    );
    let d: Vec<u8> = dims
        .iter()
        .flat_map(|&x| i32::try_from(x).unwrap_or(i32::MAX).to_le_bytes())
        .collect();
    inner.extend(element(MI_INT32, &d));
    inner.extend(element(MI_INT8, name.as_bytes()));
    for b in body {
        inner.extend_from_slice(b);
    }
    element(MI_MATRIX, &inner)
}

fn mat_value(name: &str, v: &Value) -> Vec<u8> {
    let doubles = |xs: &[f64]| {
        element(
            MI_DOUBLE,
            &xs.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<_>>(),
        )
    };
    match v {
        Value::Matrix(r, c, xs) => {
            let col_major: Vec<f64> = (0..*c)
                .flat_map(|j| (0..*r).map(move |i| (i, j)))
                .map(|(i, j)| xs[i * c + j])
                .collect();
            matrix(MX_DOUBLE, &[*r, *c], name, &[doubles(&col_major)])
        }
        Value::Vector(xs) => matrix(MX_DOUBLE, &[xs.len(), 1], name, &[doubles(xs)]),
        Value::Scalar(x) => matrix(MX_DOUBLE, &[1, 1], name, &[doubles(&[*x])]),
        Value::Names(ns) => {
            let cells: Vec<Vec<u8>> = ns
                .iter()
                .map(|n| {
                    let units: Vec<u16> = n.encode_utf16().collect();
                    let bytes: Vec<u8> = units.iter().flat_map(|u| u.to_le_bytes()).collect();
                    matrix(
                        MX_CHAR,
                        &[1, units.len()],
                        "",
                        &[element(MI_UINT16, &bytes)],
                    )
                })
                .collect();
            matrix(MX_CELL, &[1, ns.len()], name, &cells)
        }
    }
}

/// The `.mat` (level 5) bytes.
#[must_use]
pub fn mat(entries: &Entries) -> Vec<u8> {
    let mut text = b"MATLAB 5.0 MAT-file, written by triad linearize".to_vec();
    text.resize(116, b' ');
    let mut out = text;
    out.extend_from_slice(&[0u8; 8]);
    out.extend_from_slice(&0x0100u16.to_le_bytes());
    out.extend_from_slice(b"IM");
    for (k, v) in entries {
        out.extend(mat_value(k, v));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn npy_headers_are_aligned_and_mat_elements_padded() {
        let v = Value::Names(vec!["joint.a.q".into(), "b".into()]);
        let bytes = npy(&v);
        let hl = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + hl) % 64, 0);
        assert_eq!(bytes.len(), 10 + hl + 2 * 9 * 4);
        let m = mat(&vec![("A", Value::Matrix(2, 3, vec![1.0; 6]))]);
        assert_eq!(m.len() % 8, 0);
        assert_eq!(&m[126..128], b"IM");
    }
}
