//! The landing maps: the landing points, the 1/2/3σ ellipses (as polygons), the R90 and R99
//! circles and the launch point of every sweep point, in WGS 84 longitude and latitude, as
//! KML for Google Earth (the `kml` crate) and GeoJSON for QGIS and web maps (the `geojson`
//! crate). Written only when the scenario gives the site's latitude and longitude.
//!
//! The launch frame is the plane tangent to the WGS 84 ellipsoid at the rail's foot (x east,
//! y north, z up). A point of it is carried to the Earth through Earth-centred coordinates
//! (exactly, no small-offset approximation) and back by the inverse, so a map's vertex read
//! back gives the metres it was drawn from.

use super::data::Run;
use super::numbers::radii;
use geojson::{Feature, FeatureCollection, Geometry, GeometryValue, JsonObject};
use kml::types::{
    AltitudeMode, Coord, Element, Folder, Geometry as KmlGeometry, LineStyle, LinearRing,
    MultiGeometry, Placemark, Point, PolyStyle, Polygon, Style,
};
use kml::{Kml, KmlWriter};
use std::collections::HashMap;

/// WGS 84's semi-major axis, m, and flattening.
const A: f64 = 6_378_137.0;
const F: f64 = 1.0 / 298.257_223_563;

/// Vertices of an ellipse or a circle polygon (the ring closes on its first).
pub const VERTICES: usize = 72;

/// The launch site on the Earth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    /// Height of the rail's foot above the ellipsoid, m (the scenario's elevation).
    pub height_m: f64,
}

fn e2() -> f64 {
    F * (2.0 - F)
}

fn ecef(lat_deg: f64, lon_deg: f64, h: f64) -> [f64; 3] {
    let (phi, lam) = (lat_deg.to_radians(), lon_deg.to_radians());
    let n = A / (1.0 - e2() * phi.sin().powi(2)).sqrt();
    [
        (n + h) * phi.cos() * lam.cos(),
        (n + h) * phi.cos() * lam.sin(),
        (n * (1.0 - e2()) + h) * phi.sin(),
    ]
}

/// Latitude, longitude (degrees) and height (m) of an Earth-centred point (iterated to
/// convergence; points near the surface need a handful of rounds).
fn geodetic(p: [f64; 3]) -> (f64, f64, f64) {
    let lam = p[1].atan2(p[0]);
    let r = p[0].hypot(p[1]);
    let mut phi = p[2].atan2(r * (1.0 - e2()));
    let mut h = 0.0;
    for _ in 0..20 {
        let n = A / (1.0 - e2() * phi.sin().powi(2)).sqrt();
        h = r / phi.cos() - n;
        let next = p[2].atan2(r * (1.0 - e2() * n / (n + h)));
        if (next - phi).abs() < 1e-15 {
            phi = next;
            break;
        }
        phi = next;
    }
    (phi.to_degrees(), lam.to_degrees(), h)
}

impl Site {
    /// The latitude and longitude (degrees) of a point `east`, `north` m from the rail's
    /// foot in the launch frame's ground plane.
    pub fn to_geodetic(&self, east: f64, north: f64) -> (f64, f64) {
        let (phi, lam) = (
            self.latitude_deg.to_radians(),
            self.longitude_deg.to_radians(),
        );
        let o = ecef(self.latitude_deg, self.longitude_deg, self.height_m);
        let (sp, cp, sl, cl) = (phi.sin(), phi.cos(), lam.sin(), lam.cos());
        let p = [
            o[0] - sl * east - sp * cl * north,
            o[1] + cl * east - sp * sl * north,
            o[2] + cp * north,
        ];
        let (lat, lon, _) = geodetic(p);
        (lat, lon)
    }

    /// East and north, m, in the launch frame of the point at `lat`, `lon`: where the
    /// Earth's normal there meets the launch frame's ground plane (the exact inverse of
    /// [`Site::to_geodetic`]).
    pub fn to_launch_frame(&self, lat: f64, lon: f64) -> (f64, f64) {
        let (phi, lam) = (
            self.latitude_deg.to_radians(),
            self.longitude_deg.to_radians(),
        );
        let o = ecef(self.latitude_deg, self.longitude_deg, self.height_m);
        let (sp, cp, sl, cl) = (phi.sin(), phi.cos(), lam.sin(), lam.cos());
        let (east, north, up) = (
            [-sl, cl, 0.0],
            [-sp * cl, -sp * sl, cp],
            [cp * cl, cp * sl, sp],
        );
        let p0 = ecef(lat, lon, self.height_m);
        let (pp, pl) = (lat.to_radians(), lon.to_radians());
        let normal = [pp.cos() * pl.cos(), pp.cos() * pl.sin(), pp.sin()];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let d0 = [p0[0] - o[0], p0[1] - o[1], p0[2] - o[2]];
        let s = -dot(d0, up) / dot(normal, up);
        let d = [
            d0[0] + s * normal[0],
            d0[1] + s * normal[1],
            d0[2] + s * normal[2],
        ];
        (dot(d, east), dot(d, north))
    }
}

