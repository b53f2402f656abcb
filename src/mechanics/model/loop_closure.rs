//! Closed loops in minimal coordinates: the tree's coordinates `q` (`tree_dynamics`, the
//! spanning tree) subject to the rows of the loop-closing joints, and the split of `q` into
//! independent coordinates `I` and dependent ones `D`.
//!
//! ```text
//! closure    Φ(q) = 0:  the closing joints' rows g = u·w − c (`constraint::DotRow`) on the nodes
//!            φ = o + R c,  dᵢ = R eᵢ  of the bodies placed by the tree's kinematics at q, and
//!            the joint couplings q_b − r q_a − o (`[[coupling]]`, linear in the coordinates)
//! rates      Φ̇ = u̇·w + u·ẇ = G(q) ν             φ̇ = v_G,  ḋᵢ = ω × dᵢ
//! accel.     Φ̈ = ü·w + 2 u̇·ẇ + u·ẅ = G ν̇ + Ġ ν   φ̈ = a_G,  d̈ᵢ = α × dᵢ + ω × (ω × dᵢ)
//!            (G's column k: Φ̇ at ν = e_k; the motion's velocities and accelerations give Φ̇,
//!            Φ̈ exactly, in any scalar, so dual numbers differentiate them)
//! rows       r independent rows of all the closing rows (pivoted Gram–Schmidt on G's rows, at
//!            the operating point: a planar loop's out-of-plane rows are redundant)
//! split      I: n − r coordinates with G_D (r × r) regular; picked in order of preference
//!            (the actuated joints' coordinates, then the others, in model order), each taken
//!            when its row of the null-space projector P = I − Gᵀ(GGᵀ)⁻¹G keeps ≥ 0.1 of the
//!            largest row's norm after the rows taken before it are projected out (a
//!            well-conditioned G_D), then the largest such remainders; or named by the user
//! IFT        q_D(q_I): Newton  q_D ← q_D − G_D⁻¹ Φ(q)  (G = ∂Φ/∂q where the rates are the
//!            coordinates' derivatives: everywhere but rotation vectors off θ = 0);
//!            ν_D = −G_D⁻¹ G_I ν_I;  δq_D = −G_D⁻¹ G_I δq_I
//! ```
//!
//! Dual numbers: the Newton iteration is run in the scalar; once the real part has converged,
//! one more iteration makes the derivative parts exact (they solve the linear IFT equations).

use super::constraint::{DotRow, LinVec, NODES};
use super::def::ModelDef;
use super::runtime::Model;
use super::tree_dynamics::{c, Coord, Motion, Real, TreeDynamics};
use nalgebra::{DMatrix, DVector, Vector3};

/// Which tree coordinates are the independent ones.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Independent {
    /// triad picks them (module docs: the actuated joints first, then model order).
    Auto,
    /// Every coordinate of these joints, by name.
    Joints(Vec<String>),
    /// These tree coordinates (indices into `TreeDynamics::coords`).
    Coords(Vec<usize>),
}

/// One row of the closure: a loop-closing joint's row on its parent body (`None`: the world)
/// and child body, or a joint coupling `q_b − r q_a − o` on two tree coordinates.
#[derive(Clone, Debug)]
enum ClosingRow {
    /// A row of a loop-closing joint.
    Joint {
        parent: Option<usize>,
        child: usize,
        row: DotRow,
    },
    /// A coupling: tree coordinates `a`, `b`, `ratio`, `offset`.
    Coupling {
        a: usize,
        b: usize,
        ratio: f64,
        offset: f64,
    },
}

/// The loop closure of a model at an operating point: the independent rows and the split of
/// the tree's coordinates (module docs).
#[derive(Clone, Debug)]
pub struct Closure {
    rows: Vec<ClosingRow>,
    /// Independent coordinates `I`, ascending tree-coordinate indices.
    pub indep: Vec<usize>,
    /// Dependent coordinates `D`, ascending.
    pub dep: Vec<usize>,
}

