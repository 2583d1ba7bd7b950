//! Tests of the bundled library against the values its README tabulates (integrated there
//! by an independent script), and of look-up by name.

use super::*;

/// One README row: file, designation, manufacturer (as written), diameter mm, length mm,
/// propellant kg, total kg, total impulse N·s (to 0.1), class, burn time s (last point),
/// average thrust N (to 0.1).
struct Row {
    file: &'static str,
    designation: &'static str,
    manufacturer: &'static str,
    diameter_mm: f64,
    length_mm: f64,
    propellant_kg: f64,
    total_kg: f64,
    impulse_ns: f64,
    class: char,
    burn_s: f64,
    average_n: f64,
}

#[rustfmt::skip]
const README: &[Row] = &[
    Row { file: "AeroTech_I175WS.eng", designation: "I175WS", manufacturer: "AT", diameter_mm: 38.0, length_mm: 214.0, propellant_kg: 0.168, total_kg: 0.348, impulse_ns: 333.2, class: 'I', burn_s: 1.970, average_n: 169.1 },
    Row { file: "Cesaroni_I175.eng", designation: "411-I175-WH-14A", manufacturer: "CTI", diameter_mm: 38.0, length_mm: 245.0, propellant_kg: 0.2289, total_kg: 0.4375, impulse_ns: 411.4, class: 'I', burn_s: 2.500, average_n: 164.6 },
    Row { file: "AeroTech_H128W.eng", designation: "H128W", manufacturer: "AT", diameter_mm: 29.0, length_mm: 194.0, propellant_kg: 0.09408, total_kg: 0.2016, impulse_ns: 177.8, class: 'H', burn_s: 1.293, average_n: 137.5 },
    Row { file: "AeroTech_H238T.eng", designation: "H238T", manufacturer: "AT", diameter_mm: 29.0, length_mm: 194.0, propellant_kg: 0.08064, total_kg: 0.18816, impulse_ns: 177.6, class: 'H', burn_s: 1.036, average_n: 171.4 },
    Row { file: "AeroTech_I161W.eng", designation: "I161W", manufacturer: "AT", diameter_mm: 38.0, length_mm: 191.0, propellant_kg: 0.189952, total_kg: 0.370048, impulse_ns: 332.7, class: 'I', burn_s: 2.279, average_n: 146.0 },
    Row { file: "AeroTech_I284W.eng", designation: "I284W", manufacturer: "AT", diameter_mm: 38.0, length_mm: 297.0, propellant_kg: 0.310016, total_kg: 0.555072, impulse_ns: 599.5, class: 'I', burn_s: 2.160, average_n: 277.6 },
    Row { file: "Cesaroni_I216.eng", designation: "I216-CL(I)", manufacturer: "CTI", diameter_mm: 38.0, length_mm: 367.0, propellant_kg: 0.3125, total_kg: 0.601, impulse_ns: 636.1, class: 'I', burn_s: 3.100, average_n: 205.2 },
    Row { file: "AeroTech_J350W.eng", designation: "J350W", manufacturer: "AT", diameter_mm: 38.0, length_mm: 337.0, propellant_kg: 0.375872, total_kg: 0.650944, impulse_ns: 689.8, class: 'J', burn_s: 1.981, average_n: 348.2 },
    Row { file: "AeroTech_J570W.eng", designation: "J570W", manufacturer: "AT", diameter_mm: 38.0, length_mm: 479.0, propellant_kg: 0.547904, total_kg: 0.886144, impulse_ns: 1033.8, class: 'J', burn_s: 2.052, average_n: 503.8 },
    Row { file: "Cesaroni_J295.eng", designation: "J295", manufacturer: "CTI", diameter_mm: 54.0, length_mm: 329.0, propellant_kg: 0.594, total_kg: 1.119, impulse_ns: 1196.2, class: 'J', burn_s: 4.000, average_n: 299.0 },
    Row { file: "AeroTech_K550W.eng", designation: "K550W", manufacturer: "AT", diameter_mm: 54.0, length_mm: 410.0, propellant_kg: 0.919744, total_kg: 1.48736, impulse_ns: 1624.9, class: 'K', burn_s: 3.356, average_n: 484.2 },
    Row { file: "AeroTech_K1100T.eng", designation: "K1100T", manufacturer: "AT", diameter_mm: 54.0, length_mm: 398.0, propellant_kg: 0.7616, total_kg: 1.32518, impulse_ns: 1585.9, class: 'K', burn_s: 1.742, average_n: 910.4 },
    Row { file: "Cesaroni_K445.eng", designation: "K445", manufacturer: "CTI", diameter_mm: 54.0, length_mm: 404.0, propellant_kg: 0.792, total_kg: 1.398, impulse_ns: 1636.6, class: 'K', burn_s: 3.670, average_n: 445.9 },
    Row { file: "Cesaroni_K660.eng", designation: "K660", manufacturer: "CTI", diameter_mm: 54.0, length_mm: 572.0, propellant_kg: 1.177, total_kg: 1.949, impulse_ns: 2437.4, class: 'K', burn_s: 3.690, average_n: 660.5 },
    Row { file: "AeroTech_L1170FJ.eng", designation: "L1170FJ", manufacturer: "AT", diameter_mm: 75.0, length_mm: 665.0, propellant_kg: 2.8, total_kg: 4.99, impulse_ns: 4214.5, class: 'L', burn_s: 3.670, average_n: 1148.4 },
    Row { file: "Cesaroni_L1115.eng", designation: "L1115", manufacturer: "CTI", diameter_mm: 75.0, length_mm: 621.0, propellant_kg: 2.39, total_kg: 4.40, impulse_ns: 4965.8, class: 'L', burn_s: 4.480, average_n: 1108.4 },
    Row { file: "AeroTech_M1939W.eng", designation: "M1939W", manufacturer: "AT", diameter_mm: 98.0, length_mm: 732.0, propellant_kg: 5.656, total_kg: 8.98822, impulse_ns: 10368.6, class: 'N', burn_s: 6.950, average_n: 1491.9 },
    Row { file: "Cesaroni_M1670.eng", designation: "M1670-BS", manufacturer: "CTI", diameter_mm: 75.0, length_mm: 757.0, propellant_kg: 3.101, total_kg: 5.231, impulse_ns: 6026.4, class: 'M', burn_s: 3.900, average_n: 1545.2 },
    Row { file: "AeroTech_H148.eng", designation: "H148R", manufacturer: "AT", diameter_mm: 38.0, length_mm: 152.0, propellant_kg: 0.14784, total_kg: 0.30912, impulse_ns: 215.2, class: 'H', burn_s: 1.535, average_n: 140.2 },
    Row { file: "Cesaroni_1597K400-14A.eng", designation: "K400-GR", manufacturer: "CTI", diameter_mm: 54.0, length_mm: 404.0, propellant_kg: 0.969, total_kg: 1.5513, impulse_ns: 1594.8, class: 'K', burn_s: 4.017, average_n: 397.0 },
    Row { file: "Loki_K960-LW.eng", designation: "K960", manufacturer: "Loki", diameter_mm: 54.0, length_mm: 498.0, propellant_kg: 0.929864, total_kg: 1.74633, impulse_ns: 1949.5, class: 'K', burn_s: 2.000, average_n: 974.7 },
    Row { file: "AeroTech_L1040DM.eng", designation: "L1040DM-P", manufacturer: "AT", diameter_mm: 75.0, length_mm: 681.0, propellant_kg: 2.602, total_kg: 4.717, impulse_ns: 3871.6, class: 'L', burn_s: 4.127, average_n: 938.1 },
    Row { file: "AeroTech_I175WS.rse", designation: "I175WS", manufacturer: "Aerotech", diameter_mm: 38.0, length_mm: 214.0, propellant_kg: 0.168, total_kg: 0.348, impulse_ns: 333.2, class: 'I', burn_s: 1.970, average_n: 169.1 },
    Row { file: "AeroTech_J570W.rse", designation: "J570W", manufacturer: "Aerotech", diameter_mm: 38.0, length_mm: 479.0, propellant_kg: 0.547904, total_kg: 0.886144, impulse_ns: 1033.8, class: 'J', burn_s: 2.052, average_n: 503.8 },
    Row { file: "Cesaroni_I175.rse", designation: "411-I175-WH-14A", manufacturer: "CTI", diameter_mm: 38.0, length_mm: 245.0, propellant_kg: 0.2289, total_kg: 0.4375, impulse_ns: 411.4, class: 'I', burn_s: 2.500, average_n: 164.6 },
    Row { file: "Cesaroni_M1670.rse", designation: "M1670-BS", manufacturer: "CTI", diameter_mm: 75.0, length_mm: 757.0, propellant_kg: 3.101, total_kg: 5.231, impulse_ns: 6026.4, class: 'M', burn_s: 3.900, average_n: 1545.2 },
];

