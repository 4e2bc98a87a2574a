//! Every CDR message against its published `ros2msg` schema, field by field, by a
//! codec written here from the schema text alone (XCDR1 little-endian: header
//! `00 01 00 00`, each primitive aligned to its size from the end of the header,
//! `T[]` a `uint32` length then the elements, `T[n]` n elements). Each field is
//! compared by its schema name with the Rust value, floats bit for bit, in both
//! directions: carom's encoder against this decoder, this encoder against carom's
//! decoder. A field written in the wrong place or type, or two fields swapped
//! consistently in carom's writer and reader (which a round trip cannot see),
//! fails here. Every value in the samples is distinct, so a swap shows. A
//! `string` is its bytes with the terminating NUL, as CDR stores it (a `uint8[]`).
//! (A unit test: carom's `CdrWriter` is crate-private.)

use super::cdr::{CdrError, CdrWriter};
use super::{
    CollisionBatch, CollisionRecord, CompactBatch, LogCheckpoint, Snapshot, CHECKPOINT_MSG,
    COLLISION_BATCH_MSG, COMPACT_COLLISION_BATCH_MSG, SNAPSHOT_MSG,
};
use carom_core::{Axis, DVec2, WallSide};
use carom_engine::{PairCollision, WallCollision};

/// A primitive type of the schemas and its size in bytes (also its alignment).
fn size_of(ty: &str) -> usize {
    match ty {
        "uint8" => 1,
        "uint16" => 2,
        "uint32" | "int32" => 4,
        "uint64" | "float64" => 8,
        _ => panic!("type {ty} is not used by carom's schemas"),
    }
}

/// One field of a schema: name, primitive type, and `None` for a scalar,
/// `Some(None)` for a sequence `T[]`, `Some(Some(n))` for an array `T[n]`.
struct Field {
    name: String,
    ty: String,
    shape: Option<Option<usize>>,
}

fn parse_schema(schema: &str) -> Vec<Field> {
    schema
        .lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| {
            let (ty, name) = l.split_once(char::is_whitespace).unwrap();
            let (ty, shape) = match ty.split_once('[') {
                None if ty == "string" => ("uint8", Some(None)),
                None => (ty, None),
                Some((t, "]")) => (t, Some(None)),
                Some((t, n)) => (t, Some(Some(n.trim_end_matches(']').parse().unwrap()))),
            };
            Field {
                name: name.trim().to_string(),
                ty: ty.to_string(),
                shape,
            }
        })
        .collect()
}

/// A field's values as raw little-endian words: integers as themselves, floats
/// as their bits.
type Values = Vec<(String, Vec<u64>)>;

fn f(v: impl IntoIterator<Item = f64>) -> Vec<u64> {
    v.into_iter().map(f64::to_bits).collect()
}

fn u<T: Into<u64>>(v: impl IntoIterator<Item = T>) -> Vec<u64> {
    v.into_iter().map(Into::into).collect()
}

/// Signed 32-bit values as their two's-complement words.
fn i(v: impl IntoIterator<Item = i32>) -> Vec<u64> {
    v.into_iter().map(|x| x as u32 as u64).collect()
}

fn named(fields: Vec<(&str, Vec<u64>)>) -> Values {
    fields
        .into_iter()
        .map(|(n, v)| (n.to_string(), v))
        .collect()
}

fn align(pos: usize, size: usize) -> usize {
    4 + (pos - 4).div_ceil(size) * size
}

/// Decode `bytes` as the schema says, every byte accounted for.
fn decode(schema: &str, bytes: &[u8]) -> Values {
    assert_eq!(bytes[..4], [0, 1, 0, 0], "CDR little-endian header");
    let mut pos = 4;
    let word = |pos: &mut usize, size: usize| {
        *pos = align(*pos, size);
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(&bytes[*pos..*pos + size]);
        *pos += size;
        u64::from_le_bytes(b)
    };
    let out = parse_schema(schema)
        .into_iter()
        .map(|fl| {
            let size = size_of(&fl.ty);
            let n = match fl.shape {
                None => 1,
                Some(None) => word(&mut pos, 4) as usize,
                Some(Some(n)) => n,
            };
            let v = (0..n).map(|_| word(&mut pos, size)).collect();
            (fl.name, v)
        })
        .collect();
    assert_eq!(pos, bytes.len(), "bytes beyond the schema's last field");
    out
}

