//! The reduced iteration's preallocated workspace, per body (6-vectors and 6 × 6 blocks in
//! the joint-rate and twist coordinates of `maps`), and the stage-start data of each joint.

use crate::math::{Mat3, Vec3};
use crate::mechanics::model::runtime::{covers, Model};

use super::bordered::Couplings;
use super::maps::{Map, V6};
use super::split::{split, JointRow, Split};

/// The configuration of a joint at the stage start that the reparametrization carries.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointStart {
    /// Parent joint-frame axes `a₁, a₂, a₃` (world frame).
    pub a: [Vec3; 3],
    /// Child axis `b₂` (world frame; universal joints, else zero).
    pub b2: Vec3,
    /// `r = p_B − p_A` (m; the slide pairs, else zero).
    pub r: Vec3,
    /// Joint point from the parent's centre of mass (m; zero for the world).
    pub rho_a: Vec3,
    /// Joint point from the child's centre of mass (m).
    pub rho_b: Vec3,
    /// `a₂a₁ᵀ − a₁a₂ᵀ`: the turn about `a₃` is `I + sin ϑ ·skew3 + (cos ϑ − 1)·plane3`
    /// (revolute, cylindrical, planar pairs; else zero).
    pub skew3: Mat3,
    /// `a₁a₁ᵀ + a₂a₂ᵀ` (see `skew3`).
    pub plane3: Mat3,
}

/// Preallocated workspace of the reduced Newton iteration (body-indexed; empty for models it
/// does not cover).
#[derive(Clone, Debug, Default)]
pub(crate) struct RedWork {
    /// Joint increments read off the bodies (`place::read_off`; the universal joints' defects
    /// and the tests' placement `Φ(u)`), 6 slots per body (rotational first; the slots of
    /// absolute rotations are unused, see `eabs`).
    pub u: Vec<V6>,
    /// `R − I` of the absolute rotation increment of spherical children and free roots (the
    /// tests' placement `Φ(u)`).
    pub eabs: Vec<Mat3>,
    /// `R − I` of every body's rotation increment over the stage (placement).
    pub e: Vec<Mat3>,
    /// Every body's centre-of-mass increment (m).
    pub dphi: Vec<Vec3>,
    /// Stage-start joint data, per body (unused for free roots).
    pub start: Vec<JointStart>,
    /// Body residual rows `r_b` (6), then the accumulated wrench `W_b` of the subtree.
    pub w: Vec<V6>,
    /// Reduced residual `P̄ᵀ r` per body (its joint's rates), then the solution `δu`.
    pub res: Vec<V6>,
    /// Body diagonal blocks `K_bb` (row-major 6 × 6), then articulated blocks.
    pub kd: Vec<[[f64; 6]; 6]>,
    /// Child rows, parent columns `K_cp` of the joint loads (per child body).
    pub kcp: Vec<[[f64; 6]; 6]>,
    /// Parent rows, child columns `K_pc` of the joint loads (per child body).
    pub kpc: Vec<[[f64; 6]; 6]>,
    /// Geometric stiffness of the joint equations: rows of the body's joint rates, columns of
    /// its own twist (`xc`) and its parent's (`xp`).
    pub xc: Vec<[[f64; 6]; 6]>,
    /// See `xc`.
    pub xp: Vec<[[f64; 6]; 6]>,
    /// Whether `kcp`, `kpc` of the body hold anything (else they are not read).
    pub coupled: Vec<bool>,
    /// The geometric stiffness's part of `K_pc`: its moment rows and turn columns (3 × 3).
    pub gpc: Vec<[[f64; 3]; 3]>,
    /// `Q` maps at the iterate (set in a Jacobian pass).
    pub q: Vec<Map>,
    /// `P̄` maps at the midpoint (every pass).
    pub p: Vec<Map>,
    /// Factors: maps `Q`, `P̄` of the factored matrix.
    pub fq: Vec<Map>,
    /// See `fq`.
    pub fp: Vec<Map>,
    /// Factors: `D⁻¹` (f × f).
    pub dinv: Vec<[[f64; 6]; 6]>,
    /// Factors: `Y = D⁻¹ S̄ᵀ (K A + K_cp)` (f × 6).
    pub y: Vec<[[f64; 6]; 6]>,
    /// Factors: `H = Āᵀ K + K_pc` (6 × 6).
    pub hm: Vec<[[f64; 6]; 6]>,
    /// Solve scratch: bias of the eliminated subtree (6) and `D⁻¹ e` (f).
    pub bias: Vec<V6>,
    /// See `bias`.
    pub yv: Vec<V6>,
    /// Body twist updates `δx` of the last solve.
    pub dx: Vec<V6>,
    /// The joints' defects at the iterate as body twists (`place::defects`).
    pub c: Vec<V6>,
    /// The couplings' bordered solve (`couple`).
    pub cpl: Couplings,
    /// Per joint: its split if its loads are taken in joint space (`joint_space`).
    pub split: Vec<Option<Split>>,
    /// Per body: what its joint added in joint space in the last evaluation (where `jon`).
    pub jrow: Vec<JointRow>,
    /// See `jrow`.
    pub jon: Vec<bool>,
}

impl RedWork {
    /// Workspace for `model` (empty unless [`covers`]).
    pub fn new(model: &Model) -> Self {
        if !covers(model) {
            return Self::default();
        }
        let nb = model.bodies.len();
        let z6 = [[0.0; 6]; 6];
        let js = JointStart {
            a: [Vec3::zeros(); 3],
            b2: Vec3::zeros(),
            r: Vec3::zeros(),
            rho_a: Vec3::zeros(),
            rho_b: Vec3::zeros(),
            skew3: Mat3::zeros(),
            plane3: Mat3::zeros(),
        };
        Self {
            u: vec![[0.0; 6]; nb],
            eabs: vec![Mat3::zeros(); nb],
            e: vec![Mat3::zeros(); nb],
            dphi: vec![Vec3::zeros(); nb],
            start: vec![js; nb],
            w: vec![[0.0; 6]; nb],
            res: vec![[0.0; 6]; nb],
            kd: vec![z6; nb],
            kcp: vec![z6; nb],
            kpc: vec![z6; nb],
            xc: vec![z6; nb],
            xp: vec![z6; nb],
            coupled: vec![false; nb],
            gpc: vec![[[0.0; 3]; 3]; nb],
            q: vec![Map::free(); nb],
            p: vec![Map::free(); nb],
            fq: vec![Map::free(); nb],
            fp: vec![Map::free(); nb],
            dinv: vec![z6; nb],
            y: vec![z6; nb],
            hm: vec![z6; nb],
            bias: vec![[0.0; 6]; nb],
            yv: vec![[0.0; 6]; nb],
            dx: vec![[0.0; 6]; nb],
            c: vec![[0.0; 6]; nb],
            cpl: Couplings::new(model),
            split: (0..model.joints.len()).map(|j| split(model, j)).collect(),
            jrow: vec![JointRow::default(); nb],
            jon: vec![false; nb],
        }
    }
}