fn bundled_text(file: &str) -> &'static str {
    BUNDLED_FILES
        .iter()
        .find(|f| f.file_name == file)
        .map(|f| f.text)
        .unwrap_or_else(|| panic!("{file} is not bundled"))
}

#[test]
fn every_bundled_file_loads_with_the_readme_impulse_class_burn_time_and_header() {
    assert_eq!(README.len(), BUNDLED_FILES.len());
    for row in README {
        let m = Motor::parse(bundled_text(row.file).as_bytes(), row.file)
            .unwrap_or_else(|e| panic!("{e}"));
        let f = row.file;
        // README values are rounded to 0.1 N·s and 0.1 N.
        assert!(
            (m.total_impulse_ns() - row.impulse_ns).abs() <= 0.05,
            "{f}: {} N·s",
            m.total_impulse_ns()
        );
        assert!(
            (m.average_thrust_n() - row.average_n).abs() <= 0.05,
            "{f}: {} N",
            m.average_thrust_n()
        );
        assert_eq!(m.impulse_class(), row.class, "{f}");
        assert_eq!(m.burn_time_s(), row.burn_s, "{f}");
        assert_eq!(m.designation, row.designation, "{f}");
        assert_eq!(m.manufacturer, row.manufacturer, "{f}");
        assert!((m.diameter_m - row.diameter_mm * 1e-3).abs() < 1e-15, "{f}");
        assert!((m.length_m - row.length_mm * 1e-3).abs() < 1e-15, "{f}");
        assert!(
            (m.propellant_mass_kg - row.propellant_kg).abs() < 1e-12,
            "{f}: {}",
            m.propellant_mass_kg
        );
        assert!(
            (m.total_mass_kg - row.total_kg).abs() < 1e-12,
            "{f}: {}",
            m.total_mass_kg
        );
        assert_eq!(m.times_s()[0], 0.0, "{f}");
        assert_eq!(m.thrust_n().last(), Some(&0.0), "{f}");
        assert!(m.times_s().windows(2).all(|w| w[1] > w[0]), "{f}");
        assert_eq!(m.source, f.rsplit_once('.').unwrap().0);
    }
}

