//! The FMI 3 view of the variable table (interface.md §3, "FMI 3 names"): a run of consecutive
//! scalars `base[i]` or `base[i,j]` of one base name becomes one array variable `base` with its
//! dimensions, its elements in row-major order (as FMI 3 serialises arrays); every other
//! variable stays a scalar under its own name. FMI 3 value references are this view's own:
//! [`TIME_VR`] is `time`, the independent variable, then `1, 2, …` in table order.
//!
//! ```text
//! body.B.r[1], body.B.r[2], body.B.r[3]      → body.B.r        dims [3]     members vr₂ of each
//! body.B.R[1,1] … body.B.R[3,3]              → body.B.R        dims [3, 3]  row-major
//! joint.J.tau                                → joint.J.tau     dims []      (a scalar)
//! ```

use super::types::VariableTable;

/// The FMI 3 value reference of `time`, the independent variable.
pub const TIME_VR: u32 = 0;

/// One FMI 3 variable: a scalar or an array of the table's scalars.
#[derive(Clone, Debug, PartialEq)]
pub struct Var3 {
    /// FMI 3 value reference.
    pub vr: u32,
    /// Name: the scalar's, or an array's base name.
    pub name: String,
    /// Dimensions (empty: a scalar).
    pub dims: Vec<usize>,
    /// The table's (FMI 2) value references of the elements, row-major.
    pub members: Vec<u32>,
    /// What it is: the elements' description less the parts that name the element.
    pub description: String,
}

impl Var3 {
    /// Number of values (1 for a scalar).
    #[must_use]
    pub fn len(&self) -> usize {
        self.members.len()
    }

    /// Whether it holds no value (never: every variable has one or more).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }
}

/// The FMI 3 variables of a table, in table order ([`TIME_VR`] not among them).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table3 {
    /// Variables; `vars[k].vr == k + 1`.
    pub vars: Vec<Var3>,
}

/// `(base, indices)` of a name `base[i]` or `base[i,j]` (1-based indices).
fn indexed(name: &str) -> Option<(&str, Vec<usize>)> {
    let open = name.rfind('[')?;
    let inner = name.strip_suffix(']')?.get(open + 1..)?;
    let idx: Option<Vec<usize>> = inner.split(',').map(|s| s.trim().parse().ok()).collect();
    Some((&name[..open], idx?))
}

/// The description shared by every element: the `", "`-separated parts equal in all.
fn common_description(parts: &[&str]) -> String {
    let split: Vec<Vec<&str>> = parts.iter().map(|d| d.split(", ").collect()).collect();
    split[0]
        .iter()
        .filter(|p| split.iter().all(|s| s.contains(p)))
        .copied()
        .collect::<Vec<_>>()
        .join(", ")
}

