//! The report, the maps, the time series and `fly --variant`, checked against the rows of
//! the files the run wrote: what is drawn is what the files hold.

use super::*;
use hpr_mc::campaign::report::maps::Site;
use hpr_mc::campaign::report::numbers::binomial_upper;
use hpr_mc::campaign::{run::prepare, Prepared};

/// A windy scenario of 2 sweep points × `n` variants placed on the Earth, its main at apogee,
/// scattered in drag, wind and rail heading, with `requirements` lines.
fn mapped(n: u64, requirements: &str) -> String {
    windy(
        "wind_speed_m_s = 5.0\nwind_from_deg = 250.0\nlatitude_deg = 32.99\nlongitude_deg = -106.97\nelevation_m = 1400.0",
        "rail_inclination_deg = [84.0, 88.0]",
    )
    .replace("variants_per_point = 4", &format!("variants_per_point = {n}"))
    .replace(
        "[dispersions]\n",
        "[dispersions]\nwind_speed_m_s = { dist = \"truncated_normal\", sigma = 1.5, min = -4.0 }\nrail_heading_deg = { dist = \"normal\", sigma = 3.0 }\n",
    ) + &format!("[outputs]\ntrajectories = 3\n[requirements]\n{requirements}")
}

/// The SVG element of the chart whose clip path is `clip-<id>`.
fn chart<'a>(html: &'a str, id: &str) -> &'a str {
    let at = html
        .find(&format!("id=\"clip-{id}\""))
        .unwrap_or_else(|| panic!("no chart {id}"));
    let start = html[..at].rfind("<svg").unwrap();
    let end = at + html[at..].find("</svg>").unwrap();
    &html[start..end]
}

/// Every value of attribute `name` in `text`, in order.
fn attrs(text: &str, name: &str) -> Vec<String> {
    text.match_indices(&format!(" {name}=\""))
        .map(|(k, m)| {
            let rest = &text[k + m.len()..];
            rest[..rest.find('"').unwrap()].to_string()
        })
        .collect()
}

