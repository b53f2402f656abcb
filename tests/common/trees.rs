//! Tree models shared by the linear-model and joint-space tests: every joint type and load, a
//! floating base, a rotor.

/// A chain of every joint type with springs, dampers and inputs, off its rest state.
pub const ALL_KINDS: &str = r#"
name = "AllKinds"
gravity = [0.0, -1.0, -9.81]
[solver]
max_step = 1e-3
[[body]]
name = "a"
mass = 1.3
com = [0.1, 0.0, -0.3]
inertia = [0.05, 0.06, 0.02, 0.001, 0.002, -0.001]
[[body]]
name = "b"
mass = 0.9
com = [0.0, 0.05, -0.2]
inertia = [0.03, 0.02, 0.025]
[[body]]
name = "c"
mass = 0.7
com = [0.02, 0.0, -0.15]
inertia = [0.01, 0.012, 0.008]
[[body]]
name = "d"
mass = 0.5
com = [0.0, 0.0, -0.1]
inertia = [0.004, 0.005, 0.003]
[[body]]
name = "e"
mass = 0.4
com = [0.03, -0.02, -0.1]
inertia = [0.003, 0.002, 0.0025]
[[body]]
name = "f"
mass = 0.3
com = [0.0, 0.02, 0.05]
inertia = [0.002, 0.001, 0.0015]
[[joint]]
name = "j1"
type = "revolute"
parent = "world"
child = "a"
axis = [0.2, 1.0, 0.1]
actuated = true
damping = 0.3
stiffness = 2.0
initial = { q = 0.4, qd = -0.7 }
[[joint]]
name = "j2"
type = "prismatic"
parent = "a"
child = "b"
origin = { xyz = [0.1, 0.0, -0.6], rpy = [0.1, 0.2, 0.3] }
axis = [1.0, 0.0, 0.2]
actuated = true
damping = 0.5
initial = { q = 0.05, qd = 0.3 }
[[joint]]
name = "j3"
type = "cylindrical"
parent = "b"
child = "c"
origin = { xyz = [0.0, 0.1, -0.4], rpy = [0.0, 0.3, 0.0] }
axis = [0.0, 0.0, 1.0]
actuated = true
stiffness = 1.5
initial = { q = [0.02, 0.5], qd = [-0.1, 1.1] }
[[joint]]
name = "j4"
type = "universal"
parent = "c"
child = "d"
origin = { xyz = [0.05, 0.0, -0.3] }
axis = [1.0, 0.0, 0.0]
axis2 = [0.0, 1.0, 0.0]
actuated = true
damping = 0.05
initial = { q = [0.3, -0.4], qd = [0.8, -0.6] }
[[joint]]
name = "j5"
type = "spherical"
parent = "d"
child = "e"
origin = { xyz = [0.0, 0.0, -0.2] }
actuated = true
damping = 0.02
initial = { quat = [0.9, 0.2, -0.3, 0.1], w = [0.5, -1.0, 2.0] }
[[joint]]
name = "j6"
type = "planar"
parent = "e"
child = "f"
origin = { xyz = [0.0, 0.1, -0.2], rpy = [0.4, 0.0, 0.0] }
axis = [0.0, 0.0, 1.0]
stiffness = 0.7
initial = { q = [0.01, -0.02, 0.3], qd = [0.1, 0.2, -0.5] }
[[load]]
body = "c"
torque = true
force = true
"#;