/// Encode named values as the schema says (every schema field must be given,
/// in any order).
fn encode(schema: &str, values: &Values) -> Vec<u8> {
    let mut out = vec![0, 1, 0, 0];
    let put = |out: &mut Vec<u8>, x: u64, size: usize| {
        out.resize(align(out.len(), size), 0);
        out.extend_from_slice(&x.to_le_bytes()[..size]);
    };
    for fl in parse_schema(schema) {
        let v = &values.iter().find(|(n, _)| *n == fl.name).unwrap().1;
        let size = size_of(&fl.ty);
        match fl.shape {
            None => assert_eq!(v.len(), 1, "{}", fl.name),
            Some(None) => put(&mut out, v.len() as u64, 4),
            Some(Some(n)) => assert_eq!(v.len(), n, "{}", fl.name),
        }
        for &x in v {
            put(&mut out, x, size);
        }
    }
    out
}

/// `decode(encoded)` holds exactly `expected`, field by field in schema order.
fn assert_layout(schema: &str, encoded: &[u8], expected: &Values) {
    let got = decode(schema, encoded);
    let names = |v: &Values| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    let mut want_names = names(expected);
    let mut got_names = names(&got);
    want_names.sort();
    got_names.sort();
    assert_eq!(got_names, want_names, "the schema's fields");
    for (name, v) in &got {
        let want = &expected.iter().find(|(n, _)| n == name).unwrap().1;
        assert_eq!(v, want, "field `{name}`");
    }
}

fn collision_fields(b: &CollisionBatch) -> Values {
    named(vec![
        ("first_ordinal", vec![b.first_ordinal]),
        ("stride", vec![b.stride]),
        ("time", f(b.time.clone())),
        ("kind", u(b.kind.clone())),
        ("i", u(b.i.clone())),
        ("j", u(b.j.clone())),
        ("nx", f(b.nx.clone())),
        ("ny", f(b.ny.clone())),
        ("vix_before", f(b.vix_before.clone())),
        ("viy_before", f(b.viy_before.clone())),
        ("vjx_before", f(b.vjx_before.clone())),
        ("vjy_before", f(b.vjy_before.clone())),
        ("vix_after", f(b.vix_after.clone())),
        ("viy_after", f(b.viy_after.clone())),
        ("vjx_after", f(b.vjx_after.clone())),
        ("vjy_after", f(b.vjy_after.clone())),
        ("energy_lost", f(b.energy_lost.clone())),
        ("virial", f(b.virial.clone())),
    ])
}

/// A pair collision whose every number differs from every other (offset by `k`).
fn pair(k: f64) -> PairCollision {
    let v = |a: f64, b: f64| DVec2::new(a + k, b + k);
    PairCollision {
        time: 10.0 + k,
        i: 3 + k as u32,
        j: 9 + k as u32,
        normal: DVec2::new(0.6, 0.8),
        vi_before: v(1.125, 2.25),
        vj_before: v(-1.5, 0.375),
        vi_after: v(0.0625, 0.1875),
        vj_after: v(0.3125, 0.4375),
        energy_lost: 0.046875 + k,
        virial: -0.71875 - k,
        impulse: DVec2::new(-0.90625, -1.8125),
    }
}

fn wall() -> WallCollision {
    WallCollision {
        time: 11.5,
        i: 4,
        axis: Axis::Y,
        side: WallSide::High,
        v_before: DVec2::new(0.53125, 1.03125),
        v_after: DVec2::new(0.53125, -0.90625),
        impulse: 1.9375,
        energy_lost: 0.0546875,
    }
}

fn records() -> Vec<CollisionRecord> {
    vec![
        CollisionRecord::from_pair(&pair(0.0), 7),
        CollisionRecord::from_wall(&wall(), 8),
        CollisionRecord::from_pair(&pair(100.0), 9),
    ]
}

#[test]
fn full_collision_batches_follow_their_schema() {
    let mut b = CollisionBatch::with_capacity(3);
    b.first_ordinal = 70;
    b.stride = 3;
    for r in records() {
        b.push(&r);
    }
    let fields = collision_fields(&b);
    let mut w = CdrWriter::new();
    b.encode(&mut w);
    assert_layout(COLLISION_BATCH_MSG, w.bytes(), &fields);
    CollisionBatch::encode_records(&records(), 70, 3, &mut w);
    assert_layout(COLLISION_BATCH_MSG, w.bytes(), &fields);
    let mut back = CollisionBatch::default();
    back.decode_into(&encode(COLLISION_BATCH_MSG, &fields))
        .unwrap();
    assert_eq!(collision_fields(&back), fields);
    assert_eq!(back, b);
}

