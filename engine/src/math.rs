//! The geometry vocabulary of the engine: parry's types (glam underneath), so that
//! positions go to parry's ray casts and BVH without conversion. Signatures use
//! these names, never glam's or nalgebra's.

pub use parry2d_f64::math::{Pose, Vector};

/// A position in the world frame, metres: a vector from the world origin (glam has
/// no separate point type).
pub type Point = Vector;