/// The site a run's metadata gives (`hpr_mc.latitude_deg`, `hpr_mc.longitude_deg`), at the
/// scenario's elevation.
pub fn site(run: &Run, elevation_m: f64) -> Option<Site> {
    let lat = run.meta.get("hpr_mc.latitude_deg")?.parse().ok()?;
    let lon = run.meta.get("hpr_mc.longitude_deg")?.parse().ok()?;
    Some(Site {
        latitude_deg: lat,
        longitude_deg: lon,
        height_m: elevation_m,
    })
}

/// The vertices (east, north, m) of the ellipse of semi-axes `a` along `angle_deg`
/// (counterclockwise from east) and `b`, closed on the first.
pub fn ellipse_ring(c: (f64, f64), a: f64, b: f64, angle_deg: f64) -> Vec<(f64, f64)> {
    let (s, co) = angle_deg.to_radians().sin_cos();
    (0..=VERTICES)
        .map(|k| {
            let t = std::f64::consts::TAU * (k % VERTICES) as f64 / VERTICES as f64;
            let (u, v) = (a * t.cos(), b * t.sin());
            (c.0 + u * co - v * s, c.1 + u * s + v * co)
        })
        .collect()
}

/// What one sweep point puts on the map.
pub struct PointShapes {
    pub point: usize,
    pub label: String,
    /// Landings: variant id, east, north (of the rows the report holds: the first N of the
    /// point's flights when the run is larger than it holds).
    pub landings: Vec<(u64, f64, f64)>,
    /// Where the landings are a sample, said in words (empty when they are every flight).
    pub sample: String,
    /// k σ ellipses: sigma and ring.
    pub ellipses: Vec<(u8, Vec<(f64, f64)>)>,
    /// R90 and R99 about the mean landing point: name, radius, ring.
    pub circles: Vec<(String, f64, Vec<(f64, f64)>)>,
}

/// The shapes of every point of the run.
pub fn shapes(run: &Run, labels: &[String]) -> Vec<PointShapes> {
    let (Some(mx), Some(my)) = (run.metric("landing_x_m"), run.metric("landing_y_m")) else {
        return vec![];
    };
    (0..run.points())
        .map(|pt| {
            let landings: Vec<(u64, f64, f64)> = (0..run.id.len())
                .filter(|&r| run.point[r] == pt && run.status[r] == super::data::Status::Landed)
                .map(|r| {
                    (
                        run.id[r],
                        run.metric_values[mx][r],
                        run.metric_values[my][r],
                    )
                })
                .filter(|(_, x, y)| x.is_finite() && y.is_finite())
                .collect();
            let ellipses = run
                .ellipses
                .iter()
                .filter(|e| e.point == pt && e.body == super::data::Body::Rocket)
                .map(|e| {
                    (
                        e.sigma,
                        ellipse_ring(
                            (e.center_x_m, e.center_y_m),
                            e.semi_major_m,
                            e.semi_minor_m,
                            e.major_axis_deg,
                        ),
                    )
                })
                .collect();
            let xs: Vec<f64> = landings.iter().map(|l| l.1).collect();
            let ys: Vec<f64> = landings.iter().map(|l| l.2).collect();
            let circles = if xs.is_empty() {
                vec![]
            } else {
                let n = xs.len() as f64;
                let c = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
                let r = radii(&xs, &ys, c, &[0.9, 0.99]);
                ["R90", "R99"]
                    .iter()
                    .zip(r)
                    .map(|(name, r)| (name.to_string(), r, ellipse_ring(c, r, r, 0.0)))
                    .collect()
            };
            PointShapes {
                point: pt,
                label: labels.get(pt).cloned().unwrap_or_default(),
                landings,
                sample: run.sample_text(pt),
                ellipses,
                circles,
            }
        })
        .collect()
}

fn text(name: &str, content: &str) -> Kml {
    Kml::Element(Element {
        name: name.to_string(),
        content: Some(content.to_string()),
        ..Element::default()
    })
}

