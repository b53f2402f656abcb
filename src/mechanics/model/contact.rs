//! Contact geometry at run time: the collision shapes turned into ground points and body–body
//! features whose gaps are functions of quadratic invariants, so that their forces are exact,
//! momentum-preserving discrete gradients (the laws are `contact_law`'s).
//!
//! **The ground** is the plane `n·x = h₀` (`n` against gravity). A shape touches it through
//! points `X` fixed in its body (relative to the centre of mass), each with a radius `r`: a
//! sphere its centre (r), a capsule its two segment ends (r), a box its eight corners, a
//! cylinder 12 points on each rim (a 12-sided prism: rolling on the ground is not smooth).
//! A point's gap is linear in the coordinates,
//!
//! ```text
//! g(q) = n·(φ + Σᵢ Xᵢ dᵢ) − h₀ − r,      Δg = n·Δx  exactly,
//! ```
//!
//! so the normal force `f n` at the point (through a sphere's centre) does exactly `f Δg`.
//! Friction acts at the contact point `φ + Σ Xᵢ dᵢ − r n`, as a material point of the body
//! fixed over the step (`X_c = X − r D̄ᵀn`): its work is the force times that point's
//! displacement, exactly.
//!
//! **Body–body features** (shape pairs, opt-in) measure the distance of two bodies' shapes by
//! invariants `π_k = u_k·w_k`, each a [`DotRow`] over the two bodies' nodes (dot products of
//! differences of material points and body axes; invariant under rigid motions of the pair):
//!
//! | feature | invariants | distance |
//! |---|---|---|
//! | sphere–sphere | `|c_a − c_b|²` | `√π₀` |
//! | point–segment (sphere–capsule) | `|c − m|²`, `(c − m)·v` (`m` the segment's centre, `v` its span) | to the nearest point `m + t v`, `t` clamped to `[−½, ½]` |
//! | segment–segment (capsule–capsule) | `u·v, u·w, v·w, w·w` (`u, v` the segments, `w = c_a − c_b` their centres) | nearest points `c + s u`, clamped to `[−½, ½]` (Ericson) |
//! | point–box (sphere–box, box corners, capsule ends) | `e_i·(c − o)`, the point in the box's axes | to the box; inside: minus the depth to the nearest face |
//!
//! The gap `G(π) − r_a − r_b` takes the discrete gradient of sequential difference quotients,
//! symmetrised over the two orders of the invariants:
//!
//! ```text
//! ΔG = Σ_k Q_k Δπ_k,   Q_k = [G(…π_k¹, π_{k+1}⁰…) − G(…π_k⁰, π_{k+1}⁰…)] / Δπ_k,
//! Δπ_k = ∇π_k(q̄)·Δq                      (exact: π_k is quadratic)
//! ```
//!
//! so the force `f Σ Q_k ∇π_k(q̄)` does exactly `f ΔG` of work, and since every `∇π_k(q̄)` is
//! the gradient of an invariant its forces and moments on the two bodies cancel: linear and
//! angular momentum are exact. (Below `|Δπ_k| ≤ 1e-8 π_scale²` the quotient is replaced by the
//! derivative at the mean, whose error is of third order in `Δπ_k`; the derivative is exact,
//! `∂G/∂π_k = (∂d²/∂π_k)/(2G)` at the nearest parameters held, since they minimise `d²`.)
//!
//! **Symmetry.** Segments and points are measured from the shapes' centres: a mirror symmetry of
//! the pair (a capsule dropped square across another, a sphere onto a capsule's middle) maps
//! each invariant to itself or to its negative, and `G` is even in the negated ones, bit for bit
//! (`s`, `t` change sign exactly; every term of `d²` is a product of an even number of them).
//! So where a symmetric motion keeps an odd invariant at 0 its quotient is the exact derivative
//! there, `2s = 0`: no sideways force, no moment. (Measured from a segment's end, the same
//! invariants mix a secant along `w·w` with a derivative along `u·w`, and their `O(Δπ²)`
//! mismatch kicked a symmetric impact sideways.) Friction between bodies
//! acts at one point, the middle of the nearest points at the midpoint configuration, as a
//! material point of each body fixed over the step, so its two forces have no moment either.
//! Not modelled: a box's edges crossing another box's edges or faces (box–box touches through
//! the corners of each against the other), the middle of a capsule against a box (its ends
//! only), and cylinders against other shapes (they touch the ground only).

use super::constraint::{body_nodes, DotRow, LinVec, Nodes};
use super::def::{ContactDef, ContactLaw, ModelDef, ShapeKind, SolverSettings};
use super::one_sided::energy;
use crate::math::{Mat3, Vec3};

/// Points on each rim of a cylinder touching the ground.
pub(crate) const RIM_POINTS: usize = 12;

/// A point of a shape that touches the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GroundPoint {
    /// The shape (index into `ContactDef::shapes`).
    pub shape: usize,
    /// Its body.
    pub body: usize,
    /// The point, body axes, relative to the centre of mass, m.
    pub x: Vec3,
    /// Its radius (sphere, capsule end) or 0 (corners), m.
    pub radius: f64,
    /// The laws.
    pub law: ContactLaw,
}