#[test]
fn the_embedded_files_are_exactly_the_files_of_the_motors_folder() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("motors");
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".eng") || n.ends_with(".rse"))
        .collect();
    on_disk.sort();
    let mut embedded: Vec<String> = BUNDLED_FILES
        .iter()
        .map(|f| f.file_name.to_string())
        .collect();
    embedded.sort();
    assert_eq!(embedded, on_disk);
    for f in BUNDLED_FILES {
        assert_eq!(
            f.text.as_bytes(),
            std::fs::read(dir.join(f.file_name)).unwrap(),
            "{}",
            f.file_name
        );
    }
    assert_eq!(
        BUNDLED_README.as_bytes(),
        std::fs::read(dir.join("README.md")).unwrap()
    );
}

#[test]
fn header_quirks_of_the_real_files_are_read() {
    let m = find("Cesaroni_I175").unwrap();
    assert_eq!(m.delays_s, [6.0, 8.0, 9.0, 11.0, 12.0, 13.0]);
    assert_eq!(m.propellant_mass_kg, 0.22890000000000002);
    assert!(
        find("AeroTech_L1040DM").unwrap().delays_s.is_empty(),
        "P is plugged"
    );
    assert_eq!(find("Cesaroni_M1670").unwrap().delays_s, [0.0]);
    assert_eq!(
        find("Cesaroni_L1115").unwrap().propellant_mass_kg,
        2.39,
        "tab-separated header"
    );
    assert_eq!(
        find("AeroTech_I175WS.rse").unwrap().delays_s,
        [5.0, 9.0, 13.0]
    );
    // A file whose first sample is after 0 s gets the implicit (0, 0).
    let k400 = find("Cesaroni_1597K400-14A").unwrap();
    assert_eq!(
        (k400.times_s()[..2].to_vec(), k400.thrust_n()[..2].to_vec()),
        (vec![0.0, 0.014], vec![0.0, 359.164])
    );
    // An .rse file that writes its (0, 0) sample has no extra one.
    let rse = find("Cesaroni_I175.rse").unwrap();
    assert_eq!(rse.times_s().len(), 30);
}

