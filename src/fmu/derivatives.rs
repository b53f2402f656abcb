//! Directional derivatives (FMI 2.0.4 §2.1.9, FMI 3.0 §3.2.3 directional and adjoint) at the
//! current communication point, exact: `mechanics::Operating::directional`, one forward pass
//! of dual numbers per call (adjoint: one per known element).
//!
//! Knowns are the states (`joint.J.q`, `joint.J.qd` of `variables::linear::States`) and the
//! inputs; unknowns are outputs that can be differentiated (`joint.J.qd` and `joint.J.qdd` are
//! the state derivatives). In a tree the other coordinates (spherical joints, a floating base)
//! are held at their values.
//!
//! Closed loops and couplings: the states are the independent coordinates `triad linearize`
//! picks by default at the model's initial state (`VariableTable::loops`, decided when the
//! table is built); the other tree joints follow them around the loops (their `joint.J.q`,
//! `qd`, `qdd` are outputs with derivatives, rows of `C`, `D`), and cannot be knowns. At each
//! call triad's pick at the current point must be the declared one, so that the values are
//! `triad linearize`'s `A, B, C, D` there; where it is not (near a singular configuration of
//! the loop) the call is refused. Loop-closing joints' coordinates and rates have no
//! derivatives.

use super::instance::{Instance, Op};
use super::params::Base;
use super::status::{FmuError, Status};
use crate::mechanics::{Coord, Operating, Quantity};
use crate::variables::linear::{differentiable, quantity, states, States};
use crate::variables::{Accessor, Causality, Variable};

impl Instance {
    /// The states this instance declares, or why it provides no directional derivatives.
    fn declared_states(&self) -> Result<States, FmuError> {
        if let Err(e) = crate::mechanics::linearizable(&self.def) {
            return Err(FmuError::rejected(format!(
                "this model provides no directional derivatives: {e}"
            )));
        }
        states(&self.table).ok_or_else(|| {
            FmuError::rejected(if crate::mechanics::supported(&self.def).is_err() {
                "this model provides no directional derivatives (its closed loops or couplings \
                 could not be split into independent joint coordinates at the initial state)"
            } else {
                "this model provides no directional derivatives (no joint coordinates to be states, or too many for the description's dependencies)"
            })
        })
    }

    /// The name of tree coordinate `c`, for messages.
    fn coord_name(&self, c: Coord) -> String {
        match c {
            Coord::Joint { joint, k } => {
                let j = &self.def.joints[joint];
                if j.kind.dof() == 1 {
                    format!("joint.{}.q", j.name)
                } else {
                    format!("joint.{}.q[{}]", j.name, k + 1)
                }
            }
            Coord::Free { body, i } => {
                format!("body {} coordinate {}", self.def.bodies[body].name, i + 1)
            }
        }
    }

    /// With closed loops or couplings: the declared states must be the independent
    /// coordinates triad picks at `op` (module docs), else why not.
    fn check_pick(&self, op: &Operating) -> Result<(), FmuError> {
        let Some(loops) = &self.table.loops else {
            return Ok(());
        };
        let declared: Vec<Coord> = loops
            .independent
            .iter()
            .map(|&(joint, k)| Coord::Joint { joint, k })
            .collect();
        let here = op.independent().unwrap_or_default();
        if here == declared {
            return Ok(());
        }
        let names = |cs: &[Coord]| {
            cs.iter()
                .map(|&c| self.coord_name(c))
                .collect::<Vec<_>>()
                .join(", ")
        };
        Err(FmuError::rejected(format!(
            "no directional derivatives at this point: the independent coordinates triad picks \
             here ({}) are not the declared states ({}), picked at the initial state; the loops \
             are near a singular configuration for the declared ones (`triad linearize \
             --coordinates` linearises in others)",
            names(&here),
            names(&declared)
        )))
    }

