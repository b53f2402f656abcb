//! Unit tests of the tree elimination against dense LU solves.
use super::*;

/// Deterministic uniform numbers in `[−½, ½)`.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }
}

/// A random tree system with supernode sizes `6 + ms[b]`: `K` diagonally dominant, random
/// `C`, `U`; if `general`, random `B`, `L` and μμ block `E`, else the real pattern: `E = 0`
/// and `B`, `L_μ` close to the transposes of `C`, `U_μ` (not equal: the matrix is not
/// symmetric).
/// Returns the blocks (right-hand sides set) and the dense copy `(a, nt, offsets)`.
fn system(
    parent: &[Option<usize>],
    ms: &[usize],
    general: bool,
    rng: &mut Rng,
) -> (Vec<Block>, Vec<f64>, usize, Vec<usize>) {
    let mut blocks: Vec<Block> = ms.iter().map(|&m| Block::new(6 + m)).collect();
    for (c, b) in blocks.iter_mut().enumerate() {
        for i in 0..b.n {
            for j in 0..b.n {
                let v = if i < 6 && j < 6 {
                    rng.next() + if i == j { 4.0 } else { 0.0 }
                } else if i >= 6 && j >= 6 && !general {
                    0.0
                } else {
                    rng.next()
                };
                b.d[i * NMAX + j] = v;
            }
            b.r[i] = rng.next();
        }
        if !general {
            // as in the Newton matrix: independent joint rows (C of full rank, here a
            // perturbed unit matrix: joint gradients are close to orthonormal) and
            // B = Cᵀ + a small non-symmetric part (gradients at q̄ and at q)
            for k in 6..b.n {
                b.d[k * NMAX + (k + 3 * c) % 6] += 2.0;
            }
            for i in 0..6 {
                for j in 6..b.n {
                    b.d[i * NMAX + j] = b.d[j * NMAX + i] + 0.05 * rng.next();
                }
            }
        }
        if parent[c].is_some() {
            // as in the Newton matrix: body–body couplings O(h²), the joint rows' parent
            // columns U_μ O(1), the parent's multiplier columns L_μ ≈ U_μᵀ (so that the
            // Schur updates of the parent's K are close to positive semi-definite)
            for i in 0..b.n {
                let s = if i < 6 && !general { 0.05 } else { 1.0 };
                for j in 0..6 {
                    b.u[i * 6 + j] = s * rng.next();
                    b.l[j * NMAX + i] = if i >= 6 && !general {
                        b.u[i * 6 + j] + 0.05 * rng.next()
                    } else {
                        s * rng.next()
                    };
                }
            }
        }
    }
    let (a, nt, off) = dense_of(&blocks, parent);
    (blocks, a, nt, off)
}

/// The dense matrix `(a, nt, offsets)` of a tree system.
fn dense_of(blocks: &[Block], parent: &[Option<usize>]) -> (Vec<f64>, usize, Vec<usize>) {
    let off: Vec<usize> = blocks
        .iter()
        .scan(0, |s, b| {
            let o = *s;
            *s += b.n;
            Some(o)
        })
        .collect();
    let nt: usize = blocks.iter().map(|b| b.n).sum();
    let mut a = vec![0.0; nt * nt];
    for (c, b) in blocks.iter().enumerate() {
        for i in 0..b.n {
            for j in 0..b.n {
                a[(off[c] + i) * nt + off[c] + j] = b.d[i * NMAX + j];
            }
        }
        if let Some(p) = parent[c] {
            for i in 0..b.n {
                for j in 0..6 {
                    a[(off[c] + i) * nt + off[p] + j] = b.u[i * 6 + j];
                    a[(off[p] + j) * nt + off[c] + i] = b.l[j * NMAX + i];
                }
            }
        }
    }
    (a, nt, off)
}

/// Dense solution of `a x = r` for the right-hand sides held in the blocks.
fn dense_solve(a: &[f64], nt: usize, off: &[usize], blocks: &[Block]) -> Dense {
    let mut f = a.to_vec();
    let mut rhs = vec![0.0; nt];
    for (c, b) in blocks.iter().enumerate() {
        rhs[off[c]..off[c] + b.n].copy_from_slice(&b.r[..b.n]);
    }
    let mut x = rhs.clone();
    let mut piv = vec![0; nt];
    assert!(lu_factor(&mut f, nt, nt, &mut piv, 1e-14));
    lu_solve(&f, nt, nt, &piv, &mut x);
    Dense {
        a: a.to_vec(),
        rhs,
        x,
    }
}

/// A dense system, its right-hand side and its LU solution.
struct Dense {
    a: Vec<f64>,
    rhs: Vec<f64>,
    x: Vec<f64>,
}

/// Max norm.
fn norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// Relative residual `‖A x − r‖ / (‖A‖ ‖x‖ + ‖r‖)` (max norms).
fn residual(d: &Dense, x: &[f64]) -> f64 {
    let nt = d.rhs.len();
    let amax = (0..nt)
        .map(|i| norm(&d.a[i * nt..(i + 1) * nt]) * nt as f64)
        .fold(0.0, f64::max);
    let res: Vec<f64> = (0..nt)
        .map(|i| (0..nt).map(|j| d.a[i * nt + j] * x[j]).sum::<f64>() - d.rhs[i])
        .collect();
    norm(&res) / (amax * norm(x) + norm(&d.rhs))
}

