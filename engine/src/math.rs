//! The geometry vocabulary of the engine. Signatures use these names, never
//! nalgebra's generic types.

/// The scalar type: metres, seconds, radians.
pub type Real = f64;
/// A position in the world frame, metres.
pub type Point = nalgebra::Point2<Real>;
/// A displacement in the world frame, metres.
pub type Vector = nalgebra::Vector2<Real>;
