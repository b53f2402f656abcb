//! The ground contact's share of the step's tangent map (`tangent`): exact derivatives of a
//! ground point's node residual and of its bristle at the stage's end, by one forward-mode
//! dual-number pass of `contact::ground_law` per direction.
//!
//! Per ground point `p` on body `b` (`contact`'s laws, `hh = h²/2`):
//!
//! ```text
//! R̃_c(q₀, q₁, s₀) = −hh [f n + F ;  Xᵢ f n + X_cᵢ F]         (the node residual it adds)
//! s₁(q₀, q₁, s₀)                                               (the bristle at the end)
//! a twist ξ = (δφ, δθ) at nodes q:  δq = (δφ, δθ × d₁, δθ × d₂, δθ × d₃)
//! Δq = q₁ − q₀,  q̄ = q₀ + ½ Δq:  δΔq = δq₁ − δq₀,  δq̄ = δq₀ + ½ δΔq
//! ```
//!
//! - The Newton matrix's block at the root (`ContactJacobian::Exact`): `P̄ᵀ ∂R̃_c/∂ξ₁`, one
//!   pass per twist component of the end (the projection's own derivative `½ Σ hat(R̃_dᵢ)
//!   hat(dᵢ)` is `body_terms`'s, on the whole node residual).
//! - A column's right-hand side moves both ends by the same ξ and the bristle by `δs₀`:
//!   `δ(P̄ᵀ R̃_c) = P̄ᵀ δR̃_c + [0 ; Σᵢ (δθ × d̄ᵢ) × R̃_c,dᵢ]` (`δd̄ᵢ = δθ × d̄ᵢ`).
//! - The bristle's column at the end: `δs₁` along `(ξ₀ = ξ, ξ₁ = ξ + Y, δs₀)`.
//!
//! The laws are C¹ where they are used (stick, slip and the normal damper's fade; the
//! one-sided spring's kink at first touch aside), so these are the derivatives of the step as
//! it is taken. Body–body features are not covered: the tangent marks itself inexact where one
//! touches (`Tangent::inexact`).

use super::ground_law::ground_law;
use super::work::Work;
use crate::math::Vec3;
use crate::mechanics::model::constraint::{body_nodes, read3, Nodes};
use crate::mechanics::model::contact::GroundRt;
use crate::mechanics::model::kernels::project;
use crate::mechanics::model::scalar::c;
use nalgebra::Vector3;
use num_dual::Dual64;

type D3 = Vector3<Dual64>;

/// The nodes' change `(δφ, δθ × dᵢ)` under the twist `xi` (6) at nodes `q`.
pub(super) fn moved(q: &Nodes, xi: &[f64]) -> Nodes {
    let (dp, dt) = (read3(xi, 0), read3(xi, 3));
    [dp, dt.cross(&q[1]), dt.cross(&q[2]), dt.cross(&q[3])]
}

/// Dual nodes of value `re` and derivative `eps`.
fn dual(re: &Nodes, eps: &Nodes) -> [D3; 4] {
    std::array::from_fn(|k| Vector3::from_fn(|i, _| Dual64::new(re[k][i], eps[k][i])))
}

/// Ground point `k`'s node residual `R̃_c` and bristle `s₁` over the stage in `ws`, along the
/// start twist `xi0`, the end twist `xi1` (6 each, of the point's body) and the bristle `ds0`.
pub(super) fn ground_dual(
    g: &GroundRt,
    k: usize,
    ws: &Work,
    [xi0, xi1]: [&[f64]; 2],
    ds0: &Vec3,
    h: f64,
) -> ([D3; 4], D3) {
    let p = &g.points[k];
    let b = p.body;
    let (q0, q1) = (body_nodes(&ws.qn, b), body_nodes(&ws.q, b));
    let (e0, e1) = (moved(&q0, xi0), moved(&q1, xi1));
    let ed: Nodes = std::array::from_fn(|i| e1[i] - e0[i]);
    let em: Nodes = std::array::from_fn(|i| e0[i] + ed[i] * 0.5);
    let dq = dual(&body_nodes(&ws.dq, b), &ed);
    let qbar = dual(&body_nodes(&ws.qbar, b), &em);
    let q0 = dual(&q0, &e0);
    let s = read3(&ws.bristle, 3 * k);
    let s0 = Vector3::from_fn(|i, _| Dual64::new(s[i], ds0[i]));
    let st = ground_law(p, &g.normal, g.height, [&q0, &dq, &qbar], s0, h);
    let hh = c::<Dual64>(0.5 * h * h);
    let f = g.normal.map(c::<Dual64>) * st.normal.force;
    let fr = st.friction.force;
    let x = p.x.map(c::<Dual64>);
    let mut r = [-(f + fr) * hh, D3::zeros(), D3::zeros(), D3::zeros()];
    for i in 0..3 {
        r[i + 1] = -(f * x[i] + fr * st.xc[i]) * hh;
    }
    (r, st.friction.s1)
}

