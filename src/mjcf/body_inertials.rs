//! The MuJoCo bodies' inertials as the compiler makes them (given, or from the geoms for
//! `inertiafromgeom`; then `boundmass`, `boundinertia`, `settotalmass`); `lower` adds each to
//! the triad body that carries its MuJoCo body, in that body's frame.

use super::model::{FromGeom, Model, Shape};
use crate::import::inertia::{merge, Part};
use crate::math::{Mat3, Vec3};
use crate::spec::Problem;

/// The MuJoCo body's mass, centre of mass and inertia (body frame), as the compiler makes them.
fn body_part(m: &Model, i: usize, problems: &mut Vec<Problem>) -> Part {
    let b = &m.bodies[i];
    let from_geoms = match m.compiler.from_geom {
        FromGeom::Always => true,
        FromGeom::Never => false,
        FromGeom::Auto => b.inertial.is_none(),
    };
    let (mass, com, j) = if from_geoms {
        let mut parts = Vec::new();
        for g in &b.geoms {
            match &g.shape {
                Shape::Solid(s) => {
                    let v = s.volume();
                    let mass = g.mass.unwrap_or(g.density * v);
                    let j = s.inertia(mass);
                    parts.push((mass, g.frame.p, g.frame.r * j * g.frame.r.transpose()));
                }
                Shape::Plane => problems.push(Problem::new(
                    g.at.clone(),
                    "a plane geom belongs in <worldbody> (it has no volume to give a body mass)",
                )),
                Shape::Other(kind) if g.mass != Some(0.0) && g.density != 0.0 => {
                    problems.push(Problem::new(
                        g.at.clone(),
                        format!(
                            "the body's inertia would come from this {kind} geom, which triad cannot compute: give the body an <inertial> (or the geom mass=\"0\")"
                        ),
                    ));
                }
                Shape::Other(_) => {}
            }
        }
        merge(&parts)
    } else {
        b.inertial.map_or((0.0, Vec3::zeros(), Mat3::zeros()), |i| {
            (i.mass, i.com, i.inertia)
        })
    };
    // the compiler's lower bounds: on the mass, and on the principal moments
    let mass = mass.max(m.compiler.boundmass);
    let j = if m.compiler.boundinertia > 0.0 {
        let e = j.symmetric_eigen();
        let d = Mat3::from_diagonal(&e.eigenvalues.map(|x| x.max(m.compiler.boundinertia)));
        e.eigenvectors * d * e.eigenvectors.transpose()
    } else {
        j
    };
    (mass, com, j)
}

/// Every MuJoCo body's own inertial (the world's zero), scaled to `settotalmass` when given.
pub(super) fn own_parts(m: &Model, problems: &mut Vec<Problem>) -> Vec<Part> {
    let mut own: Vec<Part> = (0..m.bodies.len())
        .map(|i| {
            if i == 0 {
                (0.0, Vec3::zeros(), Mat3::zeros())
            } else {
                body_part(m, i, problems)
            }
        })
        .collect();
    if let Some(total) = m.compiler.settotalmass {
        let sum: f64 = own.iter().map(|p| p.0).sum();
        if sum > 0.0 {
            let s = total / sum;
            for p in &mut own {
                p.0 *= s;
                p.2 *= s;
            }
        }
    }
    own
}
