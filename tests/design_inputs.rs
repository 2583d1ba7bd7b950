//! A scenario sweeps and disperses a design's dimensions and sweeps the motor: each sweep
//! point flies the design (or the motor) it names, checked against `hpr-mc inspect` of that
//! design written out by hand and against a scenario that names the motor itself; a variant
//! whose design breaks a rule is a `refused` row naming the rule.

use arrow::array::{Array, Float64Array, StringArray};
use arrow::compute::concat_batches;
use arrow::record_batch::RecordBatch;
use hpr_mc::campaign::{run_campaign, RunConfig};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn reference() -> PathBuf {
    root().join("validation/designs/synthetic-54mm-three-fin.json")
}

fn read(path: &Path) -> RecordBatch {
    let builder = ParquetRecordBatchReaderBuilder::try_new(File::open(path).unwrap()).unwrap();
    let schema = builder.schema().clone();
    let batches: Vec<RecordBatch> = builder.build().unwrap().map(|b| b.unwrap()).collect();
    concat_batches(&schema, &batches).unwrap()
}

fn floats<'a>(b: &'a RecordBatch, name: &str) -> &'a Float64Array {
    b.column_by_name(name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap()
}

fn strings<'a>(b: &'a RecordBatch, name: &str) -> &'a StringArray {
    b.column_by_name(name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap()
}

/// Run the scenario `toml` (written into a fresh directory) and return its variants' rows.
fn run(toml: &str) -> RecordBatch {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scenario.toml");
    std::fs::write(&file, toml).unwrap();
    let config = RunConfig {
        out: Some(dir.path().join("out")),
        quiet: true,
        no_report: true,
        threads: Some(2),
        ..RunConfig::default()
    };
    let report = run_campaign(&file, &config).unwrap();
    read(&report.outputs.variants)
}

/// A scenario of the reference design on `motor`, with `rest` (its sweep and dispersions).
fn scenario(motor: &str, rest: &str) -> String {
    format!(
        r#"name = "design_inputs"
seed = 7
variants_per_point = 2

[design]
file = "{}"

[motor]
name = "{motor}"

[environment]
elevation_m = 0.0
wind_speed_m_s = 3.0

[rail]
length_m = 2.0
inclination_deg = 85.0

[[parachutes]]
name = "main"
cds_m2 = 0.9
lag_s = 1.0
trigger = "apogee"

{rest}
"#,
        reference().display()
    )
}