/// The ground at run time.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct GroundRt {
    /// Unit normal, world frame (against gravity).
    pub normal: Vec3,
    /// Height along the normal, m.
    pub height: f64,
    /// The touching points of every shape.
    pub points: Vec<GroundPoint>,
}

/// How a body–body feature measures its distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Measure {
    /// Sphere centres: invariant `|c_a − c_b|²`.
    Spheres,
    /// A point of A and a segment of B (centre and span) of squared length `l2`.
    PointSegment {
        /// `|p₁ − p₀|²`, m².
        l2: f64,
    },
    /// Segments of A and B (centres and spans) of squared lengths `la2`, `lb2`.
    Segments {
        /// `|a₁ − a₀|²`, m².
        la2: f64,
        /// `|b₁ − b₀|²`, m².
        lb2: f64,
    },
    /// A point of A and a box of B with half edges `half`.
    PointBox {
        /// Half edge lengths, m.
        half: Vec3,
    },
}

/// A body–body contact feature.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Feature {
    /// The shapes (indices into `ContactDef::shapes`): `a` on body `a`, `b` on body `b`.
    pub shapes: (usize, usize),
    /// The bodies (A, B of the rows).
    pub bodies: (usize, usize),
    /// What the invariants measure.
    pub measure: Measure,
    /// The invariants (1 to 4 used), rows over A's and B's nodes.
    pub rows: [DotRow; 4],
    /// How many rows are used.
    pub nrows: usize,
    /// Material points and axes of A and B that locate the nearest points (see
    /// [`Feature::nearest`]): sphere centre; a segment's centre and span; a point and a box's
    /// centre on B.
    pub pts: [LinVec; 4],
    /// Sum of the radii, m.
    pub radii: f64,
    /// The radius of A's side (a sphere, a capsule's), m.
    pub radius_a: f64,
    /// Scale of the invariants (a length, m).
    pub scale: f64,
    /// The laws.
    pub law: ContactLaw,
}

/// Contact at run time.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ContactRt {
    /// The ground, if the model has one.
    pub ground: Option<GroundRt>,
    /// Body–body features.
    pub features: Vec<Feature>,
}

impl ContactRt {
    /// Number of bristles (ground points, then features): 3 numbers each in the state.
    #[must_use]
    pub fn bristles(&self) -> usize {
        self.ground.as_ref().map_or(0, |g| g.points.len()) + self.features.len()
    }

    /// Whether there is any contact at all.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bristles() == 0
    }
}

/// A shape's frame relative to its body's centre of mass: `(origin, rotation)`, body axes.
fn placed(def: &ModelDef, s: usize) -> (usize, Vec3, Mat3) {
    let shape = &def.contact.shapes[s];
    let body = &def.bodies[shape.body];
    (
        shape.body,
        shape.frame.translation - body.com,
        shape.frame.rotation,
    )
}

/// The ground points of shape `s`: `(point relative to the centre of mass, radius)`.
fn shape_points(def: &ModelDef, s: usize) -> Vec<(Vec3, f64)> {
    let (_, o, r) = placed(def, s);
    let at = |p: Vec3| o + r * p;
    match def.contact.shapes[s].kind {
        ShapeKind::Sphere { radius } => vec![(o, radius)],
        ShapeKind::Capsule { radius, length } => vec![
            (at(Vec3::new(0.0, 0.0, -0.5 * length)), radius),
            (at(Vec3::new(0.0, 0.0, 0.5 * length)), radius),
        ],
        ShapeKind::Cuboid { size } => {
            let h = size * 0.5;
            (0..8)
                .map(|k| {
                    let sx = if k & 1 == 0 { -1.0 } else { 1.0 };
                    let sy = if k & 2 == 0 { -1.0 } else { 1.0 };
                    let sz = if k & 4 == 0 { -1.0 } else { 1.0 };
                    (at(Vec3::new(sx * h.x, sy * h.y, sz * h.z)), 0.0)
                })
                .collect()
        }
        ShapeKind::Cylinder { radius, length } => {
            let mut v = Vec::with_capacity(2 * RIM_POINTS);
            for z in [-0.5 * length, 0.5 * length] {
                for k in 0..RIM_POINTS {
                    let a = std::f64::consts::TAU * k as f64 / RIM_POINTS as f64;
                    v.push((at(Vec3::new(radius * a.cos(), radius * a.sin(), z)), 0.0));
                }
            }
            v
        }
    }
}

/// The ground's unit normal for `gravity`: against it, or `+z` without gravity.
#[must_use]
pub fn ground_normal(gravity: &Vec3) -> Vec3 {
    let n = gravity.norm();
    if n > 0.0 && n.is_finite() {
        -gravity / n
    } else {
        Vec3::z()
    }
}

/// `|u|²` as a row over A and B.
fn square(u: LinVec) -> DotRow {
    DotRow::new(u, u, 0.0)
}