/// The tree solution in the blocks is backward stable (relative residual at round-off) and
/// agrees with the dense LU solution.
fn assert_close(blocks: &[Block], off: &[usize], d: &Dense) {
    let mut x = vec![0.0; d.rhs.len()];
    for (c, b) in blocks.iter().enumerate() {
        x[off[c]..off[c] + b.n].copy_from_slice(&b.r[..b.n]);
    }
    let (rt, rd) = (residual(d, &x), residual(d, &d.x));
    let diff: Vec<f64> = x.iter().zip(&d.x).map(|(a, b)| a - b).collect();
    assert!(rt < 1e-15, "tree residual {rt:e} (dense {rd:e})");
    assert!(norm(&diff) < 1e-12 * norm(&d.x), "{diff:?}");
}

/// The tree elimination reproduces a dense solve of the same system (general diagonal
/// blocks, non-zero μμ block included).
#[test]
fn tree_matches_dense() {
    // chain 0 ← 1 ← 2 plus 3 attached to 1; sizes 6+5, 6+5, 6+3, 6+0
    let parent = [None, Some(0), Some(1), Some(1)];
    let mut rng = Rng(1);
    let (mut blocks, a, nt, off) = system(&parent, &[5, 5, 3, 0], true, &mut rng);
    let x = dense_solve(&a, nt, &off, &blocks);
    assert!(solve_tree(&mut blocks, &[0, 1, 2, 3], &parent));
    assert_close(&blocks, &off, &x);
}

/// The real `[K B; C 0]` pattern for every row count 0..=6 (3, 5, 6 and 0 at leaves,
/// inner nodes and the root), as one tree and as single supernodes.
#[test]
fn saddle_blocks_match_dense() {
    // 0 (root) ← 1 ← 2 ← 3, 1 ← 4, 0 ← 5 ← 6, 5 ← 7
    let parent = [
        None,
        Some(0),
        Some(1),
        Some(2),
        Some(1),
        Some(0),
        Some(5),
        Some(5),
    ];
    let order = [0, 1, 2, 3, 4, 5, 6, 7];
    let mut rng = Rng(7);
    for ms in [
        [0, 3, 5, 6, 0, 6, 3, 5],
        [6, 5, 0, 3, 6, 1, 2, 4],
        [3, 0, 6, 5, 3, 0, 0, 6],
    ] {
        let (mut blocks, a, nt, off) = system(&parent, &ms, false, &mut rng);
        let x = dense_solve(&a, nt, &off, &blocks);
        assert!(solve_tree(&mut blocks, &order, &parent));
        assert_close(&blocks, &off, &x);
    }
    // the projection system has no body–body couplings between bodies (U_x = L_x = 0)
    let (mut blocks, a, nt, off) = {
        let (mut blocks, ..) = system(&parent, &[5, 3, 6, 0, 5, 2, 4, 6], false, &mut rng);
        for b in &mut blocks {
            b.u[..36].fill(0.0);
            for j in 0..6 {
                b.l[j * NMAX..j * NMAX + 6].fill(0.0);
            }
        }
        let (a, nt, off) = dense_of(&blocks, &parent);
        (blocks, a, nt, off)
    };
    let x = dense_solve(&a, nt, &off, &blocks);
    assert!(solve_tree(&mut blocks, &order, &parent));
    assert_close(&blocks, &off, &x);
    for m in 0..=6 {
        let (mut blocks, a, nt, off) = system(&[None], &[m], false, &mut rng);
        let x = dense_solve(&a, nt, &off, &blocks);
        assert!(solve_tree(&mut blocks, &[0], &[None]));
        assert_close(&blocks, &off, &x);
    }
}

/// One factorisation serves several right-hand sides; the factorisation leaves `r` alone.
#[test]
fn factor_once_solve_twice() {
    let parent = [None, Some(0), Some(1), Some(1), Some(3)];
    let order = [0, 1, 3, 4, 2];
    let mut rng = Rng(3);
    let (mut blocks, a, nt, off) = system(&parent, &[6, 5, 3, 0, 6], false, &mut rng);
    let r0: Vec<[f64; NMAX]> = blocks.iter().map(|b| b.r).collect();
    let x1 = dense_solve(&a, nt, &off, &blocks);
    assert!(factor_tree(&mut blocks, &order, &parent));
    for (b, r) in blocks.iter().zip(&r0) {
        assert_eq!(b.r, *r, "factor_tree touched r");
    }
    solve_factored(&mut blocks, &order, &parent);
    assert_close(&blocks, &off, &x1);
    // a new right-hand side, written as the assembly does (zero, then add)
    for b in &mut blocks {
        b.r.fill(0.0);
        for i in 0..b.n {
            b.r[i] += 3.0 * rng.next();
        }
    }
    let x2 = dense_solve(&a, nt, &off, &blocks);
    solve_factored(&mut blocks, &order, &parent);
    assert_close(&blocks, &off, &x2);
}

