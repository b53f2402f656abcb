//! Small kernels of the Newton residual and Jacobian, on the nodes of one body: the reciprocal
//! basis `dⁱ` (`dⁱ·dⱼ = δᵢⱼ`) and the discrete rotation increment `θ = ½ Σᵢ d̄ⁱ × Δdᵢ`, the
//! projected blocks `P̄ᵀ (C ⊗ I) Q`, the torque Jacobians and the accurate `exp(θ̂) − I`.
//! Where the blocks go in the linear system is `sink`.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::constraint::{read3, write3, Nodes};
use crate::math::{skew, Mat3, Vec3};

/// Reciprocal basis `dⁱ` of `d₁, d₂, d₃`.
#[inline]
pub(crate) fn reciprocal(d: &[Vec3; 3]) -> [Vec3; 3] {
    let det = d[0].dot(&d[1].cross(&d[2]));
    let s = 1.0 / det;
    [
        d[1].cross(&d[2]) * s,
        d[2].cross(&d[0]) * s,
        d[0].cross(&d[1]) * s,
    ]
}

/// `θ = ½ Σᵢ d̄ⁱ × (dᵢ − dᵢₙ)` for body nodes at the start `n` and the iterate `q`.
#[inline]
pub(crate) fn rotation_increment(n: &Nodes, q: &Nodes) -> Vec3 {
    let dbar = [
        (n[1] + q[1]) * 0.5,
        (n[2] + q[2]) * 0.5,
        (n[3] + q[3]) * 0.5,
    ];
    let rec = reciprocal(&dbar);
    let mut t = Vec3::zeros();
    for i in 0..3 {
        t += rec[i].cross(&(q[i + 1] - n[i + 1]));
    }
    t * 0.5
}

/// The 6 × 6 block `P̄_aᵀ (C ⊗ I) Q_b` (row body `a` with midpoint directors `dbar`, column
/// body `b` with iterate directors `d`), added to `out` (row-major).
pub(crate) fn node_block(c: &[f64; 16], dbar: &[Vec3; 3], d: &[Vec3; 3], out: &mut [f64; 36]) {
    // with hat(a) hat(b) = b aᵀ − (a·b) I every 3 × 3 block is a few outer products:
    // pt = −Σⱼ c₀ⱼ hat(dⱼ) = −hat(p),  mp = Σᵢ cᵢ₀ hat(d̄ᵢ) = hat(s),
    // mt = −Σᵢ hat(d̄ᵢ) hat(wᵢ) = Σᵢ (d̄ᵢ·wᵢ) I − wᵢ d̄ᵢᵀ,  wᵢ = Σⱼ cᵢⱼ dⱼ
    let p = d[0] * c[1] + d[1] * c[2] + d[2] * c[3];
    let sv = dbar[0] * c[4] + dbar[1] * c[8] + dbar[2] * c[12];
    let mut mt = [[0.0; 3]; 3];
    let mut tr = 0.0;
    for i in 0..3 {
        let o = 4 * (i + 1);
        let w = d[0] * c[o + 1] + d[1] * c[o + 2] + d[2] * c[o + 3];
        tr += dbar[i].dot(&w);
        for r in 0..3 {
            for s in 0..3 {
                mt[r][s] -= w[r] * dbar[i][s];
            }
        }
    }
    for r in 0..3 {
        out[r * 6 + r] += c[0];
        out[(r + 3) * 6 + 3 + r] += tr;
        for s in 0..3 {
            out[(r + 3) * 6 + 3 + s] += mt[r][s];
        }
    }
    // −hat(p) into rows φ, columns θ and hat(s) into rows θ, columns φ, written out
    // (hat(v) = [0 −v_z v_y; v_z 0 −v_x; −v_y v_x 0], its zero diagonal left out)
    out[4] += p.z;
    out[5] -= p.y;
    out[9] -= p.z;
    out[11] += p.x;
    out[15] += p.y;
    out[16] -= p.x;
    out[19] -= sv.z;
    out[20] += sv.y;
    out[24] += sv.z;
    out[26] -= sv.x;
    out[30] -= sv.y;
    out[31] += sv.x;
}

