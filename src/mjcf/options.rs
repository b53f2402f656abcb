//! The options of MJCF import (`triad import`; the defaults are those of every other command).

/// The options of MJCF import.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    /// Leave out the collision shapes and the ground (`--no-contacts`).
    pub no_contacts: bool,
    /// The `<key>` whose `qpos` and `qvel` are the initial state (`--keyframe NAME`); by
    /// default the model's own pose (`qpos0`: hinges and slides at their `ref`).
    pub keyframe: Option<String>,
}