/// A vector's value and first two time derivatives.
#[derive(Clone, Copy, Debug)]
struct Jet<T: Real> {
    x: Vector3<T>,
    v: Vector3<T>,
    a: Vector3<T>,
}

/// Per body its four nodes' jets `[φ, d1, d2, d3]`.
type BodyJets<T> = Vec<[Jet<T>; NODES]>;

fn jets<T: Real>(td: &TreeDynamics, m: &Motion<T>) -> BodyJets<T> {
    (0..td.n_bodies())
        .map(|b| {
            let (pg, vg) = td.com_of(m, b);
            let (w, al) = (m.w[b], m.al[b]);
            let rc = pg - m.o[b];
            let ag = m.a[b] + al.cross(&rc) + w.cross(&w.cross(&rc));
            let dir = |i: usize| {
                let d = m.r[b].column(i).into_owned();
                Jet {
                    x: d,
                    v: w.cross(&d),
                    a: al.cross(&d) + w.cross(&w.cross(&d)),
                }
            };
            [
                Jet {
                    x: pg,
                    v: vg,
                    a: ag,
                },
                dir(0),
                dir(1),
                dir(2),
            ]
        })
        .collect()
}

/// The world's nodes `[0, e1, e2, e3]`, at rest.
fn world<T: Real>() -> [Jet<T>; NODES] {
    let z = Vector3::zeros();
    let e = |i: usize| Jet {
        x: Vector3::ith(i, T::one()),
        v: z,
        a: z,
    };
    [Jet { x: z, v: z, a: z }, e(0), e(1), e(2)]
}

/// `v = Σ a_k qᴬ_k + Σ b_k qᴮ_k + c` and its two time derivatives.
fn lin<T: Real>(l: &LinVec, ja: &[Jet<T>; NODES], jb: &[Jet<T>; NODES]) -> Jet<T> {
    let mut out = Jet {
        x: l.c.map(c::<T>),
        v: Vector3::zeros(),
        a: Vector3::zeros(),
    };
    for k in 0..NODES {
        for (coef, j) in [(l.a[k], &ja[k]), (l.b[k], &jb[k])] {
            if coef != 0.0 {
                let s = c::<T>(coef);
                out.x += j.x * s;
                out.v += j.v * s;
                out.a += j.a * s;
            }
        }
    }
    out
}

/// Solves `a x = b` in the scalar.
pub(crate) fn solve<T: Real>(a: DMatrix<T>, b: DVector<T>) -> Option<DVector<T>> {
    a.lu().solve(&b)
}

/// Pivoted Gram–Schmidt: the indices of `vs` taken, first in `order` when their remainder
/// keeps `strict` of the largest norm, then by the largest remainder above `1e-9` of it, until
/// `need` are taken (or none is left above that floor).
fn pivoted(vs: &[DVector<f64>], order: &[usize], strict: f64, need: usize) -> Vec<usize> {
    let scale = vs.iter().map(DVector::norm).fold(0.0, f64::max);
    let mut basis: Vec<DVector<f64>> = Vec::new();
    let mut taken = Vec::new();
    let remainder = |v: &DVector<f64>, basis: &[DVector<f64>]| {
        let mut r = v.clone();
        for e in basis {
            r -= e * e.dot(&r);
        }
        r
    };
    if scale == 0.0 {
        return taken;
    }
    for &k in order {
        if taken.len() == need {
            break;
        }
        let r = remainder(&vs[k], &basis);
        if r.norm() >= strict * scale {
            basis.push(r.normalize());
            taken.push(k);
        }
    }
    while taken.len() < need {
        let best = (0..vs.len())
            .filter(|k| !taken.contains(k))
            .map(|k| (k, remainder(&vs[k], &basis)))
            .max_by(|a, b| a.1.norm().total_cmp(&b.1.norm()));
        match best {
            Some((k, r)) if r.norm() > 1e-9 * scale => {
                basis.push(r.normalize());
                taken.push(k);
            }
            _ => break,
        }
    }
    taken
}

