//! Aerodynamic inputs: drag tables and CSVs, RASAero exports, airfoil lift tables, fin sweeps.

use super::*;

#[test]
fn drag_tables_must_have_mach_strictly_increasing() {
    let (rule, loc, field) = invalid(with(|v| *at(v, "/drag/power_off/2/0") = json!(0.3)));
    assert_eq!(
        rule,
        Rule::MachNotIncreasing {
            row: 2,
            previous: 0.3,
            got: 0.3
        }
    );
    assert_eq!((loc, field.as_deref()), (Location::Drag, Some("power_off")));
    let (rule, ..) = invalid(with(|v| *at(v, "/drag/power_off") = json!([])));
    assert_eq!(rule, Rule::EmptyTable);
    let (rule, ..) = invalid(with(|v| {
        at(v, "/drag")
            .as_object_mut()
            .unwrap()
            .insert("estimate".into(), json!({}));
    }));
    assert_eq!(rule, Rule::DragModelNotExactlyOne { given: 2 });
    let d = with(|v| *at(v, "/drag") = json!({"estimate": {"roughness_m": 20e-6}})).unwrap();
    assert_eq!(d.drag, DragSpec::Estimate { roughness_m: 20e-6 });
    let d = with(|v| {
        v.as_object_mut().unwrap().remove("drag");
    })
    .unwrap();
    assert_eq!(
        d.drag,
        DragSpec::Estimate {
            roughness_m: super::super::DEFAULT_ROUGHNESS_M
        }
    );
}

