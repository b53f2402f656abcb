//! Directional derivatives (FMI 2.0.4 §2.1.9, FMI 3.0 §3.2.3 directional and adjoint) at the
//! current communication point, exact: `mechanics::TreeDynamics::directional`, one forward
//! pass of dual numbers per call (adjoint: one per known element).
//!
//! Knowns are the states (`joint.J.q`, `joint.J.qd` of `variables::linear::States`) and the
//! inputs; unknowns are outputs that can be differentiated (`joint.J.qd` and `joint.J.qdd` are
//! the state derivatives). The other coordinates (spherical joints, a floating base) are held
//! at their values. Models with closed loops are refused (`mechanics::supported`): their
//! declared states are every tree joint's, which the loops do not leave independent;
//! `triad linearize` linearises them in independent coordinates.

use super::instance::{Instance, Op};
use super::params::Base;
use super::status::{FmuError, Status};
use crate::mechanics::Quantity;
use crate::variables::linear::{quantity, states, States};
use crate::variables::{Accessor, Causality, Variable};

impl Instance {
    /// The states this instance declares, or why it provides no directional derivatives.
    fn declared_states(&self) -> Result<States, FmuError> {
        if let Err(e) = crate::mechanics::supported(&self.def) {
            return Err(FmuError::rejected(format!(
                "this model provides no directional derivatives: {e}"
            )));
        }
        states(&self.table).ok_or_else(|| {
            FmuError::rejected("this model provides no directional derivatives (no joint coordinates to be states, or too many for the description's dependencies)")
        })
    }

    /// The seed slot of a known: `(0, i)` coordinate, `(1, i)` rate, `(2, i)` input.
    fn known_slot(
        &self,
        v: &Variable,
        st: &States,
        at: &dyn Fn(usize) -> Option<usize>,
    ) -> Option<(u8, usize)> {
        let index = self.index.get(&v.vr).copied();
        let declared = |list: &[usize]| index.is_some_and(|i| list.contains(&i));
        match v.accessor {
            Accessor::Input(i) => Some((2, i)),
            Accessor::JointQ { joint, k } if declared(&st.q) => at(joint).map(|a| (0, a + k)),
            Accessor::JointQd { joint, k } if declared(&st.qd) => at(joint).map(|a| (1, a + k)),
            _ => None,
        }
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
        let n = op.q.len();
        let at = |j: usize| op.dynamics.joint_at(j);
        let (mut dq, mut dnu, mut du) = (vec![0.0; n], vec![0.0; n], vec![0.0; op.u.len()]);
        for (v, &s) in knowns.iter().zip(seed) {
            match self.known_slot(v, &st, &at) {
                Some((0, i)) => dq[i] += s,
                Some((1, i)) => dnu[i] += s,
                Some((_, i)) => du[i] += s,
                None => {
                    return Err(FmuError::rejected(format!(
                    "value reference {} ({}) is neither a state nor an input: it cannot be a known",
                    v.vr, v.name
                )))
                }
            }
        }
        let mut ys: Vec<Quantity> = Vec::with_capacity(unknowns.len());
        for v in unknowns {
            match (v.causality, quantity(v.accessor)) {
                (Causality::Output, Some(q)) => ys.push(q),
                _ => {
                    return Err(FmuError::rejected(format!(
                        "value reference {} ({}) is not an output or state derivative that can be differentiated",
                        v.vr, v.name
                    )))
                }
            }
        }
        op.dynamics
            .directional(&op.q, &op.nu, &op.u, &dq, &dnu, &du, &ys)
            .map_err(FmuError::rejected)
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
