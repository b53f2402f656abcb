//! Rigid placements of robot-description import: a frame's rotation and translation in its
//! host frame, composed left to right.
//!
//! ```text
//! (R_a, p_a) ∘ (R_b, p_b) = (R_a R_b, p_a + R_a p_b)
//! ```

use crate::math::{matrix_to_rpy, Mat3, Vec3};
use crate::spec::OriginSpec;

/// A rigid placement: rotation and translation (a frame in its host frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Iso {
    /// Rotation host ← frame.
    pub r: Mat3,
    /// The frame's origin in the host frame, m.
    pub p: Vec3,
}

impl Iso {
    /// The identity placement.
    pub const IDENTITY: Iso = Iso {
        r: Mat3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        p: Vec3::new(0.0, 0.0, 0.0),
    };

    /// `self ∘ b`: `b` placed in the frame `self` places.
    #[must_use]
    pub fn then(&self, b: &Iso) -> Iso {
        Iso {
            r: self.r * b.r,
            p: self.p + self.r * b.p,
        }
    }

    /// The inverse placement (the host in the frame).
    #[must_use]
    pub fn inverse(&self) -> Iso {
        let rt = self.r.transpose();
        Iso {
            r: rt,
            p: -(rt * self.p),
        }
    }

    /// A pure translation.
    #[must_use]
    pub fn shift(p: Vec3) -> Iso {
        Iso {
            r: Mat3::identity(),
            p,
        }
    }

    /// True for the identity, exactly.
    #[must_use]
    pub fn is_identity(&self) -> bool {
        self.p == Vec3::zeros() && self.r == Mat3::identity()
    }

    /// The spec's `origin = { xyz, rpy }` of this placement.
    #[must_use]
    pub fn origin_spec(&self) -> OriginSpec {
        let rpy = matrix_to_rpy(&self.r);
        OriginSpec {
            xyz: [self.p.x, self.p.y, self.p.z],
            rpy: [rpy.x, rpy.y, rpy.z],
        }
    }
}
