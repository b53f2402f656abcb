//! Shared helpers of the integration tests: the tolerance knob and model builders (free body,
//! double pendulum, heavy top, chainN as in `shared/peers/models/*.json`).
#![allow(dead_code)]

pub mod contact_models;
pub mod step_diff;
pub mod trees;

use triad::math::{exp_so3, Mat3, Vec3};
use triad::mechanics::{
    BodyDef, BodyLoadDef, Frame, FreeBodyInitial, JointDef, JointInitial, JointType, Model,
    ModelDef, SolverSettings, State,
};

/// Every joint type, in the order of `JointType`'s documentation.
pub const KINDS: [JointType; 7] = [
    JointType::Revolute,
    JointType::Prismatic,
    JointType::Cylindrical,
    JointType::Universal,
    JointType::Spherical,
    JointType::Planar,
    JointType::Fixed,
];

/// Model and initial state of a TOML spec text (panics with the spec's message).
pub fn spec_model(text: &str) -> (Model, State) {
    let spec = triad::spec::Spec::from_str(text, triad::spec::Format::Toml, "test.toml")
        .unwrap_or_else(|e| panic!("{e}"));
    let (def, settings) = spec.lower().unwrap();
    let m = Model::new(&def, settings).unwrap_or_else(|e| panic!("{e}"));
    let s = State::new(&m);
    (m, s)
}

/// The error of a TOML spec text that is refused (reading or lowering it), or "" if accepted.
pub fn spec_error(text: &str) -> String {
    triad::spec::Spec::from_str(text, triad::spec::Format::Toml, "bad.toml")
        .and_then(|s| s.lower().map(|_| ()))
        .map(|()| String::new())
        .unwrap_or_else(|e| e.to_string())
}

/// Runs the `triad` binary with `args` in `cwd` (integration tests only: the binary's path is
/// known to them, not to the benches and examples that share this module).
pub fn triad(args: &[&str], cwd: &std::path::Path) -> std::process::Output {
    let Some(bin) = option_env!("CARGO_BIN_EXE_triad") else {
        panic!("the triad binary is known to integration tests only");
    };
    std::process::Command::new(bin)
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run triad")
}

/// Header and rows of a result CSV (as `triad simulate` writes it: every cell a number).
pub fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header = reader.headers().unwrap().iter().map(String::from).collect();
    let rows = reader
        .records()
        .map(|r| r.unwrap().iter().map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// Scales a tolerance by the env knob `TRIAD_TOL_SCALE` (default 1).
#[must_use]
pub fn tol(x: f64) -> f64 {
    let s = std::env::var("TRIAD_TOL_SCALE")
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap_or(1.0);
    x * s
}

/// Deterministic uniform numbers in (−1, 1) (a 64-bit LCG), with random vectors and rotations.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
    pub fn vec(&mut self, s: f64) -> Vec3 {
        Vec3::new(self.next() * s, self.next() * s, self.next() * s)
    }
    pub fn rot(&mut self) -> Mat3 {
        exp_so3(&self.vec(2.0))
    }
}

/// Solver settings with step `h`, `order`, tolerance 1e-12 (round-off conservation).
#[must_use]
pub fn settings(h: f64, order: u8) -> SolverSettings {
    SolverSettings {
        max_step: h,
        order,
        tolerance: 1e-12,
        max_iterations: 30,
        ..SolverSettings::default()
    }
}

/// Inertia of a homogeneous box `a × b × c` of mass `m` (edges along the body axes).
#[must_use]
pub fn box_inertia(m: f64, a: f64, b: f64, c: f64) -> Mat3 {
    Mat3::from_diagonal(&Vec3::new(b * b + c * c, a * a + c * c, a * a + b * b)) * (m / 12.0)
}

/// Inertia `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` as a matrix.
#[must_use]
pub fn inertia6(i: [f64; 6]) -> Mat3 {
    Mat3::new(i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2])
}

/// A body named `name`.
#[must_use]
pub fn body(name: &str, mass: f64, com: Vec3, inertia: Mat3) -> BodyDef {
    BodyDef {
        name: name.into(),
        mass,
        com,
        inertia,
    }
}

/// One free body (COM at the frame origin) with rotation `r0`, spatial angular velocity `w0`,
/// velocity `v0`, optional torque/force inputs, no gravity.
#[must_use]
pub fn free_body(
    mass: f64,
    inertia: Mat3,
    r0: Mat3,
    w0: Vec3,
    v0: Vec3,
    torque: bool,
    force: bool,
) -> ModelDef {
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::zeros(),
        bodies: vec![body("b", mass, Vec3::zeros(), inertia)],
        joints: vec![],
        loads: if torque || force {
            vec![BodyLoadDef {
                body: 0,
                torque,
                force,
            }]
        } else {
            vec![]
        },
        free_bodies: vec![FreeBodyInitial {
            body: 0,
            position: Vec3::zeros(),
            orientation: r0,
            velocity: v0,
            angular_velocity: w0,
        }],
        sites: vec![],
    }
}

