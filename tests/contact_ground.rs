//! Contact with the ground (`[ground]`, `[[collision]]`; `model::contact_law`): the forces are
//! exact discrete gradients and dissipative terms, so `energy − work` stays at round-off through
//! impacts, sliding and rolling, and the motions follow their analytic references:
//!
//! ```text
//! elastic ball, 100 bounces:           |E − W − E₀| ≤ 1e-12 |E₀|   (fixed steps and error control)
//! Hunt–Crossley restitution e:         x − ln(1 + x) = −y − ln(1 − y),  x = d v_in, y = d v_out
//! sliding box:                          stopping distance v₀²/(2μg), ΔE = W
//! ball thrown sliding without spin:     rolls at v = 5/7 v₀ from t = 2v₀/(7μg)
//! box tumbling onto corners and edges:  E − W at round-off, orders 2 and 4; at rest with damping
//! ```

mod common;

use common::spec_model as model;
use triad::mechanics::{controlled_step, step, State, Verdict};

/// A ball of mass 1 kg, radius 0.1 m (inertia 2/5 m r²) at height `z` with velocity `v` and
/// angular velocity `w`, on a ground with friction `mu`, stiffness `k`, damping `d`.
#[allow(clippy::too_many_arguments)]
fn ball(
    z: f64,
    v: [f64; 3],
    w: [f64; 3],
    mu: f64,
    k: f64,
    d: f64,
    gravity: f64,
    solver: &str,
) -> String {
    format!(
        "name = \"Ball\"\ngravity = [0.0, 0.0, {g}]\n[solver]\n{solver}\n\
         [ground]\nfriction = {mu}\nstiffness = {k}\ndamping = {d}\n\
         [[body]]\nname = \"ball\"\nmass = 1.0\ninertia = [0.004, 0.004, 0.004]\n\
         position = [0.0, 0.0, {z}]\nvelocity = {v:?}\nangular_velocity = {w:?}\n\
         [[collision]]\nname = \"shell\"\nbody = \"ball\"\nsphere = {{ radius = 0.1 }}\n",
        g = -gravity
    )
}

fn drift(s: &State, e0: f64) -> f64 {
    let o = s.outputs();
    (o.energy - o.work - e0).abs() / e0.abs()
}

#[test]
fn an_elastic_ball_bounces_100_times_with_exact_energy() {
    // 0.5 m above the ground: a bounce every 0.64 s
    let text = ball(
        0.6,
        [0.3, 0.0, 0.0],
        [0.0, 2.0, 0.0],
        0.5,
        1e5,
        0.0,
        9.81,
        "max_step = 1e-3",
    );
    let (m, mut s) = model(&text);
    let e0 = s.outputs().energy;
    let (mut bounces, mut touching, mut worst) = (0, false, 0.0_f64);
    while bounces < 100 {
        step(&m, &mut s, 1e-3).unwrap();
        let gap = s.outputs().contacts[0].gap;
        if gap < 0.0 && !touching {
            bounces += 1;
        }
        touching = gap < 0.0;
        worst = worst.max(drift(&s, e0));
        assert!(s.time() < 100.0, "only {bounces} bounces");
    }
    eprintln!("100 bounces at h = 1e-3: |E − W − E₀| ≤ {worst:.1e} E₀");
    assert!(
        worst <= 1e-12,
        "E − W drift {worst:e} of E₀ over 100 bounces"
    );
    // elastic: the ball still reaches its height (energy is conserved, not just accounted)
    let o = s.outputs();
    assert!(
        (o.work).abs() <= 0.05 * e0,
        "friction took {} of {e0} J",
        -o.work
    );
}