#[test]
fn the_rse_prop_weight_not_the_mass_column_is_the_propellant_mass() {
    // The I175WS .rse's mass column starts at 180 g while propWt says 168 g.
    let rse = find("AeroTech_I175WS.rse").unwrap();
    assert_eq!(rse.format, MotorFormat::Rse);
    assert_eq!(rse.propellant_mass_kg, 0.168);
    assert_eq!(rse.total_mass_kg, 0.348);
    assert!((rse.dry_mass_kg() - 0.18).abs() < 1e-15);
    let cti = find("Cesaroni_I175.rse").unwrap();
    assert!(
        (cti.propellant_mass_kg - 0.2289).abs() < 1e-15
            && (cti.total_mass_kg - 0.4375).abs() < 1e-15
    );
}

#[test]
fn an_eng_and_its_rse_describe_the_same_motor() {
    for stem in [
        "AeroTech_I175WS",
        "AeroTech_J570W",
        "Cesaroni_I175",
        "Cesaroni_M1670",
    ] {
        let eng = find(&format!("{stem}.eng")).unwrap();
        let rse = find(&format!("{stem}.rse")).unwrap();
        assert_eq!(
            (eng.format, rse.format),
            (MotorFormat::Eng, MotorFormat::Rse)
        );
        assert_eq!(eng.common_name, rse.common_name, "{stem}");
        assert!(
            (eng.total_impulse_ns() - rse.total_impulse_ns()).abs() < 0.05,
            "{stem}"
        );
        assert!(
            (eng.propellant_mass_kg - rse.propellant_mass_kg).abs() < 1e-9,
            "{stem}"
        );
    }
}

#[test]
fn i175_is_ambiguous_between_the_cesaroni_and_the_aerotech_motor() {
    let err = find("I175").unwrap_err();
    assert_eq!(
        err.to_string(),
        "motor name `I175` is ambiguous between AeroTech I175WS (file AeroTech_I175WS) and \
         Cesaroni Technology 411-I175-WH-14A (file Cesaroni_I175); name one by its file stem or full designation"
    );
    assert!(matches!(err, MotorError::Ambiguous { ref candidates, .. } if candidates.len() == 2));
}

#[test]
fn a_stem_a_file_name_a_designation_or_a_unique_common_name_finds_one_motor() {
    let by_stem = find("Cesaroni_I175").unwrap();
    assert_eq!(
        (by_stem.source.as_str(), by_stem.format),
        ("Cesaroni_I175", MotorFormat::Eng)
    );
    assert_eq!(find("cesaroni_i175").unwrap(), by_stem);
    // The .eng and .rse share the designation: not ambiguous, the .eng is preferred.
    assert_eq!(find("411-I175-WH-14A").unwrap(), by_stem);
    assert_eq!(find("411i175wh14a").unwrap(), by_stem);
    assert_eq!(find("cesaroni_i175.RSE").unwrap().format, MotorFormat::Rse);
    let ws = find("I175WS").unwrap();
    assert_eq!(
        (ws.source.as_str(), ws.format, ws.common_name.as_str()),
        ("AeroTech_I175WS", MotorFormat::Eng, "I175")
    );
    let m1670 = find("M1670").unwrap();
    assert_eq!(
        (m1670.source.as_str(), m1670.designation.as_str()),
        ("Cesaroni_M1670", "M1670-BS")
    );
    assert_eq!(find("K400").unwrap().source, "Cesaroni_1597K400-14A");
    assert_eq!(find(" K960 ").unwrap().source, "Loki_K960-LW");
}

#[test]
fn m1939w_is_named_an_m_but_integrates_to_class_n() {
    let m = find("M1939W").unwrap();
    assert_eq!(m.common_name, "M1939");
    assert_eq!(m.impulse_class(), 'N');
    assert!((m.total_impulse_ns() - 10368.6).abs() <= 0.05);
}

