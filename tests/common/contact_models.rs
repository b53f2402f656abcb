//! Contact models shared by the tests of linear models: a ball and a box resting on the
//! ground at their equilibrium depths.

/// The ground's stiffness of the models, N/m.
pub const K: f64 = 1e5;
/// Gravity, m/s².
pub const G: f64 = 9.81;

/// A 1 kg ball of radius 0.1 m (I = 0.004 kg·m²) resting on the ground (k = 1e5 N/m, μ = 0.5,
/// d = 0.5 s/m) at its equilibrium depth, with velocity `v` and angular velocity `w`.
pub fn ball(v: [f64; 3], w: [f64; 3]) -> String {
    format!(
        r#"
name = "Ball"
gravity = [0.0, 0.0, -9.81]
[solver]
max_step = 1e-3
[ground]
friction = 0.5
stiffness = 1e5
damping = 0.5
[[body]]
name = "ball"
mass = 1.0
inertia = [0.004, 0.004, 0.004]
position = [0.0, 0.0, {z}]
velocity = {v:?}
angular_velocity = {w:?}
[[load]]
body = "ball"
force = true
[[collision]]
name = "shell"
body = "ball"
sphere = {{ radius = 0.1 }}
"#,
        z = 0.1 - G / K
    )
}

/// A 2 kg box 0.4 × 0.3 × 0.1 m resting on its four lower corners at their equilibrium depth.
pub fn resting_box() -> String {
    let (m, a, b, c) = (2.0_f64, 0.4_f64, 0.3_f64, 0.1_f64);
    format!(
        r#"
name = "Box"
gravity = [0.0, 0.0, -9.81]
[solver]
max_step = 1e-3
[ground]
friction = 0.8
stiffness = 1e5
damping = 1.0
[[body]]
name = "box"
mass = {m}
inertia = [{ix}, {iy}, {iz}]
position = [0.0, 0.0, {z}]
[[load]]
body = "box"
force = true
torque = true
[[collision]]
name = "block"
body = "box"
box = {{ size = [{a}, {b}, {c}] }}
"#,
        ix = m * (b * b + c * c) / 12.0,
        iy = m * (a * a + c * c) / 12.0,
        iz = m * (a * a + b * b) / 12.0,
        z = c / 2.0 - m * G / (4.0 * K)
    )
}