/// The features of the pair of shapes `(sa, sb)` (ordered as the measures need: a sphere or
/// point first; box on B).
fn features(def: &ModelDef, c: &ContactDef, sa: usize, sb: usize, out: &mut Vec<Feature>) {
    let law = pair_law(c, sa, sb);
    let kinds = (c.shapes[sa].kind, c.shapes[sb].kind);
    // spheres and capsules of a shape as (points on its body, radius)
    let ends = |s: usize| -> Option<(Vec<Vec3>, f64)> {
        let (_, o, r) = placed(def, s);
        match c.shapes[s].kind {
            ShapeKind::Sphere { radius } => Some((vec![o], radius)),
            ShapeKind::Capsule { radius, length } => Some((
                vec![
                    o + r * Vec3::new(0.0, 0.0, -0.5 * length),
                    o + r * Vec3::new(0.0, 0.0, 0.5 * length),
                ],
                radius,
            )),
            _ => None,
        }
    };
    let (ba, bb) = (c.shapes[sa].body, c.shapes[sb].body);
    let push = |out: &mut Vec<Feature>,
                shapes: (usize, usize),
                bodies: (usize, usize),
                measure: Measure,
                rows: &[DotRow],
                pts: &[LinVec],
                (radius_a, radii): (f64, f64),
                scale: f64| {
        let mut r = [DotRow::new(LinVec::default(), LinVec::default(), 0.0); 4];
        r[..rows.len()].copy_from_slice(rows);
        let mut p = [LinVec::default(); 4];
        p[..pts.len()].copy_from_slice(pts);
        out.push(Feature {
            shapes,
            bodies,
            measure,
            rows: r,
            nrows: rows.len(),
            pts: p,
            radii,
            radius_a,
            scale,
            law,
        });
    };
    match kinds {
        (ShapeKind::Cuboid { .. }, ShapeKind::Sphere { .. } | ShapeKind::Capsule { .. })
        | (ShapeKind::Capsule { .. }, ShapeKind::Sphere { .. }) => {
            features(def, c, sb, sa, out);
        }
        (ShapeKind::Sphere { .. }, ShapeKind::Sphere { .. }) => {
            let (pa, ra) = ends(sa).expect("sphere");
            let (pb, rb) = ends(sb).expect("sphere");
            let (ca, cb) = (LinVec::point_a(&pa[0]), LinVec::point_b(&pb[0]));
            let rows = [square(ca.sub(&cb))];
            push(
                out,
                (sa, sb),
                (ba, bb),
                Measure::Spheres,
                &rows,
                &[ca, cb],
                (ra, ra + rb),
                ra + rb,
            );
        }
        (ShapeKind::Sphere { .. } | ShapeKind::Capsule { .. }, ShapeKind::Capsule { .. }) => {
            let (pa, ra) = ends(sa).expect("sphere or capsule");
            let (pb, rb) = ends(sb).expect("capsule");
            // centre and span of B's segment (module docs: "Symmetry")
            let cb = LinVec::point_b(&(0.5 * (pb[0] + pb[1])));
            let v = LinVec::axis_b(&(pb[1] - pb[0]));
            let lb2 = (pb[1] - pb[0]).norm_squared();
            if pa.len() == 1 {
                let cpt = LinVec::point_a(&pa[0]);
                let w = cpt.sub(&cb);
                let rows = [square(w), DotRow::new(w, v, 0.0)];
                let scale = lb2.sqrt() + ra + rb;
                let m = Measure::PointSegment { l2: lb2 };
                push(
                    out,
                    (sa, sb),
                    (ba, bb),
                    m,
                    &rows,
                    &[cpt, cb, v],
                    (ra, ra + rb),
                    scale,
                );
            } else {
                let ca = LinVec::point_a(&(0.5 * (pa[0] + pa[1])));
                let u = LinVec::axis_a(&(pa[1] - pa[0]));
                let w = ca.sub(&cb);
                let la2 = (pa[1] - pa[0]).norm_squared();
                let rows = [
                    DotRow::new(u, v, 0.0),
                    DotRow::new(u, w, 0.0),
                    DotRow::new(v, w, 0.0),
                    square(w),
                ];
                let scale = la2.sqrt() + lb2.sqrt() + ra + rb;
                let m = Measure::Segments { la2, lb2 };
                push(
                    out,
                    (sa, sb),
                    (ba, bb),
                    m,
                    &rows,
                    &[ca, u, cb, v],
                    (ra, ra + rb),
                    scale,
                );
            }
        }
        (
            ShapeKind::Sphere { .. } | ShapeKind::Capsule { .. } | ShapeKind::Cuboid { .. },
            ShapeKind::Cuboid { size },
        ) => {
            // every point of A (sphere centre, capsule ends, box corners) against box B
            let points: Vec<(Vec3, f64)> = match ends(sa) {
                Some((p, r)) => p.into_iter().map(|x| (x, r)).collect(),
                None => shape_points(def, sa),
            };
            let (_, ob, rb) = placed(def, sb);
            let centre = LinVec::point_b(&ob);
            let axes: [LinVec; 3] = std::array::from_fn(|i| {
                let e = rb.column(i).into_owned();
                LinVec::axis_b(&e)
            });
            let half = size * 0.5;
            for (x, r) in points {
                let p = LinVec::point_a(&x);
                let rel = p.sub(&centre);
                let rows = [
                    DotRow::new(axes[0], rel, 0.0),
                    DotRow::new(axes[1], rel, 0.0),
                    DotRow::new(axes[2], rel, 0.0),
                ];
                let m = Measure::PointBox { half };
                let scale = half.norm() + r;
                push(
                    out,
                    (sa, sb),
                    (ba, bb),
                    m,
                    &rows,
                    &[p, centre],
                    (r, r),
                    scale,
                );
            }
            if let ShapeKind::Cuboid { size: a_size } = kinds.0 {
                // and B's corners against box A (the corner's body in the rows' A slot)
                let (_, oa, ra) = placed(def, sa);
                let centre = LinVec::point_b(&oa);
                let axes: [LinVec; 3] = std::array::from_fn(|i| {
                    let e = ra.column(i).into_owned();
                    LinVec::axis_b(&e)
                });
                let half = a_size * 0.5;
                for (x, _) in shape_points(def, sb) {
                    let p = LinVec::point_a(&x);
                    let rel = p.sub(&centre);
                    let rows = [
                        DotRow::new(axes[0], rel, 0.0),
                        DotRow::new(axes[1], rel, 0.0),
                        DotRow::new(axes[2], rel, 0.0),
                    ];
                    let m = Measure::PointBox { half };
                    let scale = half.norm();
                    push(
                        out,
                        (sb, sa),
                        (bb, ba),
                        m,
                        &rows,
                        &[p, centre],
                        (0.0, 0.0),
                        scale,
                    );
                }
            }
        }
        _ => {}
    }
}

