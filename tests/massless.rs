//! Bodies of any mass: massless links, massless welded frames and rods with one zero moment are
//! accepted where the motion stays determined, and change nothing of the dynamics: the joint
//! trajectories of a model with massless links equal those of the same model with the links
//! merged away (to 1e-10 over 1 s at order 4, both Newton forms: a welded frame to round-off
//! at h = 1e-3; a two-axis wrist's yoke, another discretisation of the same motion, at
//! h = 2.5e-4 with the difference falling as h⁴). Where the motion
//! is not determined (a massless leaf on a movable joint, a massless free body, a rod free to
//! spin about its zero-moment axis) the model is refused with the body's name.

mod common;
use common::*;
use triad::math::{exp_so3, Mat3, Vec3};
use triad::mechanics::{step, Frame, FreeBodyInitial, JointDef, JointType, Model, ModelDef, State};

fn actuated(mut j: JointDef, q: &[f64], qd: &[f64]) -> JointDef {
    set_q(&mut j, q, qd);
    j.actuated = true;
    j
}

fn arm() -> triad::mechanics::BodyDef {
    body(
        "arm",
        2.0,
        Vec3::new(0.0, 0.0, -0.3),
        box_inertia(2.0, 0.06, 0.06, 0.6),
    )
}

fn hand() -> triad::mechanics::BodyDef {
    body(
        "hand",
        1.0,
        Vec3::new(0.05, 0.02, -0.15),
        inertia6([0.012, 0.010, 0.004, 0.001, -0.0005, 0.0008]),
    )
}

fn shoulder() -> JointDef {
    actuated(
        joint(
            "shoulder",
            JointType::Revolute,
            None,
            0,
            Vec3::zeros(),
            Vec3::y(),
        ),
        &[0.8],
        &[0.5],
    )
}