    /// The position of a known in the seed `(δx, δu)`: `(false, i)` state `i` of
    /// `Operating::x` (coordinates, then rates), `(true, i)` input `i`; or why it is no known.
    fn known_slot(
        &self,
        v: &Variable,
        st: &States,
        op: &Operating,
    ) -> Result<(bool, usize), FmuError> {
        let index = self.index.get(&v.vr).copied();
        let declared = |list: &[usize]| index.is_some_and(|i| list.contains(&i));
        // the position of tree coordinate `joint`, `k` among the state's coordinates
        let position = |joint: usize, k: usize| -> Option<usize> {
            let i = op.dynamics.joint_at(joint)? + k;
            match &op.loops {
                Some(cl) => cl.indep.iter().position(|&c| c == i),
                None => Some(i),
            }
        };
        let nx = op.x().len() / 2;
        let slot = match v.accessor {
            Accessor::Input(i) => Some((true, i)),
            Accessor::JointQ { joint, k } if declared(&st.q) => {
                position(joint, k).map(|a| (false, a))
            }
            Accessor::JointQd { joint, k } if declared(&st.qd) => {
                position(joint, k).map(|a| (false, nx + a))
            }
            _ => None,
        };
        if let Some(slot) = slot {
            return Ok(slot);
        }
        let dependent = matches!(
            v.accessor,
            Accessor::JointQ { joint, .. } | Accessor::JointQd { joint, .. }
                if self.table.loops.as_ref().is_some_and(|l| !l.closing.contains(&joint))
        );
        Err(FmuError::rejected(if dependent {
            format!(
                "value reference {} ({}) is a dependent joint's: it follows the states around the \
                 closed loops and couplings, so it is no state and cannot be a known (the states \
                 are the declared derivatives' <Derivatives> joints)",
                v.vr, v.name
            )
        } else {
            format!(
                "value reference {} ({}) is neither a state nor an input: it cannot be a known",
                v.vr, v.name
            )
        }))
    }

    /// `C δx + D δu` for the table variables `unknowns` along `seed` over `knowns`.
    fn directional_table(
        &self,
        unknowns: &[&Variable],
        knowns: &[&Variable],
        seed: &[f64],
    ) -> Result<Vec<f64>, FmuError> {
        let st = self.declared_states()?;
        if let Some(k) = seed.iter().position(|x| !x.is_finite()) {
            return Err(FmuError::rejected(format!(
                "seed {k} ({}) is not finite",
                seed[k]
            )));
        }
        let Some(sim) = &self.sim else {
            return Err(FmuError::rejected(
                "directional derivatives need the simulation: call after entering initialization mode",
            ));
        };
        let op = sim.operating().map_err(FmuError::rejected)?;
        self.check_pick(&op)?;
        let (mut dx, mut du) = (vec![0.0; op.x().len()], vec![0.0; op.u.len()]);
        for (v, &s) in knowns.iter().zip(seed) {
            match self.known_slot(v, &st, &op)? {
                (false, i) => dx[i] += s,
                (true, i) => du[i] += s,
            }
        }
        let mut ys: Vec<Quantity> = Vec::with_capacity(unknowns.len());
        for v in unknowns {
            match (v.causality, quantity(v.accessor)) {
                (Causality::Output, Some(q)) if differentiable(&self.table, v.accessor) => {
                    ys.push(q);
                }
                (Causality::Output, Some(_)) => {
                    return Err(FmuError::rejected(format!(
                        "value reference {} ({}) is a loop-closing joint's, no coordinate of the \
                         tree: it has no directional derivatives",
                        v.vr, v.name
                    )))
                }
                _ => {
                    return Err(FmuError::rejected(format!(
                        "value reference {} ({}) is not an output or state derivative that can be differentiated",
                        v.vr, v.name
                    )))
                }
            }
        }
        op.directional(&dx, &du, &ys).map_err(FmuError::rejected)
    }