/// The laws of a pair: the larger friction (as MuJoCo does), the mean stiffness and damping.
fn pair_law(c: &ContactDef, sa: usize, sb: usize) -> ContactLaw {
    let (a, b) = (c.law(sa), c.law(sb));
    ContactLaw {
        friction: a.friction.max(b.friction),
        stiffness: 0.5 * (a.stiffness + b.stiffness),
        damping: 0.5 * (a.damping + b.damping),
    }
}

/// Whether a pair of shape kinds can touch (cylinders touch the ground only).
#[must_use]
pub fn pair_supported(a: &ShapeKind, b: &ShapeKind) -> bool {
    !matches!(a, ShapeKind::Cylinder { .. }) && !matches!(b, ShapeKind::Cylinder { .. })
}

/// Builds the run-time contact of `def`.
#[must_use]
pub(crate) fn build(def: &ModelDef) -> ContactRt {
    let c = &def.contact;
    let ground = c.ground.map(|g| GroundRt {
        normal: ground_normal(&def.gravity),
        height: g.height,
        points: (0..c.shapes.len())
            .flat_map(|s| {
                let law = c.law(s);
                let body = c.shapes[s].body;
                shape_points(def, s)
                    .into_iter()
                    .map(move |(x, radius)| GroundPoint {
                        shape: s,
                        body,
                        x,
                        radius,
                        law,
                    })
            })
            .collect(),
    });
    let mut feats = Vec::new();
    for &(sa, sb) in &c.pairs {
        features(def, c, sa, sb, &mut feats);
    }
    ContactRt {
        ground,
        features: feats,
    }
}

