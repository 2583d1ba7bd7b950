//! A solid motor's propellant as BATES grains (RocketPy's `SolidMotor`): `n` hollow
//! cylinders of outer radius `R`, bore `r` and height `h`, stacked `h₀ + s` apart, burning
//! from the bore and both ends. Each grain's bore grows as its ends recede (`h′ = −2 r′`), so
//! its height is `h = h₀ − 2 (r − r₀)` and the propellant left fixes the bore:
//!
//! ```text
//! m = n ρ π (R² − r²) (H − 2 r),   H = h₀ + 2 r₀
//! ```
//!
//! (RocketPy integrates the two rates from the mass flow; the closed form is the same curve.)
//! About the grains' common center (RocketPy's `propellant_I_11`, `propellant_I_33`):
//!
//! ```text
//! I_transverse = m (¼ (R² + r²) + h²/12 + D/n),   D = Σ dᵢ² = (h₀ + s)² n (n² − 1)/12
//! I_axial      = ½ m (R² + r²)
//! ```
//!
//! with the grains' centers `dᵢ = (i − (n − 1)/2)(h₀ + s)` from the middle, as RocketPy keeps
//! them. The flight needs the inertia's first rate (and the tests its second), which follow
//! from `dr/dm = 1/(n ρ π g′(r))`, `g(r) = (R² − r²)(H − 2r)`. The bore for a mass is found by
//! Newton's method kept inside its bracket: a pure function, so every lane finds the same.

use super::MotorField;

/// The grains of one motor (RocketPy's `grain_number`, `grain_outer_radius`,
/// `grain_initial_inner_radius`, `grain_initial_height`, `grain_separation`, `grain_density`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grains {
    pub count: u32,
    pub outer_radius_m: f64,
    pub inner_radius_m: f64,
    pub height_m: f64,
    pub separation_m: f64,
    pub density_kg_m3: f64,
}

/// The propellant's inertia about its center and its derivatives in the propellant's mass:
/// `[axial, transverse]` each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrainInertia {
    pub inertia_kg_m2: [f64; 2],
    /// d/dm, m².
    pub per_kg_m2: [f64; 2],
    /// d²/dm², m²/kg.
    pub per_kg2_m2: [f64; 2],
}

impl Grains {
    /// The grains' propellant mass, kg: `n ρ π (R² − r₀²) h₀`.
    pub fn mass_kg(&self) -> f64 {
        self.scale() * (self.outer_radius_m.powi(2) - self.inner_radius_m.powi(2)) * self.height_m
    }

    /// Length of the stack, m: `n h₀ + (n − 1) s`.
    pub fn stack_length_m(&self) -> f64 {
        let n = f64::from(self.count);
        n * self.height_m + (n - 1.0) * self.separation_m
    }

