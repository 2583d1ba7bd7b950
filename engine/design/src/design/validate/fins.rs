//! Fin sets: the count, the planform (free-form outline, elliptical, or trapezoidal with its
//! tip chord and sweep), the section and the cant, checked before the fin set is placed on
//! its body.

use super::{Builder, MAX_CANT_DEG, MAX_FINS};
use crate::design::model::*;
use crate::design::raw::*;
use crate::error::{DesignError, Location, Rule};

/// A free-form fin's outline checked: at least three corners, every one finite and none below
/// the root (`y >= 0`), the first the root's leading edge `(0, 0)`, the last its trailing edge
/// `(root chord > 0, 0)`, some corner off the root, no corner twice in a row, and no two edges
/// crossing (the root, from the last corner back to the first, is an edge too). The error is
/// the corner and the rule.
fn fin_outline(points: &[[f64; 2]]) -> Result<(), (usize, &'static str)> {
    let n = points.len();
    if n < 3 {
        return Err((n, "an outline needs at least three corners"));
    }
    for (i, p) in points.iter().enumerate() {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err((i, "must be finite"));
        }
        if p[1] < 0.0 {
            return Err((i, "must not be below the root (y >= 0)"));
        }
        if p[0].abs() > MAX_PART_SIZE_M || p[1] > MAX_PART_SIZE_M {
            return Err((
                i,
                "must be within 30 m (MAX_PART_SIZE_M) of the root's leading edge: \
                 the outline is in metres",
            ));
        }
        if i > 0 && *p == points[i - 1] {
            return Err((i, "repeats the corner before it"));
        }
    }
    if points[0] != [0.0, 0.0] {
        return Err((0, "must be the root's leading edge, [0, 0]"));
    }
    let last = points[n - 1];
    if !(last[1] == 0.0 && last[0] > 0.0) {
        return Err((
            n - 1,
            "must be the root's trailing edge, [root chord > 0, 0]",
        ));
    }
    if points.iter().all(|p| p[1] == 0.0) {
        return Err((1, "the outline must leave the root (some y > 0)"));
    }
    // Edges i: points[i] → points[i + 1 mod n]; adjacent edges share a corner.
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    for i in 0..n {
        for j in i + 1..n {
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            let ((a, b), (c, d)) = (edge(i), edge(j));
            let (d1, d2) = (orient(a, b, c), orient(a, b, d));
            let (d3, d4) = (orient(c, d, a), orient(c, d, b));
            let straddle = d1 * d2 <= 0.0 && d3 * d4 <= 0.0;
            // Four zeros: the edges lie on one line and meet only if their extents overlap.
            let collinear = d1 == 0.0 && d2 == 0.0 && d3 == 0.0 && d4 == 0.0;
            let overlap =
                |k: usize| a[k].min(b[k]).max(c[k].min(d[k])) <= a[k].max(b[k]).min(c[k].max(d[k]));
            if straddle && (!collinear || (overlap(0) && overlap(1))) {
                return Err((j, "its edge crosses another edge of the outline"));
            }
        }
    }
    Ok(())
}