/// A warning when fixed steps (`rtol = 0`) do not resolve a contact: the period `2π√(m/k)` of
/// the lightest body that carries a shape (mass `m` > 0) on its law, against `max_step`, which
/// must keep `ω h ≤ 1` (`h ≤ √(m/k)`, a sixth of the period: the midpoint rule's phase error
/// stays below 10 %; it is stable at any step).
#[must_use]
pub(crate) fn period_note(def: &ModelDef, settings: &SolverSettings) -> Option<String> {
    let c = &def.contact;
    if settings.rtol > 0.0 || (c.ground.is_none() && c.pairs.is_empty()) {
        return None;
    }
    let (s, period) = (0..c.shapes.len())
        .filter(|&s| def.bodies[c.shapes[s].body].mass > 0.0)
        .map(|s| {
            let m = def.bodies[c.shapes[s].body].mass;
            (s, std::f64::consts::TAU * (m / c.law(s).stiffness).sqrt())
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let bound = period / std::f64::consts::TAU;
    (settings.max_step > bound).then(|| {
        let body = &def.bodies[c.shapes[s].body];
        format!(
            "warning: max_step = {} s does not resolve the contact of collision shape '{}' on \
             body '{}' (period 2π√(m/k) = {:.3e} s for m = {} kg, k = {:e} N/m): take max_step \
             ≤ √(m/k) = {:.1e} s, a softer contact, or error-controlled steps (solver.rtol)",
            settings.max_step,
            c.shapes[s].name,
            body.name,
            period,
            body.mass,
            c.law(s).stiffness,
            bound
        )
    })
}

/// Nodes of A and B of a feature.
#[must_use]
pub(crate) fn pair_nodes(q: &[f64], f: &Feature) -> (Nodes, Nodes) {
    (body_nodes(q, f.bodies.0), body_nodes(q, f.bodies.1))
}

impl Feature {
    /// The invariants at nodes `(qa, qb)`.
    #[must_use]
    pub fn invariants(&self, qa: &Nodes, qb: &Nodes) -> [f64; 4] {
        let mut p = [0.0; 4];
        for (v, row) in p.iter_mut().zip(&self.rows[..self.nrows]) {
            *v = row.eval(qa, qb);
        }
        p
    }

    /// The distance (signed for a point inside a box) of the invariants `p`, before radii.
    #[must_use]
    pub fn distance(&self, p: &[f64; 4]) -> f64 {
        match self.measure {
            Measure::Spheres => p[0].max(0.0).sqrt(),
            Measure::PointSegment { l2 } => point_segment_d2(l2, p).0.max(0.0).sqrt(),
            Measure::Segments { la2, lb2 } => segments_d2(la2, lb2, p).0.max(0.0).sqrt(),
            Measure::PointBox { half } => match box_side(&half, &Vec3::new(p[0], p[1], p[2])) {
                BoxSide::Outside(o) => o.norm(),
                BoxSide::Inside(_, depth) => -depth,
            },
        }
    }

    /// The gap `distance − radii` of invariants `p`, m.
    #[must_use]
    pub fn gap(&self, p: &[f64; 4]) -> f64 {
        self.distance(p) - self.radii
    }

    /// The derivatives `∂G/∂π_k` of the distance at invariants `p` (module docs), exact: the
    /// nearest parameters minimise `d²`, so they are held. Zero where the distance is not
    /// differentiable (zero distance between spheres or to a segment).
    #[must_use]
    pub fn distance_gradient(&self, p: &[f64; 4]) -> [f64; 4] {
        // ∂√d² = ∂d² / (2√d²)
        let root = |d2: f64, g: [f64; 4]| -> [f64; 4] {
            let d = d2.max(0.0).sqrt();
            if d > 0.0 {
                g.map(|x| x / (2.0 * d))
            } else {
                [0.0; 4]
            }
        };
        match self.measure {
            Measure::Spheres => root(p[0], [1.0, 0.0, 0.0, 0.0]),
            Measure::PointSegment { l2 } => {
                let (d2, t) = point_segment_d2(l2, p);
                root(d2, [1.0, -2.0 * t, 0.0, 0.0])
            }
            Measure::Segments { la2, lb2 } => {
                let (d2, (s, t)) = segments_d2(la2, lb2, p);
                root(d2, [-2.0 * s * t, 2.0 * s, -2.0 * t, 1.0])
            }
            Measure::PointBox { half } => {
                let xi = Vec3::new(p[0], p[1], p[2]);
                match box_side(&half, &xi) {
                    BoxSide::Outside(o) => {
                        let g = o / o.norm();
                        [g.x, g.y, g.z, 0.0]
                    }
                    // inside: minus the depth below the nearest face
                    BoxSide::Inside(i, _) => {
                        let mut g = [0.0; 4];
                        g[i] = if xi[i] < 0.0 { -1.0 } else { 1.0 };
                        g
                    }
                }
            }
        }
    }

    /// The discrete gradient of the gap in the invariants from `p0` to `p1` (module formulas),
    /// symmetrised over the two orders.
    #[must_use]
    pub fn gap_quotients(&self, p0: &[f64; 4], p1: &[f64; 4]) -> [f64; 4] {
        let n = self.nrows;
        let mut q = [0.0; 4];
        for order in [false, true] {
            let mut cur = *p0;
            for step in 0..n {
                let k = if order { n - 1 - step } else { step };
                let dp = p1[k] - p0[k];
                let tiny = 1e-8 * self.scale * self.scale;
                let value = if dp.abs() > tiny {
                    let before = self.gap(&cur);
                    cur[k] = p1[k];
                    (self.gap(&cur) - before) / dp
                } else {
                    // the derivative at the mean
                    let mut mid = cur;
                    mid[k] = 0.5 * (p0[k] + p1[k]);
                    cur[k] = p1[k];
                    self.distance_gradient(&mid)[k]
                };
                q[k] += 0.5 * value;
            }
        }
        q
    }

    /// The nearest points `(on A, on B)` and the unit normal from A to B at nodes `(qa, qb)`
    /// (world frame; the radii not applied).
    #[must_use]
    pub fn nearest(&self, qa: &Nodes, qb: &Nodes) -> (Vec3, Vec3, Vec3) {
        let pt = |k: usize| self.pts[k].eval(qa, qb);
        let (pa, pb, fallback) = match self.measure {
            Measure::Spheres => (pt(0), pt(1), Vec3::z()),
            Measure::PointSegment { l2 } => {
                let (c, m, v) = (pt(0), pt(1), pt(2));
                let t = point_param(l2, (c - m).dot(&v));
                (c, m + v * t, Vec3::z())
            }
            Measure::Segments { la2, lb2 } => {
                let (ca, u, cb, v) = (pt(0), pt(1), pt(2), pt(3));
                let w = ca - cb;
                let (s, t) = segment_params(la2, lb2, u.dot(&v), u.dot(&w), v.dot(&w));
                let fallback = u.cross(&v);
                (ca + u * s, cb + v * t, fallback)
            }
            Measure::PointBox { half } => {
                let p = self.invariants(qa, qb);
                let xi = Vec3::new(p[0], p[1], p[2]);
                let (c, o) = (pt(0), pt(1));
                let axes = [
                    self.rows[0].u.eval(qa, qb),
                    self.rows[1].u.eval(qa, qb),
                    self.rows[2].u.eval(qa, qb),
                ];
                let world = |v: Vec3| axes[0] * v.x + axes[1] * v.y + axes[2] * v.z;
                match box_side(&half, &xi) {
                    BoxSide::Outside(off) => (c, o + world(xi - off), Vec3::z()),
                    BoxSide::Inside(i, _) => {
                        // inside: out through the nearest face
                        let mut face = xi;
                        face[i] = half[i] * xi[i].signum();
                        let pb = o + world(face);
                        let mut e = Vec3::zeros();
                        e[i] = -xi[i].signum();
                        let n = world(e);
                        let n = n / n.norm().max(1e-300);
                        return (c, pb, n);
                    }
                }
            }
        };
        let d = pb - pa;
        let n = if d.norm() > 1e-12 * self.scale {
            d / d.norm()
        } else if fallback.norm() > 0.0 {
            fallback / fallback.norm()
        } else {
            Vec3::z()
        };
        (pa, pb, n)
    }
}

/// Where a point `xi` (box axes, relative to the centre) lies against a box of half edges
/// `half`.
enum BoxSide {
    /// Outside: the point less the nearest point of the box (not zero).
    Outside(Vec3),
    /// Inside or on the surface: the axis of the nearest face and the depth below it (≥ 0).
    Inside(usize, f64),
}

/// Where `xi` lies against the box of half edges `half` ([`BoxSide`]).
fn box_side(half: &Vec3, xi: &Vec3) -> BoxSide {
    let clamped = Vec3::new(
        xi.x.clamp(-half.x, half.x),
        xi.y.clamp(-half.y, half.y),
        xi.z.clamp(-half.z, half.z),
    );
    let out = xi - clamped;
    if out.norm() > 0.0 {
        return BoxSide::Outside(out);
    }
    let i = (0..3)
        .min_by(|&a, &b| (half[a] - xi[a].abs()).total_cmp(&(half[b] - xi[b].abs())))
        .unwrap_or(0);
    BoxSide::Inside(i, half[i] - xi[i].abs())
}

/// The nearest parameter `t ∈ [−½, ½]` on a segment `m + t v` (`|v|² = l2`) of a point `c`,
/// from `(c − m)·v`; odd in it, exactly.
fn point_param(l2: f64, cv: f64) -> f64 {
    if l2 > 0.0 {
        (cv / l2).clamp(-0.5, 0.5)
    } else {
        0.0
    }
}

/// `(d², t)` of a point and a segment from the invariants `p = [|c − m|², (c − m)·v]`.
fn point_segment_d2(l2: f64, p: &[f64; 4]) -> (f64, f64) {
    let t = point_param(l2, p[1]);
    (p[0] - 2.0 * t * p[1] + t * t * l2, t)
}

/// `(d², (s, t))` of two segments from the invariants `p = [u·v, u·w, v·w, w·w]`.
fn segments_d2(la2: f64, lb2: f64, p: &[f64; 4]) -> (f64, (f64, f64)) {
    let (s, t) = segment_params(la2, lb2, p[0], p[1], p[2]);
    let d2 =
        p[3] + s * s * la2 + t * t * lb2 - 2.0 * s * t * p[0] + 2.0 * s * p[1] - 2.0 * t * p[2];
    (d2, (s, t))
}

/// Ericson's nearest parameters `(s, t) ∈ [−½, ½]²` of segments `c_a + s u`, `c_b + t v` from
/// `|u|² = la2`, `|v|² = lb2`, `b = u·v`, `c = u·w`, `f = v·w` (`w = c_a − c_b`). Odd in
/// `(b, c)` for `s` and in `(b, f)` for `t`, bit for bit (module docs: "Symmetry").
#[must_use]
pub(crate) fn segment_params(la2: f64, lb2: f64, b: f64, c: f64, f: f64) -> (f64, f64) {
    let denom = la2 * lb2 - b * b;
    let mut s = if denom > 1e-12 * la2 * lb2 {
        ((b * f - c * lb2) / denom).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    let mut t = if lb2 > 0.0 { (b * s + f) / lb2 } else { 0.0 };
    if t < -0.5 {
        t = -0.5;
        s = if la2 > 0.0 {
            ((-0.5 * b - c) / la2).clamp(-0.5, 0.5)
        } else {
            0.0
        };
    } else if t > 0.5 {
        t = 0.5;
        s = if la2 > 0.0 {
            ((0.5 * b - c) / la2).clamp(-0.5, 0.5)
        } else {
            0.0
        };
    }
    (s, t)
}

/// The body-axes point `X` of body nodes `q` that lies at the world point `p`:
/// `φ + Σᵢ Xᵢ dᵢ = p` (a 3 × 3 solve; the directors' transpose if they are singular).
#[must_use]
pub(crate) fn material_point(q: &Nodes, p: &Vec3) -> Vec3 {
    let d = Mat3::from_columns(&[q[1], q[2], q[3]]);
    let r = p - q[0];
    d.try_inverse()
        .map_or_else(|| d.transpose() * r, |inv| inv * r)
}

/// What one collision shape reads at the current state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShapeContact {
    /// Total contact force on the shape's body through this shape (ground and other shapes),
    /// world frame, N: the spring and Hunt–Crossley damper at the current penetration and rate,
    /// and the friction bristle's force, within the cone.
    pub force: Vec3,
    /// Signed distance to the ground (negative: penetration), m; +∞ without a ground.
    pub gap: f64,
}

/// The state's contact forces and gaps per shape into `out` (len: the shapes), and the
/// contact's stored energy (springs and bristles), J. `q`, `v` per body (12 each), the
/// bristles as in the state.
#[must_use]
pub(crate) fn state_outputs(
    c: &ContactRt,
    q: &[f64],
    v: &[f64],
    bristle: &[f64],
    out: &mut [ShapeContact],
) -> f64 {
    for o in out.iter_mut() {
        *o = ShapeContact {
            force: Vec3::zeros(),
            gap: f64::INFINITY,
        };
    }
    let mut stored = 0.0;
    let bristle_at = |k: usize| Vec3::new(bristle[3 * k], bristle[3 * k + 1], bristle[3 * k + 2]);
    // normal and friction forces of a law at penetration x, rate xd, bristle s
    let forces = |law: &ContactLaw, x: f64, xd: f64, s: &Vec3, n: &Vec3| -> Vec3 {
        let f = if x > 0.0 {
            (law.stiffness * x * (1.0 + law.damping * xd)).max(0.0)
        } else {
            0.0
        };
        let spring = -s * law.stiffness;
        let cap = law.friction * f;
        let t = if spring.norm() > cap {
            spring * (cap / spring.norm())
        } else {
            spring
        };
        n * f + t
    };
    if let Some(g) = &c.ground {
        for (k, p) in g.points.iter().enumerate() {
            let (qb, vb) = (body_nodes(q, p.body), body_nodes(v, p.body));
            let x = qb[0] + qb[1] * p.x.x + qb[2] * p.x.y + qb[3] * p.x.z;
            let xd = vb[0] + vb[1] * p.x.x + vb[2] * p.x.y + vb[3] * p.x.z;
            let gap = g.normal.dot(&x) - g.height - p.radius;
            let s = bristle_at(k);
            let o = &mut out[p.shape];
            o.gap = o.gap.min(gap);
            o.force += forces(&p.law, -gap, -g.normal.dot(&xd), &s, &g.normal);
            stored += energy(p.law.stiffness, -gap) + 0.5 * p.law.stiffness * s.norm_squared();
        }
    }
    let off = c.ground.as_ref().map_or(0, |g| g.points.len());
    for (k, f) in c.features.iter().enumerate() {
        let (qa, qb) = pair_nodes(q, f);
        let (va, vb) = pair_nodes(v, f);
        let p = f.invariants(&qa, &qb);
        let gap = f.gap(&p);
        let s = bristle_at(off + k);
        if gap >= 0.0 && s == Vec3::zeros() {
            continue;
        }
        // the gap's rate: the invariants' rates through a central difference in time
        let e = 1e-7;
        let shift = |sign: f64| -> [f64; 4] {
            let na: Nodes = std::array::from_fn(|i| qa[i] + va[i] * (sign * e));
            let nb: Nodes = std::array::from_fn(|i| qb[i] + vb[i] * (sign * e));
            f.invariants(&na, &nb)
        };
        let rate = (f.gap(&shift(1.0)) - f.gap(&shift(-1.0))) / (2.0 * e);
        let (_, _, n) = f.nearest(&qa, &qb);
        let on_b = forces(&f.law, -gap, -rate, &s, &n);
        out[f.shapes.1].force += on_b;
        out[f.shapes.0].force -= on_b;
        stored += energy(f.law.stiffness, -gap) + 0.5 * f.law.stiffness * s.norm_squared();
    }
    stored
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::model::def::{BodyDef, Frame, ShapeDef};

    fn body(name: &str) -> BodyDef {
        BodyDef {
            name: name.into(),
            mass: 1.0,
            com: Vec3::new(0.1, 0.0, 0.0),
            inertia: Mat3::identity() * 0.01,
        }
    }

    fn shape(name: &str, body: usize, kind: ShapeKind, at: Vec3) -> ShapeDef {
        ShapeDef {
            name: name.into(),
            body,
            kind,
            frame: Frame {
                translation: at,
                rotation: crate::math::rpy_to_matrix(&Vec3::new(0.3, -0.2, 0.5)),
            },
            law: None,
        }
    }

    fn model(kinds: [ShapeKind; 2]) -> ModelDef {
        ModelDef {
            couplings: Vec::new(),
            actuators: Vec::new(),
            gravity: Vec3::new(0.0, 0.0, -9.81),
            bodies: vec![body("a"), body("b")],
            joints: Vec::new(),
            loads: Vec::new(),
            free_bodies: Vec::new(),
            sites: Vec::new(),
            contact: ContactDef {
                ground: None,
                shapes: vec![
                    shape("sa", 0, kinds[0], Vec3::new(0.0, 0.1, 0.0)),
                    shape("sb", 1, kinds[1], Vec3::new(0.05, 0.0, 0.02)),
                ],
                pairs: vec![(0, 1)],
            },
        }
    }

    /// Random body nodes: a rotation and a position.
    fn nodes_at(seed: u64) -> Nodes {
        let r = |k: u64| {
            (seed.wrapping_mul(2_654_435_761).wrapping_add(k * 97) % 1000) as f64 / 1000.0 - 0.5
        };
        let rot = crate::math::rpy_to_matrix(&Vec3::new(3.0 * r(1), 3.0 * r(2), 3.0 * r(3)));
        [
            Vec3::new(0.3 * r(4), 0.3 * r(5), 0.3 * r(6)),
            rot.column(0).into_owned(),
            rot.column(1).into_owned(),
            rot.column(2).into_owned(),
        ]
    }

    /// The invariants' distance equals the distance of the nearest points, for every feature
    /// kind, at many configurations.
    #[test]
    fn invariants_measure_the_nearest_points() {
        let kinds = [
            [
                ShapeKind::Sphere { radius: 0.05 },
                ShapeKind::Sphere { radius: 0.07 },
            ],
            [
                ShapeKind::Sphere { radius: 0.05 },
                ShapeKind::Capsule {
                    radius: 0.03,
                    length: 0.2,
                },
            ],
            [
                ShapeKind::Capsule {
                    radius: 0.02,
                    length: 0.3,
                },
                ShapeKind::Capsule {
                    radius: 0.03,
                    length: 0.2,
                },
            ],
            [
                ShapeKind::Sphere { radius: 0.05 },
                ShapeKind::Cuboid {
                    size: Vec3::new(0.2, 0.1, 0.3),
                },
            ],
        ];
        for k in kinds {
            let def = model(k);
            let rt = build(&def);
            assert!(!rt.features.is_empty());
            for seed in 0..200 {
                let (qa, qb) = (nodes_at(seed), nodes_at(seed + 1000));
                for f in &rt.features {
                    let (qa, qb) = if f.bodies.0 == 0 { (qa, qb) } else { (qb, qa) };
                    let d = f.distance(&f.invariants(&qa, &qb));
                    let (pa, pb, _) = f.nearest(&qa, &qb);
                    let want = (pb - pa).norm();
                    if d >= 0.0 {
                        assert!((d - want).abs() <= 1e-12, "{k:?} {seed}: {d} vs {want}");
                    }
                }
            }
        }
    }

    /// The quotients are an exact discrete gradient: `Σ Q_k Δπ_k = ΔG`.
    #[test]
    fn quotients_telescope() {
        let def = model([
            ShapeKind::Capsule {
                radius: 0.02,
                length: 0.3,
            },
            ShapeKind::Capsule {
                radius: 0.03,
                length: 0.2,
            },
        ]);
        let rt = build(&def);
        let f = &rt.features[0];
        for seed in 0..100 {
            let (qa0, qb0) = (nodes_at(seed), nodes_at(seed + 7));
            let (qa1, qb1) = (nodes_at(seed + 3), nodes_at(seed + 11));
            let (p0, p1) = (f.invariants(&qa0, &qb0), f.invariants(&qa1, &qb1));
            let q = f.gap_quotients(&p0, &p1);
            let lhs: f64 = (0..4).map(|k| q[k] * (p1[k] - p0[k])).sum();
            let rhs = f.gap(&p1) - f.gap(&p0);
            assert!((lhs - rhs).abs() <= 1e-13, "{lhs} vs {rhs}");
        }
    }
    /// The exact derivatives agree with central differences, and the distance is even in the
    /// invariants that a mirror symmetry negates, bit for bit.
    #[test]
    fn distance_gradient_is_exact_and_distance_is_even() {
        let capsule = |radius, length| ShapeKind::Capsule { radius, length };
        let kinds = [
            [ShapeKind::Sphere { radius: 0.05 }, capsule(0.03, 0.2)],
            [capsule(0.02, 0.3), capsule(0.03, 0.2)],
            [
                ShapeKind::Sphere { radius: 0.05 },
                ShapeKind::Cuboid {
                    size: Vec3::new(0.2, 0.1, 0.3),
                },
            ],
        ];
        for k in kinds {
            let rt = build(&model(k));
            for seed in 0..100 {
                let (qa, qb) = (nodes_at(seed), nodes_at(seed + 517));
                for f in &rt.features {
                    let (qa, qb) = if f.bodies.0 == 0 { (qa, qb) } else { (qb, qa) };
                    let p = f.invariants(&qa, &qb);
                    let g = f.distance_gradient(&p);
                    for i in 0..f.nrows {
                        let e = 1e-7 * f.scale * f.scale;
                        let (mut hi, mut lo) = (p, p);
                        hi[i] += e;
                        lo[i] -= e;
                        let fd = (f.distance(&hi) - f.distance(&lo)) / (2.0 * e);
                        assert!(
                            (g[i] - fd).abs() <= 1e-5 * (1.0 + fd.abs()),
                            "{k:?} {seed} {i}: {} vs {fd} at {p:?}",
                            g[i]
                        );
                    }
                    // mirror symmetries: a segment's span reversed negates the invariants
                    // that are linear in it
                    let flips: &[&[usize]] = match f.measure {
                        Measure::PointSegment { .. } => &[&[1]],
                        Measure::Segments { .. } => &[&[0, 1], &[0, 2]],
                        _ => &[],
                    };
                    for flip in flips {
                        let mut m = p;
                        for &i in *flip {
                            m[i] = -m[i];
                        }
                        assert_eq!(f.distance(&m).to_bits(), f.distance(&p).to_bits(), "{k:?}");
                    }
                }
            }
        }
    }
}
