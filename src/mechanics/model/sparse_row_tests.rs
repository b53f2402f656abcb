//! The sparse row kernels reproduce the dense [`DotRow`] formulas bit for bit.
use super::*;
use crate::mechanics::model::kernels::project as dense_project;

fn nodes_of(s: f64) -> Nodes {
    std::array::from_fn(|k| {
        let x = s + k as f64;
        Vec3::new(x.sin(), (1.3 * x).cos(), 0.2 * x - 0.7)
    })
}

/// A point row (linear), an axis row and a row with both factors over several nodes.
fn rows() -> Vec<DotRow> {
    let pb = LinVec::point_b(&Vec3::new(0.2, -0.1, 0.4));
    let pa = LinVec::point_a(&Vec3::new(-0.3, 0.0, 0.1));
    let r = pb.sub(&pa);
    vec![
        DotRow::component(r, Vec3::new(0.0, 0.6, 0.8)),
        DotRow::new(
            LinVec::axis_a(&Vec3::new(1.0, 0.0, 0.0)),
            LinVec::axis_b(&Vec3::new(0.0, 0.0, 1.0)),
            0.0,
        ),
        DotRow::new(r, LinVec::axis_a(&Vec3::new(0.1, 0.2, 0.97)), 0.25),
        DotRow::new(
            LinVec::point_b(&Vec3::new(0.0, 0.3, 0.0)),
            LinVec::axis_b(&Vec3::new(0.0, 1.0, 0.0)),
            0.1,
        ),
    ]
}

fn hess_dense(row: &DotRow, hc: f64, has_a: bool) -> [[f64; 16]; 3] {
    let s = row.hessian();
    let mut out = [[0.0; 16]; 3];
    for n in 0..4 {
        for m in 0..4 {
            if has_a {
                out[0][4 * n + m] = hc * s[n][m];
                out[2][4 * n + m] = hc * s[n][4 + m];
            }
            out[1][4 * n + m] = hc * s[4 + n][4 + m];
        }
    }
    out
}

#[test]
fn sparse_matches_dense() {
    let (qa, qb) = (nodes_of(0.3), nodes_of(1.7));
    let zero = [Vec3::zeros(); 4];
    let d: [Vec3; 3] = [qa[1], qb[2], qa[3]];
    for row in rows() {
        for has_a in [true, false] {
            // a world parent has zero nodes in the step (its coordinates live in `c`)
            let row = if has_a {
                row
            } else {
                let mut r = row;
                r.u.a = [0.0; 4];
                r.w.a = [0.0; 4];
                r
            };
            let qa = if has_a { qa } else { zero };
            let sr = SparseRow::new(&row, has_a);
            let (u, w) = sr.uw(&qa, &qb);
            assert_eq!(u, row.u.eval(&qa, &qb));
            assert_eq!(w, row.w.eval(&qa, &qb));
            assert_eq!(sr.value(&u, &w), row.eval(&qa, &qb));
            let mut buf = [Vec3::zeros(); 8];
            let g = *sr.grad(&u, &w, &mut buf);
            let mut buf2 = [Vec3::zeros(); 8];
            assert_eq!(sr.expand(sr.grad_at(&qa, &qb, &mut buf2)), sr.expand(&g));
            let mut gd = [Vec3::zeros(); 8];
            row.gradient(&qa, &qb, &mut gd);
            assert_eq!(sr.expand(&g), gd);
            let (mut fa, mut fb) = ([Vec3::zeros(); 4], [Vec3::zeros(); 4]);
            sr.add_forces(&g, 0.7, &mut fa, &mut fb);
            for k in 0..4 {
                if has_a {
                    assert_eq!(fa[k], gd[k] * 0.7);
                }
                assert_eq!(fb[k], gd[4 + k] * 0.7);
            }
            for (side, range) in [(Side::A, 0..4), (Side::B, 4..8)] {
                let dense = dense_project(&gd[range], &d);
                let sparse = sr.project(&g, side, &d).unwrap_or([0.0; 6]);
                assert_eq!(sparse, dense);
            }
            let mut cb = [[0.0; 16]; 2];
            let mut cab = [0.0; 16];
            sr.add_hessian(0.35, &mut cb, has_a.then_some(0), 1, &mut cab);
            let hd = hess_dense(&row, 0.35, has_a);
            for e in 0..16 {
                assert!((cb[0][e] - hd[0][e]).abs() <= 1e-15, "A-A");
                assert!((cb[1][e] - hd[1][e]).abs() <= 1e-15, "B-B");
                assert!((cab[e] - hd[2][e]).abs() <= 1e-15, "A-B");
            }
        }
    }
}