fn compact_fields(b: &CompactBatch) -> Values {
    named(vec![
        ("first_ordinal", vec![b.first_ordinal]),
        ("stride", vec![1]),
        ("time", f(b.time.clone())),
        ("i", u(b.i.clone())),
        ("j", u(b.j.clone())),
        ("dpx", f(b.dpx.clone())),
        ("dpy", f(b.dpy.clone())),
        ("nx", f(b.nx.clone())),
        ("ny", f(b.ny.clone())),
    ])
}

#[test]
fn compact_collision_batches_follow_their_schema() {
    let recs = records();
    for normals in [false, true] {
        let (p, q) = (pair(0.0), pair(100.0));
        let (nx, ny) = if normals {
            (vec![0.6, 0.0, 0.6], vec![0.8, 0.0, 0.8])
        } else {
            (vec![], vec![])
        };
        // The wall: j codes (y, high); Δp_i = (0, −J), away from the wall.
        let expected = CompactBatch {
            first_ordinal: 7,
            time: vec![p.time, 11.5, q.time],
            i: vec![p.i, 4, q.i],
            j: vec![p.j, u32::MAX, q.j],
            dpx: vec![p.impulse.x, 0.0, q.impulse.x],
            dpy: vec![p.impulse.y, -1.9375, q.impulse.y],
            nx,
            ny,
        };
        let fields = compact_fields(&expected);
        let mut w = CdrWriter::new();
        CompactBatch::encode_records(&recs, 7, normals, &mut w);
        assert_layout(COMPACT_COLLISION_BATCH_MSG, w.bytes(), &fields);
        expected.encode(&mut w);
        assert_layout(COMPACT_COLLISION_BATCH_MSG, w.bytes(), &fields);
        let mut back = CompactBatch::default();
        back.decode_into(&encode(COMPACT_COLLISION_BATCH_MSG, &fields))
            .unwrap();
        assert_eq!(back, expected);
        assert!(back.len() == 3 && !back.is_empty());
    }
}

fn snapshot_fields(s: &Snapshot) -> Values {
    named(vec![
        ("time", f([s.time])),
        ("box_x", f([s.box_size.x])),
        ("box_y", f([s.box_size.y])),
        ("boundary_x", u([s.boundary[0]])),
        ("boundary_y", u([s.boundary[1]])),
        ("species_radius", f(s.species_radius.clone())),
        ("species_mass", f(s.species_mass.clone())),
        ("species", u(s.species.clone())),
        ("x", f(s.positions.iter().map(|p| p.x))),
        ("y", f(s.positions.iter().map(|p| p.y))),
        ("vx", f(s.velocities.iter().map(|v| v.x))),
        ("vy", f(s.velocities.iter().map(|v| v.y))),
        ("image_x", i(s.images.iter().map(|m| m[0]))),
        ("image_y", i(s.images.iter().map(|m| m[1]))),
    ])
}

#[test]
fn snapshots_follow_their_schema() {
    let s = Snapshot {
        time: 2.75,
        box_size: DVec2::new(7.5, 4.25),
        boundary: [0, 1],
        species_radius: vec![0.5, 0.6875],
        species_mass: vec![1.0625, 2.5],
        species: vec![0, 1, 1],
        positions: vec![
            DVec2::new(1.125, 1.375),
            DVec2::new(3.0625, 2.125),
            DVec2::new(5.5, 2.625),
        ],
        velocities: vec![
            DVec2::new(0.09375, -0.203125),
            DVec2::new(-1.53125, 0.28125),
            DVec2::new(0.015625, 3.03125),
        ],
        images: vec![[-3, 0], [7, 0], [-200_000, 0]],
    };
    let fields = snapshot_fields(&s);
    let mut w = CdrWriter::new();
    s.encode(&mut w);
    assert_layout(SNAPSHOT_MSG, w.bytes(), &fields);
    assert_eq!(Snapshot::decode(&encode(SNAPSHOT_MSG, &fields)).unwrap(), s);
}