impl Closure {
    /// Every row of the loop-closing joints and couplings of `model`, or `None` for a tree
    /// without couplings.
    fn all_rows(td: &TreeDynamics, model: &Model) -> Option<Vec<ClosingRow>> {
        let def = model.def();
        let mut rows: Vec<ClosingRow> = def
            .joints
            .iter()
            .enumerate()
            .filter(|(_, jd)| jd.loop_closing)
            .flat_map(|(j, _)| {
                let g = &model.joints[j].geom;
                g.rows.iter().map(|row| ClosingRow::Joint {
                    parent: g.parent,
                    child: g.child,
                    row: *row,
                })
            })
            .collect();
        for cd in &def.couplings {
            if let (Some(a), Some(b)) = (td.joint_at(cd.a), td.joint_at(cd.b)) {
                rows.push(ClosingRow::Coupling {
                    a,
                    b,
                    ratio: cd.ratio,
                    offset: cd.offset,
                });
            }
        }
        (!rows.is_empty()).then_some(rows)
    }

    /// The closure of `model`'s loops at the tree coordinates `q` (which should close them),
    /// with the independent coordinates `pick`; `None` for a tree.
    ///
    /// # Errors
    /// For [`Independent::Joints`]: an unknown, loop-closing or repeated joint, the wrong number
    /// of coordinates, or a choice that leaves `G_D` singular at `q` (a message naming them).
    pub fn new(
        td: &TreeDynamics,
        model: &Model,
        q: &[f64],
        pick: &Independent,
    ) -> Result<Option<Self>, String> {
        let Some(rows) = Self::all_rows(td, model) else {
            return match pick {
                Independent::Joints(_) => Err(
                    "the model has no closed loops or couplings: its state is every tree joint's \
                     coordinate and rate, so there is nothing to pick (--coordinates is for closed \
                     loops)"
                        .into(),
                ),
                _ => Ok(None),
            };
        };
        let n = td.n();
        let mut all = Self {
            rows,
            indep: Vec::new(),
            dep: Vec::new(),
        };
        let g = all.jacobian(td, q);
        let gr: Vec<DVector<f64>> = (0..g.nrows()).map(|i| g.row(i).transpose()).collect();
        let kept = pivoted(&gr, &[], 0.0, gr.len());
        let r = kept.len();
        let mut kept_sorted = kept.clone();
        kept_sorted.sort_unstable();
        all.rows = kept_sorted.iter().map(|&i| all.rows[i].clone()).collect();
        let def = model.def();
        let indep = match pick {
            Independent::Auto => {
                let gk = all.jacobian(td, q);
                let qt = gk.transpose().qr().q();
                let p = DMatrix::identity(n, n) - &qt * qt.transpose();
                let prow: Vec<DVector<f64>> = (0..n).map(|i| p.row(i).transpose()).collect();
                let mut order: Vec<usize> = (0..n).collect();
                let actuated = |i: &usize| match td.coords()[*i] {
                    Coord::Joint { joint, .. } => def.joints[joint].actuated,
                    Coord::Free { .. } => false,
                };
                order.sort_by_key(|i| (!actuated(i), *i));
                let mut taken = pivoted(&prow, &order, 0.1, n - r);
                taken.sort_unstable();
                taken
            }
            Independent::Joints(names) => coords_of_joints(td, def, names)?,
            Independent::Coords(ix) => {
                let mut ix = ix.clone();
                ix.sort_unstable();
                ix
            }
        };
        if indep.len() != n - r {
            return Err(format!(
                "the closed loops leave {} independent coordinate(s) of the tree's {n}; {} \
                 named",
                n - r,
                indep.len()
            ));
        }
        all.dep = (0..n).filter(|i| !indep.contains(i)).collect();
        all.indep = indep;
        let gd = all.split(&all.jacobian(td, q)).1;
        let sv = gd.singular_values();
        let (smax, smin) = (sv.max(), sv.min());
        let regular = smin > 1e-8 * smax;
        if r > 0 && !regular {
            return Err(format!(
                "the coordinates of {} are not independent here: the other coordinates ({}) \
                 cannot follow them around the loop (their block of the loop's Jacobian is \
                 singular, σ_min/σ_max = {:.1e}); pick other joints",
                names_of(td, def, &all.indep),
                names_of(td, def, &all.dep),
                smin / smax
            ));
        }
        Ok(Some(all))
    }

