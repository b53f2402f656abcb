//! Value shapes that accept several spellings: inertia (3, 6 numbers or 3×3), orientation
//! (quaternion or 3×3), joint coordinates (a scalar or a list). Each keeps the spelling it was
//! read with, so a spec serialises back the way it was written.

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::fmt;

use crate::math::Mat3;

/// Inertia tensor about the centre of mass, body axes, kg·m².
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum InertiaSpec {
    /// `[Ixx, Iyy, Izz]`: principal axes along the body axes.
    Diagonal([f64; 3]),
    /// `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` (the products are the tensor's off-diagonal entries).
    Full([f64; 6]),
    /// The full symmetric 3×3 matrix, row by row.
    Matrix([[f64; 3]; 3]),
}

impl InertiaSpec {
    /// Every number written, for finiteness checks.
    #[must_use]
    pub fn numbers(&self) -> Vec<f64> {
        match self {
            Self::Diagonal(a) => a.to_vec(),
            Self::Full(a) => a.to_vec(),
            Self::Matrix(m) => m.iter().flatten().copied().collect(),
        }
    }

    /// The tensor as a matrix (the 3×3 form as written, possibly unsymmetric).
    #[must_use]
    pub fn matrix(&self) -> Mat3 {
        match self {
            Self::Diagonal([a, b, c]) => Mat3::new(*a, 0.0, 0.0, 0.0, *b, 0.0, 0.0, 0.0, *c),
            Self::Full([xx, yy, zz, xy, xz, yz]) => {
                Mat3::new(*xx, *xy, *xz, *xy, *yy, *yz, *xz, *yz, *zz)
            }
            Self::Matrix(m) => rows_to_matrix(m),
        }
    }
}

/// Orientation world ← body of a free body.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum OrientationSpec {
    /// Unit quaternion `[w, x, y, z]` (normalised when lowered).
    Quat([f64; 4]),
    /// Rotation matrix, row by row (its columns are the body axes in world coordinates).
    Matrix([[f64; 3]; 3]),
}

impl OrientationSpec {
    /// Every number written, for finiteness checks.
    #[must_use]
    pub fn numbers(&self) -> Vec<f64> {
        match self {
            Self::Quat(q) => q.to_vec(),
            Self::Matrix(m) => m.iter().flatten().copied().collect(),
        }
    }
}

/// Joint coordinates or rates: a bare number for one-coordinate joints, else a list.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Coords {
    /// One value.
    Scalar(f64),
    /// One value per coordinate.
    List(Vec<f64>),
}

impl Coords {
    /// The values as a list.
    #[must_use]
    pub fn values(&self) -> Vec<f64> {
        match self {
            Self::Scalar(x) => vec![*x],
            Self::List(v) => v.clone(),
        }
    }
}

/// A 3×3 matrix from rows.
#[must_use]
pub fn rows_to_matrix(m: &[[f64; 3]; 3]) -> Mat3 {
    Mat3::new(
        m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
    )
}

/// A number, a flat list of numbers, or a list of rows, as read (before the shape is checked).
enum Raw {
    Number(f64),
    Flat(Vec<f64>),
    Rows(Vec<Vec<f64>>),
}

struct RawVisitor;