/// The checkpoint's fields by schema name, read from carom's own decoded form:
/// the schema and carom's encoder must agree on every one of them.
fn checkpoint_fields(c: &LogCheckpoint) -> Values {
    use carom_core::{Boundary, Restitution};
    let (d, e) = (&c.driver, &c.engine);
    let s = &e.stats;
    let code = |b: &Boundary| u64::from(!b.is_periodic());
    let we = |b: &Boundary| match *b {
        Boundary::Periodic => 1.0,
        Boundary::Walls { restitution } => restitution,
    };
    let (kind, coef) = match e.params.restitution {
        Restitution::Elastic => (0, 1.0),
        Restitution::CentreOfMass(r) => (1, r),
        Restitution::Normal(x) => (2, x),
    };
    let b = &e.sim_box.boundary;
    let sched = super::checkpoint::scheduled_entries(e);
    named(
        vec![
            ("format_version", vec![6]),
            ("run_start_time", f([d.run_start_time])),
            ("logged_collisions", vec![d.logged_collisions]),
            ("next_sequence", u(d.next_sequence)),
            ("box_x", f([e.sim_box.size.x])),
            ("box_y", f([e.sim_box.size.y])),
            ("boundary_x", vec![code(&b[0])]),
            ("boundary_y", vec![code(&b[1])]),
            ("wall_restitution_x", f([we(&b[0])])),
            ("wall_restitution_y", f([we(&b[1])])),
            (
                "species_count",
                e.species.iter().map(|s| s.count as u64).collect(),
            ),
            ("species_radius", f(e.species.iter().map(|s| s.radius))),
            ("species_mass", f(e.species.iter().map(|s| s.mass))),
            ("species", u(e.species_of.clone())),
            ("restitution_kind", vec![kind]),
            ("restitution", f([coef])),
            ("tc", f([e.params.tc])),
            (
                "max_events_without_time_advance",
                vec![e.params.max_events_without_time_advance],
            ),
            ("now", f([e.now])),
            ("epoch", f([e.epoch])),
            ("clock", f([e.clock])),
            ("same_time_collisions", vec![e.same_time_collisions]),
            ("pair_collisions", vec![s.pair_collisions]),
            ("wall_collisions", vec![s.wall_collisions]),
            ("cell_crossings", vec![s.cell_crossings]),
            ("stale_events", vec![s.stale_events]),
            ("virial_sum", f([s.virial_sum])),
            ("wall_impulse", f(s.wall_impulse.iter().flatten().copied())),
            ("energy_lost", f([s.energy_lost])),
            ("x", f(e.positions.iter().map(|p| p.x))),
            ("y", f(e.positions.iter().map(|p| p.y))),
            ("vx", f(e.velocities.iter().map(|v| v.x))),
            ("vy", f(e.velocities.iter().map(|v| v.y))),
            ("t", f(e.times.clone())),
            ("collision_count", u(e.counts.clone())),
            ("last_collision", f(e.last_collision.clone())),
            ("event_time", f(e.event_times.clone())),
            ("pair_time", f(e.pair_times.clone())),
            ("pending_partner", u(e.pending.iter().map(|p| p[0]))),
            ("pending_partner_count", u(e.pending.iter().map(|p| p[1]))),
            ("pending_kind", u(e.pending.iter().map(|p| p[2]))),
            ("cell_head", u(e.cell_head.clone())),
            ("cell_next", u(e.cell_next.clone())),
            ("cell_prev", u(e.cell_prev.clone())),
            ("cell_column", u(e.cell.iter().map(|c| c[0]))),
            ("cell_row", u(e.cell.iter().map(|c| c[1]))),
            ("scheduled_time", f(sched.iter().map(|s| s.0))),
            ("scheduled_seq", sched.iter().map(|s| s.1).collect()),
            ("scheduled_tag", sched.iter().map(|s| s.2).collect()),
            ("next_seq", vec![e.next_seq]),
            ("labels", u(e.labels.clone())),
            ("next_reorder", vec![e.next_reorder]),
            ("image_x", i(e.images.iter().map(|m| m[0]))),
            ("image_y", i(e.images.iter().map(|m| m[1]))),
            ("gravity", f([e.params.gravity])),
        ]
        .into_iter()
        .chain(thermostat_fields(e.thermostat))
        .chain(growth_fields(&e.params.growth, &e.growth))
        .chain(floor_fields(e))
        .chain(neighbour_fields(e))
        .collect::<Vec<_>>(),
    )
}