/// Arm, massless yoke, hand: a two-axis wrist (yaw about z, then pitch about the yoke's x).
fn wrist_with_yoke() -> ModelDef {
    let wrist = Vec3::new(0.0, 0.0, -0.6);
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![
            arm(),
            body("yoke", 0.0, Vec3::zeros(), Mat3::zeros()),
            hand(),
        ],
        joints: vec![
            shoulder(),
            actuated(
                joint("yaw", JointType::Revolute, Some(0), 1, wrist, Vec3::z()),
                &[0.3],
                &[1.2],
            ),
            actuated(
                joint(
                    "pitch",
                    JointType::Revolute,
                    Some(1),
                    2,
                    Vec3::zeros(),
                    Vec3::x(),
                ),
                &[-0.4],
                &[-0.7],
            ),
        ],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// The same wrist with the yoke merged away: a universal joint (z in the arm, then x in the hand).
fn wrist_universal() -> ModelDef {
    let mut u = joint(
        "wrist",
        JointType::Universal,
        Some(0),
        1,
        Vec3::new(0.0, 0.0, -0.6),
        Vec3::z(),
    );
    u.axis2 = Vec3::x();
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![arm(), hand()],
        joints: vec![shoulder(), actuated(u, &[0.3, -0.4], &[1.2, -0.7])],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// The flange's placement on `l1` and `l2`'s joint frame on the flange.
fn flange_frames() -> (Frame, Frame) {
    let f = Frame {
        translation: Vec3::new(0.1, 0.0, -0.5),
        rotation: exp_so3(&Vec3::new(0.2, 0.0, 0.4)),
    };
    let j2 = Frame {
        translation: Vec3::new(0.0, 0.05, -0.1),
        rotation: exp_so3(&Vec3::new(0.0, 0.3, 0.0)),
    };
    (f, j2)
}

fn link(name: &str, m: f64, l: f64) -> triad::mechanics::BodyDef {
    body(
        name,
        m,
        Vec3::new(0.0, 0.0, -0.5 * l),
        box_inertia(m, 0.05, 0.04, l),
    )
}

/// Three links; a massless flange welded between the first two and a massless `tool0` frame
/// welded to the last (or, `merged`, the same chain without them).
fn welded_chain(merged: bool) -> ModelDef {
    let (f, j2f) = flange_frames();
    let axis2 = Vec3::new(0.3, 1.0, 0.1).normalize();
    let mut bodies = vec![
        link("l1", 1.5, 0.5),
        link("l2", 1.0, 0.4),
        link("l3", 0.5, 0.4),
    ];
    let j1 = actuated(
        joint("j1", JointType::Revolute, None, 0, Vec3::zeros(), Vec3::y()),
        &[1.0],
        &[-0.3],
    );
    let mut j2 = actuated(
        joint("j2", JointType::Revolute, Some(0), 1, Vec3::zeros(), axis2),
        &[0.5],
        &[2.0],
    );
    let j3 = actuated(
        joint(
            "j3",
            JointType::Revolute,
            Some(1),
            2,
            Vec3::new(0.0, 0.0, -0.4),
            Vec3::x(),
        ),
        &[-0.2],
        &[0.7],
    );
    if merged {
        // the flange's placement composed with j2's frame on it
        j2.parent_frame = Frame {
            translation: f.translation + f.rotation * j2f.translation,
            rotation: f.rotation * j2f.rotation,
        };
        return ModelDef {
            couplings: Vec::new(),
            actuators: Vec::new(),
            contact: Default::default(),
            gravity: Vec3::new(0.0, 0.0, -9.81),
            bodies,
            joints: vec![j1, j2, j3],
            loads: vec![],
            free_bodies: vec![],
            sites: vec![],
        };
    }
    bodies.push(body("flange", 0.0, Vec3::zeros(), Mat3::zeros()));
    bodies.push(body("tool0", 0.0, Vec3::zeros(), Mat3::zeros()));
    let mut weld = joint(
        "weld",
        JointType::Fixed,
        Some(0),
        3,
        Vec3::zeros(),
        Vec3::z(),
    );
    weld.parent_frame = f;
    let mut tool = joint(
        "tool",
        JointType::Fixed,
        Some(2),
        4,
        Vec3::new(0.0, 0.0, -0.4),
        Vec3::z(),
    );
    tool.parent_frame.rotation = exp_so3(&Vec3::new(0.5, 0.0, 0.0));
    j2.parent = Some(3);
    j2.parent_frame = j2f;
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies,
        joints: vec![j1, weld, j2, j3, tool],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// Joint angles and rates of `names` every 0.1 s over 1 s at order 4, step `h` (s), under constant
/// actuator inputs `inputs` (the model's input order), in the multiplier form or not.
fn trajectory(def: &ModelDef, h: f64, inputs: &[f64], names: &[&str], reduced: bool) -> Vec<f64> {
    let mut model = Model::new(def, settings(h, 4)).expect("model");
    model.set_reduced_solver(reduced);
    let mut s = State::new(&model);
    s.inputs_mut().copy_from_slice(inputs);
    let index: Vec<usize> = names
        .iter()
        .map(|n| def.joints.iter().position(|j| j.name == *n).expect("joint"))
        .collect();
    let mut out = Vec::new();
    for k in 0..(1.0 / h).round() as usize {
        step(&model, &mut s, h).expect("step");
        if (k + 1) % ((0.1 / h).round() as usize) == 0 {
            for &j in &index {
                let o = &s.outputs().joints[j];
                out.extend(&o.q);
                out.extend(&o.qd);
            }
        }
    }
    out
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The two models are two discretisations of the same motion (the yoke's directors are
/// integrated, the universal joint's rows are not those of two revolutes), so their joint
/// trajectories differ by the order-4 error: 1.5e-8 at h = 1e-3. Halving the step must divide
/// the difference by 2⁴ (the two converge to one motion), and at h = 2.5e-4 it is below 1e-10.
#[test]
fn a_massless_yoke_moves_like_a_universal_joint() {
    let tau = [1.5, -0.4, 0.25];
    for reduced in [true, false] {
        let diff = |h: f64| {
            let yoke = trajectory(
                &wrist_with_yoke(),
                h,
                &tau,
                &["shoulder", "yaw", "pitch"],
                reduced,
            );
            let uni = trajectory(&wrist_universal(), h, &tau, &["shoulder", "wrist"], reduced);
            // yoke: [q_s, qd_s, q_yaw, qd_yaw, q_pitch, qd_pitch]; universal: [q_s, qd_s, α, β, α̇, β̇]
            let yoke: Vec<f64> = yoke
                .chunks(6)
                .flat_map(|c| [c[0], c[1], c[2], c[4], c[3], c[5]])
                .collect();
            max_diff(&yoke, &uni)
        };
        let (d1, d2) = (diff(5e-4), diff(2.5e-4));
        eprintln!("reduced = {reduced}: largest difference {d1:.2e} at h = 5e-4, {d2:.2e} at 2.5e-4 (rad, rad/s)");
        assert!(d2 <= 1e-10, "reduced = {reduced}: {d2:e}");
        assert!(
            d1 / d2 >= 12.0,
            "reduced = {reduced}: not order 4 ({d1:e}, {d2:e})"
        );
    }
}

#[test]
fn massless_welded_frames_change_nothing() {
    let tau = [2.0, -0.5, 0.3];
    for reduced in [true, false] {
        let a = trajectory(
            &welded_chain(false),
            1e-3,
            &tau,
            &["j1", "j2", "j3"],
            reduced,
        );
        let b = trajectory(
            &welded_chain(true),
            1e-3,
            &tau,
            &["j1", "j2", "j3"],
            reduced,
        );
        let d = max_diff(&a, &b);
        eprintln!("reduced = {reduced}: largest difference {d:.2e} (rad, rad/s)");
        assert!(d <= 1e-10, "reduced = {reduced}: {d:e}");
    }
}

/// A 1 m rod (1 kg) with no moment about its own axis, on a revolute joint about y.
fn rod(kind: JointType) -> ModelDef {
    let mut j = joint("pivot", kind, None, 0, Vec3::zeros(), Vec3::y());
    if kind == JointType::Revolute {
        set_q(&mut j, &[1.2], &[0.0]);
    }
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![body(
            "rod",
            1.0,
            Vec3::new(0.0, 0.0, -0.5),
            Mat3::from_diagonal(&Vec3::new(1.0 / 12.0, 1.0 / 12.0, 0.0)),
        )],
        joints: vec![j],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

#[test]
fn a_rod_with_one_zero_moment_swings_with_its_energy_kept() {
    let model = Model::new(&rod(JointType::Revolute), settings(1e-2, 2)).expect("rod");
    let mut s = State::new(&model);
    let e0 = s.outputs().energy;
    let mut drift = 0.0_f64;
    for _ in 0..1000 {
        step(&model, &mut s, 1e-2).expect("step");
        drift = drift.max((s.outputs().energy - e0).abs() / e0.abs());
    }
    eprintln!("rod: relative energy drift {drift:.1e}");
    assert!(drift <= 1e-12, "{drift:e}");
    // released at rest: energy conservation keeps the swing within the initial angle
    assert!(s.outputs().joints[0].q[0].abs() <= 1.2 + 1e-9);
}

fn refusal(def: &ModelDef) -> String {
    match Model::new(def, settings(1e-3, 2)) {
        Ok(_) => panic!("model accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn undetermined_bodies_are_refused_by_name() {
    // a massless leaf on a revolute joint
    let mut def = wrist_with_yoke();
    def.bodies.pop();
    def.joints.pop();
    let msg = refusal(&def);
    assert!(
        msg.contains("body 'yoke' has no mass") && msg.contains("leaf"),
        "{msg}"
    );
    // a rod on a ball joint may spin about its own axis
    let msg = refusal(&rod(JointType::Spherical));
    assert!(
        msg.contains("body 'rod' has no inertia about an axis"),
        "{msg}"
    );
    // a massless free body
    let mut def = free_body(
        1.0,
        Mat3::identity(),
        Mat3::identity(),
        Vec3::zeros(),
        Vec3::zeros(),
        false,
        false,
    );
    def.bodies[0].mass = 0.0;
    def.bodies[0].inertia = Mat3::zeros();
    let msg = refusal(&def);
    assert!(
        msg.contains("body 'b' has no mass") && msg.contains("free body"),
        "{msg}"
    );
    // a massless floating base carrying a massive body on a revolute joint
    let mut def = wrist_universal();
    def.bodies[0].mass = 0.0;
    def.bodies[0].inertia = Mat3::zeros();
    def.joints.remove(0);
    def.joints[0].parent = Some(0);
    def.free_bodies.push(FreeBodyInitial {
        body: 0,
        position: Vec3::zeros(),
        orientation: Mat3::identity(),
        velocity: Vec3::zeros(),
        angular_velocity: Vec3::zeros(),
    });
    let msg = refusal(&def);
    assert!(msg.contains("body 'arm' has no mass"), "{msg}");
}

#[test]
fn a_massless_welded_base_is_accepted() {
    // the same floating base welded to a massive body is determined
    let mut def = wrist_universal();
    def.bodies[0].mass = 0.0;
    def.bodies[0].inertia = Mat3::zeros();
    def.joints.remove(0);
    def.joints[0].kind = JointType::Fixed;
    def.joints[0].initial = triad::mechanics::JointInitial::Coords {
        q: vec![],
        qd: vec![],
    };
    def.joints[0].actuated = false;
    def.free_bodies.push(FreeBodyInitial {
        body: 0,
        position: Vec3::zeros(),
        orientation: Mat3::identity(),
        velocity: Vec3::new(0.1, 0.0, 0.0),
        angular_velocity: Vec3::new(0.0, 0.0, 1.0),
    });
    def.gravity = Vec3::zeros();
    let model = Model::new(&def, settings(1e-2, 2)).expect("determined");
    let mut s = State::new(&model);
    let (p0, l0) = (s.outputs().p, s.outputs().l);
    for _ in 0..200 {
        step(&model, &mut s, 1e-2).expect("step");
    }
    assert!((s.outputs().p - p0).norm() <= 1e-13 && (s.outputs().l - l0).norm() <= 1e-13);
}
