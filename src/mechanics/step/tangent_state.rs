//! The state of the step's tangent map (`tangent`): perturbation columns carried through a run
//! and their value at the start of the step in progress (held by `Work::tangent`).

use crate::mechanics::model::runtime::Model;

/// Perturbation columns of a run's state (module docs), and their value at the start of the
/// step in progress (a rejected or redone step starts again from there).
#[derive(Clone, Debug)]
pub struct Tangent {
    /// Number of columns.
    pub(crate) cols: usize,
    /// Twist increments `(δφ, δθ)`, 6 per body, per column (column-major), m and rad.
    pub(crate) xi: Vec<f64>,
    /// Nodal velocity perturbations, 12 per body, per column, m/s and 1/s.
    pub(crate) dv: Vec<f64>,
    /// Input perturbations, one per model input, per column.
    pub(crate) du: Vec<f64>,
    /// Rotor rate perturbations, one per rotor (`Model::narm`), per column, rad/s or m/s.
    pub(crate) dw: Vec<f64>,
    /// Ground contact bristle perturbations, 3 per ground point (world), per column, m.
    pub(crate) ds: Vec<f64>,
    /// Joint friction bristle perturbations, one per coordinate with friction
    /// (`Model::nfric`), per column, rad or m.
    pub(crate) df: Vec<f64>,
    /// `xi`, `dv`, `dw`, `ds`, `df` at the start of the step in progress, kept only once a stage
    /// moves them (`None` while the columns are still the start: a step that is never redone,
    /// or the last one of a run, copies nothing).
    start: Option<[Vec<f64>; 5]>,
    /// Why the columns are not the step's derivatives (two bodies' shapes touched in a
    /// stage: their features are not covered, `contact_tangent`).
    pub(crate) inexact: Option<String>,
    /// The ground points touching at the map's start (`Sticking::touching`): the same must
    /// touch at its end, where the bristle states are read off.
    pub(crate) touching: Vec<usize>,
    /// The model with its stop dampers and its actuators' rate terms negated and its joint
    /// friction mirrored, when it has any (the swapped evaluation).
    pub(crate) mirror: Option<Box<Model>>,
}

impl Tangent {
    /// Columns `xi` (6 per body each), `dv` (12 per body each), `du` (one per model input
    /// each), `dw` (one per rotor each), `ds` (3 per ground point each) and `df` (one per
    /// joint friction bristle each), column-major, for `model`.
    ///
    /// # Panics
    /// When the lengths do not match `cols` columns of `model`.
    #[must_use]
    pub fn new(
        model: &Model,
        cols: usize,
        (xi, dv): (Vec<f64>, Vec<f64>),
        du: Vec<f64>,
        (dw, ds, df): (Vec<f64>, Vec<f64>, Vec<f64>),
    ) -> Self {
        let nb = model.bodies.len();
        assert_eq!(xi.len(), 6 * nb * cols, "tangent: xi length");
        assert_eq!(dv.len(), 12 * nb * cols, "tangent: dv length");
        assert_eq!(du.len(), model.inputs.len() * cols, "tangent: du length");
        assert_eq!(dw.len(), model.narm * cols, "tangent: dw length");
        assert_eq!(
            ds.len(),
            3 * ground_points(model) * cols,
            "tangent: ds length"
        );
        let damped = model.joints.iter().any(|j| {
            j.stops.is_some_and(|s| s.damping != 0.0)
                || j.acts.list.iter().any(|a| a.has_rate_term())
                || j.friction.is_some()
        });
        let mirror = damped.then(|| {
            let mut m = model.clone();
            for j in &mut m.joints {
                if let Some(s) = &mut j.stops {
                    s.damping = -s.damping;
                }
                for a in &mut j.acts.list {
                    a.rate_sign = -a.rate_sign;
                }
                if let Some(f) = &mut j.friction {
                    f.mirrored = true;
                }
            }
            Box::new(m)
        });
        Self {
            cols,
            start: None,
            xi,
            dv,
            du,
            dw,
            ds,
            df,
            inexact: None,
            touching: Vec::new(),
            mirror,
        }
    }

    /// Back to the start of the step in progress.
    pub(crate) fn rewind(&mut self) {
        if let Some([xi, dv, dw, ds, df]) = &self.start {
            self.xi.copy_from_slice(xi);
            self.dv.copy_from_slice(dv);
            self.dw.copy_from_slice(dw);
            self.ds.copy_from_slice(ds);
            self.df.copy_from_slice(df);
        }
    }

    /// The step in progress is committed: its end is the next step's start.
    pub(crate) fn accept(&mut self) {
        self.start = None;
    }

    /// Keeps the start of the step in progress before a stage moves the columns (once per
    /// step).
    pub(crate) fn keep_start(&mut self) {
        if self.start.is_none() {
            self.start = Some([
                self.xi.clone(),
                self.dv.clone(),
                self.dw.clone(),
                self.ds.clone(),
                self.df.clone(),
            ]);
        }
    }
}

/// The number of ground contact points of `model` (each with a bristle column).
#[must_use]
pub fn ground_points(model: &Model) -> usize {
    model.contact.ground.as_ref().map_or(0, |g| g.points.len())
}
