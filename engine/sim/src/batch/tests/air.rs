//! A chunk's variants of the same site air share one air table.

use super::*;

#[test]
fn variants_of_the_same_swept_temperature_share_one_air_table_and_fly_as_with_their_own() {
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let cols = Columns::new(4).with(Input::TemperatureK, vec![300.0, 310.0, 300.0, 310.0]);
    let tables = AirTables::default();
    let sims: Vec<Simulation> = (0..4)
        .map(|r| batch.variant_in(&cols, r, &tables).unwrap())
        .collect();
    let air = |r: usize| &sims[r].model().air;
    assert!(
        std::sync::Arc::ptr_eq(air(0), air(2)),
        "300 K twice, two tables"
    );
    assert!(
        std::sync::Arc::ptr_eq(air(1), air(3)),
        "310 K twice, two tables"
    );
    assert!(!std::sync::Arc::ptr_eq(air(0), air(1)));
    assert_eq!(air(1).model().site_values(0.0).1, 310.0);
    // A variant given the shared table flies exactly as one that built its own.
    let own = batch.variant(&cols, 2).unwrap();
    assert!(!std::sync::Arc::ptr_eq(&own.model().air, air(2)));
    assert_eq!(
        sims[2].run(&mut ()).unwrap().metrics,
        own.run(&mut ()).unwrap().metrics
    );
    // A candidate of other air is not taken: 310 K offered where 305 K is asked.
    let offered = AirTables::default();
    offered.keep(air(1));
    let other = Columns::new(1).with(Input::TemperatureK, vec![305.0]);
    let s = batch.variant_in(&other, 0, &offered).unwrap();
    assert_eq!(s.model().air.model().site_values(0.0).1, 305.0);
}