    /// The first rule the grains break, as (field, its value, rule), if any.
    pub fn check(&self) -> Option<(MotorField, f64, &'static str)> {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if self.count == 0 {
            return Some((MotorField::GrainsCount, 0.0, "must be at least 1"));
        }
        if !positive(self.outer_radius_m) {
            return Some((
                MotorField::GrainsOuterRadius,
                self.outer_radius_m,
                "must be positive and finite",
            ));
        }
        if !(self.inner_radius_m.is_finite()
            && self.inner_radius_m >= 0.0
            && self.inner_radius_m < self.outer_radius_m)
        {
            return Some((
                MotorField::GrainsInnerRadius,
                self.inner_radius_m,
                "must be at least 0 and less than outer_radius_m",
            ));
        }
        if !positive(self.height_m) {
            return Some((
                MotorField::GrainsHeight,
                self.height_m,
                "must be positive and finite",
            ));
        }
        if !(self.separation_m.is_finite() && self.separation_m >= 0.0) {
            return Some((
                MotorField::GrainsSeparation,
                self.separation_m,
                "must be finite and not negative",
            ));
        }
        if !positive(self.density_kg_m3) {
            return Some((
                MotorField::GrainsDensity,
                self.density_kg_m3,
                "must be positive and finite",
            ));
        }
        None
    }

    /// `n ρ π`, kg/m³.
    fn scale(&self) -> f64 {
        f64::from(self.count) * self.density_kg_m3 * std::f64::consts::PI
    }

    /// `H = h₀ + 2 r₀`: the height is `H − 2r`.
    fn h_total(&self) -> f64 {
        self.height_m + 2.0 * self.inner_radius_m
    }

    /// The bore where the grains hold `mass_kg` of propellant (`r₀` full, where the wall or
    /// the height runs out empty).
    pub fn bore_m(&self, mass_kg: f64) -> f64 {
        let (big_r, r0, h) = (self.outer_radius_m, self.inner_radius_m, self.h_total());
        let full = self.mass_kg();
        if mass_kg >= full {
            return r0;
        }
        let end = big_r.min(0.5 * h);
        if mass_kg <= 0.0 {
            return end;
        }
        let v = mass_kg / self.scale();
        let g = |r: f64| (big_r * big_r - r * r) * (h - 2.0 * r);
        let dg = |r: f64| 6.0 * r * r - 2.0 * r * h - 2.0 * big_r * big_r;
        // g falls from its full value at r₀ to 0 at the end: keep the root bracketed.
        let (mut lo, mut hi) = (r0, end);
        let mut r = r0 + (end - r0) * (1.0 - mass_kg / full);
        for _ in 0..100 {
            let f = g(r) - v;
            if f > 0.0 {
                lo = r;
            } else {
                hi = r;
            }
            let d = dg(r);
            let mut next = r - f / d;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - r).abs() <= 1e-15 * big_r || hi - lo <= 1e-15 * big_r {
                return next;
            }
            r = next;
        }
        r
    }

    /// Inertia and its derivatives for `mass_kg` of propellant in these grains.
    pub fn inertia(&self, mass_kg: f64) -> GrainInertia {
        let (big_r, h_total) = (self.outer_radius_m, self.h_total());
        let n = f64::from(self.count);
        let pitch = self.height_m + self.separation_m;
        let spread = pitch * pitch * (n * n - 1.0) / 12.0;
        let r = self.bore_m(mass_kg);
        let h = h_total - 2.0 * r;
        let m = mass_kg.max(0.0);
        // dr/dm and d²r/dm² from g(r) = m / (n ρ π).
        let dg = 6.0 * r * r - 2.0 * r * h_total - 2.0 * big_r * big_r;
        let d2g = 12.0 * r - 2.0 * h_total;
        let r1 = 1.0 / (self.scale() * dg);
        let r2 = -self.scale() * d2g * r1 * r1 * r1;
        // Transverse: m f(r), f = ¼(R² + r²) + h²/12 + D/n, f′ = r/2 − h/3, f″ = 7/6.
        let f = 0.25 * (big_r * big_r + r * r) + h * h / 12.0 + spread;
        let f1 = 0.5 * r - h / 3.0;
        let f2 = 7.0 / 6.0;
        // Axial: m a(r), a = ½ (R² + r²), a′ = r, a″ = 1.
        let a = 0.5 * (big_r * big_r + r * r);
        GrainInertia {
            inertia_kg_m2: [m * a, m * f],
            per_kg_m2: [a + m * r * r1, f + m * f1 * r1],
            per_kg2_m2: [
                2.0 * r * r1 + m * (r1 * r1 + r * r2),
                2.0 * f1 * r1 + m * (f2 * r1 * r1 + f1 * r2),
            ],
        }
    }
}

impl Grains {
    /// The inertia of `motors` such stacks sharing `mass_kg` of propellant equally, each about
    /// its own center: `k I(m/k)`, its derivatives `I′(m/k)` and `I″(m/k)/k`. (Where their
    /// centers lie off the axis is the cluster's parallel-axis term, proportional to the mass.)
    pub fn cluster_inertia(&self, motors: usize, mass_kg: f64) -> GrainInertia {
        if motors <= 1 {
            return self.inertia(mass_kg);
        }
        let k = motors as f64;
        let one = self.inertia(mass_kg / k);
        GrainInertia {
            inertia_kg_m2: one.inertia_kg_m2.map(|i| i * k),
            per_kg_m2: one.per_kg_m2,
            per_kg2_m2: one.per_kg2_m2.map(|i| i / k),
        }
    }
}
