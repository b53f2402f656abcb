//! Joint frames are exact for any axis: a revolute axis tilted from a coordinate axis by t
//! (0, and 1e-15 … 1e-6 rad, as CAD exports write them: `-1.3e-08 -1.0000003 0`) gives body
//! orientations orthonormal to round-off, `|RᵀR − I| ≤ 1e-14` after 1 000 steps at orders 2
//! and 4. (A tilt whose normalised axis rounds to a coordinate component of exactly ±1 once
//! took the coordinate axis's permutation frame while keeping the tilted axis, a frame off by
//! t, and every body below turned non-orthonormal by ≈ 2t per such joint.)

mod common;
use common::build;
use triad::math::Mat3;
use triad::mechanics::step;
use triad::urdf::{import, ImportOptions};

fn chain_with_tilt(t: f64) -> String {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf/tilted_chain.urdf"),
    )
    .unwrap();
    // the axes of the file, each tilted by t (its direction cosines written unnormalised)
    text.replace("-1.3e-08 -1.0000003 0", &format!("{:e} -1.0000003 0", -t))
        .replace("1 0 1.3e-08", &format!("1 0 {t:e}"))
        .replace("0 -1.3e-08 1", &format!("0 {:e} 1", -t))
}

#[test]
fn tilted_axes_keep_the_bodies_orthonormal() {
    for order in [2u8, 4] {
        for t in [0.0, 1e-15, 1e-13, 1e-11, 1.3e-8, 1e-8, 1.8e-8, 1e-7, 1e-6] {
            let (spec, _) = import(
                &chain_with_tilt(t),
                "tilted_chain.urdf",
                &ImportOptions::default(),
            )
            .unwrap_or_else(|e| panic!("{e}"));
            let (mut def, _) = spec.lower().unwrap();
            for (k, j) in def.joints.iter_mut().enumerate() {
                common::set_q(j, &[0.3 + 0.2 * k as f64], &[1.0 - 0.7 * k as f64]);
            }
            let (model, mut state) = build(&def, common::settings(1e-3, order));
            let worst = |state: &triad::mechanics::State| {
                state
                    .outputs()
                    .bodies
                    .iter()
                    .map(|b| (b.rot.transpose() * b.rot - Mat3::identity()).amax())
                    .fold(0.0, f64::max)
            };
            assert!(
                worst(&state) <= 1e-14,
                "t = {t:e}, order {order}: at t = 0: {:e}",
                worst(&state)
            );
            for _ in 0..1000 {
                step(&model, &mut state, 1e-3).unwrap();
            }
            assert!(
                worst(&state) <= 1e-14,
                "t = {t:e}, order {order}: |RᵀR − I| = {:e}",
                worst(&state)
            );
        }
    }
}
