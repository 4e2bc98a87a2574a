//! What a disc is made of.

/// One kind of disc: how many there are, their radius and their mass.
///
/// Radius is in the user's length unit (the reference data use diameter σ = 1,
/// i.e. radius 0.5); mass in the user's mass unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Species {
    /// Number of discs of this species.
    pub count: usize,
    /// Disc radius `a` (length).
    pub radius: f64,
    /// Disc mass `m` (mass).
    pub mass: f64,
}

impl Species {
    /// Area covered by one disc, π a² (length²).
    pub fn disc_area(&self) -> f64 {
        std::f64::consts::PI * self.radius * self.radius
    }
}