/// A floating base with a two-link arm, a body load and a stop near its limit.
pub const FLOATING: &str = r#"
name = "Floating"
gravity = [0.0, 0.0, -9.81]
[solver]
max_step = 1e-3
[[body]]
name = "base"
mass = 5.0
com = [0.02, 0.01, 0.0]
inertia = [0.2, 0.3, 0.25, 0.01, 0.0, 0.02]
position = [0.1, 0.2, 0.3]
orientation = [0.9, 0.1, 0.3, -0.2]
velocity = [0.3, -0.2, 0.1]
angular_velocity = [0.4, 0.5, -0.6]
[[body]]
name = "l1"
mass = 1.0
com = [0.0, 0.0, -0.25]
inertia = [0.02, 0.02, 0.002]
[[body]]
name = "l2"
mass = 0.6
com = [0.0, 0.0, -0.2]
inertia = [0.01, 0.01, 0.001]
[[joint]]
name = "hip"
type = "revolute"
parent = "base"
child = "l1"
origin = { xyz = [0.1, 0.0, -0.1] }
axis = [0.0, 1.0, 0.0]
actuated = true
lower = -1.0
upper = 0.45
stop_damping = 3.0
initial = { q = 0.5, qd = 0.2 }
[[joint]]
name = "knee"
type = "revolute"
parent = "l1"
child = "l2"
origin = { xyz = [0.0, 0.0, -0.5] }
axis = [1.0, 0.0, 0.0]
actuated = true
effort = 2.0
initial = { q = -0.3, qd = 0.4 }
[[load]]
body = "base"
torque = true
force = true
"#;

/// A disc on an actuated vertical shaft without gravity (inertia 0.04 kg·m² about it); the
/// joint-space terms are appended to its `[[joint]]` table by the tests.
pub const ROTOR: &str = r#"
name = "Rotor"
gravity = [0.0, 0.0, 0.0]
[solver]
max_step = 1e-3
[[body]]
name = "disc"
mass = 2.0
inertia = [0.02, 0.02, 0.04]
[[joint]]
name = "shaft"
type = "revolute"
parent = "world"
child = "disc"
axis = [0.0, 0.0, 1.0]
actuated = true
"#;

/// Two pendulums, the second following the first at half its angle, and two slides, the second
/// following the first (`[[coupling]]`s are closure rows of the same kind).
pub const COUPLED: &str = r#"
name = "Coupled"
gravity = [0.0, -3.0, -9.81]
[solver]
max_step = 1e-3
[[body]]
name = "p1"
mass = 1.0
com = [0.0, 0.0, -0.4]
inertia = [0.02, 0.02, 0.005]
[[body]]
name = "p2"
mass = 0.6
com = [0.1, 0.0, -0.3]
inertia = [0.01, 0.012, 0.004]
[[body]]
name = "s1"
mass = 0.3
inertia = [0.001, 0.001, 0.001]
[[body]]
name = "s2"
mass = 0.2
inertia = [0.001, 0.001, 0.001]
[[joint]]
name = "j1"
type = "revolute"
parent = "world"
child = "p1"
axis = [1.0, 0.0, 0.0]
actuated = true
initial = { q = 1.0, qd = 2.0 }
[[joint]]
name = "j2"
type = "revolute"
parent = "world"
child = "p2"
origin = { xyz = [0.5, 0.0, 0.0], rpy = [0.0, 0.3, 0.0] }
axis = [1.0, 0.0, 0.0]
stiffness = 3.0
[[joint]]
name = "k1"
type = "prismatic"
parent = "p1"
child = "s1"
origin = { xyz = [0.0, 0.0, -0.5] }
axis = [0.0, 1.0, 0.0]
actuated = true
initial = { q = 0.05, qd = -0.2 }
[[joint]]
name = "k2"
type = "prismatic"
parent = "p2"
child = "s2"
origin = { xyz = [0.0, 0.0, -0.4] }
axis = [0.0, 0.0, 1.0]
stiffness = 20.0
[[coupling]]
a = "j1"
b = "j2"
ratio = 0.5
offset = -0.2
[[coupling]]
a = "k1"
b = "k2"
ratio = -1.5
"#;

/// Every joint kind that takes an armature gets one (the spherical joint j5 cannot).
pub fn with_armature(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        out.push_str(line);
        out.push('\n');
        if line.starts_with("type = \"") && !line.contains("spherical") && !line.contains("fixed") {
            out.push_str("armature = 0.35\n");
        }
    }
    out
}
