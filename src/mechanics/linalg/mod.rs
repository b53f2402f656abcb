//! Layer 0, the linear algebra: dense fixed-size blocks and the solves of the Newton and
//! projection systems. Knows nothing of bodies or joints: a tree is a parent array, an
//! elimination order and one block per node.
//!
//! - `small_mat`: row-major fixed-size matrix kernels (load, multiply, invert, store);
//! - `dense`: LU with partial pivoting (the test oracle and the small Schur systems);
//! - `tree`: the O(N) block factorisation of a tree-structured KKT matrix (Baraff's supernodes:
//!   a body's 6 unknowns with the rows of its tree joint), factor/solve split for chord
//!   iterations;
//! - `border`: the bordered solve of a tree plus the rows and couplings of loop-closing joints
//!   (`W = A⁻¹P`, a small dense Schur system).
//!
//! Uses: `crate::math` only.

pub(crate) mod border;
pub(crate) mod dense;
pub(crate) mod small_mat;
pub(crate) mod tree;