/// `hpr-mc inspect --json` of the reference design with its fin span set to `span_m` in
/// the design's own JSON: the static margin at burnout, calibres.
fn inspected_margin(span_m: f64, dir: &Path) -> f64 {
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(reference()).unwrap()).unwrap();
    let body = json["stages"][0]["components"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|c| c["id"] == "body")
        .unwrap();
    let fins = body["children"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|c| c["id"] == "fins")
        .unwrap();
    fins["span_m"] = serde_json::json!(span_m);
    let file = dir.join(format!("fins-{span_m}.json"));
    std::fs::write(&file, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    // Drag curves the design names are found beside it.
    let out = Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
        .args(["inspect", "--json", "--motor", "Cesaroni_I175"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    report["after_burnout"]["static_margin_cal"]
        .as_f64()
        .unwrap_or_else(|| panic!("no burnout margin in {report}"))
}

#[test]
fn a_swept_fin_span_gives_at_each_point_the_margin_inspect_gives_for_that_design() {
    let spans = [0.05, 0.066477123, 0.085];
    let rows = run(&scenario(
        "Cesaroni_I175",
        "[sweep]\ndesign.fins.span_m = [0.05, 0.066477123, 0.085]\n\n[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 1.0 }\n",
    ));
    assert_eq!(rows.num_rows(), 6, "three points, two variants each");
    let span = floats(&rows, "design_fins_span_m");
    let swept = floats(&rows, "sweep_design_fins_span_m");
    let margin = floats(&rows, "static_margin_burnout_cal");
    let status = strings(&rows, "status");
    let dir = tempfile::tempdir().unwrap();
    let mut margins = Vec::new();
    for (k, &s) in spans.iter().enumerate() {
        let by_hand = inspected_margin(s, dir.path());
        margins.push(by_hand);
        for r in (0..rows.num_rows()).filter(|&r| swept.value(r) == s) {
            assert_eq!(status.value(r), "landed", "row {r}");
            assert_eq!(span.value(r), s);
            let m = margin.value(r);
            assert!(
                (m - by_hand).abs() <= 1e-12,
                "point {k}: span {s} m: the run's margin {m} cal, inspect's {by_hand} cal"
            );
        }
    }
    // `hpr-mc fly --scenario FILE --point K` flies the point's own design.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scenario.toml");
    std::fs::write(
        &file,
        scenario(
            "Cesaroni_I175",
            "[sweep]\ndesign.fins.span_m = [0.05, 0.066477123, 0.085]\n",
        ),
    )
    .unwrap();
    let prepared = hpr_mc::campaign::run::prepare(&file, &RunConfig::default()).unwrap();
    for (k, &s) in spans.iter().enumerate() {
        let sim = prepared.nominal_flight(k).unwrap();
        let fins = sim.design().component_index("fins").unwrap();
        let model = sim.model();
        let margin = sim.static_margin_for(sim.mass_properties_at(model.burnout_s).cg_m.x);
        assert!(
            (margin - margins[k]).abs() <= 1e-12,
            "point {k}: span {s} m: fly's margin {margin} cal, inspect's {} cal (fins {fins})",
            margins[k]
        );
    }
    // Longer fins move the center of pressure aft: the margin grows with the span.
    assert!(
        margins[0] < margins[1] && margins[1] < margins[2],
        "{margins:?}"
    );
}

#[test]
fn a_dispersed_dimension_whose_variants_break_a_rule_are_refused_rows_naming_it() {
    // The fin span scattered so widely that some variants have fins of no span at all.
    let rows = run(&scenario(
        "Cesaroni_I175",
        "[dispersions]\ndesign.fins.span_m = { dist = \"normal\", sigma = 0.05 }\n\n[run]\nchunk_size = 8\n",
    )
    .replace("variants_per_point = 2", "variants_per_point = 40"));
    let span = floats(&rows, "design_fins_span_m");
    let status = strings(&rows, "status");
    let error = strings(&rows, "error");
    let (mut refused, mut landed) = (0, 0);
    for r in 0..rows.num_rows() {
        if span.value(r) > 0.0 {
            assert_eq!(status.value(r), "landed", "row {r}: {:?}", error.value(r));
            landed += 1;
        } else {
            assert_eq!(status.value(r), "refused", "row {r}");
            let e = error.value(r);
            assert!(
                e.contains("fins") && e.contains("span_m") && e.contains("positive"),
                "row {r}: the refusal names the component, the field and the rule: {e}"
            );
            refused += 1;
        }
    }
    assert!(
        refused >= 1 && landed >= 20,
        "{refused} refused, {landed} landed"
    );
}

#[test]
fn a_sweep_of_motors_flies_each_point_on_its_own_motor_named_in_a_column() {
    let motors = ["Cesaroni_I175", "AeroTech_I161W"];
    let swept = run(&scenario(
        "Cesaroni_I175",
        "[sweep]\nmotor = [\"Cesaroni_I175\", \"AeroTech_I161W\"]\n\n[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 1.0 }\n",
    ));
    assert_eq!(swept.num_rows(), 4);
    let names = strings(&swept, "motor");
    let apogee = floats(&swept, "apogee_m");
    for (k, m) in motors.iter().enumerate() {
        // The same scenario naming the motor itself, with the same draws (replicate r of
        // every point sees the same numbers).
        let alone = run(&scenario(
            m,
            "[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 1.0 }\n",
        ));
        let alone_apogee = floats(&alone, "apogee_m");
        for r in 0..2 {
            let row = 2 * k + r;
            assert!(
                names.value(row).contains(&m[m.find('_').unwrap() + 1..]),
                "row {row}: {} for {m}",
                names.value(row)
            );
            assert_eq!(
                apogee.value(row).to_bits(),
                alone_apogee.value(r).to_bits(),
                "row {row}: {m}: {} m swept, {} m alone",
                apogee.value(row),
                alone_apogee.value(r)
            );
        }
    }
    assert_ne!(apogee.value(0), apogee.value(2), "two motors, two apogees");
}

#[test]
fn a_sweep_of_motors_is_labelled_by_designation_in_the_printed_table_and_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scenario.toml");
    std::fs::write(
        &file,
        scenario(
            "Cesaroni_I175",
            "[sweep]\nmotor = [\"Cesaroni_I175\", \"AeroTech_I161W\"]\n",
        ),
    )
    .unwrap();
    let config = RunConfig {
        out: Some(dir.path().join("out")),
        quiet: true,
        threads: Some(2),
        ..RunConfig::default()
    };
    let report = run_campaign(&file, &config).unwrap();
    let rows = read(&report.outputs.variants);
    let names = strings(&rows, "motor");
    // The designations as the variants file holds them, one per point (two rows each).
    let d: Vec<String> = (0..2).map(|p| names.value(2 * p).to_string()).collect();
    assert_ne!(d[0], d[1]);
    let table = hpr_mc::campaign::cli::sweep_table(&report);
    let lines: Vec<&str> = table.lines().collect();
    let head = lines
        .iter()
        .position(|l| l.trim_start().starts_with("point"))
        .unwrap();
    let cells: Vec<&str> = lines[head].split_whitespace().collect();
    assert_eq!(&cells[..2], &["point", "motor"], "{table}");
    for (p, name) in d.iter().enumerate() {
        let cells: Vec<&str> = lines[head + 1 + p].split_whitespace().collect();
        assert_eq!(cells[0], p.to_string(), "{table}");
        assert_eq!(cells[1], name, "{table}");
    }
    let html = std::fs::read_to_string(&report.outputs.report).unwrap();
    assert!(!html.contains("motor_index = "), "no numbered motor");
    for (p, name) in d.iter().enumerate() {
        // The point's heading, its row of the answer's table and the charts' x axis.
        assert!(html.contains(&format!("(motor = {name})")), "point {p}");
        assert!(
            html.contains(&format!("<tr><td class=\"n\">{p}</td><td>{name}</td>")),
            "point {p}'s row"
        );
        assert!(html.contains(&format!(">{name}</text>")), "tick {name}");
    }
    assert!(html.contains("<th>motor</th>"));
    // The inputs' table names the motor by its designations, once each in the points'
    // order, with no statistics of its number in the sweep's list.
    let inputs = &html[html.find("<h3>Inputs</h3>").unwrap()..];
    let inputs = &inputs[..inputs.find("</table>").unwrap()];
    assert!(!inputs.contains("motor_index"), "{inputs}");
    let row = format!(
        "<tr><td><code>motor</code></td><td></td><td>{}, {}</td><td>–</td>{}</tr>",
        d[0],
        d[1],
        "<td class=\"n\">–</td>".repeat(4)
    );
    assert!(inputs.contains(&row), "{row} in {inputs}");
}

#[test]
fn a_sweep_of_motors_names_each_point_s_motor_in_the_summary_beside_its_statistics() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scenario.toml");
    std::fs::write(
        &file,
        scenario(
            "Cesaroni_I175",
            "[sweep]\nmotor = [\"Cesaroni_I175\", \"AeroTech_I161W\"]\n\n[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 1.0 }\n",
        ),
    )
    .unwrap();
    let config = RunConfig {
        out: Some(dir.path().join("out")),
        quiet: true,
        no_report: true,
        threads: Some(2),
        ..RunConfig::default()
    };
    let report = run_campaign(&file, &config).unwrap();
    let rows = read(&report.outputs.variants);
    let (names, apogee) = (strings(&rows, "motor"), floats(&rows, "apogee_m"));
    let points = rows
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<arrow::array::UInt32Array>()
        .unwrap();
    let summary = read(&report.outputs.summary);
    let field = summary.schema().field_with_name("motor").unwrap().clone();
    assert_eq!(field.data_type(), &arrow::datatypes::DataType::Utf8);
    let (motor, metric, mean) = (
        strings(&summary, "motor"),
        strings(&summary, "metric"),
        floats(&summary, "mean"),
    );
    let summary_points = summary
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<arrow::array::UInt32Array>()
        .unwrap();
    let mut seen = 0;
    for r in 0..summary.num_rows() {
        let pt = summary_points.value(r);
        // The point's rows in variants.parquet: their designation, and their mean apogee
        // (two landed variants a point).
        let own: Vec<usize> = (0..rows.num_rows())
            .filter(|&v| points.value(v) == pt)
            .collect();
        assert_eq!(own.len(), 2);
        assert_eq!(motor.value(r), names.value(own[0]), "summary row {r}");
        if metric.value(r) == "apogee_m" {
            let m = own.iter().map(|&v| apogee.value(v)).sum::<f64>() / 2.0;
            assert!(
                (mean.value(r) - m).abs() <= 1e-12 * m,
                "point {pt}: {} m in the summary, {m} m from the rows",
                mean.value(r)
            );
            seen += 1;
        }
    }
    assert_eq!(seen, 2, "one apogee row a point");
    assert_ne!(names.value(0), names.value(2), "two motors, two names");
    // The other statistics files name the motor too.
    let ellipses = read(&report.outputs.ellipses);
    let e = strings(&ellipses, "motor");
    assert!((0..ellipses.num_rows())
        .all(|r| e.value(r) == names.value(0) || e.value(r) == names.value(2)));
}