#[test]
fn an_elastic_ball_under_error_control_lands_on_its_contacts() {
    let text = ball(
        0.6,
        [0.0; 3],
        [0.0; 3],
        0.0,
        1e5,
        0.0,
        9.81,
        "max_step = 0.02\nrtol = 1e-6\norder = 4\nstages = 5",
    );
    let (m, mut s) = model(&text);
    let e0 = s.outputs().energy;
    let (mut bounces, mut touching, mut worst, mut steps) = (0, false, 0.0_f64, 0);
    let mut h = m.settings().max_step * 1e-3;
    while bounces < 100 {
        match controlled_step(&m, &mut s, h).unwrap() {
            Verdict::Accept => {
                steps += 1;
                s.refresh_outputs(&m);
                let gap = s.outputs().contacts[0].gap;
                if gap < -1e-9 && !touching {
                    bounces += 1;
                }
                touching = gap < -1e-9;
                worst = worst.max(drift(&s, e0));
            }
            Verdict::Land(hl) => {
                h = hl;
                continue;
            }
            _ => {}
        }
        h = s.control().proposal(&m).min(m.settings().max_step);
        assert!(steps < 2_000_000, "{bounces} bounces");
    }
    eprintln!(
        "100 bounces under error control ({steps} steps): |E − W − E₀| ≤ {worst:.1e} E₀, \
         apex energy off by {:.1e}",
        (s.outputs().energy - e0).abs() / e0
    );
    assert!(worst <= 1e-12, "E − W drift {worst:e} under error control");
    // the apex after 100 bounces is still the drop height (error control resolves every impact)
    let o = s.outputs();
    assert!((o.energy - e0).abs() <= 1e-4 * e0, "{} vs {e0}", o.energy);
}

/// `y` of `x − ln(1 + x) = −y − ln(1 − y)` (Newton).
fn restitution(x: f64) -> f64 {
    let lhs = x - (1.0 + x).ln();
    let mut y = 0.5 * x;
    for _ in 0..50 {
        let f = -y - (1.0 - y).ln() - lhs;
        let df = -1.0 + 1.0 / (1.0 - y);
        y -= f / df;
    }
    y / x
}

#[test]
fn a_damped_impact_restitutes_as_hunt_and_crossley() {
    // no gravity: the ball meets the ground at v_in and leaves at e v_in
    for (v_in, d) in [(1.0, 0.3), (0.5, 0.6), (2.0, 0.1)] {
        let text = ball(
            0.11,
            [0.0, 0.0, -v_in],
            [0.0; 3],
            0.0,
            1e5,
            d,
            0.0,
            "max_step = 1e-5",
        );
        let (m, mut s) = model(&text);
        for _ in 0..4000 {
            step(&m, &mut s, 1e-5).unwrap();
        }
        let v_out = s.outputs().bodies[0].v.z;
        assert!(s.outputs().contacts[0].gap > 0.0, "still in contact");
        let e = v_out / v_in;
        let want = restitution(d * v_in);
        eprintln!(
            "v_in {v_in}, d {d}: e = {e:.5}, Hunt–Crossley {want:.5} ({:+.2} %)",
            100.0 * (e / want - 1.0)
        );
        assert!(
            (e - want).abs() <= 0.02 * want,
            "v_in {v_in}, d {d}: e = {e}, Hunt–Crossley {want}"
        );
    }
}

/// A 1 kg box 0.2 × 0.2 × 0.1 m resting on the ground, sliding at `v0` along x.
fn sliding_box(v0: f64, mu: f64) -> String {
    format!(
        "name = \"Box\"\n[solver]\nmax_step = 1e-3\n\
         [ground]\nfriction = {mu}\nstiffness = 1e5\ndamping = 1.0\n\
         [[body]]\nname = \"box\"\nmass = 1.0\ninertia = [0.0041667, 0.0041667, 0.0066667]\n\
         position = [0.0, 0.0, 0.0499]\nvelocity = [{v0}, 0.0, 0.0]\n\
         [[collision]]\nname = \"block\"\nbody = \"box\"\nbox = {{ size = [0.2, 0.2, 0.1] }}\n"
    )
}

#[test]
fn a_sliding_box_stops_where_coulomb_says_and_its_loss_is_the_work() {
    let (v0, mu, g) = (2.0, 0.5, 9.81);
    let (m, mut s) = model(&sliding_box(v0, mu));
    let (e0, x0) = (s.outputs().energy, s.outputs().bodies[0].r.x);
    for _ in 0..1500 {
        step(&m, &mut s, 1e-3).unwrap();
    }
    let o = s.outputs();
    let distance = o.bodies[0].r.x - x0;
    let want = v0 * v0 / (2.0 * mu * g);
    let lost = e0 - o.energy;
    eprintln!(
        "sliding box: stops after {distance:.5} m, Coulomb {want:.5} m ({:+.2} %); \
         ΔE + W = {:.1e} ΔE",
        100.0 * (distance / want - 1.0),
        (lost + o.work).abs() / lost
    );
    assert!(
        (distance - want).abs() <= 0.01 * want,
        "stopped after {distance} m, Coulomb {want} m"
    );
    assert!(
        o.bodies[0].v.norm() < 1e-3,
        "still moving at {}",
        o.bodies[0].v.norm()
    );
    // what the contact dissipated is the whole loss of energy
    assert!(
        (lost + o.work).abs() <= 1e-10 * lost,
        "ΔE {lost} J, work {} J",
        o.work
    );
    assert!(lost > 0.99 * 0.5 * v0 * v0);
}