#[test]
fn a_path_to_a_file_is_read_from_disk() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("motors")
        .join("Cesaroni_I175.rse");
    let m = find(path.to_str().unwrap()).unwrap();
    assert_eq!(
        (m.format, m.source.as_str()),
        (MotorFormat::Rse, "Cesaroni_I175")
    );
    assert!(
        (m.propellant_mass_kg - 0.2289).abs() < 1e-15,
        "propWt 228.9 g"
    );

    let custom =
        std::env::temp_dir().join(format!("hpr_design_motor_test_{}.eng", std::process::id()));
    std::fs::write(
        &custom,
        "; mine\r\nMINE-G80 29 124 7 0.06 0.12 Me\r\n0.5 100\r\n1.5 60\r\n2 0\r\n",
    )
    .unwrap();
    let mine = find(custom.to_str().unwrap());
    let broken_path = custom.with_extension("txt");
    std::fs::write(&broken_path, "x").unwrap();
    let broken = find(broken_path.to_str().unwrap()).unwrap_err().to_string();
    std::fs::remove_file(&custom).unwrap();
    std::fs::remove_file(&broken_path).unwrap();
    let mine = mine.unwrap();
    // 0.5·100/2 + (100+60)/2·1 + 60·0.5/2 = 25 + 80 + 15.
    assert!((mine.total_impulse_ns() - 120.0).abs() < 1e-12);
    assert_eq!(
        (mine.impulse_class(), mine.common_name.as_str()),
        ('G', "G80")
    );
    assert!(
        broken.ends_with("unknown motor file type (expected a RASP `.eng` or RockSim `.rse` file)"),
        "{broken}"
    );
}

#[test]
fn a_motor_of_a_file_of_several_is_named_after_a_hash_by_designation_or_place() {
    // ThrustCurve's downloads can hold several curves: two tests of one motor and another.
    let path = std::env::temp_dir().join(format!(
        "hpr_design_motor_several_{}.eng",
        std::process::id()
    ));
    std::fs::write(
        &path,
        "H128W 29 194 0 0.09 0.2 AT\n0.1 150\n1.2 0\n\
         H128W 29 194 0 0.09 0.2 AT\n0.1 140\n1.3 0\n\
         G80T 29 124 7 0.06 0.12 AT\n0.5 100\n2 0\n",
    )
    .unwrap();
    let file = path.to_str().unwrap().to_owned();
    let by = |name: &str| find(&format!("{file}#{name}"));
    let g80 = by("g-80t");
    let g80_common = by("G80");
    let second = by("2");
    let ambiguous = by("H128W").unwrap_err().to_string();
    let missing = by("K550").unwrap_err().to_string();
    let whole = find(&file).unwrap_err();
    std::fs::remove_file(&path).unwrap();
    // By designation, ignoring case and punctuation; by common name too (G80).
    assert_eq!(g80.unwrap().designation, "G80T");
    assert_eq!(g80_common.unwrap().designation, "G80T");
    // By place: the second H128W test, known by its own burn time.
    assert_eq!(second.unwrap().burn_time_s(), 1.3);
    assert_eq!(
        ambiguous,
        format!("{file}: 2 motors are named `H128W`; name one by its place in the file, `{file}#K` (from 1)")
    );
    assert_eq!(
        missing,
        format!("{file}: no motor named `K550` (it holds H128W, H128W, G80T); name one as `{file}#DESIGNATION`, or `{file}#K` by its place in the file (from 1)")
    );
    assert!(matches!(whole, MotorError::SeveralMotors { .. }), "{whole}");
}

#[test]
fn an_unknown_name_lists_the_bundled_motors() {
    let err = find("Z9000").unwrap_err().to_string();
    assert!(
        err.starts_with(
            "no motor file or bundled motor matches `Z9000` (bundled motors: AeroTech_H128W, "
        ),
        "{err}"
    );
    assert!(err.contains("Loki_K960-LW"), "{err}");
    assert!(matches!(find(""), Err(MotorError::NotFound { .. })));
}

#[test]
fn a_path_that_names_no_file_is_said_to_be_missing() {
    for name in ["motors/my_I175.eng", "my_I175.rse", "motors\\I175"] {
        let err = find(name).unwrap_err();
        assert!(
            matches!(err, MotorError::NoSuchFile { .. }),
            "{name}: {err}"
        );
        assert!(
            err.to_string()
                .starts_with(&format!("no such motor file: `{name}`")),
            "{err}"
        );
    }
    // A bundled motor's own file name still finds it.
    assert_eq!(
        find("Cesaroni_I175.eng").unwrap().designation,
        "411-I175-WH-14A"
    );
}