    /// Number of independent rows `r`.
    #[must_use]
    pub fn n_rows(&self) -> usize {
        self.rows.len()
    }

    /// The rows' values `Φ`, rates `Φ̇` and accelerations `Φ̈` at `m`, the motion at `(q, ν, ν̇)`
    /// (module formulas; a coupling's are `q_b − r q_a − o`, `ν_b − r ν_a`, `ν̇_b − r ν̇_a`).
    fn values<T: Real>(
        &self,
        td: &TreeDynamics,
        m: &Motion<T>,
        (q, nu, nud): (&[T], &[T], &[T]),
    ) -> (Vec<T>, Vec<T>, Vec<T>) {
        let jets = jets(td, m);
        let w0 = world::<T>();
        let (mut g, mut gd, mut gdd) = (Vec::new(), Vec::new(), Vec::new());
        for cr in &self.rows {
            match cr {
                ClosingRow::Joint { parent, child, row } => {
                    let ja = parent.map_or(&w0, |p| &jets[p]);
                    let jb = &jets[*child];
                    let (u, w) = (lin(&row.u, ja, jb), lin(&row.w, ja, jb));
                    g.push(u.x.dot(&w.x) - c::<T>(row.offset));
                    gd.push(u.v.dot(&w.x) + u.x.dot(&w.v));
                    gdd.push(u.a.dot(&w.x) + u.v.dot(&w.v) * c::<T>(2.0) + u.x.dot(&w.a));
                }
                ClosingRow::Coupling {
                    a,
                    b,
                    ratio,
                    offset,
                } => {
                    let r = c::<T>(*ratio);
                    g.push(q[*b] - r * q[*a] - c::<T>(*offset));
                    gd.push(nu[*b] - r * nu[*a]);
                    gdd.push(nud[*b] - r * nud[*a]);
                }
            }
        }
        (g, gd, gdd)
    }

    /// `Φ(q)` (r).
    pub fn phi<T: Real>(&self, td: &TreeDynamics, q: &[T]) -> Vec<T> {
        let z = vec![T::zero(); td.n()];
        self.values(td, &td.motion(q, &z, Some(&z)), (q, &z, &z)).0
    }

    /// `Φ̈(q, ν, ν̇) = G ν̇ + Ġ ν` (r).
    pub fn phi_ddot<T: Real>(&self, td: &TreeDynamics, q: &[T], nu: &[T], nud: &[T]) -> Vec<T> {
        self.values(td, &td.motion(q, nu, Some(nud)), (q, nu, nud))
            .2
    }

    /// `G(q) = ∂Φ̇/∂ν` (r × n).
    pub fn jacobian<T: Real>(&self, td: &TreeDynamics, q: &[T]) -> DMatrix<T> {
        let n = td.n();
        let mut g = DMatrix::zeros(self.rows.len(), n);
        let z = vec![T::zero(); n];
        for k in 0..n {
            let mut e = z.clone();
            e[k] = T::one();
            let (_, gd, _) = self.values(td, &td.motion(q, &e, Some(&z)), (q, &e, &z));
            for (i, v) in gd.into_iter().enumerate() {
                g[(i, k)] = v;
            }
        }
        g
    }

    /// The columns of `g` at `I` and at `D`.
    pub fn split<T: Real>(&self, g: &DMatrix<T>) -> (DMatrix<T>, DMatrix<T>) {
        (g.select_columns(&self.indep), g.select_columns(&self.dep))
    }

