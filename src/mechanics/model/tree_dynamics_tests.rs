use super::*;
use num_dual::Dual64;

/// `exp_small` is exact at `θ = 0` with its first derivative (`d/dε exp(ε v̂) = v̂`), and a
/// third-order approximation away from it.
#[test]
fn small_exponential_is_exact_to_first_order_at_zero() {
    let v = Vector3::new(0.3, -0.7, 0.2);
    let th = v.map(|x| Dual64::new(0.0, x));
    let e = exp_small(&th);
    let want = hat(&v);
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(e[(i, j)].re, if i == j { 1.0 } else { 0.0 });
            assert_eq!(e[(i, j)].eps, want[(i, j)]);
        }
    }
    let th = Vector3::new(1e-3, -2e-3, 3e-3);
    let err = (exp_small(&th) - crate::math::exp_so3(&th)).norm();
    assert!(err < th.norm().powi(3), "{err:e}");
}