#[test]
fn a_ball_thrown_sliding_rolls_at_five_sevenths() {
    let (v0, mu, g) = (2.0, 0.3, 9.81);
    let text = ball(
        0.0999,
        [v0, 0.0, 0.0],
        [0.0; 3],
        mu,
        1e5,
        1.0,
        g,
        "max_step = 1e-4",
    );
    let (m, mut s) = model(&text);
    let t_roll = 2.0 * v0 / (7.0 * mu * g);
    let mut rolled_at = None;
    for _ in 0..5000 {
        step(&m, &mut s, 1e-4).unwrap();
        let b = &s.outputs().bodies[0];
        let slip = b.v.x - b.w.y * 0.1;
        if rolled_at.is_none() && slip.abs() < 1e-3 * v0 {
            rolled_at = Some(s.time());
        }
    }
    let t = rolled_at.expect("the ball never rolled");
    eprintln!(
        "rolling ball: rolls from t = {t:.5} s (analytic {t_roll:.5} s) at {:.5} m/s (5/7 v₀ = {:.5})",
        s.outputs().bodies[0].v.x,
        5.0 / 7.0 * v0
    );
    assert!(
        (t - t_roll).abs() <= 0.01 * t_roll,
        "rolls from t = {t} s, analytic {t_roll} s"
    );
    let v = s.outputs().bodies[0].v.x;
    assert!(
        (v - 5.0 / 7.0 * v0).abs() <= 0.01 * 5.0 / 7.0 * v0,
        "rolls at {v} m/s"
    );
}

/// A box dropped tilted about two axes and spinning, so it lands on a corner, then an edge.
fn tumbling_box(order: u8, d: f64) -> String {
    format!(
        "name = \"Tumble\"\n[solver]\nmax_step = 1e-3\norder = {order}\n\
         [ground]\nfriction = 0.6\nstiffness = 1e5\ndamping = {d}\n\
         [[body]]\nname = \"box\"\nmass = 2.0\ninertia = [0.0083, 0.0133, 0.0167]\n\
         position = [0.0, 0.0, 0.4]\norientation = [0.9, 0.3, 0.25, 0.2]\n\
         velocity = [0.4, 0.0, 0.0]\nangular_velocity = [1.0, -3.0, 2.0]\n\
         [[collision]]\nbody = \"box\"\nbox = {{ size = [0.2, 0.15, 0.1] }}\n"
    )
}

#[test]
fn a_tumbling_box_keeps_its_energy_account_at_both_orders() {
    for order in [2u8, 4] {
        let (m, mut s) = model(&tumbling_box(order, 0.0));
        let e0 = s.outputs().energy;
        let mut worst = 0.0_f64;
        for _ in 0..2000 {
            step(&m, &mut s, 1e-3).unwrap();
            worst = worst.max(drift(&s, e0));
        }
        eprintln!("tumbling box, order {order}: |E − W − E₀| ≤ {worst:.1e} E₀");
        assert!(worst <= 1e-12, "order {order}: E − W drift {worst:e}");
    }
}

#[test]
fn a_damped_tumbling_box_comes_to_rest() {
    for order in [2u8, 4] {
        let (m, mut s) = model(&tumbling_box(order, 2.0));
        let e0 = s.outputs().energy;
        for _ in 0..4000 {
            step(&m, &mut s, 1e-3).unwrap();
        }
        let o = s.outputs();
        let b = &o.bodies[0];
        assert!(
            b.v.norm() < 1e-3 && b.w.norm() < 1e-2,
            "order {order}: still moving {} {}",
            b.v.norm(),
            b.w.norm()
        );
        assert!(
            drift(&s, e0) <= 1e-12,
            "order {order}: E − W drift {:e}",
            drift(&s, e0)
        );
        // at rest on a face: the contact carries the weight
        let fz: f64 = o.contacts.iter().map(|c| c.force.z).sum();
        assert!(
            (fz - 2.0 * 9.81).abs() <= 1e-3 * 2.0 * 9.81,
            "order {order}: {fz} N"
        );
    }
}
