//! Spec entries an importer starts from: a spec without bodies, a body without mass, a collision shape without a
//! geometry or law of its own; the importer fills in the rest.

use crate::spec::{BodySpec, CollisionSpec, InertiaSpec, OriginSpec, Spec};

/// A jointed body named `name`, without mass (its inertials are set later).
pub(crate) fn massless_body(name: String, description: String) -> BodySpec {
    BodySpec {
        name,
        mass: 0.0,
        com: [0.0; 3],
        inertia: InertiaSpec::Full([0.0; 6]),
        position: None,
        orientation: None,
        velocity: None,
        angular_velocity: None,
        description,
    }
}

/// A collision shape on `body` at `origin`, its shape and law still to be set.
pub(crate) fn collision_on(body: String, origin: OriginSpec) -> CollisionSpec {
    CollisionSpec {
        name: None,
        body,
        origin,
        sphere: None,
        capsule: None,
        cuboid: None,
        cylinder: None,
        friction: None,
        stiffness: None,
        damping: None,
    }
}

/// A spec named `name` with nothing in it (default gravity, experiment and solver).
pub(crate) fn empty_spec(name: String, description: String) -> Spec {
    Spec {
        name,
        description,
        gravity: [0.0, 0.0, -9.81],
        experiment: Default::default(),
        solver: Default::default(),
        body: Vec::new(),
        joint: Vec::new(),
        load: Vec::new(),
        site: Vec::new(),
        visual: Vec::new(),
        ground: None,
        collision: Vec::new(),
        contact_pair: Vec::new(),
        self_collision: false,
        coupling: Vec::new(),
        actuator: Vec::new(),
    }
}