#[test]
fn drag_csvs_are_read_relative_to_the_design_file() {
    let dir = std::env::temp_dir().join(format!("hpr-design-csv-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(
        dir.join("data/off.csv"),
        "mach,cd\n0.0,0.5\n# a comment\n0.5, 0.52\n\n1.0,0.7\n",
    )
    .unwrap();
    std::fs::write(dir.join("data/bad.csv"), "0.0,0.5\n0.5,0.52\n0.4,0.7\n").unwrap();
    let mut v = example_value();
    v["drag"] = json!({"power_off_csv": "data/off.csv", "power_on": [[0.0, 0.4], [2.0, 0.5]]});
    let design_path = dir.join("rocket.json");
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert_eq!(
        d.drag,
        DragSpec::Curves {
            power_off: vec![(0.0, 0.5), (0.5, 0.52), (1.0, 0.7)],
            power_on: vec![(0.0, 0.4), (2.0, 0.5)]
        }
    );
    v["drag"] = json!({"power_off_csv": "data/bad.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    let DesignError::Csv {
        file,
        line,
        message,
    } = &e
    else {
        panic!("{e}")
    };
    assert!(file.ends_with("bad.csv") && *line == 3, "{e}");
    assert!(message.contains("strictly increasing"), "{e}");
    // A missing table is the fault of the field that names it: the error says which.
    v["drag"] = json!({"power_off_csv": "data/missing.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    let text = e.to_string();
    assert!(
        matches!(
            &e,
            DesignError::Invalid { at: Location::Drag, field: Some(f), rule: Rule::FileUnreadable { file, .. }, .. }
                if f == "power_off_csv" && file.ends_with("missing.csv")
        ),
        "{e}"
    );
    assert!(
        text.contains("drag: field \"power_off_csv\": names ")
            && text.contains("missing.csv, which cannot be read"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_rasaero_export_gives_its_power_off_and_power_on_curves_at_zero_angle_of_attack() {
    // RASAero II's aerodynamic export: a row per Mach number and angle of attack, the drag
    // with the motor off and burning in their own columns.
    let dir = std::env::temp_dir().join(format!("hpr-design-rasaero-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let header = "Mach,Alpha,CD,CD Power-Off,CD Power-On,CA Power-Off,CA Power-On,CL,CN,\
                  CN Potential,CN Viscous,Cn alpha (0-4 deg) (per rad),CP,CP 0-4 deg,\
                  Reynolds Number";
    let row = |mach: f64, alpha: f64, off: f64, on: f64| {
        format!("{mach},{alpha},{off},{off},{on},{off},{on},0,0,0,0,10.5,30.1,30.2,1e6\n")
    };
    let mut text = format!("{header}\n");
    for (mach, off, on) in [(0.01, 0.61, 0.52), (0.5, 0.55, 0.47), (1.2, 0.83, 0.71)] {
        for alpha in [0.0, 2.0, 4.0] {
            // At 2 and 4 degrees the drag grows: those rows must not be read.
            text += &row(mach, alpha, off + alpha * 0.01, on + alpha * 0.01);
        }
    }
    std::fs::write(dir.join("ras.csv"), &text).unwrap();
    let design_path = dir.join("rocket.json");
    let mut v = example_value();
    v["drag"] = json!({"power_off_csv": "ras.csv"});
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert_eq!(
        d.drag,
        DragSpec::Curves {
            power_off: vec![(0.01, 0.61), (0.5, 0.55), (1.2, 0.83)],
            power_on: vec![(0.01, 0.52), (0.5, 0.47), (1.2, 0.71)]
        }
    );
    // A power-on curve given beside it wins; the file can also give just the power-on one.
    v["drag"] = json!({"power_off_csv": "ras.csv", "power_on": [[0.0, 0.4]]});
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert!(matches!(&d.drag, DragSpec::Curves { power_on, .. } if power_on == &vec![(0.0, 0.4)]));
    v["drag"] = json!({"power_off": [[0.0, 0.5]], "power_on_csv": "ras.csv"});
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert!(matches!(&d.drag, DragSpec::Curves { power_on, .. }
        if power_on == &vec![(0.01, 0.52), (0.5, 0.47), (1.2, 0.71)]));
    // A broken row names its line; a file with no row at zero angle of attack is refused.
    std::fs::write(
        dir.join("bad.csv"),
        format!(
            "{header}\n{}0.5,0,0.5,x,0.4,0,0,0,0,0,0,0,0,0,0\n",
            row(0.01, 0.0, 0.6, 0.5)
        ),
    )
    .unwrap();
    v["drag"] = json!({"power_off_csv": "bad.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    assert!(matches!(&e, DesignError::Csv { line: 3, .. }), "{e}");
    std::fs::write(
        dir.join("tilted.csv"),
        format!("{header}\n{}", row(0.01, 2.0, 0.6, 0.5)),
    )
    .unwrap();
    v["drag"] = json!({"power_off_csv": "tilted.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    assert!(e.to_string().contains("without rows at Alpha 0"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_fin_s_airfoil_lift_table_gives_rocketpy_s_slope() {
    // RocketPy's NACA 0012 table (validation/rocketpy/data), read as RocketPy reads it: the
    // slope of the linear table at 0.001 rad, 6.302535573086407 /rad in RocketPy 1.13
    // (barrowman_reference.json), against a flat plate's 2π.
    let naca = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/rocketpy/data/NACA0012-radians.txt"
    );
    let rocketpy = 6.302535573086407;
    let fins_with = |airfoil: Value| {
        with(|v| {
            at(v, FINS)["airfoil"] = airfoil;
        })
    };
    let slope = |d: Design| {
        let i = d.component_index("fins").unwrap();
        match &d.components[i].kind {
            ComponentKind::FinSet(f) => f.lift_slope_2d_per_rad,
            _ => unreachable!(),
        }
    };
    assert_eq!(slope(with(|_| {}).unwrap()), 2.0 * std::f64::consts::PI);
    let got = slope(fins_with(json!({"csv": naca, "angles": "radians"})).unwrap());
    assert!((got / rocketpy - 1.0).abs() < 1e-15, "{got}");
    // The same table in degrees gives the same slope per radian.
    let dir = std::env::temp_dir().join(format!("hpr-airfoil-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let degrees: String = std::fs::read_to_string(naca)
        .unwrap()
        .lines()
        .map(|l| {
            let (a, cl) = l.split_once(',').unwrap();
            format!("{},{cl}\n", a.trim().parse::<f64>().unwrap().to_degrees())
        })
        .collect();
    let deg_file = dir.join("naca-deg.csv");
    std::fs::write(&deg_file, format!("alpha_deg,cl\n{degrees}")).unwrap();
    let got = slope(fins_with(json!({"csv": deg_file, "angles": "degrees"})).unwrap());
    assert!((got / rocketpy - 1.0).abs() < 1e-12, "{got}");
    let given = slope(fins_with(json!({"lift_slope_per_rad": 6.1})).unwrap());
    assert_eq!(given, 6.1);
    // Refusals: both, neither, no unit, a non-increasing table.
    for bad in [
        json!({"lift_slope_per_rad": 6.1, "csv": naca}),
        json!({}),
        json!({"csv": naca}),
        json!({"lift_slope_per_rad": 6.1, "angles": "radians"}),
    ] {
        let (rule, _, field) = invalid(fins_with(bad.clone()));
        assert!(matches!(rule, Rule::Airfoil { .. }), "{bad}: {rule}");
        assert!(field.unwrap().starts_with("airfoil"), "{bad}");
    }
    let (rule, _, field) = invalid(fins_with(json!({"lift_slope_per_rad": -1.0})));
    assert!(matches!(rule, Rule::NotPositive { .. }));
    assert_eq!(field.as_deref(), Some("airfoil.lift_slope_per_rad"));
    let back = dir.join("back.csv");
    std::fs::write(&back, "0.0,0.0\n0.1,0.6\n0.05,0.7\n").unwrap();
    let e = fins_with(json!({"csv": back, "angles": "radians"})).unwrap_err();
    assert!(matches!(&e, DesignError::Csv { line: 3, .. }), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_trapezoidal_fin_s_sweep_may_be_its_leading_edge_angle_as_rocketpy_gives_it() {
    // The example's fins: span 0.07 m, the tip's leading edge 0.06 m behind the root's, so
    // Γ = atan(0.06/0.07); RocketPy's x_t = s tan Γ gives the 0.06 m back.
    let deg = (0.06f64 / 0.07).atan().to_degrees();
    let d = with(|v| {
        let fins = at(v, FINS).as_object_mut().unwrap();
        fins.remove("sweep_m");
        fins.insert("sweep_deg".into(), json!(deg));
    })
    .unwrap();
    let i = d.component_index("fins").unwrap();
    let ComponentKind::FinSet(f) = &d.components[i].kind else {
        unreachable!()
    };
    let FinPlanform::Trapezoidal { sweep_m, .. } = f.planform else {
        unreachable!()
    };
    assert!((sweep_m - 0.06).abs() < 1e-15, "{sweep_m}");
    let (rule, _, field) = invalid(with(|v| {
        at(v, FINS)["sweep_deg"] = json!(deg);
    }));
    assert!(matches!(rule, Rule::AtMostOneOf { .. }), "{rule}");
    assert_eq!(field.as_deref(), Some("sweep_deg"));
    let (rule, _, field) = invalid(with(|v| {
        let fins = at(v, FINS).as_object_mut().unwrap();
        fins.remove("sweep_m");
        fins.insert("sweep_deg".into(), json!(90.0));
    }));
    assert!(matches!(rule, Rule::OutOfRange { .. }), "{rule}");
    assert_eq!(field.as_deref(), Some("sweep_deg"));
}

#[test]
fn a_table_that_never_ends_is_refused_at_its_limit_naming_the_field() {
    for (field, drag) in [
        ("power_off_csv", json!({"power_off_csv": "/dev/zero"})),
        (
            "power_on_csv",
            json!({"power_off": [[0.0, 0.5], [1.0, 0.6]], "power_on_csv": "/dev/zero"}),
        ),
    ] {
        let (rule, loc, f) = invalid(with(|v| v["drag"] = drag));
        assert_eq!((loc, f.as_deref()), (Location::Drag, Some(field)));
        assert_eq!(
            rule,
            Rule::FileUnreadable {
                file: "/dev/zero".into(),
                why: "it is larger than 16 MiB, the most hpr-mc reads for a table (CSV)".into()
            }
        );
    }
    let (rule, loc, f) = invalid(with(|v| {
        at(v, FINS)["airfoil"] = json!({"csv": "/dev/zero", "angles": "degrees"});
    }));
    assert_eq!((loc, f.as_deref()), (comp("fins"), Some("airfoil.csv")));
    assert!(matches!(rule, Rule::FileUnreadable { .. }), "{rule:?}");
}