impl Table3 {
    /// The FMI 3 view of `table` (module docs). A run of indexed names forms an array only
    /// when its indices fill the row-major box of its dimensions in order; otherwise its
    /// elements stay scalars.
    #[must_use]
    pub fn new(table: &VariableTable) -> Self {
        let mut vars: Vec<Var3> = Vec::new();
        let mut k = 0;
        let all = &table.vars;
        while k < all.len() {
            let v = &all[k];
            let run_end = match indexed(&v.name) {
                Some((base, first)) if first.iter().all(|&i| i == 1) => {
                    let mut end = k + 1;
                    while end < all.len()
                        && indexed(&all[end].name)
                            .is_some_and(|(b, idx)| b == base && idx.len() == first.len())
                    {
                        end += 1;
                    }
                    end
                }
                _ => k + 1,
            };
            let run = &all[k..run_end];
            let dims = indexed(&v.name).map_or_else(Vec::new, |(_, first)| {
                (0..first.len())
                    .map(|d| {
                        run.iter()
                            .filter_map(|x| indexed(&x.name).map(|(_, i)| i[d]))
                            .max()
                            .unwrap_or(1)
                    })
                    .collect()
            });
            // the run is an array when its indices are the row-major enumeration of `dims`
            let row_major = !dims.is_empty()
                && run.len() == dims.iter().product::<usize>()
                && run.iter().enumerate().all(|(n, x)| {
                    let idx = indexed(&x.name).map(|(_, i)| i).unwrap_or_default();
                    let mut rest = n;
                    let mut want = vec![0; dims.len()];
                    for d in (0..dims.len()).rev() {
                        want[d] = rest % dims[d] + 1;
                        rest /= dims[d];
                    }
                    idx == want
                })
                && run.iter().all(|x| {
                    x.ty == v.ty
                        && x.causality == v.causality
                        && x.variability == v.variability
                        && x.initial == v.initial
                        && x.unit == v.unit
                });
            if row_major {
                let descriptions: Vec<&str> = run.iter().map(|x| x.description.as_str()).collect();
                vars.push(Var3 {
                    vr: 0,
                    name: indexed(&v.name)
                        .map(|(b, _)| b.to_string())
                        .unwrap_or_default(),
                    dims,
                    members: run.iter().map(|x| x.vr).collect(),
                    description: common_description(&descriptions),
                });
                k = run_end;
            } else {
                vars.push(Var3 {
                    vr: 0,
                    name: v.name.clone(),
                    dims: Vec::new(),
                    members: vec![v.vr],
                    description: v.description.clone(),
                });
                k += 1;
            }
        }
        for (n, v) in vars.iter_mut().enumerate() {
            v.vr = u32::try_from(n + 1).unwrap_or(u32::MAX);
        }
        Self { vars }
    }

    /// The variable with FMI 3 value reference `vr` ([`TIME_VR`] is not one).
    #[must_use]
    pub fn by_vr(&self, vr: u32) -> Option<&Var3> {
        let k = usize::try_from(vr).ok()?.checked_sub(1)?;
        self.vars.get(k)
    }

    /// The variable called `name`.
    #[must_use]
    pub fn by_name(&self, name: &str) -> Option<&Var3> {
        self.vars.iter().find(|v| v.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::{bundled, Format, Spec};

    fn table(name: &str) -> VariableTable {
        let text = bundled()
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, t)| *t)
            .unwrap();
        let spec = Spec::from_str(text, Format::Toml, "spec.toml").unwrap();
        let (def, settings) = spec.lower().unwrap();
        VariableTable::new(&def, &settings)
    }

    #[test]
    fn vectors_and_matrices_become_arrays_and_scalars_stay() {
        let t = table("space_arm");
        let v3 = Table3::new(&t);
        let r = v3.by_name("body.bus.r").unwrap();
        assert_eq!(r.dims, vec![3]);
        assert_eq!(r.members.len(), 3);
        assert_eq!(t.by_vr(r.members[0]).unwrap().name, "body.bus.r[1]");
        assert_eq!(r.description, "origin of body bus's frame, world frame");
        let rot = v3.by_name("body.bus.R").unwrap();
        assert_eq!(rot.dims, vec![3, 3]);
        assert_eq!(t.by_vr(rot.members[5]).unwrap().name, "body.bus.R[2,3]");
        let tau = v3.by_name("joint.elbow.tau").unwrap();
        assert!(tau.dims.is_empty());
        assert_eq!(v3.by_name("gravity").unwrap().dims, vec![3]);
        // every scalar of the table is in exactly one FMI 3 variable, in order
        let members: Vec<u32> = v3.vars.iter().flat_map(|v| v.members.clone()).collect();
        let all: Vec<u32> = t.vars.iter().map(|v| v.vr).collect();
        assert_eq!(members, all);
        for (k, v) in v3.vars.iter().enumerate() {
            assert_eq!(v3.by_vr(v.vr).unwrap().name, v.name);
            assert_eq!(v.vr as usize, k + 1);
        }
        assert!(v3.by_vr(TIME_VR).is_none());
    }
}