/// The value and derivative parts of dual nodes.
fn parts(r: &[D3; 4]) -> (Nodes, Nodes) {
    (
        std::array::from_fn(|k| r[k].map(|x| x.re)),
        std::array::from_fn(|k| r[k].map(|x| x.eps)),
    )
}

/// The midpoint directors `d̄ᵢ` of body `b`.
fn dbar(ws: &Work, b: usize) -> [Vec3; 3] {
    let q = body_nodes(&ws.qbar, b);
    [q[1], q[2], q[3]]
}

/// Per ground point, whether it touches at either end of the stage in `ws` (penetration
/// `x₀ > 0` or `x₁ > 0`). One that does not carries no force and ends with its bristle
/// released (`s₁ = 0`) whatever the column: its shares are exactly 0 and are skipped.
pub(super) fn touching_points(g: &GroundRt, ws: &Work, h: f64) -> Vec<bool> {
    g.points
        .iter()
        .map(|p| {
            let b = p.body;
            let (q0, dq, qbar) = (
                body_nodes(&ws.qn, b),
                body_nodes(&ws.dq, b),
                body_nodes(&ws.qbar, b),
            );
            let st = ground_law(p, &g.normal, g.height, [&q0, &dq, &qbar], Vec3::zeros(), h);
            st.x0 > 0.0 || st.x1 > 0.0
        })
        .collect()
}

/// Adds the exact blocks `P̄ᵀ ∂R̃_c/∂ξ₁` of every ground point that touches to
/// `ws.xbody` (row-major 6 × 6), module formulas.
pub(super) fn exact_blocks(g: &GroundRt, ws: &mut Work, h: f64) {
    let zero = [0.0; 6];
    let touching = touching_points(g, ws, h);
    for (k, p) in g.points.iter().enumerate() {
        if !touching[k] {
            continue;
        }
        let d = dbar(ws, p.body);
        for e in 0..6 {
            let mut unit = [0.0; 6];
            unit[e] = 1.0;
            let (r, _) = ground_dual(g, k, ws, [&zero, &unit], &Vec3::zeros(), h);
            let (_, dr) = parts(&r);
            let col = project(&dr, &d);
            let blk = &mut ws.xbody[p.body];
            for row in 0..6 {
                blk[6 * row + e] += col[row];
            }
        }
    }
}

/// Adds the share of every ground point that touches (`touching`) to a column's right-hand
/// side, `δ(P̄ᵀ R̃_c)` with both ends moved by the column's twists `xi` (6 per body) and the
/// bristles by `ds` (3 per point), to `y` (6 per body); module formulas.
pub(super) fn column_share(
    (g, touching): (&GroundRt, &[bool]),
    ws: &Work,
    (xi, ds): (&[f64], &[f64]),
    h: f64,
    y: &mut [f64],
) {
    for (k, p) in g.points.iter().enumerate() {
        if !touching[k] {
            continue;
        }
        let b = p.body;
        let xb = &xi[6 * b..6 * b + 6];
        let ds0 = read3(ds, 3 * k);
        let (r, _) = ground_dual(g, k, ws, [xb, xb], &ds0, h);
        let (rv, dr) = parts(&r);
        let d = dbar(ws, b);
        let mut col = project(&dr, &d);
        let dt = read3(xb, 3);
        let turned = (0..3).fold(Vec3::zeros(), |m, i| m + dt.cross(&d[i]).cross(&rv[i + 1]));
        for i in 0..3 {
            col[3 + i] += turned[i];
        }
        for (yi, ci) in y[6 * b..6 * b + 6].iter_mut().zip(col) {
            *yi += ci;
        }
    }
}

/// The bristles' columns at the stage's end (3 per point, into `ds1`) along the start twists
/// `xi0`, the end twists `xi1` (6 per body) and the start bristles `ds0`; module formulas (a
/// point that does not touch, `touching`, is released: 0).
pub(super) fn bristle_column(
    (g, touching): (&GroundRt, &[bool]),
    ws: &Work,
    [xi0, xi1]: [&[f64]; 2],
    ds0: &[f64],
    h: f64,
    ds1: &mut [f64],
) {
    for (k, p) in g.points.iter().enumerate() {
        if !touching[k] {
            ds1[3 * k..3 * k + 3].fill(0.0);
            continue;
        }
        let b = p.body;
        let at = 6 * b..6 * b + 6;
        let (_, s1) = ground_dual(
            g,
            k,
            ws,
            [&xi0[at.clone()], &xi1[at]],
            &read3(ds0, 3 * k),
            h,
        );
        for i in 0..3 {
            ds1[3 * k + i] = s1[i].eps;
        }
    }
}