fn kml_ring(site: &Site, ring: &[(f64, f64)]) -> KmlGeometry {
    let coords = ring
        .iter()
        .map(|&(e, n)| {
            let (lat, lon) = site.to_geodetic(e, n);
            Coord::new(lon, lat, None)
        })
        .collect();
    let mut poly = Polygon::new(
        LinearRing {
            coords,
            ..LinearRing::default()
        },
        vec![],
    );
    poly.tessellate = true;
    poly.altitude_mode = AltitudeMode::ClampToGround;
    KmlGeometry::Polygon(poly)
}

fn placemark(name: String, style: &str, geometry: KmlGeometry) -> Kml {
    Kml::Placemark(Placemark {
        name: Some(name),
        style_url: Some(format!("#{style}")),
        geometry: Some(geometry),
        ..Placemark::default()
    })
}

/// KML's colour (aabbggrr) of an RGB hex colour with an opacity.
fn kml_color(rgb: &str, opacity: f64) -> String {
    let h = rgb.trim_start_matches('#');
    let a = (opacity.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("{a:02x}{}{}{}", &h[4..6], &h[2..4], &h[0..2]).to_lowercase()
}

fn line_style(id: &str, rgb: &str, width: f64) -> Kml {
    Kml::Style(Style {
        id: Some(id.to_string()),
        line: Some(LineStyle {
            color: kml_color(rgb, 1.0),
            width,
            ..LineStyle::default()
        }),
        poly: Some(PolyStyle {
            color: kml_color(rgb, 0.12),
            fill: true,
            outline: true,
            ..PolyStyle::default()
        }),
        ..Style::default()
    })
}

/// The KML document of the run's landing maps.
pub fn kml(site: &Site, title: &str, points: &[PointShapes]) -> anyhow::Result<String> {
    let mut elements = vec![
        text("name", &format!("{title}: landings")),
        line_style("ellipse", "#D55E00", 2.0),
        line_style("radius", "#0072B2", 1.5),
        Kml::Style(Style {
            id: Some("landing".into()),
            icon: Some(kml::types::IconStyle {
                scale: 0.4,
                color: kml_color("#0072B2", 0.8),
                icon: kml::types::Icon {
                    href: "http://maps.google.com/mapfiles/kml/shapes/shaded_dot.png".into(),
                    ..kml::types::Icon::default()
                },
                ..kml::types::IconStyle::default()
            }),
            ..Style::default()
        }),
        Kml::Style(Style {
            id: Some("pad".into()),
            icon: Some(kml::types::IconStyle {
                scale: 1.1,
                color: kml_color("#000000", 1.0),
                icon: kml::types::Icon {
                    href: "http://maps.google.com/mapfiles/kml/shapes/triangle.png".into(),
                    ..kml::types::Icon::default()
                },
                ..kml::types::IconStyle::default()
            }),
            ..Style::default()
        }),
        placemark(
            "launch point".into(),
            "pad",
            KmlGeometry::Point(Point::new(site.longitude_deg, site.latitude_deg, None)),
        ),
    ];
    for p in points {
        let mut inner = vec![];
        for (k, ring) in &p.ellipses {
            inner.push(placemark(
                format!("{k}σ landing ellipse"),
                "ellipse",
                kml_ring(site, ring),
            ));
        }
        for (name, r, ring) in &p.circles {
            inner.push(placemark(
                format!("{name} = {r:.0} m about the mean landing point"),
                "radius",
                kml_ring(site, ring),
            ));
        }
        if !p.landings.is_empty() {
            let points = p
                .landings
                .iter()
                .map(|&(_, e, n)| {
                    let (lat, lon) = site.to_geodetic(e, n);
                    KmlGeometry::Point(Point::new(lon, lat, None))
                })
                .collect();
            inner.push(placemark(
                if p.sample.is_empty() {
                    format!("{} landings", p.landings.len())
                } else {
                    format!("{} landings: {}", p.landings.len(), p.sample)
                },
                "landing",
                KmlGeometry::MultiGeometry(MultiGeometry::new(points)),
            ));
        }
        elements.push(Kml::Folder(Folder {
            name: Some(format!("point {}{}", p.point, p.label)),
            elements: inner,
            ..Folder::default()
        }));
    }
    let doc = Kml::KmlDocument(kml::KmlDocument {
        attrs: HashMap::from([(
            "xmlns".to_string(),
            "http://www.opengis.net/kml/2.2".to_string(),
        )]),
        elements: vec![Kml::Document {
            attrs: HashMap::new(),
            elements,
        }],
        ..kml::KmlDocument::default()
    });
    let mut buf = b"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n".to_vec();
    KmlWriter::from_writer(&mut buf).write(&doc)?;
    Ok(String::from_utf8(buf)?)
}

fn properties(pairs: &[(&str, serde_json::Value)]) -> JsonObject {
    pairs
        .iter()
        .map(|(k, v)| (k.to_string(), v.clone()))
        .collect()
}

fn feature(geometry: GeometryValue, props: JsonObject) -> Feature {
    Feature {
        geometry: Some(Geometry::new(geometry)),
        properties: Some(props),
        ..Feature::default()
    }
}

/// The GeoJSON feature collection of the run's landing maps (RFC 7946: longitude, latitude
/// in WGS 84; polygons' outer rings counterclockwise).
pub fn geojson(site: &Site, points: &[PointShapes]) -> String {
    use serde_json::json;
    let ring = |ring: &[(f64, f64)]| -> Vec<Vec<f64>> {
        ring.iter()
            .map(|&(e, n)| {
                let (lat, lon) = site.to_geodetic(e, n);
                vec![lon, lat]
            })
            .collect()
    };
    let mut features = vec![feature(
        GeometryValue::new_point([site.longitude_deg, site.latitude_deg]),
        properties(&[("kind", json!("launch_point"))]),
    )];
    for p in points {
        for (k, r) in &p.ellipses {
            features.push(feature(
                GeometryValue::new_polygon([ring(r)]),
                properties(&[
                    ("kind", json!("ellipse")),
                    ("point", json!(p.point)),
                    ("sigma", json!(k)),
                ]),
            ));
        }
        for (name, radius, r) in &p.circles {
            features.push(feature(
                GeometryValue::new_polygon([ring(r)]),
                properties(&[
                    ("kind", json!("radius")),
                    ("point", json!(p.point)),
                    ("name", json!(name)),
                    ("radius_m", json!(radius)),
                ]),
            ));
        }
        if !p.landings.is_empty() {
            let coords: Vec<Vec<f64>> = p
                .landings
                .iter()
                .map(|&(_, e, n)| {
                    let (lat, lon) = site.to_geodetic(e, n);
                    vec![lon, lat]
                })
                .collect();
            let ids: Vec<u64> = p.landings.iter().map(|l| l.0).collect();
            let mut props = vec![
                ("kind", json!("landings")),
                ("point", json!(p.point)),
                ("variant_ids", json!(ids)),
            ];
            if !p.sample.is_empty() {
                props.push(("sample", json!(p.sample)));
            }
            features.push(feature(
                GeometryValue::new_multi_point(coords),
                properties(&props),
            ));
        }
    }
    let fc = FeatureCollection::new(features);
    serde_json::to_string(&fc).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kilometre_north_is_the_meridian_arc_of_a_kilometre() {
        // M = a (1 − e²) / (1 − e² sin² φ)^(3/2): the meridian's radius of curvature. The
        // tangent plane's point sits 0.08 m above the ground; its arc is shorter than the
        // kilometre by d³/3R² = 8e-6 m.
        let site = Site {
            latitude_deg: 45.0,
            longitude_deg: -100.0,
            height_m: 0.0,
        };
        let phi = 45f64.to_radians();
        let m_at = |phi: f64| A * (1.0 - e2()) / (1.0 - e2() * phi.sin().powi(2)).powf(1.5);
        let (lat, lon) = site.to_geodetic(0.0, 1000.0);
        // The arc ∫ M dφ by Simpson's rule (M grows by 1.6e-6 of itself over it).
        let (p0, p1) = (phi, lat.to_radians());
        let arc_m = (p1 - p0) / 6.0 * (m_at(p0) + 4.0 * m_at(0.5 * (p0 + p1)) + m_at(p1));
        assert!((arc_m - 1000.0).abs() < 1e-4, "{arc_m}");
        assert!((lon + 100.0).abs() < 1e-12);
        // East: the parallel's radius N cos φ.
        let n = A / (1.0 - e2() * phi.sin().powi(2)).sqrt();
        let (lat, lon) = site.to_geodetic(1000.0, 0.0);
        let arc_m = (lon + 100.0).to_radians() * n * phi.cos();
        assert!((arc_m - 1000.0).abs() < 1e-4, "{arc_m}");
        assert!(lat < 45.0 && (45.0 - lat).to_radians() * m_at(phi) < 0.1);
    }

    #[test]
    fn the_launch_frame_comes_back_from_the_map() {
        let site = Site {
            latitude_deg: 32.99,
            longitude_deg: -106.97,
            height_m: 1400.0,
        };
        for (e, n) in [(0.0, 0.0), (350.0, -1200.0), (-2500.0, 800.0)] {
            let (lat, lon) = site.to_geodetic(e, n);
            let (e2_, n2) = site.to_launch_frame(lat, lon);
            assert!(
                (e2_ - e).abs() < 1e-7 && (n2 - n).abs() < 1e-7,
                "{e2_} {n2}"
            );
        }
    }
}