impl<'de> Visitor<'de> for RawVisitor {
    type Value = Raw;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or an array of numbers")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Raw, E> {
        Ok(Raw::Number(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Raw, E> {
        Ok(Raw::Number(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Raw, E> {
        Ok(Raw::Number(v as f64))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Raw, A::Error> {
        let mut items: Vec<Raw> = Vec::new();
        while let Some(item) = seq.next_element_seed(ElementSeed)? {
            items.push(item);
        }
        if items.iter().all(|r| matches!(r, Raw::Number(_))) {
            Ok(Raw::Flat(
                items
                    .into_iter()
                    .filter_map(|r| {
                        if let Raw::Number(x) = r {
                            Some(x)
                        } else {
                            None
                        }
                    })
                    .collect(),
            ))
        } else {
            let mut rows = Vec::new();
            for r in items {
                match r {
                    Raw::Flat(v) => rows.push(v),
                    _ => return Err(de::Error::custom("mixes numbers and arrays")),
                }
            }
            Ok(Raw::Rows(rows))
        }
    }
}

struct ElementSeed;

impl<'de> de::DeserializeSeed<'de> for ElementSeed {
    type Value = Raw;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Raw, D::Error> {
        d.deserialize_any(RawVisitor)
    }
}

fn rows3<E: de::Error>(rows: &[Vec<f64>], what: &str) -> Result<[[f64; 3]; 3], E> {
    if rows.len() != 3 || rows.iter().any(|r| r.len() != 3) {
        let shape: Vec<String> = rows.iter().map(|r| r.len().to_string()).collect();
        return Err(E::custom(format!(
            "{what}: a 3x3 array needs 3 rows of 3 numbers, found rows of [{}] numbers",
            shape.join(", ")
        )));
    }
    Ok([
        [rows[0][0], rows[0][1], rows[0][2]],
        [rows[1][0], rows[1][1], rows[1][2]],
        [rows[2][0], rows[2][1], rows[2][2]],
    ])
}

impl<'de> Deserialize<'de> for InertiaSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        const HINT: &str =
            "expected [Ixx, Iyy, Izz], [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] or a 3x3 array";
        match d.deserialize_any(RawVisitor)? {
            Raw::Flat(v) if v.len() == 3 => Ok(Self::Diagonal([v[0], v[1], v[2]])),
            Raw::Flat(v) if v.len() == 6 => Ok(Self::Full([v[0], v[1], v[2], v[3], v[4], v[5]])),
            Raw::Flat(v) => Err(de::Error::custom(format!(
                "{HINT}, found {} numbers",
                v.len()
            ))),
            Raw::Rows(r) => rows3(&r, HINT).map(Self::Matrix),
            Raw::Number(_) => Err(de::Error::custom(format!("{HINT}, found a single number"))),
        }
    }
}

impl<'de> Deserialize<'de> for OrientationSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        const HINT: &str = "expected a quaternion [w, x, y, z] or a 3x3 rotation matrix";
        match d.deserialize_any(RawVisitor)? {
            Raw::Flat(v) if v.len() == 4 => Ok(Self::Quat([v[0], v[1], v[2], v[3]])),
            Raw::Flat(v) => Err(de::Error::custom(format!(
                "{HINT}, found {} numbers",
                v.len()
            ))),
            Raw::Rows(r) => rows3(&r, HINT).map(Self::Matrix),
            Raw::Number(_) => Err(de::Error::custom(format!("{HINT}, found a single number"))),
        }
    }
}

impl<'de> Deserialize<'de> for Coords {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match d.deserialize_any(RawVisitor)? {
            Raw::Number(x) => Ok(Self::Scalar(x)),
            Raw::Flat(v) => Ok(Self::List(v)),
            Raw::Rows(_) => Err(de::Error::custom(
                "expected a number or a list of numbers, found nested arrays",
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inertia_spellings() {
        let d: InertiaSpec = serde_json::from_str("[1, 2, 3]").unwrap();
        assert_eq!(d, InertiaSpec::Diagonal([1.0, 2.0, 3.0]));
        let f: InertiaSpec = serde_json::from_str("[1, 2, 3, 0.1, 0.2, 0.3]").unwrap();
        assert_eq!(f.matrix()[(0, 2)], 0.2);
        let m: InertiaSpec = serde_json::from_str("[[1,0,0],[0,2,0],[0,0,3]]").unwrap();
        assert_eq!(m.matrix(), d.matrix());
        let e = serde_json::from_str::<InertiaSpec>("[1, 2]")
            .unwrap_err()
            .to_string();
        assert!(e.contains("found 2 numbers"), "{e}");
    }

    #[test]
    fn coords_scalar_or_list() {
        assert_eq!(
            serde_json::from_str::<Coords>("2").unwrap(),
            Coords::Scalar(2.0)
        );
        assert_eq!(
            serde_json::from_str::<Coords>("[1, 2.5]").unwrap().values(),
            vec![1.0, 2.5]
        );
        let t: toml::Value = toml::from_str("q = [1, 2]").unwrap();
        let c: Coords = t["q"].clone().try_into().unwrap();
        assert_eq!(c, Coords::List(vec![1.0, 2.0]));
    }
}

/// `solver.order`: an integer, also accepted as an integral float (`2.0`) since JSON writers
/// often produce those.
pub(crate) fn order<'de, D: Deserializer<'de>>(d: D) -> Result<u8, D::Error> {
    match d.deserialize_any(RawVisitor)? {
        Raw::Number(x) if x.fract() == 0.0 && (0.0..=255.0).contains(&x) => Ok(x as u8),
        Raw::Number(x) => Err(de::Error::custom(format!("expected 2 or 4, found {x}"))),
        _ => Err(de::Error::custom("expected 2 or 4, found an array")),
    }
}

/// Wrapper used by the structural pass to check `solver.order` on its own (the value itself is
/// read with the whole spec).
#[derive(Deserialize)]
pub(crate) struct Order(
    #[serde(deserialize_with = "order")]
    #[allow(dead_code)]
    u8,
);