/// The thermostat's fields by schema name (format 4 on).
fn thermostat_fields(t: Option<carom_engine::ThermostatState>) -> Vec<(&'static str, Vec<u64>)> {
    use carom_engine::Thermostat;
    let (kind, a, b, rng, events, added, origin) = match t {
        None => (0, 0.0, 0.0, 0u128, 0, 0.0, 0.0),
        Some(t) => {
            let (kind, a, b) = match t.thermostat {
                Thermostat::Andersen { kt, rate } => (1, kt, rate),
                Thermostat::Driven { xi2, interval } => (2, xi2, interval),
            };
            (
                kind,
                a,
                b,
                t.rng,
                t.stats.events,
                t.stats.energy_added,
                t.origin,
            )
        }
    };
    vec![
        ("thermostat_kind", vec![kind]),
        ("thermostat_a", f([a])),
        ("thermostat_b", f([b])),
        ("thermostat_rng", vec![(rng >> 64) as u64, rng as u64]),
        ("thermostat_events", vec![events]),
        ("thermostat_energy_added", f([added])),
        ("thermostat_origin", f([origin])),
    ]
}

/// The growth's fields by schema name (format 5 on).
fn growth_fields(
    g: &carom_engine::Growth,
    st: &carom_engine::GrowthState,
) -> Vec<(&'static str, Vec<u64>)> {
    vec![
        ("growth_rate", f([g.rate])),
        ("growth_target_scale", f([g.target_scale])),
        ("growth_kt", f([g.kt])),
        ("growth_rescale_interval", f([g.rescale_interval])),
        ("growth_max_reduced_pressure", f([g.max_reduced_pressure])),
        ("growth_scale0", f([st.scale0])),
        ("growth_rate_now", f([st.rate])),
        ("growth_end", f([st.end])),
        ("growth_next_rescale", f([st.next_rescale])),
        ("growth_virial_mark", f([st.virial_mark])),
        ("growth_ended", vec![st.ended as u64]),
        ("growth_last_z", f([st.last_z])),
    ]
}

/// The vibrating floor's fields by schema name (format 5 on).
fn floor_fields(e: &carom_engine::Checkpoint) -> Vec<(&'static str, Vec<u64>)> {
    let (a, w) = e
        .params
        .floor
        .map_or((0.0, 0.0), |fl| (fl.amplitude, fl.omega));
    vec![
        ("floor_amplitude", f([a])),
        ("floor_omega", f([w])),
        ("floor_origin", f([e.floor_origin])),
        ("floor_work", f([e.stats.floor_work])),
    ]
}

/// The neighbour search's fields by schema name (format 6 on): the setting's
/// name as a CDR string, and the lists (skin 0, no centres on the cell grid).
fn neighbour_fields(e: &carom_engine::Checkpoint) -> Vec<(&'static str, Vec<u64>)> {
    let name = e.params.neighbours.name().bytes().chain([0]);
    let (skin, centres) = e
        .lists
        .as_ref()
        .map_or((0.0, &[][..]), |l| (l.skin, &l.centres[..]));
    vec![
        ("neighbours", u(name)),
        ("lists_skin", f([skin])),
        ("lists_centre_x", f(centres.iter().map(|c| c.x))),
        ("lists_centre_y", f(centres.iter().map(|c| c.y))),
    ]
}

