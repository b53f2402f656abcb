//! FMI 3 early return: with `earlyReturnAllowed`, `fmi3DoStep` returns at the time a contact
//! touches or leaves the ground and a joint reaches or leaves its stop (`earlyReturn`,
//! `lastSuccessfulTime` there), the next step continues from there, and the run ends where the
//! host asked; without the permission it steps through as `fmi2DoStep` does.

mod fmu_support;

use fmu_support::api3::{fmi3DoStep, fmi3ExitInitializationMode};
use fmu_support::fmi3::{instantiate3, Fmu3};
use fmu_support::*;
use triad::ffi::fmi3::types::*;
use triad::variables::fmi3::Table3;

fn early_instance(m: &TestModel) -> Fmu3 {
    let path = m.resources().to_string_lossy().into_owned();
    let (c, log) = instantiate3(&m.guid, Some(&path), false, true);
    assert!(!c.is_null());
    let f = Fmu3 {
        c,
        log,
        t3: Table3::new(&m.table),
    };
    assert_eq!(f.enter_init(0.0), fmi3OK);
    assert_eq!(unsafe { fmi3ExitInitializationMode(f.c) }, fmi3OK);
    f
}

/// (status, earlyReturn, lastSuccessfulTime) of one `fmi3DoStep`.
fn step(f: &Fmu3, t: f64, h: f64) -> (fmi3Status, bool, f64) {
    let (mut ev, mut term, mut early, mut last) = (false, false, false, f64::NAN);
    let s = unsafe { fmi3DoStep(f.c, t, h, false, &mut ev, &mut term, &mut early, &mut last) };
    (s, early, last)
}

fn value(f: &Fmu3, name: &str) -> f64 {
    let vr = f.var(name).vr;
    f.get_f64(&[vr], 1).1[0]
}

/// The bouncing ball (free fall from a 0.9 m gap, exact under the midpoint rule): the first
/// early return is at touchdown `√(2·0.9/g)` to 1e-12 s, with the gap 0 there to 1e-11 m; the
/// ball leaves and touches again, each an early return; the run still ends at the host's time.
#[test]
fn a_ball_returns_early_at_each_touch_and_lift_off() {
    ball_returns_early("max_step = 1e-3");
}

/// The same under error control: the accepted step that crossed is retaken to end on the event.
#[test]
fn a_ball_returns_early_under_error_control() {
    ball_returns_early("max_step = 1e-2\nrtol = 1e-6\natol = 1e-8");
}

fn ball_returns_early(solver: &str) {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/specs/bouncing_ball.toml"
    ))
    .unwrap()
    .replace("max_step = 1e-3", solver);
    let m = TestModel::new(&text);
    let f = early_instance(&m);
    let (s, early, t1) = step(&f, 0.0, 1.5);
    assert_eq!(s, fmi3OK, "{:?}", f.messages());
    assert!(early);
    let touchdown = (2.0 * 0.9 / 9.81_f64).sqrt();
    eprintln!(
        "{solver}: first return {:.3e} s from touchdown, gap {:.3e} m",
        t1 - touchdown,
        value(&f, "contact.shell.gap")
    );
    assert!((t1 - touchdown).abs() < 1e-12, "{t1} vs {touchdown}");
    assert!(value(&f, "contact.shell.gap").abs() < 1e-11);
    // continue: lift-off, the next touch, ... up to 1.5 s
    let (mut t, mut events) = (t1, 1);
    while t < 1.5 {
        let (s, early, last) = step(&f, t, 1.5 - t);
        assert_eq!(s, fmi3OK, "{:?}", f.messages());
        assert!(last > t, "no progress at {t}");
        if early {
            events += 1;
            assert!(
                value(&f, "contact.shell.gap").abs() < 1e-11,
                "gap at {last}"
            );
        }
        t = last;
    }
    assert_eq!(t, 1.5);
    assert!(events >= 3, "touch, lift-off, touch: {events}");
    // without the permission: one step through
    let g = Fmu3::initialised(&m);
    let (s, early, last) = step(&g, 0.0, 1.5);
    assert_eq!((s, early, last), (fmi3OK, false, 1.5));
}

/// A pendulum released at 1 rad swings into a stop at −0.5 rad: the early return is where
/// the coordinate reaches the limit.
#[test]
fn a_joint_returns_early_at_its_stop() {
    let text = r#"
name = "Stopped"
gravity = [0.0, 0.0, -9.81]
[solver]
max_step = 1e-3
[[body]]
name = "rod"
mass = 1.0
com = [0.0, 0.0, -0.5]
inertia = [0.0834, 0.0834, 1e-4]
[[joint]]
name = "hinge"
type = "revolute"
parent = "world"
child = "rod"
axis = [0.0, 1.0, 0.0]
lower = -0.5
upper = 2.0
initial = { q = 1.0 }
"#;
    let m = TestModel::new(text);
    let f = early_instance(&m);
    let (s, early, t1) = step(&f, 0.0, 2.0);
    assert_eq!(s, fmi3OK);
    assert!(early && t1 < 2.0);
    let q = value(&f, "joint.hinge.q");
    eprintln!("stop reached at {t1} s: q + 0.5 = {:.3e} rad", q + 0.5);
    assert!((q + 0.5).abs() < 1e-11, "q = {q} at {t1}");
    // leaving the stop is the next event
    let (_, early, t2) = step(&f, t1, 2.0 - t1);
    assert!(early && t2 > t1);
    let q = value(&f, "joint.hinge.q");
    assert!((q + 0.5).abs() < 1e-11, "q = {q} at {t2}");
}