/// `P̄ᵀ` applied to one body's node vectors: `[f_φ ; Σ d̄ᵢ × f_{dᵢ}]`.
#[inline]
pub(crate) fn project(f: &[Vec3], dbar: &[Vec3; 3]) -> [f64; 6] {
    let m = dbar[0].cross(&f[1]) + dbar[1].cross(&f[2]) + dbar[2].cross(&f[3]);
    [f[0].x, f[0].y, f[0].z, m.x, m.y, m.z]
}

/// Row vector `∇g · Q` of one body: `[∇_φ ; Σ dᵢ × ∇_{dᵢ}]`.
#[inline]
pub(crate) fn row_q(f: &[Vec3], d: &[Vec3; 3]) -> [f64; 6] {
    project(f, d)
}

/// `∂(LinVec at q̄)/∂x` for the A or B coefficients `k`: 3 × 6 (row-major) `½[k₀ I, −Σ kᵢ hat(dᵢ)]`.
pub(crate) fn linvec_jac(k: &[f64; 4], d: &[Vec3; 3]) -> [f64; 18] {
    let mut out = [0.0; 18];
    let mut m = Mat3::zeros();
    for i in 0..3 {
        m -= skew(&d[i]) * k[i + 1];
    }
    for r in 0..3 {
        out[r * 6 + r] = 0.5 * k[0];
        for s in 0..3 {
            out[r * 6 + 3 + s] = 0.5 * m[(r, s)];
        }
    }
    out
}

/// Adds the scaled joint torque `t` (already times `h²/2`) to the projected moment rows:
/// `−t` on the child, `+t` on the parent. Consistent director forces `½ t × d̄ⁱ` project to
/// exactly `t` for any basis, so the pair enters the moment rows directly.
pub(crate) fn push_torque(mom: &mut [f64], child: usize, parent: Option<usize>, t: &Vec3) {
    let v = read3(mom, 3 * child) - t;
    write3(mom, 3 * child, &v);
    if let Some(a) = parent {
        let v = read3(mom, 3 * a) + t;
        write3(mom, 3 * a, &v);
    }
}

/// `out += s · col ⊗ row` (6 × 6).
pub(crate) fn outer(out: &mut [f64; 36], s: f64, col: &[f64; 6], row: &[f64; 6]) {
    for r in 0..6 {
        for c in 0..6 {
            out[r * 6 + c] += s * col[r] * row[c];
        }
    }
}

/// Jacobian of the moments `−t n̄` (child) and `+t n̄` (parent) through `n̄(q̄)`, `t = hh·τ`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn torque_jac(
    x_bb: &mut [f64; 36],
    x_ba: &mut [f64; 36],
    x_ab: &mut [f64; 36],
    x_aa: &mut [f64; 36],
    t: f64,
    jb: &[f64; 18],
    ja: &[f64; 18],
    has_a: bool,
) {
    for r in 0..3 {
        for c in 0..6 {
            x_bb[(r + 3) * 6 + c] -= t * jb[r * 6 + c];
            if has_a {
                x_ba[(r + 3) * 6 + c] -= t * ja[r * 6 + c];
                x_ab[(r + 3) * 6 + c] += t * jb[r * 6 + c];
                x_aa[(r + 3) * 6 + c] += t * ja[r * 6 + c];
            }
        }
    }
}

/// `exp(θ̂) − I = s θ̂ + c θ̂²` without the cancellation of subtracting `I`
/// (`c = 2 sin²(|θ|/2)/|θ|²`), so that director increments stay accurate to round-off.
#[must_use]
pub(crate) fn expm1_so3(theta: &Vec3) -> Mat3 {
    let a2 = theta.norm_squared();
    let k = skew(theta);
    let (s, c) = if a2 < 1e-8 {
        (
            1.0 - a2 / 6.0 * (1.0 - a2 / 20.0),
            0.5 - a2 / 24.0 * (1.0 - a2 / 30.0),
        )
    } else {
        let a = a2.sqrt();
        let sh = (0.5 * a).sin();
        (a.sin() / a, 2.0 * sh * sh / a2)
    };
    k * s + k * k * c
}