fn attr_f64(text: &str, name: &str) -> Vec<f64> {
    attrs(text, name)
        .iter()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn run_mapped(text: &str) -> (tempfile::TempDir, PathBuf, hpr_mc::campaign::RunReport) {
    let (dir, file) = setup(text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    assert!(report.complete);
    (dir, file, report)
}

#[test]
fn each_drawn_ellipse_has_the_semi_axes_and_angle_that_ellipses_parquet_holds() {
    let (_dir, _file, report) = run_mapped(&mapped(12, "landing_distance_m = { max = 900.0 }\n"));
    let html = std::fs::read_to_string(&report.report.as_ref().unwrap().report).unwrap();
    let e = read(&report.outputs.ellipses);
    let point = e
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    assert_eq!(e.num_rows(), 6, "two points × 1, 2, 3 σ");
    for pt in 0..2u32 {
        let svg = chart(&html, &format!("p{pt}-map"));
        // The map's scale: pixels per metre from its scale bar (both in full precision).
        let per = attr_f64(svg, "data-pixels")[0] / attr_f64(svg, "data-metres")[0];
        let (rx, ry) = (attr_f64(svg, "rx"), attr_f64(svg, "ry"));
        let (a, b, ang) = (
            attr_f64(svg, "data-semi-major-m"),
            attr_f64(svg, "data-semi-minor-m"),
            attr_f64(svg, "data-angle-deg"),
        );
        let rows: Vec<usize> = (0..e.num_rows())
            .filter(|&r| point.value(r) == pt)
            .collect();
        assert_eq!(rx.len(), rows.len());
        for (k, &r) in rows.iter().enumerate() {
            let (pa, pb) = (
                f64s(&e, "semi_major_m").value(r),
                f64s(&e, "semi_minor_m").value(r),
            );
            assert_eq!((a[k], b[k]), (pa, pb), "point {pt}, ellipse {k}: labels");
            assert_eq!(ang[k], f64s(&e, "major_axis_deg").value(r));
            // Drawn to a thousandth of a pixel: read back in metres to that.
            let tol = 0.0005 / per + 1e-9;
            assert!(
                (rx[k] / per - pa).abs() <= tol,
                "{} against {pa}",
                rx[k] / per
            );
            assert!(
                (ry[k] / per - pb).abs() <= tol,
                "{} against {pb}",
                ry[k] / per
            );
        }
        assert!(a[0] > 1.0, "a real scatter: {} m", a[0]);
    }
}

#[test]
fn a_histogram_s_bars_add_up_to_the_landed_flights_of_its_point() {
    let (_dir, _file, report) = run_mapped(&mapped(12, "rail_exit_speed_m_s = { min = 15.0 }\n"));
    let html = std::fs::read_to_string(&report.report.as_ref().unwrap().report).unwrap();
    let v = read(&report.outputs.variants);
    let point = v
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    let status = strings(&v, "status");
    for pt in 0..2u32 {
        let landed = (0..v.num_rows())
            .filter(|&r| point.value(r) == pt && status.value(r) == "landed")
            .count() as u64;
        for what in ["apogee-hist", "rail", "max_mach"] {
            let svg = chart(&html, &format!("p{pt}-{what}"));
            let bars: u64 = attrs(svg, "data-count")
                .iter()
                .map(|c| c.parse::<u64>().unwrap())
                .sum();
            assert_eq!(bars, landed, "point {pt}, {what}");
        }
    }
}

#[test]
fn the_printed_chance_of_passing_the_ceiling_is_the_share_of_rows_above_it() {
    // A first run finds the apogees; the ceiling then sits among them.
    let (_d, _f, first) = run_mapped(&mapped(15, "rail_exit_speed_m_s = { min = 15.0 }\n"));
    let b = read(&first.outputs.variants);
    let mut apogees: Vec<f64> = f64s(&b, "apogee_m").iter().flatten().collect();
    apogees.sort_by(f64::total_cmp);
    let ceiling = (apogees[apogees.len() * 3 / 4] * 10.0).round() / 10.0;
    let (_dir, _file, report) =
        run_mapped(&mapped(15, &format!("apogee_m = {{ max = {ceiling} }}\n")));
    let html = std::fs::read_to_string(&report.report.as_ref().unwrap().report).unwrap();
    let v = read(&report.outputs.variants);
    let point = v
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    let (status, apogee) = (strings(&v, "status"), f64s(&v, "apogee_m"));
    let spans: Vec<&str> = html.split("<span class=\"p-exceed\"").skip(1).collect();
    assert_eq!(spans.len(), 2, "one per point");
    for (pt, span) in spans.iter().enumerate() {
        let rows: Vec<usize> = (0..v.num_rows())
            .filter(|&r| point.value(r) == pt as u32 && status.value(r) == "landed")
            .collect();
        let k = rows.iter().filter(|&&r| apogee.value(r) > ceiling).count() as u64;
        let n = rows.len() as u64;
        assert!(
            k > 0 && k < n,
            "the ceiling is among the apogees: {k} of {n}"
        );
        let got = (
            attrs(span, "data-k")[0].parse::<u64>().unwrap(),
            attrs(span, "data-n")[0].parse::<u64>().unwrap(),
        );
        assert_eq!(got, (k, n), "point {pt}");
        assert_eq!(
            attr_f64(span, "data-upper")[0],
            binomial_upper(k, n, 0.95),
            "point {pt}"
        );
        // The printed share is k/n to the printed digit.
        let printed = format!(
            "= {:.1} % ({k} of {n} landed flights)",
            100.0 * k as f64 / n as f64
        );
        assert!(span.contains(&printed), "{printed} in {span}");
    }
}

#[test]
fn the_kml_and_geojson_ellipse_vertices_lie_on_the_ellipses_of_ellipses_parquet() {
    let (_dir, _file, report) = run_mapped(&mapped(12, "landing_distance_m = { max = 900.0 }\n"));
    let written = report.report.as_ref().unwrap();
    let site = Site {
        latitude_deg: 32.99,
        longitude_deg: -106.97,
        height_m: 1400.0,
    };
    let e = read(&report.outputs.ellipses);
    // Point 0's ellipses, k = 1, 2, 3, are the first three rows.
    let row = |k: usize| {
        (
            f64s(&e, "center_x_m").value(k),
            f64s(&e, "center_y_m").value(k),
            f64s(&e, "semi_major_m").value(k),
            f64s(&e, "semi_minor_m").value(k),
            f64s(&e, "major_axis_deg").value(k),
        )
    };
    // (u/a)² + (v/b)² in the ellipse's own axes.
    let on = |k: usize, lat: f64, lon: f64| {
        let (cx, cy, a, b, ang) = row(k);
        let (east, north) = site.to_launch_frame(lat, lon);
        let (s, c) = ang.to_radians().sin_cos();
        let (dx, dy) = (east - cx, north - cy);
        let (u, v) = (dx * c + dy * s, -dx * s + dy * c);
        (u / a).powi(2) + (v / b).powi(2)
    };
    let kml_text = std::fs::read_to_string(written.kml.as_ref().unwrap()).unwrap();
    let doc: kml::Kml = kml_text.parse().unwrap();
    let mut rings: Vec<(String, Vec<(f64, f64)>)> = vec![];
    fn walk(k: &kml::Kml, out: &mut Vec<(String, Vec<(f64, f64)>)>) {
        match k {
            kml::Kml::KmlDocument(d) => d.elements.iter().for_each(|e| walk(e, out)),
            kml::Kml::Document { elements, .. } => elements.iter().for_each(|e| walk(e, out)),
            kml::Kml::Folder(f) => f.elements.iter().for_each(|e| walk(e, out)),
            kml::Kml::Placemark(p) => {
                if let Some(kml::types::Geometry::Polygon(poly)) = &p.geometry {
                    let coords = poly.outer.coords.iter().map(|c| (c.y, c.x)).collect();
                    out.push((p.name.clone().unwrap_or_default(), coords));
                }
            }
            _ => {}
        }
    }
    walk(&doc, &mut rings);
    let ellipses: Vec<&(String, Vec<(f64, f64)>)> = rings
        .iter()
        .filter(|(n, _)| n.contains("ellipse"))
        .collect();
    assert_eq!(ellipses.len(), 6, "three per point");
    for (k, (name, coords)) in ellipses.iter().take(3).enumerate() {
        assert!(name.starts_with(&format!("{}σ", k + 1)), "{name}");
        assert_eq!(coords.len(), 73, "72 vertices and the closing one");
        for &(lat, lon) in coords.iter() {
            let m = on(k, lat, lon);
            assert!((m - 1.0).abs() < 1e-9, "{name}: {m}");
        }
    }
    // The GeoJSON's polygons are the same rings (RFC 7946: longitude first).
    let gj: geojson::FeatureCollection = std::fs::read_to_string(written.geojson.as_ref().unwrap())
        .unwrap()
        .parse()
        .unwrap();
    let mut seen = 0;
    for f in &gj.features {
        let p = f.properties.as_ref().unwrap();
        if p["kind"] != "ellipse" || p["point"] != 0 {
            continue;
        }
        let k = p["sigma"].as_u64().unwrap() as usize - 1;
        let geojson::GeometryValue::Polygon { coordinates } = &f.geometry.as_ref().unwrap().value
        else {
            panic!("an ellipse is a polygon")
        };
        for pos in &coordinates[0] {
            let m = on(k, pos[1], pos[0]);
            assert!((m - 1.0).abs() < 1e-9, "GeoJSON ellipse {k}: {m}");
        }
        seen += 1;
    }
    assert_eq!(seen, 3);
}

#[test]
fn hpr_mc_report_draws_again_from_the_files_the_page_the_run_drew() {
    let (_dir, _file, report) = run_mapped(&mapped(6, "landing_distance_m = { max = 900.0 }\n"));
    let path = report.report.as_ref().unwrap().report.clone();
    let first = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    let (code, out, err) = hpr_mc(&["report", report.outputs.dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("report.html"), "{out}");
    assert_eq!(
        std::fs::read(&path).unwrap(),
        first,
        "the same page, byte for byte"
    );
    // Nothing on it is fetched: no URL but the SVG namespace.
    let page = String::from_utf8(first).unwrap();
    let urls: Vec<&str> = page
        .match_indices("http")
        .map(|(k, _)| &page[k..(k + 30).min(page.len())])
        .filter(|u| !u.starts_with("http://www.w3.org/2000/svg"))
        .collect();
    assert!(urls.is_empty(), "{urls:?}");
    assert!(!page.contains("<script"));
    // A directory without a run's files is an error naming the file.
    let empty = tempfile::tempdir().unwrap();
    let (code, _, err) = hpr_mc(&["report", empty.path().to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("variants.parquet: no variants file"), "{err}");
}

#[test]
fn no_report_writes_no_page_and_the_summary_says_how_to_draw_it() {
    let (dir, file) = setup(&mapped(3, "landing_distance_m = { max = 900.0 }\n"));
    let out = dir.path().join("out");
    let (code, text, err) = hpr_mc(&[
        file.to_str().unwrap(),
        "--quiet",
        "--no-report",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(code <= 1, "{err}");
    assert!(!out.join("report.html").exists());
    assert!(
        text.contains("no report (--no-report); hpr-mc report"),
        "{text}"
    );
}

#[test]
fn the_printed_table_has_a_row_per_point_with_the_shares_of_requirements_parquet() {
    let (dir, file) = setup(&mapped(6, "landing_distance_m = { max = 400.0 }\n"));
    let out = dir.path().join("out");
    let (code, text, err) = hpr_mc(&[
        file.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(code <= 1, "{err}");
    let r = read(&out.join("requirements.parquet"));
    let fraction = f64s(&r, "fraction");
    let lines: Vec<&str> = text.lines().collect();
    let head = lines
        .iter()
        .position(|l| l.trim_start().starts_with("point"))
        .expect("a table");
    assert!(
        lines[head].contains("rail_inclination_deg (deg)"),
        "{}",
        lines[head]
    );
    for pt in 0..2 {
        let row: Vec<&str> = lines[head + 1 + pt].split_whitespace().collect();
        assert_eq!(row[0], pt.to_string());
        assert_eq!(row[1], ["84", "88"][pt]);
        assert_eq!(
            format!("{} {}", row[2], row[3]),
            format!("{:.1} %", 100.0 * fraction.value(pt))
        );
    }
    assert!(text.contains(&format!("report: {}", out.join("report.html").display())));
    assert!(text.contains("landing maps:"));
    // The per-metric statistics only with --verbose.
    assert!(!text.contains("max_dynamic_pressure_pa"));
    let (_, verbose, _) = hpr_mc(&[
        file.to_str().unwrap(),
        "--quiet",
        "--verbose",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(verbose.contains("max_dynamic_pressure_pa"), "{verbose}");
}

/// The metrics of a variants row: each metric column's value (None where null).
fn row_metrics(p: &Prepared, b: &RecordBatch, row: usize) -> Vec<Option<f64>> {
    p.metrics
        .iter()
        .map(|m| {
            let c = f64s(b, &m.name);
            c.is_valid(row).then(|| c.value(row))
        })
        .collect()
}

#[test]
fn a_variant_flown_again_alone_gives_its_row_bit_for_bit() {
    // Turbulence draws each variant's gusts from its seed: the row's seed is flown again.
    let text = windy(
        "wind_speed_m_s = 4.0\nwind_from_deg = 270.0\nwind_turbulence_intensity = 0.15",
        "rail_inclination_deg = [84.0, 88.0]",
    )
    .replace(
        "[dispersions]\n",
        "[dispersions]\nwind_speed_m_s = { dist = \"truncated_normal\", sigma = 1.5, min = -4.0 }\nparachutes.main.lag_s = { dist = \"uniform\", min = -0.5, max = 0.5 }\n",
    );
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    let b = read(&report.outputs.variants);
    assert!(b.column_by_name("sensor_seed").is_some());
    let p = prepare(&file, &Default::default()).unwrap();
    let ids = u64s(&b, "variant_id");
    for row in 0..b.num_rows() {
        let id = ids.value(row);
        let sim = p.variant_flight(id).unwrap();
        let flight = sim.run(&mut ());
        assert!(
            flight.as_ref().is_ok_and(|f| !f.samples.is_empty()),
            "samples kept"
        );
        let got = p.flight_result(id, &sim, flight);
        let want = row_metrics(&p, &b, row);
        let bits = |v: &[Option<f64>]| v.iter().map(|x| x.map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&got.metrics), bits(&want), "variant {id}");
        assert_eq!(got.status.name(), strings(&b, "status").value(row));
    }
    // The command line: its JSON's metrics are the row's, bit for bit (serde_json writes
    // the shortest decimal that reads back to the same double).
    let (code, out, err) = hpr_mc(&[
        "fly",
        "--scenario",
        file.to_str().unwrap(),
        "--variant",
        "5",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["variant"], 5);
    for name in [
        "apogee_m",
        "landing_x_m",
        "landing_y_m",
        "landing_time_s",
        "max_mach",
    ] {
        // Read with Rust's exact parser (serde_json's own may land an ulp away).
        let at = out.find(&format!("\"{name}\": ")).unwrap() + name.len() + 4;
        let end = at + out[at..].find([',', '\n']).unwrap();
        let json: f64 = out[at..end].trim().parse().unwrap();
        assert_eq!(json.to_bits(), f64s(&b, name).value(5).to_bits(), "{name}");
    }
    // An id past the run is refused, naming the count; --point and --variant don't mix.
    let (code, _, err) = hpr_mc(&[
        "fly",
        "--scenario",
        file.to_str().unwrap(),
        "--variant",
        "8",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--variant 8: the run has 8 variants (0 to 7)"),
        "{err}"
    );
    let (code, _, _) = hpr_mc(&[
        "fly",
        "--scenario",
        file.to_str().unwrap(),
        "--variant",
        "1",
        "--point",
        "1",
    ]);
    assert_eq!(code, 2);
}

#[test]
fn the_time_series_are_the_first_replicates_of_each_point_and_end_where_their_rows_do() {
    let (_dir, _file, report) = run_mapped(&mapped(5, "landing_distance_m = { max = 900.0 }\n"));
    assert_eq!(report.trajectories, 6, "3 per point");
    let t = read(&report.outputs.trajectories);
    let v = read(&report.outputs.variants);
    let ids = u64s(&t, "variant_id");
    let mut seen: Vec<u64> = ids.values().to_vec();
    seen.dedup();
    assert_eq!(seen, vec![0, 1, 2, 5, 6, 7]);
    let (time, alt) = (f64s(&t, "time_s"), f64s(&t, "altitude_m"));
    for id in seen {
        let rows: Vec<usize> = (0..t.num_rows()).filter(|&r| ids.value(r) == id).collect();
        let last = *rows.last().unwrap();
        let row = id as usize;
        assert_eq!(
            time.value(last).to_bits(),
            f64s(&v, "landing_time_s").value(row).to_bits(),
            "variant {id} ends at its landing"
        );
        let top = rows.iter().map(|&r| alt.value(r)).fold(f64::MIN, f64::max);
        let apogee = f64s(&v, "apogee_m").value(row);
        assert!(
            top <= apogee + 1e-9 && top > apogee - 5.0,
            "{top} against {apogee}"
        );
    }
}

#[test]
fn a_flight_plot_draws_its_height_to_the_apogee_and_marks_its_events() {
    let (dir, file) = setup(&mapped(2, "landing_distance_m = { max = 900.0 }\n"));
    for ext in ["html", "svg"] {
        let plot = dir.path().join(format!("flight.{ext}"));
        let (code, out, err) = hpr_mc(&[
            "fly",
            "--scenario",
            file.to_str().unwrap(),
            "--plot",
            plot.to_str().unwrap(),
            "--json",
        ]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let apogee = v["metrics"]["apogee_m"].as_f64().unwrap();
        let page = std::fs::read_to_string(&plot).unwrap();
        assert_eq!(
            page.matches("<svg").count(),
            9 + usize::from(ext == "svg"),
            "{ext}"
        );
        for label in ["apogee", "burnout", "rail exit", "main opens", "landing"] {
            assert!(page.contains(&format!(">{label}</text>")), "{ext}: {label}");
        }
        // The height chart's line reaches the apogee: its highest point (least pixel y) is
        // the apogee's pixel to the tenth of a pixel the path is written in.
        let svg = chart(&page, "height");
        let d = attrs(svg, "d")
            .into_iter()
            .find(|d| d.starts_with('M'))
            .unwrap();
        let top_px = d
            .split(['M', 'L'])
            .filter(|s| !s.is_empty())
            .map(|p| p.split(' ').nth(1).unwrap().parse::<f64>().unwrap())
            .fold(f64::MAX, f64::min);
        // The chart's own y scale: values at its two pixel edges.
        let scale: Vec<f64> = attrs(svg, "data-y-scale")[0]
            .split(' ')
            .map(|v| v.parse().unwrap())
            .collect();
        let top = scale[0] + (top_px - scale[2]) / (scale[3] - scale[2]) * (scale[1] - scale[0]);
        let metres_per_px = (scale[1] - scale[0]) / (scale[2] - scale[3]);
        // The samples are the integrator's steps, the apogee a root between two: the line's
        // top is within a step's rise (under a metre here) and its 0.05 px rounding of it.
        assert!(
            (top - apogee).abs() <= 1.0 + 0.05 * metres_per_px,
            "{ext}: drawn top {top} m, apogee {apogee} m"
        );
    }
    // A plot's format is checked before the flight.
    let (code, _, err) = hpr_mc(&[
        "fly",
        "--scenario",
        file.to_str().unwrap(),
        "--plot",
        "x.png",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("x.png: a plot is written as .html or .svg"),
        "{err}"
    );
}

#[test]
fn a_run_larger_than_the_rows_held_draws_the_first_n_of_each_point_says_so_and_counts_every_row() {
    use hpr_mc::campaign::report::{data, write_dir_holding};
    // A first run finds the apogees; the ceiling then sits among them.
    let (_d, _f, first) = run_mapped(&mapped(30, "rail_exit_speed_m_s = { min = 15.0 }\n"));
    let b = read(&first.outputs.variants);
    let mut apogees: Vec<f64> = f64s(&b, "apogee_m").iter().flatten().collect();
    apogees.sort_by(f64::total_cmp);
    let ceiling = (apogees[apogees.len() / 2] * 10.0).round() / 10.0;
    let (_dir, _file, report) = run_mapped(&mapped(
        30,
        &format!("apogee_m = {{ max = {ceiling} }}\nlanding_distance_m = {{ max = 900.0 }}\n"),
    ));
    let dir = report.outputs.dir.clone();
    let whole = std::fs::read_to_string(&report.report.as_ref().unwrap().report).unwrap();
    // The run's own report held every row (60 are far under the bound).
    let run = data::Run::read(&dir, &data::Files::in_dir(&dir, "")).unwrap();
    assert!(run.whole());
    assert_eq!(run.id.len(), 60);
    // Room for 10 rows a point: 8 bytes a value of each input and metric, with the id, the
    // point and the status (8 + 8 + 1 bytes).
    let row = 8 * (run.inputs.len() + run.metrics.len()) + 17;
    let held = write_dir_holding(&dir, 10 * row * 2 + row - 1).unwrap();
    let page = std::fs::read_to_string(&held.report).unwrap();
    let kml = std::fs::read_to_string(held.kml.as_ref().unwrap()).unwrap();
    let geojson: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(held.geojson.as_ref().unwrap()).unwrap())
            .unwrap();
    let v = read(&report.outputs.variants);
    let point = v
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    let (ids, status, apogee) = (
        u64s(&v, "variant_id"),
        strings(&v, "status"),
        f64s(&v, "apogee_m"),
    );
    for pt in 0..2u32 {
        let rows: Vec<usize> = (0..v.num_rows())
            .filter(|&r| point.value(r) == pt)
            .collect();
        assert_eq!(rows.len(), 30);
        let landed = |r: &&usize| status.value(**r) == "landed";
        let first: Vec<usize> = rows[..10].iter().filter(landed).copied().collect();
        let all: Vec<usize> = rows.iter().filter(landed).copied().collect();
        assert!(
            first.len() >= 8 && all.len() > first.len(),
            "{first:?} {all:?}"
        );
        // Stated, in the point's section and in the maps.
        let said = "the first 10 of the point's 30 flights in variant order";
        let section = &page[page.find(&format!("id=\"point-{pt}\"")).unwrap()..];
        let section = &section[..section.find("</details>").unwrap()];
        assert!(section.contains(said), "point {pt}: {section:.600}");
        assert!(section.contains("Drawn from the first 10 of the point's 30 flights."));
        assert!(
            section.contains(&format!("30 variants, {} landed.", all.len())),
            "the point's counts are over every row"
        );
        // Drawn: the histogram holds the landed flights among the first 10, the map's dots
        // are those flights, by id.
        let bars: u64 = attrs(chart(&page, &format!("p{pt}-apogee-hist")), "data-count")
            .iter()
            .map(|c| c.parse::<u64>().unwrap())
            .sum();
        assert_eq!(bars, first.len() as u64, "point {pt}");
        assert!(section.contains(&format!(
            "every one of the {} landings as a dot",
            first.len()
        )));
        let drawn: Vec<u64> = geojson["features"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| {
                f["properties"]["kind"] == "landings" && f["properties"]["point"] == pt as u64
            })
            .flat_map(|f| {
                assert_eq!(
                    f["properties"]["sample"].as_str().unwrap(),
                    format!(
                        "{said} (a uniform sample: the variants of a point are independent draws; the report holds at most {} bytes of rows)",
                        10 * row * 2 + row - 1
                    )
                );
                f["properties"]["variant_ids"].as_array().unwrap().clone()
            })
            .map(|id| id.as_u64().unwrap())
            .collect();
        let expected: Vec<u64> = first.iter().map(|&r| ids.value(r)).collect();
        assert_eq!(drawn, expected, "point {pt}");
        // (The KML escapes the apostrophe.)
        assert!(kml.contains(&format!(
            "{} landings: the first 10 of the point",
            first.len()
        )));
        assert!(kml.contains("s 30 flights in variant order"));
        // The chance of passing the ceiling counts every landed flight of the point.
        let k = all.iter().filter(|&&r| apogee.value(r) > ceiling).count() as u64;
        let span = &section[section.find("<span class=\"p-exceed\"").unwrap()..];
        assert_eq!(attrs(span, "data-k")[0], k.to_string(), "point {pt}");
        assert_eq!(
            attrs(span, "data-n")[0],
            all.len().to_string(),
            "point {pt}"
        );
        assert!(k > 0 && k < all.len() as u64, "{k} of {}", all.len());
    }
    // What counts over every row is the page that held every row: the run's counts and
    // statuses, the flights to look at and the worst flight of each point by each
    // requirement.
    let head = |h: &str| h[..h.find("<h3>Inputs").unwrap()].to_string();
    assert_eq!(head(&page), head(&whole));
    let flights = |h: &str| {
        h[h.find("<h2 id=\"flights\">").unwrap()..h.find("<h2>How this page").unwrap()].to_string()
    };
    assert_eq!(flights(&page), flights(&whole));
    assert!(flights(&page).contains("The worst flight of each point by each requirement"));
    // Nothing says "sample" on the page that held every row.
    assert!(!whole.contains("in variant order (a uniform sample"));
}

#[test]
fn a_run_within_the_rows_held_gives_the_page_of_every_row_unchanged() {
    use hpr_mc::campaign::report::write_dir_holding;
    let (_dir, _file, report) = run_mapped(&mapped(20, "landing_distance_m = { max = 900.0 }\n"));
    let dir = report.outputs.dir.clone();
    let read_all = |w: &hpr_mc::campaign::report::Written| {
        (
            std::fs::read(&w.report).unwrap(),
            std::fs::read(w.kml.as_ref().unwrap()).unwrap(),
            std::fs::read(w.geojson.as_ref().unwrap()).unwrap(),
        )
    };
    let by_run = read_all(report.report.as_ref().unwrap());
    // Holding exactly 20 rows a point, and holding without bound: the same bytes.
    let run = hpr_mc::campaign::report::data::Run::read(
        &dir,
        &hpr_mc::campaign::report::data::Files::in_dir(&dir, ""),
    )
    .unwrap();
    let row = 8 * (run.inputs.len() + run.metrics.len()) + 17;
    for bytes in [20 * row * 2, usize::MAX / 2] {
        let again = read_all(&write_dir_holding(&dir, bytes).unwrap());
        assert!(again == by_run, "holding {bytes} bytes");
    }
    let fewer = read_all(&write_dir_holding(&dir, 19 * row * 2).unwrap());
    assert!(fewer.0 != by_run.0, "19 rows a point is a sample");
}