/// A joint with defaults (identity frames, not actuated, no damping/stiffness).
#[must_use]
pub fn joint(
    name: &str,
    kind: JointType,
    parent: Option<usize>,
    child: usize,
    anchor: Vec3,
    axis: Vec3,
) -> JointDef {
    JointDef {
        name: name.into(),
        kind,
        parent,
        child,
        parent_frame: Frame {
            translation: anchor,
            rotation: Mat3::identity(),
        },
        child_frame: Frame::identity(),
        axis,
        axis2: Vec3::new(0.0, 1.0, 0.0),
        actuated: false,
        damping: 0.0,
        stiffness: 0.0,
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: JointInitial::Coords {
            q: vec![],
            qd: vec![],
        },
    }
}

/// Sets the initial coordinates of a joint.
pub fn set_q(j: &mut JointDef, q: &[f64], qd: &[f64]) {
    j.initial = JointInitial::Coords {
        q: q.to_vec(),
        qd: qd.to_vec(),
    };
}

/// Peers' double pendulum: two 1 m / 1 kg rods about world y, released from (2.0, 0.5) rad.
#[must_use]
pub fn double_pendulum() -> ModelDef {
    let i = inertia6([
        0.08335833333333333,
        0.08335833333333333,
        5e-05,
        0.0,
        0.0,
        0.0,
    ]);
    let com = Vec3::new(0.0, 0.0, -0.5);
    let mut j1 = joint("j1", JointType::Revolute, None, 0, Vec3::zeros(), Vec3::y());
    let mut j2 = joint(
        "j2",
        JointType::Revolute,
        Some(0),
        1,
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::y(),
    );
    set_q(&mut j1, &[2.0], &[]);
    set_q(&mut j2, &[0.5], &[]);
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![body("link1", 1.0, com, i), body("link2", 1.0, com, i)],
        joints: vec![j1, j2],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// Peers' heavy top: m = 1, COM 0.5 m along body z, I = diag(0.1, 0.1, 0.05), spherical tip,
/// tilted 30° about x, spin 30 rad/s.
#[must_use]
pub fn heavy_top() -> ModelDef {
    let mut j = joint(
        "tip",
        JointType::Spherical,
        None,
        0,
        Vec3::zeros(),
        Vec3::z(),
    );
    j.initial = JointInitial::Spherical {
        quat: [0.9659258262890683, 0.25881904510252074, 0.0, 0.0],
        w: Vec3::new(0.0, 0.0, 30.0),
    };
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![body(
            "top",
            1.0,
            Vec3::new(0.0, 0.0, 0.5),
            Mat3::from_diagonal(&Vec3::new(0.1, 0.1, 0.05)),
        )],
        joints: vec![j],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// Peers' chainN: rods 0.25 m / 0.25 kg hanging along −z, revolute axes alternating x, y;
/// q0: first two joints 0.8 rad, others 0.1 sin(0.7 i), at rest.
#[must_use]
pub fn chain(n: usize) -> ModelDef {
    let i = inertia6([
        0.0013036458333333335,
        0.0013036458333333335,
        3.125e-06,
        0.0,
        0.0,
        0.0,
    ]);
    let mut bodies = Vec::new();
    let mut joints = Vec::new();
    for k in 0..n {
        bodies.push(body(
            &format!("link{}", k + 1),
            0.25,
            Vec3::new(0.0, 0.0, -0.125),
            i,
        ));
        let axis = if k % 2 == 0 { Vec3::x() } else { Vec3::y() };
        let (parent, anchor) = if k == 0 {
            (None, Vec3::zeros())
        } else {
            (Some(k - 1), Vec3::new(0.0, 0.0, -0.25))
        };
        let mut j = joint(
            &format!("j{}", k + 1),
            JointType::Revolute,
            parent,
            k,
            anchor,
            axis,
        );
        let q = if k < 2 {
            0.8
        } else {
            0.1 * (0.7 * k as f64).sin()
        };
        set_q(&mut j, &[q], &[]);
        joints.push(j);
    }
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies,
        joints,
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// `chain(n)` as a floating chain: its first link is a free body (the floating base, at the pose
/// it has in `chain(n)`, at rest) instead of hanging from the world, gravity is off, and every
/// joint starts turning (`qd = 2 sin(0.7 k)` rad/s), so the chain moves about its centre of mass.
#[must_use]
pub fn floating_chain(n: usize) -> ModelDef {
    let mut def = chain(n);
    def.gravity = Vec3::zeros();
    let first = def.joints.remove(0);
    let JointInitial::Coords { q, .. } = &first.initial else {
        unreachable!("chain joints take coordinates")
    };
    def.free_bodies.push(FreeBodyInitial {
        body: 0,
        position: Vec3::zeros(),
        orientation: exp_so3(&(first.axis * q[0])),
        velocity: Vec3::zeros(),
        angular_velocity: Vec3::zeros(),
    });
    for (k, j) in def.joints.iter_mut().enumerate() {
        if let JointInitial::Coords { qd, .. } = &mut j.initial {
            *qd = vec![2.0 * (0.7 * (k + 1) as f64).sin()];
        }
    }
    def
}

/// `chain(n)` closed by a loop-closing revolute from the end of the last link (0.25 m below its
/// joint, body frame) to the world (`to = None`) or to body `to`'s frame, placed where the end is
/// at `q0` (frames coincide, axis = the last link's body x); the loop joint carries
/// `stiffness`/`damping` (N·m/rad, N·m·s/rad).
#[must_use]
pub fn chain_loop(n: usize, to: Option<usize>, stiffness: f64, damping: f64) -> ModelDef {
    use triad::mechanics::body::BodyInertia;
    use triad::mechanics::kinematics::initial_configuration;
    let mut def = chain(n);
    let (q0, _) = initial_configuration(&def).expect("chain configures");
    let pose = |b: usize| {
        BodyInertia::new(&def.bodies[b])
            .expect("body")
            .frame_from_coords(&q0[12 * b..12 * b + 12])
    };
    let (oe, re) = pose(n - 1);
    let end = Vec3::new(0.0, 0.0, -0.25);
    let p_end = oe + re * end;
    let (o_to, r_to) = to.map_or((Vec3::zeros(), Mat3::identity()), pose);
    let mut close = joint(
        "close",
        JointType::Revolute,
        to,
        n - 1,
        Vec3::zeros(),
        Vec3::x(),
    );
    close.parent_frame = Frame {
        translation: r_to.transpose() * (p_end - o_to),
        rotation: r_to.transpose() * re,
    };
    close.child_frame = Frame {
        translation: end,
        rotation: Mat3::identity(),
    };
    close.loop_closing = true;
    close.stiffness = stiffness;
    close.damping = damping;
    def.joints.push(close);
    def
}

/// Model + state.
#[must_use]
pub fn build(def: &ModelDef, s: SolverSettings) -> (Model, State) {
    let m = Model::new(def, s).expect("model builds");
    let st = State::new(&m);
    (m, st)
}

/// `exp` of a rotation vector.
#[must_use]
pub fn rot(v: [f64; 3]) -> Mat3 {
    exp_so3(&Vec3::new(v[0], v[1], v[2]))
}

/// Relative difference `|a − b| / max(|b|, floor)`.
#[must_use]
pub fn rel(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / b.abs().max(floor)
}

/// Crank-rocker four-bar (ground pivots 0 and (2, 0, 0), crank 0.6, coupler 2.2, rocker 1.5,
/// links along body x, gravity −9.81 y) closed by a loop-closing revolute at the rocker end.
#[must_use]
pub fn four_bar(theta1: f64, crank_rate: f64) -> ModelDef {
    let (g, a, b, c) = (2.0, 0.6, 2.2, 1.5);
    let link = |name: &str, len: f64| {
        body(
            name,
            len,
            Vec3::new(0.5 * len, 0.0, 0.0),
            box_inertia(len, len, 0.05, 0.05),
        )
    };
    let pa = Vec3::new(a * theta1.cos(), a * theta1.sin(), 0.0);
    let o2 = Vec3::new(g, 0.0, 0.0);
    let dist = (o2 - pa).norm();
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let u = (o2 - pa) / dist;
    let pb = pa + u * along + Vec3::z().cross(&u) * (b * b - along * along).sqrt();
    let th2 = (pb - pa).y.atan2((pb - pa).x);
    let th3 = (o2 - pb).y.atan2((o2 - pb).x);
    let mut close = joint("close", JointType::Revolute, None, 2, o2, Vec3::z());
    close.loop_closing = true;
    close.child_frame.translation = Vec3::new(c, 0.0, 0.0);
    let mut j0 = joint("j0", JointType::Revolute, None, 0, Vec3::zeros(), Vec3::z());
    set_q(&mut j0, &[theta1], &[crank_rate]);
    let mut j1 = joint(
        "j1",
        JointType::Revolute,
        Some(0),
        1,
        Vec3::new(a, 0.0, 0.0),
        Vec3::z(),
    );
    set_q(&mut j1, &[th2 - theta1], &[0.0]);
    let mut j2 = joint(
        "j2",
        JointType::Revolute,
        Some(1),
        2,
        Vec3::new(b, 0.0, 0.0),
        Vec3::z(),
    );
    set_q(&mut j2, &[th3 - th2], &[0.0]);
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, -9.81, 0.0),
        bodies: vec![link("crank", a), link("coupler", b), link("rocker", c)],
        joints: vec![j0, j1, j2, close],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}