    /// The tree coordinates and rates `(q, ν)` with `q_I`, `ν_I` given and `q_D`, `ν_D` closing
    /// the loops (module formulas), Newton started from `q_start`.
    ///
    /// # Errors
    /// A message when the Newton iteration does not converge (the loop cannot close there).
    pub fn complete<T: Real>(
        &self,
        td: &TreeDynamics,
        q_start: &[f64],
        qi: &[T],
        vi: &[T],
    ) -> Result<(Vec<T>, Vec<T>), String> {
        let n = td.n();
        let mut q: Vec<T> = q_start.iter().map(|&x| c::<T>(x)).collect();
        for (k, &i) in self.indep.iter().enumerate() {
            q[i] = qi[k];
        }
        let scale = c::<T>(1e-14 * (1.0 + q_start.iter().fold(0.0, |m: f64, x| m.max(x.abs()))));
        let mut done = None;
        for it in 0..60 {
            let phi = DVector::from_vec(self.phi(td, &q));
            let (_, gd) = self.split(&self.jacobian(td, &q));
            let dx = solve(gd, phi).ok_or("the loop's Jacobian is singular")?;
            for (k, &i) in self.dep.iter().enumerate() {
                q[i] -= dx[k];
            }
            let size = dx.iter().fold(T::zero(), |m, x| m.max(x.abs()));
            match done {
                // one more iteration after convergence: the derivative parts are exact then
                Some(last) if it > last => break,
                None if size <= scale => done = Some(it),
                _ => {}
            }
        }
        if done.is_none() {
            return Err(
                "the closed loop does not close near these coordinates (Newton on the dependent \
                 coordinates did not converge)"
                    .into(),
            );
        }
        let g = self.jacobian(td, &q);
        let mut nu = vec![T::zero(); n];
        for (k, &i) in self.indep.iter().enumerate() {
            nu[i] = vi[k];
        }
        let rhs = &g * DVector::from_vec(nu.clone());
        let (_, gd) = self.split(&g);
        let vd = solve(gd, -rhs).ok_or("the loop's Jacobian is singular")?;
        for (k, &i) in self.dep.iter().enumerate() {
            nu[i] = vd[k];
        }
        Ok((q, nu))
    }

    /// `x_I` of a tree vector.
    #[must_use]
    pub fn pick<T: Copy>(&self, v: &[T]) -> Vec<T> {
        self.indep.iter().map(|&i| v[i]).collect()
    }
}

/// The tree coordinates of the joints `names` (every coordinate of each), ascending.
fn coords_of_joints(
    td: &TreeDynamics,
    def: &ModelDef,
    names: &[String],
) -> Result<Vec<usize>, String> {
    let mut out = Vec::new();
    let mut problems = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for name in names {
        if seen.contains(&name.as_str()) {
            problems.push(format!("joint '{name}' is named twice"));
            continue;
        }
        seen.push(name);
        let Some(j) = def.joints.iter().position(|jd| &jd.name == name) else {
            let tree: Vec<&str> = def
                .joints
                .iter()
                .filter(|jd| !jd.loop_closing && jd.kind.dof() > 0)
                .map(|jd| jd.name.as_str())
                .collect();
            problems.push(format!(
                "no joint '{name}' (the tree's joints: {})",
                tree.join(", ")
            ));
            continue;
        };
        if def.joints[j].loop_closing {
            problems.push(format!(
                "joint '{name}' closes a loop: it has no coordinate of the tree; name joints of \
                 the tree"
            ));
            continue;
        }
        let Some(at) = td.joint_at(j) else {
            problems.push(format!("joint '{name}' has no coordinate"));
            continue;
        };
        let dof = def.joints[j].kind.dof();
        if dof == 0 {
            problems.push(format!("joint '{name}' is fixed: it has no coordinate"));
        }
        out.extend(at..at + dof);
    }
    if problems.is_empty() {
        out.sort_unstable();
        Ok(out)
    } else {
        Err(problems.join("; "))
    }
}

/// The joints (or free bodies) owning the coordinates `ix`, comma-separated, once each.
fn names_of(td: &TreeDynamics, def: &ModelDef, ix: &[usize]) -> String {
    let mut out: Vec<String> = Vec::new();
    for &i in ix {
        let name = match td.coords()[i] {
            Coord::Joint { joint, .. } => def.joints[joint].name.clone(),
            Coord::Free { body, .. } => format!("body {}", def.bodies[body].name),
        };
        if !out.contains(&name) {
            out.push(name);
        }
    }
    out.join(", ")
}