#[test]
fn the_bundled_list_has_one_motor_per_stem_preferring_the_eng() {
    let list = bundled();
    assert_eq!(list.len(), 22);
    assert!(list.windows(2).all(|w| w[0].0 < w[1].0));
    assert!(list
        .iter()
        .all(|(stem, m)| m.format == MotorFormat::Eng && m.source == *stem));
}

#[test]
fn a_file_with_two_motors_is_refused_by_name_and_bad_utf8_is_reported() {
    let two = "A1 29 100 0 0.05 0.1 A\n1 10\n2 0\nB2 38 200 0 0.1 0.2 B\n1 20\n3 0\n";
    let err = Motor::parse(two.as_bytes(), "two.eng")
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "two.eng: holds 2 motors (A1, B2); name one as `two.eng#DESIGNATION`, or `two.eng#K` by \
         its place in the file (from 1)"
    );
    let err = Motor::parse(b"; ok\n\xff\xfe", "bad.eng")
        .unwrap_err()
        .to_string();
    assert_eq!(err, "bad.eng, line 2, text: the file is not UTF-8 text");
}

/// The K828FJ's RASP file as RocketPy ships it (the Bella Lui flight's motor).
const K828FJ: &str =
    include_str!("../../../../validation/real-flights/bella-lui/AeroTech_K828FJ.eng");

#[test]
fn a_curve_cut_at_a_burn_time_ends_there_with_the_thrust_interpolated_as_rocketpy_clips_it() {
    // RocketPy's burn_time = 2.43 on the K828FJ (last samples 2.39 s 49.85 N, 2.50 s 0 N):
    // the samples before 2.43 s, then 2.43 s at 49.85 × (2.50 − 2.43) / (2.50 − 2.39) N,
    // then nothing. The impulse loses the triangle from 2.43 to 2.50 s.
    let m = Motor::parse(K828FJ.as_bytes(), "AeroTech_K828FJ.eng").unwrap();
    let cut = m.cut_at(2.43).unwrap();
    let f_cut = 49.85 * (2.50 - 2.43) / (2.50 - 2.39);
    assert_eq!(cut.burn_time_s(), 2.43);
    assert_eq!(cut.times_s().len(), m.times_s().len()); // 2.50 s gave way to 2.43 s
    assert!((cut.thrust_n().last().unwrap() - f_cut).abs() < 1e-12);
    assert_eq!(
        &cut.times_s()[..cut.times_s().len() - 1],
        &m.times_s()[..m.times_s().len() - 1]
    );
    let lost = 0.5 * f_cut * (2.50 - 2.43);
    assert!((cut.total_impulse_ns() - (m.total_impulse_ns() - lost)).abs() < 1e-9);
    assert!(cut.notes.last().unwrap().contains("cut at 2.43 s"));
    // At a sample's own time: that sample ends the curve.
    let at_sample = m.cut_at(2.39).unwrap();
    assert_eq!(at_sample.thrust_n().last(), Some(&49.85));
    // At burnout: unchanged.
    assert_eq!(m.cut_at(2.5).unwrap(), m);
    // Outside the curve: refused with the rule.
    for bad in [0.0, -1.0, 2.6, f64::NAN] {
        let e = m.cut_at(bad).unwrap_err().to_string();
        assert!(
            e.contains("burn_time_s") && e.contains("no later than"),
            "{e}"
        );
    }
}

#[test]
fn a_motor_in_another_casing_takes_its_diameter_and_refuses_a_nonsense_one() {
    let m = Motor::parse(K828FJ.as_bytes(), "AeroTech_K828FJ.eng").unwrap();
    assert_eq!(m.diameter_m, 0.054);
    let wide = m.with_diameter(0.098).unwrap();
    assert_eq!(wide.diameter_m, 0.098);
    assert_eq!(wide.total_impulse_ns(), m.total_impulse_ns());
    assert!(m.with_diameter(0.0).is_err() && m.with_diameter(f64::INFINITY).is_err());
}

#[test]
fn a_motor_file_past_its_limit_is_refused_saying_so() {
    let e = Motor::from_file("/dev/zero").unwrap_err().to_string();
    assert!(
        e.contains("it is larger than 16 MiB, the most hpr-mc reads for a motor file"),
        "{e}"
    );
}