impl Builder<'_> {
    /// A fin set's own fields checked: its count, planform, thickness, cant, rotation, cross
    /// section and section lift (its body radius is set once it is placed).
    pub(super) fn fin_set(&self, at: &Location, f: &RawFinSet) -> Result<FinSet, DesignError> {
        if f.count < 1 || f.count > MAX_FINS {
            return Err(self.invalid(
                at,
                Some("count"),
                Rule::FinCount {
                    got: f.count,
                    max: MAX_FINS,
                },
            ));
        }
        let (planform, root, span) = match f.planform {
            RawFinPlanform::FreeForm => self.free_form_fin(at, f)?,
            planform => self.chord_and_span_fin(at, f, planform)?,
        };
        let thickness = self.size(at, "thickness_m", f.thickness_m)?;
        let cant = self.within(at, "cant_deg", f.cant_deg, -MAX_CANT_DEG, MAX_CANT_DEG)?;
        let rotation = self.finite(at, "rotation_deg", f.rotation_deg)?;
        Ok(FinSet {
            count: f.count,
            root_chord_m: root,
            span_m: span,
            planform,
            thickness_m: thickness,
            cant_deg: cant,
            body_radius_m: 0.0, // set once placed
            rotation_deg: rotation,
            cross_section: match f.cross_section {
                RawCrossSection::Square => FinCrossSection::Square,
                RawCrossSection::Rounded => FinCrossSection::Rounded,
                RawCrossSection::Airfoil => FinCrossSection::Airfoil,
            },
            lift_slope_2d_per_rad: match &f.airfoil {
                Some(a) => self.airfoil_lift_slope(at, a)?,
                None => 2.0 * std::f64::consts::PI,
            },
        })
    }

    /// Refuses the first of `given`'s fields that is given (`true`), as one `planform` does
    /// not take.
    fn not_for_planform(
        &self,
        at: &Location,
        planform: &'static str,
        given: &[(&'static str, bool)],
    ) -> Result<(), DesignError> {
        match given.iter().find(|(_, g)| *g) {
            Some((field, _)) => {
                Err(self.invalid(at, Some(field), Rule::NotForPlanform { planform }))
            }
            None => Ok(()),
        }
    }

    /// A free-form fin: its outline checked corner by corner; its root chord is the last
    /// corner's `x`, its span the highest `y`. (planform, root chord, span), m.
    fn free_form_fin(
        &self,
        at: &Location,
        f: &RawFinSet,
    ) -> Result<(FinPlanform, f64, f64), DesignError> {
        self.not_for_planform(
            at,
            "free_form",
            &[
                ("root_chord_m", f.root_chord_m.is_some()),
                ("tip_chord_m", f.tip_chord_m.is_some()),
                ("span_m", f.span_m.is_some()),
                ("sweep_m", f.sweep_m.is_some()),
                ("sweep_deg", f.sweep_deg.is_some()),
            ],
        )?;
        let points = f.points_m.clone().ok_or_else(|| {
            self.invalid(
                at,
                Some("points_m"),
                Rule::Required {
                    when: "for a free_form fin",
                },
            )
        })?;
        fin_outline(&points).map_err(|(point, why)| {
            self.invalid(at, Some("points_m"), Rule::FinOutline { point, why })
        })?;
        let root = points[points.len() - 1][0];
        let span = points.iter().map(|p| p[1]).fold(0.0, f64::max);
        Ok((FinPlanform::FreeForm { points_m: points }, root, span))
    }

    /// An elliptical or a trapezoidal fin, given by its chords and span (and a trapezoid's
    /// sweep, in metres or degrees). (planform, root chord, span), m.
    fn chord_and_span_fin(
        &self,
        at: &Location,
        f: &RawFinSet,
        planform: RawFinPlanform,
    ) -> Result<(FinPlanform, f64, f64), DesignError> {
        self.not_for_planform(
            at,
            if planform == RawFinPlanform::Elliptical {
                "elliptical"
            } else {
                "trapezoidal"
            },
            &[("points_m", f.points_m.is_some())],
        )?;
        let shape = if planform == RawFinPlanform::Elliptical {
            self.not_for_planform(
                at,
                "elliptical",
                &[
                    ("tip_chord_m", f.tip_chord_m.is_some()),
                    ("sweep_m", f.sweep_m.is_some()),
                    ("sweep_deg", f.sweep_deg.is_some()),
                ],
            )?;
            FinPlanform::Elliptical
        } else {
            self.trapezoid(at, f)?
        };
        let required = |field: &'static str, v: Option<f64>| {
            v.ok_or_else(|| {
                self.invalid(
                    at,
                    Some(field),
                    Rule::Required {
                        when: "unless the planform is free_form",
                    },
                )
            })
        };
        let root = required("root_chord_m", f.root_chord_m)?;
        if !(root > 0.0 && root.is_finite()) {
            let rule = match shape {
                FinPlanform::Trapezoidal { tip_chord_m, .. } if tip_chord_m > 0.0 => {
                    Rule::FinRootChord {
                        root_m: root,
                        tip_m: tip_chord_m,
                    }
                }
                _ => Rule::NotPositive { got: root },
            };
            return Err(self.invalid(at, Some("root_chord_m"), rule));
        }
        self.at_most_part_size(at, "root_chord_m", root)?;
        let span = self.size(at, "span_m", required("span_m", f.span_m)?)?;
        Ok((shape, root, span))
    }

    /// A trapezoidal fin's tip chord and sweep (the tip's leading edge aft of the root's), m.
    fn trapezoid(&self, at: &Location, f: &RawFinSet) -> Result<FinPlanform, DesignError> {
        let tip = match f.tip_chord_m {
            Some(t) => self.size_or_zero(at, "tip_chord_m", t)?,
            None => {
                return Err(self.invalid(
                    at,
                    Some("tip_chord_m"),
                    Rule::Required {
                        when: "for a trapezoidal fin (the default planform)",
                    },
                ))
            }
        };
        let sweep = match (f.sweep_m, f.sweep_deg) {
            (Some(_), Some(_)) => {
                return Err(self.invalid(
                    at,
                    Some("sweep_deg"),
                    Rule::AtMostOneOf {
                        fields: "\"sweep_m\" and \"sweep_deg\"",
                    },
                ))
            }
            // RocketPy: the tip's leading edge s tan Γ behind the root's.
            (None, Some(deg)) => {
                let deg = self.within(at, "sweep_deg", deg, -89.0, 89.0)?;
                f.span_m.unwrap_or(0.0) * deg.to_radians().tan()
            }
            (m, None) => {
                let sweep = self.finite(at, "sweep_m", m.unwrap_or(0.0))?;
                self.at_most_part_size(at, "sweep_m", sweep.abs())?;
                sweep
            }
        };
        Ok(FinPlanform::Trapezoidal {
            tip_chord_m: tip,
            sweep_m: sweep,
        })
    }
}
