use super::*;

#[test]
fn small_exponential_is_exact_to_first_order_at_zero() {
    let th = Vector3::new(1e-4, -2e-4, 3e-4);
    let e = exp_small(&th);
    let r = crate::math::exp_so3(&th);
    assert!((e - r).norm() < 1e-11);
}