    /// `fmi2GetDirectionalDerivative`: `out[i] = Σ_j ∂unknown_i/∂known_j · seed_j`.
    ///
    /// # Errors
    /// Wrong mode, unknown value references, a known that is neither a state nor an input, an
    /// unknown that is not a differentiable output, a non-finite seed, a model without
    /// derivatives; `out` is then unchanged.
    pub fn directional_derivative(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<Status, FmuError> {
        const F: &str = "fmi2GetDirectionalDerivative";
        self.check(Op::GetDirectionalDerivative, F)?;
        let look = |vrs: &[u32]| -> Result<Vec<&Variable>, FmuError> {
            vrs.iter().map(|&vr| self.lookup(vr, Base::Real)).collect()
        };
        let values = self.directional_table(&look(unknowns)?, &look(knowns)?, seed)?;
        out.copy_from_slice(&values);
        Ok(Status::Ok)
    }

    /// The table variables of FMI 3 value references (arrays expanded, row-major).
    fn members3(&self, vrs: &[u32]) -> Result<Vec<&Variable>, FmuError> {
        let mut out = Vec::new();
        for &vr in vrs {
            let var = self.table3.by_vr(vr).ok_or_else(|| {
                FmuError::rejected(format!("unknown value reference {vr} for Float64"))
            })?;
            for &m in &var.members {
                out.push(self.lookup(m, Base::Real)?);
            }
        }
        Ok(out)
    }

    /// The table variables of FMI 3 `unknowns` and `knowns`, with the sizes checked: `n_seed`
    /// and `n_out` are the knowns' and unknowns' sizes (directional) or the reverse (adjoint).
    fn operands3(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        (n_seed, n_out): (usize, usize),
        adjoint: bool,
    ) -> Result<(Vec<&Variable>, Vec<&Variable>), FmuError> {
        let (u, k) = (self.members3(unknowns)?, self.members3(knowns)?);
        let (want_seed, want_out) = if adjoint {
            (u.len(), k.len())
        } else {
            (k.len(), u.len())
        };
        if n_seed != want_seed || n_out != want_out {
            return Err(FmuError::rejected(format!(
                "nSeed = {n_seed} and nSensitivity = {n_out} must be {want_seed} and {want_out} (the {} sizes)",
                if adjoint { "unknowns' and knowns'" } else { "knowns' and unknowns'" }
            )));
        }
        Ok((u, k))
    }

    /// `fmi3GetDirectionalDerivative` (`seed.len()` = `nSeed`, `out.len()` = `nSensitivity`).
    ///
    /// # Errors
    /// As [`Instance::directional_derivative`], and sizes that do not match the variables.
    pub fn directional_derivative3(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<Status, FmuError> {
        self.check(Op::GetDirectionalDerivative, "fmi3GetDirectionalDerivative")?;
        let (u, k) = self.operands3(unknowns, knowns, (seed.len(), out.len()), false)?;
        let values = self.directional_table(&u, &k, seed)?;
        out.copy_from_slice(&values);
        Ok(Status::Ok)
    }

    /// `fmi3GetAdjointDerivative`: `out[j] = Σ_i seed_i ∂unknown_i/∂known_j` (`seed.len()` =
    /// the unknowns' size, `out.len()` = the knowns'); one directional derivative per known.
    ///
    /// # Errors
    /// As [`Instance::directional_derivative3`].
    pub fn adjoint_derivative3(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<Status, FmuError> {
        self.check(Op::GetDirectionalDerivative, "fmi3GetAdjointDerivative")?;
        let (u, k) = self.operands3(unknowns, knowns, (seed.len(), out.len()), true)?;
        if let Some(i) = seed.iter().position(|x| !x.is_finite()) {
            return Err(FmuError::rejected(format!(
                "seed {i} ({}) is not finite",
                seed[i]
            )));
        }
        let mut values = vec![0.0; k.len()];
        let mut unit = vec![0.0; k.len()];
        for (j, value) in values.iter_mut().enumerate() {
            unit[j] = 1.0;
            let col = self.directional_table(&u, &k, &unit)?;
            unit[j] = 0.0;
            *value = col.iter().zip(seed).map(|(c, s)| c * s).sum();
        }
        out.copy_from_slice(&values);
        Ok(Status::Ok)
    }
}