/// A checkpoint after 300 collisions of a binary mixture, walled in x, with one
/// scheduled event.
fn sample_checkpoint() -> LogCheckpoint {
    use super::DriverState;
    use carom_core::{Boundary, Restitution, SimBox, Species};
    use carom_engine::{box_size_for, Engine, EngineParams, Placement, SystemSpec, Velocities};
    let species = vec![Species::reference(30), Species::new(8, 0.8, 3.0)];
    let spec = SystemSpec {
        sim_box: SimBox {
            size: box_size_for(&species, 0.4, 1.0),
            boundary: [Boundary::Walls { restitution: 0.875 }, Boundary::Periodic],
        },
        species,
        temperature: 1.0,
        seed: 5,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let params = EngineParams {
        restitution: Restitution::CentreOfMass(0.96875),
        tc: 1e-4,
        max_events_without_time_advance: 1001,
        ..EngineParams::default()
    };
    let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
    // An Andersen thermostat, so that its fields are not all zero.
    let andersen = carom_engine::Thermostat::Andersen {
        kt: 1.5,
        rate: 0.25,
    };
    e.set_thermostat(Some(andersen), 9).unwrap();
    e.run_collisions(300).unwrap();
    e.schedule(e.now() + 1.0, 42).unwrap();
    let mut engine = e.checkpoint();
    assert!(engine.thermostat.unwrap().stats.events > 0);
    // Images all distinct and of both signs (300 collisions cross few edges).
    for (k, m) in engine.images.iter_mut().enumerate() {
        *m = [-1 - k as i32, 1000 + k as i32];
    }
    // Made-up neighbour lists, centres all distinct (the reader does not ask the
    // engine whether it could be on them).
    engine.params.neighbours = carom_engine::Neighbours::Lists;
    engine.lists = Some(carom_engine::ListsCheckpoint {
        skin: 0.1875,
        centres: (0..engine.positions.len())
            .map(|k| DVec2::new(0.5 + k as f64, -0.25 - k as f64))
            .collect(),
    });
    LogCheckpoint {
        driver: DriverState {
            run_start_time: 0.5,
            logged_collisions: 250,
            next_sequence: [11, 12, 13, 14],
        },
        engine,
    }
}

#[test]
fn checkpoints_follow_their_schema() {
    let c = sample_checkpoint();
    let fields = checkpoint_fields(&c);
    let mut w = CdrWriter::new();
    c.encode(&mut w);
    assert_layout(CHECKPOINT_MSG, w.bytes(), &fields);
    assert_eq!(
        LogCheckpoint::decode(&encode(CHECKPOINT_MSG, &fields)).unwrap(),
        c
    );
}

/// A checkpoint whose paired arrays differ in length is refused, naming the
/// array the reader checks: any one array of a group (the species' radii and
/// masses, the pending events, the scheduled events, the cells, the list
/// centres) one entry short.
/// (Found missing by mutation testing, docs/testing.md: carom's writer cannot
/// produce such a file, so only bytes from this codec reach these checks.)
#[test]
fn a_checkpoint_with_unequal_paired_arrays_is_refused() {
    let fields = checkpoint_fields(&sample_checkpoint());
    for (short, named) in [
        ("species_radius", "species_radius"),
        ("species_mass", "species_radius"),
        ("y", "y"),
        ("vy", "vy"),
        ("pending_partner_count", "pending_kind"),
        ("pending_kind", "pending_kind"),
        ("cell_row", "cell_row"),
        ("scheduled_seq", "scheduled_tag"),
        ("scheduled_tag", "scheduled_tag"),
        ("image_x", "image_y"),
        ("image_y", "image_y"),
        ("lists_centre_x", "lists_centre_y"),
        ("lists_centre_y", "lists_centre_y"),
    ] {
        let mut cut = fields.clone();
        let values = &mut cut.iter_mut().find(|(n, _)| n == short).unwrap().1;
        assert!(values.pop().is_some(), "{short} is empty in the sample");
        match LogCheckpoint::decode(&encode(CHECKPOINT_MSG, &cut)) {
            Err(CdrError::Invalid { field, .. }) => assert_eq!(field, named, "{short} short"),
            other => panic!("{short} one entry short: {other:?}"),
        }
    }
}

/// A checkpoint of format 2 is format 4 without the images, gravity and the
/// thermostat at the end (and all that later formats append after them): it
/// reads with no images (the engine then counts them from 0), g = 0, no
/// thermostat, no growth or floor, the setting auto and no lists.
#[test]
fn a_format_2_checkpoint_reads_without_images() {
    let c = sample_checkpoint();
    let v2: String = CHECKPOINT_MSG
        .lines()
        .filter(|l| {
            !l.starts_with("int32[] image_")
                && !l.starts_with("float64 gravity")
                && !l.contains(" thermostat_")
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let mut fields = checkpoint_fields(&c);
    fields.retain(|(n, _)| {
        !n.starts_with("image_") && *n != "gravity" && !n.starts_with("thermostat_")
    });
    fields
        .iter_mut()
        .find(|(n, _)| n == "format_version")
        .unwrap()
        .1 = vec![2];
    let read = LogCheckpoint::decode(&encode(&v2, &fields)).unwrap();
    assert!(read.engine.images.is_empty());
    let mut want = c;
    want.engine.images.clear();
    // Without a thermostat every stored entry is the caller's (the sample's
    // thermostat entry too).
    want.engine.scheduled = super::checkpoint::scheduled_entries(&want.engine);
    want.engine.thermostat = None;
    want.engine.params.neighbours = carom_engine::Neighbours::Auto;
    want.engine.lists = None;
    assert_eq!(read, want);
    fields
        .iter_mut()
        .find(|(n, _)| n == "format_version")
        .unwrap()
        .1 = vec![1];
    assert!(LogCheckpoint::decode(&encode(&v2, &fields)).is_err());
}
