//! Boxes only two or three cells across, where the neighbour search sees the same
//! cell through more than one periodic image, and where a cell crossing brings
//! cells next to a disc that it saw before through another image. The engine scans
//! only the newly adjacent cells after a crossing (see the engine's `predict` module), so
//! these are the boxes where a mistake in which cells (and which images) are new
//! would show: a missed collision lets two discs pass through each other, and the
//! overlap check catches it within a few events.
//!
//! Every 500 collisions: no pair overlaps by more than 1e-10 of its contact
//! distance (`InvariantChecker::check_overlaps`, minimum image, unambiguous for box
//! edges above two diameters); every 5000: energy and momentum conserved to the
//! checker's 1e-12. 10⁵ collisions per system.

use carom_core::{SimBox, Species};
use carom_engine::{Engine, EngineParams, InvariantChecker, SystemSpec};

mod engine_common;
use engine_common::{lattice_spec, mono};

fn run_checked(name: &str, spec: SystemSpec, expect_cells_across: u32) {
    let state = spec
        .build()
        .unwrap_or_else(|e| panic!("{name}: initial state: {e}"));
    let mut engine = Engine::new(state, EngineParams::default()).expect("engine");
    assert_eq!(
        engine.cells()[0],
        expect_cells_across,
        "{name}: the box should be {expect_cells_across} cells across"
    );
    let mut checker = InvariantChecker::new(&engine);
    let mut done = 0u64;
    while done < 100_000 {
        done += engine.run_collisions(500).expect("no runaway");
        checker
            .check_overlaps(&engine)
            .unwrap_or_else(|v| panic!("{name}: after {done} collisions: {v}"));
        if done.is_multiple_of(5000) {
            checker
                .check_conservation(&engine)
                .unwrap_or_else(|v| panic!("{name}: after {done} collisions: {v}"));
        }
    }
    let crossings = engine.stats().cell_crossings;
    assert!(
        crossings > done / 10,
        "{name}: crossings must be exercised ({crossings} in {done} collisions)"
    );
}

#[test]
fn periodic_box_two_cells_across() {
    run_checked(
        "periodic 2.4 x 30, N = 30",
        lattice_spec(mono(30), SimBox::periodic(2.4, 30.0), 1),
        2,
    );
}

#[test]
fn periodic_box_three_cells_across() {
    run_checked(
        "periodic 3.3 x 25, N = 40",
        lattice_spec(mono(40), SimBox::periodic(3.3, 25.0), 2),
        3,
    );
}

#[test]
fn periodic_mixture_two_cells_across() {
    // Cells are sized by the large discs (diameter 1.2): 2.9 / 1.2 → 2 cells.
    let species = vec![Species::new(20, 0.3, 0.5), Species::new(12, 0.6, 2.0)];
    run_checked(
        "periodic mixture 2.9 x 24",
        lattice_spec(species, SimBox::periodic(2.9, 24.0), 3),
        2,
    );
}

#[test]
fn narrow_walled_channel() {
    // Periodic along y, walls along x, two cells between the walls.
    let mut b = SimBox::walled(2.6, 30.0, 1.0);
    b.boundary[1] = carom_core::Boundary::Periodic;
    run_checked("channel 2.6 wide, N = 30", lattice_spec(mono(30), b, 4), 2);
}