/// Singular blocks are reported: dependent constraint rows (`S` singular), a zero body
/// block, a non-finite entry.
#[test]
fn singular_block_fails() {
    let parent = [None, Some(0)];
    let order = [0, 1];
    let mut rng = Rng(11);
    // two equal rows of C on the leaf
    let (mut blocks, ..) = system(&parent, &[3, 4], false, &mut rng);
    for j in 0..6 {
        blocks[1].d[7 * NMAX + j] = blocks[1].d[6 * NMAX + j];
    }
    assert!(!factor_tree(&mut blocks, &order, &parent));
    // zero multiplier columns on the root
    let (mut blocks, ..) = system(&parent, &[3, 4], false, &mut rng);
    for i in 0..6 {
        blocks[0].d[i * NMAX + 8] = 0.0;
    }
    assert!(!solve_tree(&mut blocks, &order, &parent));
    // zero body block
    let (mut blocks, ..) = system(&parent, &[0, 2], false, &mut rng);
    blocks[1].d.fill(0.0);
    assert!(!factor_tree(&mut blocks, &order, &parent));
    // NaN
    let (mut blocks, ..) = system(&parent, &[2, 2], false, &mut rng);
    blocks[0].d[6 * NMAX + 1] = f64::NAN;
    assert!(!factor_tree(&mut blocks, &order, &parent));
}

/// A supernode whose body block `K` is singular while `D = [K B; C 0]` is regular (a massless
/// body: `K` holds only the children's updates) fails through `K` and is solved when factored
/// whole; whole and structured factorisations agree where both apply.
#[test]
fn whole_blocks_solve_a_singular_body_block() {
    let parent = [None, Some(0), Some(1), Some(1)];
    let order = [0, 1, 2, 3];
    let mut rng = Rng(5);
    for ms in [[6, 5, 6, 3], [5, 6, 5, 5], [3, 6, 4, 6]] {
        // a rank-deficient K on the leaf 2: its first three rows and columns (the translations
        // of a massless body) zero; D stays regular as C (m ≥ 4 rows) covers them
        let (mut blocks, ..) = system(&parent, &ms, false, &mut rng);
        for i in 0..6 {
            for j in 0..6 {
                if i < 3 || j < 3 {
                    blocks[2].d[i * NMAX + j] = 0.0;
                }
            }
        }
        let (a, nt, off) = dense_of(&blocks, &parent);
        let x = dense_solve(&a, nt, &off, &blocks);
        let mut through_k = blocks.clone();
        assert!(!factor_tree(&mut through_k, &order, &parent), "{ms:?}");
        blocks[2].whole = true;
        assert!(solve_tree(&mut blocks, &order, &parent), "{ms:?}");
        assert_close(&blocks, &off, &x);
    }
    // every block whole on a regular system: the same solution
    let (mut blocks, a, nt, off) = system(&parent, &[5, 3, 6, 0], false, &mut rng);
    let x = dense_solve(&a, nt, &off, &blocks);
    blocks.iter_mut().for_each(|b| b.whole = true);
    assert!(solve_tree(&mut blocks, &order, &parent));
    assert_close(&blocks, &off, &x);
}

/// The lanes' solve gives each lane the one-column solve's solution (to round-off), with a
/// supernode factored whole among them and an unused lane left at zero.
#[test]
fn lanes_match_single_solves() {
    use super::lanes::{solve_factored_lanes, Lanes, LANES};
    let parent = [None, Some(0), Some(1), Some(1), Some(3)];
    let order = [0, 1, 3, 4, 2];
    let mut rng = Rng(7);
    let (mut blocks, ..) = system(&parent, &[6, 5, 3, 0, 6], false, &mut rng);
    blocks[3].whole = true;
    assert!(factor_tree(&mut blocks, &order, &parent));
    let width = LANES - 1;
    let rhs: Vec<Vec<[f64; NMAX]>> = (0..width)
        .map(|_| {
            blocks
                .iter()
                .map(|b| std::array::from_fn(|i| if i < b.n { rng.next() } else { 0.0 }))
                .collect()
        })
        .collect();
    let mut lanes: Vec<Lanes> = vec![[[0.0; LANES]; NMAX]; blocks.len()];
    for (l, r) in rhs.iter().enumerate() {
        for (b, rb) in r.iter().enumerate() {
            for i in 0..NMAX {
                lanes[b][i][l] = rb[i];
            }
        }
    }
    solve_factored_lanes(&blocks, &order, &parent, &mut lanes);
    for (l, r) in rhs.iter().enumerate() {
        for (b, rb) in blocks.iter_mut().zip(r) {
            b.r = *rb;
        }
        solve_factored(&mut blocks, &order, &parent);
        for (b, lb) in blocks.iter().zip(&lanes) {
            for i in 0..b.n {
                let (one, many) = (b.r[i], lb[i][l]);
                assert!(
                    (one - many).abs() <= 1e-13 * (1.0 + one.abs()),
                    "{one} {many}"
                );
            }
        }
    }
    assert!(lanes
        .iter()
        .all(|lb| lb.iter().all(|row| row[LANES - 1] == 0.0)));
}
