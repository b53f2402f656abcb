//! The discrete null-space method with nodal reparametrization for trees (theory.md §4.5):
//! Newton on the joints' own increments instead of the body increments and joint multipliers.
//!
//! The unknowns of a Newton update are the joint rates `δu` (one per degree of freedom: an
//! angle per revolute, a slide per prismatic, the absolute rotation of a spherical joint's
//! child and of a free root body); the body twists follow down the tree, `x_c = A x_p + S δu_c
//! + c_c` (`maps`). Premultiplying the scaled momentum equations by the discrete null-space
//! matrix `P̄ = P(q̄)ᵀ` removes the constraint forces exactly, so no multiplier is needed. The
//! reduced equations `P̄ᵀ r(q) = 0` with the joint rows at their values at `qₙ` have the same
//! solution as the multiplier form (`newton`), so energy, momentum and the torque balance are
//! conserved alike; there are `f` unknowns instead of `6N + m`.
//!
//! The iterate is the bodies' own (`place`): each update turns and shifts every body by its
//! twist, so the bodies stay rigid and their joint rows err by the square of the update. The
//! next solve corrects those defects to first order through `c` (`G c = −g`, `G S = 0`), as
//! the multiplier form's does, and every few stages `settle` puts `qₙ` back on the rows, so
//! that round-off does not pile up in them. This is the null-space method of the multiplier
//! form's linear system; the nodal reparametrization `q = Φ(u, qₙ)` of theory.md §4.5 (the
//! bodies placed from the joint increments at every iterate) gives the same solution, but it
//! turns the far bodies of a chain along arcs, which made chain1000's equations ≈ 1000× more
//! nonlinear than the multiplier form's (0.4 against 4e-4 as the first chord contraction from
//! the same first update), and it carries the round-off of a joint increment near the root
//! into the whole subtree.
//!
//! Newton matrix `P̄ᵀ K Q + ∂P̄ᵀ/∂u · W` (`K` the body blocks of `newton`, `Q` the maps at the iterate, `W`
//! the subtree wrenches): the second term, the constraint forces' geometric stiffness, is exact
//! for turning pairs and approximate for slides (`eval`). The matrix is eliminated leaves to
//! root like an articulated-body recursion with fixed-size blocks (`tree`), O(N). A stage that
//! does not converge is redone by the multiplier form (`iterate`). Loop-closing joints are not
//! covered: such models use the multiplier form throughout. Joint couplings are bordered on the
//! tree factors (`couple`), and a revolute joint's loads enter as scalars on its own rate
//! (`joint_space`).
//!
//! Measured on the chainN models at h = 1e-3 over 10 s (10 000 steps), iterations per step and
//! energy balance (relative), against the multiplier form's: N = 200: 2.08 (2.54), 1e-15;
//! N = 300: 2.21 (2.74), 1e-15; N = 500: 2.83 (3.12), 4e-15; N = 1000: 4.38 (3.83), 1.7e-14,
//! 6 stages handed back, 5.7 against 9–10.5 ms per step.

mod bordered;
mod couple;
mod eval;
pub(crate) mod iterate;
mod joint_space;
mod maps;
pub(crate) mod place;
mod settle;
pub(crate) mod split;
mod tree;
pub(crate) mod work;

#[cfg(test)]
mod tests;
