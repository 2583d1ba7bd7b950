//! OpenRocket's clusters of inner tubes, as the design format's `cluster` offsets.
//!
//! OpenRocket draws a cluster from a named pattern of points whose nearest two are one unit
//! apart (`rocketcomponent/ClusterConfiguration.java`), turned by the tube's cluster
//! rotation less its radial direction and scaled by the separation, the tube's outer
//! diameter times its cluster scale (`InnerTube.getClusterPoints`). The tube's own radial
//! offset is the design's `radial_offset_m`, so the offsets here are from the tube's axis.
//! Written out by hand: the patterns are OpenRocket's data, a table of 15 rows.

use super::{DesignError, El};
use std::f64::consts::PI;

/// The points of OpenRocket's pattern `name`, in units of the separation, or `None` for a
/// name OpenRocket does not have.
fn pattern(name: &str) -> Option<Vec<[f64; 2]>> {
    let sqrt2 = 2f64.sqrt();
    let sqrt3 = 3f64.sqrt();
    let r5 = 1.0 / (2.0 * (2.0 * PI / 10.0).sin());
    // A pentagon of radius `r`, its first corner on the pattern's second axis: (r sin θ, r cos θ).
    let ring5 = |r: f64| -> Vec<[f64; 2]> {
        (0..5)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / 5.0;
                [r * a.sin(), r * a.cos()]
            })
            .collect()
    };
    let h = sqrt3 / 2.0;
    // A hexagon of unit side, its first corner on the pattern's second axis.
    let ring6 = [
        [0.0, 1.0],
        [h, 0.5],
        [h, -0.5],
        [0.0, -1.0],
        [-h, -0.5],
        [-h, 0.5],
    ];
    let d = 1.4 / sqrt2;
    Some(match name {
        "single" => vec![[0.0, 0.0]],
        "double" => vec![[-0.5, 0.0], [0.5, 0.0]],
        "3-row" => vec![[-1.0, 0.0], [0.0, 0.0], [1.0, 0.0]],
        "4-row" => vec![[-1.5, 0.0], [-0.5, 0.0], [0.5, 0.0], [1.5, 0.0]],
        "3-ring" => vec![
            [-0.5, -1.0 / (2.0 * sqrt3)],
            [0.5, -1.0 / (2.0 * sqrt3)],
            [0.0, 1.0 / sqrt3],
        ],
        "4-ring" => vec![[-0.5, 0.5], [0.5, 0.5], [0.5, -0.5], [-0.5, -0.5]],
        "5-ring" => ring5(r5),
        "6-ring" => ring6.to_vec(),
        "3-star" => vec![[0.0, 0.0], [0.0, 1.0], [h, -0.5], [-h, -0.5]],
        "4-star" => vec![
            [0.0, 0.0],
            [-1.0 / sqrt2, 1.0 / sqrt2],
            [1.0 / sqrt2, 1.0 / sqrt2],
            [1.0 / sqrt2, -1.0 / sqrt2],
            [-1.0 / sqrt2, -1.0 / sqrt2],
        ],
        "5-star" => {
            let mut v = vec![[0.0, 0.0]];
            v.extend(ring5(1.0));
            v
        }
        "6-star" => {
            let mut v = vec![[0.0, 0.0]];
            v.extend(ring6);
            v
        }
        "9-grid" => {
            let mut v = Vec::with_capacity(9);
            for y in [1.4, 0.0, -1.4] {
                for x in [-1.4, 0.0, 1.4] {
                    v.push([x, y]);
                }
            }
            v
        }
        "9-star" => vec![
            [0.0, 0.0],
            [1.4, 0.0],
            [d, -d],
            [0.0, -1.4],
            [-d, -d],
            [-1.4, 0.0],
            [-d, d],
            [0.0, 1.4],
            [d, d],
        ],
        _ => return None,
    })
}

/// The offsets from the tube's axis of the tubes of an `<innertube>`'s cluster, m (one
/// `[0, 0]` for a single tube), as OpenRocket places them.
pub(super) fn offsets(el: &El<'_, '_>, outer_radius_m: f64) -> Result<Vec<[f64; 2]>, DesignError> {
    let name = el.text("clusterconfiguration").unwrap_or("single");
    let points = pattern(name).ok_or_else(|| {
        el.bad(
            "clusterconfiguration",
            format!("\"{name}\" is not one of OpenRocket's cluster patterns"),
        )
    })?;
    if points.len() == 1 {
        return Ok(points);
    }
    let scale = el.num("clusterscale")?.unwrap_or(1.0).max(0.0);
    let separation = 2.0 * outer_radius_m * scale;
    let rotation = el.num("clusterrotation")?.unwrap_or(0.0).to_radians()
        - el.num("radialdirection")?.unwrap_or(0.0).to_radians();
    let (sin, cos) = rotation.sin_cos();
    Ok(points
        .into_iter()
        .map(|[x, y]| {
            [
                (x * cos + y * sin) * separation,
                (-x * sin + y * cos) * separation,
            ]
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::pattern;

    /// Every pattern's nearest two points are one unit apart, as OpenRocket defines them,
    /// but the nine-tube ones (a grid of pitch 1.4; a ring of radius 1.4 round a center).
    #[test]
    fn a_cluster_pattern_s_nearest_tubes_are_one_separation_apart() {
        for (name, count, nearest) in [
            ("double", 2, 1.0),
            ("3-row", 3, 1.0),
            ("4-row", 4, 1.0),
            ("3-ring", 3, 1.0),
            ("4-ring", 4, 1.0),
            ("5-ring", 5, 1.0),
            ("6-ring", 6, 1.0),
            ("3-star", 4, 1.0),
            ("4-star", 5, 1.0),
            ("5-star", 6, 1.0),
            ("6-star", 7, 1.0),
            ("9-grid", 9, 1.4),
            ("9-star", 9, 2.0 * 1.4 * (std::f64::consts::PI / 8.0).sin()),
        ] {
            let p = pattern(name).unwrap();
            assert_eq!(p.len(), count, "{name}");
            let mut min = f64::INFINITY;
            for i in 0..p.len() {
                for j in i + 1..p.len() {
                    min = min.min((p[i][0] - p[j][0]).hypot(p[i][1] - p[j][1]));
                }
            }
            assert!((min - nearest).abs() < 1e-15, "{name}: {min} vs {nearest}");
        }
        assert!(pattern("7-ring").is_none());
    }
}
