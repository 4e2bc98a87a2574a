//! The Rust reader's view of a carom log, field by field, in the shape that
//! `tests/python/read_carom_log.py --fields` prints: every message in file order
//! with its envelope and EVERY schema field (floats as the 16 hex digits of their
//! bits, so equality is bit equality), and the metadata records.
//!
//! Each message type is destructured exhaustively (no `..`), so a field added to a
//! Rust message type does not compile until it is mapped here; the Python side
//! prints every field the file's schema has, so a field added to a schema fails the
//! comparison (the key sets must be equal) until it is mapped here. The mapping
//! follows docs/log-format.md, written out again here, not taken from the codecs:
//! a field swapped consistently in a writer and its reader disagrees with it.
#![allow(dead_code)]

use carom_core::{Boundary, DVec2, Restitution, Species};
use carom_log::{
    CollisionBatch, CompactBatch, DriverState, LogCheckpoint, LogReader, RunMetadata, Snapshot,
    SummaryMetadata, Thermo, CH_CHECKPOINT, CH_COLLISIONS, CH_SCENE, CH_SNAPSHOT, CH_THERMO,
    SPECIES_COLORS, TOPICS,
};
use serde_json::{json, Map, Value};
use std::collections::BTreeMap;
use std::path::Path;

/// A float as the hex digits of its bits (what the Python side prints).
pub fn f(x: f64) -> Value {
    Value::String(format!("{:016x}", x.to_bits()))
}

/// Floats as [`f`].
pub fn fs(v: impl IntoIterator<Item = f64>) -> Value {
    Value::Array(v.into_iter().map(f).collect())
}

/// Integers as JSON numbers.
fn ints<T: Into<Value>>(v: impl IntoIterator<Item = T>) -> Value {
    Value::Array(v.into_iter().map(Into::into).collect())
}

fn xs(v: &[DVec2]) -> Value {
    fs(v.iter().map(|p| p.x))
}

fn ys(v: &[DVec2]) -> Value {
    fs(v.iter().map(|p| p.y))
}

/// 0 = periodic, 1 = hard walls; and the wall restitution (1 when periodic).
fn boundary(b: &Boundary) -> (u8, f64) {
    match *b {
        Boundary::Periodic => (0, 1.0),
        Boundary::Walls { restitution } => (1, restitution),
    }
}

/// A full collision record (`carom_msgs/msg/CollisionBatch`).
pub fn full_batch(b: &CollisionBatch) -> Value {
    let CollisionBatch {
        first_ordinal,
        stride,
        time,
        kind,
        i,
        j,
        nx,
        ny,
        vix_before,
        viy_before,
        vjx_before,
        vjy_before,
        vix_after,
        viy_after,
        vjx_after,
        vjy_after,
        energy_lost,
        virial,
        impulse_x,
        impulse_y,
    } = b;
    // Filled only by the replay of compact records; not part of the full record.
    assert!(impulse_x.is_empty() && impulse_y.is_empty());
    let c = |v: &Vec<f64>| fs(v.iter().copied());
    json!({
        "first_ordinal": first_ordinal, "stride": stride, "time": c(time),
        "kind": ints(kind.iter().copied()), "i": ints(i.iter().copied()),
        "j": ints(j.iter().copied()), "nx": c(nx), "ny": c(ny),
        "vix_before": c(vix_before), "viy_before": c(viy_before),
        "vjx_before": c(vjx_before), "vjy_before": c(vjy_before),
        "vix_after": c(vix_after), "viy_after": c(viy_after),
        "vjx_after": c(vjx_after), "vjy_after": c(vjy_after),
        "energy_lost": c(energy_lost), "virial": c(virial),
    })
}

/// A compact collision record (`carom_msgs/msg/CompactCollisionBatch`).
pub fn compact_batch(b: &CompactBatch) -> Value {
    let CompactBatch {
        first_ordinal,
        time,
        i,
        j,
        dpx,
        dpy,
        nx,
        ny,
    } = b;
    let c = |v: &Vec<f64>| fs(v.iter().copied());
    json!({
        "first_ordinal": first_ordinal, "stride": 1, "time": c(time),
        "i": ints(i.iter().copied()), "j": ints(j.iter().copied()),
        "dpx": c(dpx), "dpy": c(dpy), "nx": c(nx), "ny": c(ny),
    })
}

/// A `/snapshot` message.
pub fn snapshot(s: &Snapshot) -> Value {
    let Snapshot {
        time,
        box_size,
        boundary: [bx, by],
        species_radius,
        species_mass,
        species,
        positions,
        velocities,
        images,
    } = s;
    json!({
        "time": f(*time), "box_x": f(box_size.x), "box_y": f(box_size.y),
        "boundary_x": bx, "boundary_y": by,
        "species_radius": fs(species_radius.iter().copied()),
        "species_mass": fs(species_mass.iter().copied()),
        "species": ints(species.iter().copied()),
        "x": xs(positions), "y": ys(positions), "vx": xs(velocities), "vy": ys(velocities),
        "image_x": ints(images.iter().map(|m| m[0])), "image_y": ints(images.iter().map(|m| m[1])),
    })
}

/// A `/thermo` record (JSON; the optional keys only when present).
pub fn thermo(t: &Thermo) -> Value {
    let Thermo {
        time,
        kinetic_energy,
        temperature,
        collisions,
        pair_collisions,
        wall_collisions,
        energy_lost,
        virial_sum,
        wall_impulse,
        pressure,
        z,
        collision_rate,
        potential_energy,
        total_energy,
        radius_scale,
        packing_fraction,
        growth,
        growth_z,
        growth_event,
    } = t;
    let mut v = json!({
        "time": f(*time), "kinetic_energy": f(*kinetic_energy),
        "temperature": f(*temperature), "collisions": collisions,
        "pair_collisions": pair_collisions, "wall_collisions": wall_collisions,
        "energy_lost": f(*energy_lost), "virial_sum": f(*virial_sum),
        "wall_impulse": f(*wall_impulse),
    });
    for (k, x) in [
        ("pressure", pressure),
        ("z", z),
        ("collision_rate", collision_rate),
        ("potential_energy", potential_energy),
        ("total_energy", total_energy),
        ("radius_scale", radius_scale),
        ("packing_fraction", packing_fraction),
        ("growth_z", growth_z),
    ] {
        if let Some(x) = x {
            v[k] = f(*x);
        }
    }
    if let Some(g) = growth {
        v["growth"] = serde_json::to_value(g).unwrap();
    }
    if let Some(e) = growth_event {
        v["growth_event"] = serde_json::to_value(e).unwrap();
    }
    v
}

/// A `/checkpoint` message.
pub fn checkpoint(cp: &LogCheckpoint) -> Value {
    let LogCheckpoint {
        driver:
            DriverState {
                run_start_time,
                logged_collisions,
                next_sequence,
            },
        engine,
    } = cp;
    // Alphabetical: the order does not matter, only that every field is named.
    let carom_engine::Checkpoint {
        cell,
        cell_head,
        cell_next,
        cell_prev,
        clock,
        counts,
        epoch,
        event_times,
        floor_origin,
        growth,
        images,
        labels,
        last_collision,
        lists,
        next_reorder,
        next_seq,
        now,
        pair_times,
        params,
        pending,
        positions,
        same_time_collisions,
        scheduled,
        sim_box,
        species,
        species_of,
        stats,
        thermostat,
        times,
        velocities,
    } = engine;
    let carom_engine::EngineParams {
        restitution,
        tc,
        max_events_without_time_advance,
        gravity,
        growth: gp,
        floor,
        neighbours,
    } = params;
    let carom_engine::Stats {
        pair_collisions,
        wall_collisions,
        cell_crossings,
        stale_events,
        virial_sum,
        wall_impulse: [[wxl, wxh], [wyl, wyh]],
        energy_lost,
        floor_work,
    } = stats;
    let (restitution_kind, coefficient) = match *restitution {
        Restitution::Elastic => (0, 1.0),
        Restitution::CentreOfMass(r) => (1, r),
        Restitution::Normal(e) => (2, e),
    };
    // On the cell grid: skin 0 and no list centres.
    let (skin, centres): (f64, &[DVec2]) = match lists {
        None => (0.0, &[]),
        Some(carom_engine::ListsCheckpoint { skin, centres }) => (*skin, centres),
    };
    let [(bx, ex), (by, ey)] = sim_box.boundary.map(|b| boundary(&b));
    let sp = |g: fn(&Species) -> f64| fs(species.iter().map(g));
    let c = |v: &Vec<f64>| fs(v.iter().copied());
    let u = |v: &Vec<u32>| ints(v.iter().copied());
    let col = |v: &[[u32; 3]], k: usize| ints(v.iter().map(|p| p[k]));
    let state = json!({
        "format_version": carom_log::CHECKPOINT_FORMAT_VERSION,
        "run_start_time": f(*run_start_time), "logged_collisions": logged_collisions,
        "next_sequence": ints(next_sequence.iter().copied()),
        "box_x": f(sim_box.size.x), "box_y": f(sim_box.size.y),
        "boundary_x": bx, "boundary_y": by,
        "wall_restitution_x": f(ex), "wall_restitution_y": f(ey),
        "species_count": ints(species.iter().map(|s| s.count as u64)),
        "species_radius": sp(|s| s.radius), "species_mass": sp(|s| s.mass),
        "species": ints(species_of.iter().copied()),
        "restitution_kind": restitution_kind, "restitution": f(coefficient),
        "tc": f(*tc), "max_events_without_time_advance": max_events_without_time_advance,
        "now": f(*now), "epoch": f(*epoch), "clock": f(*clock),
        "same_time_collisions": same_time_collisions,
        "pair_collisions": pair_collisions, "wall_collisions": wall_collisions,
        "cell_crossings": cell_crossings, "stale_events": stale_events,
        "virial_sum": f(*virial_sum), "wall_impulse": fs([*wxl, *wxh, *wyl, *wyh]),
        "energy_lost": f(*energy_lost),
    });
    // In two parts: one `json!` this long exceeds the macro recursion limit.
    let per_disc = json!({
        "x": xs(positions), "y": ys(positions), "vx": xs(velocities), "vy": ys(velocities),
        "t": c(times), "collision_count": u(counts), "last_collision": c(last_collision),
        "event_time": c(event_times), "pair_time": c(pair_times),
        "pending_partner": col(pending, 0), "pending_partner_count": col(pending, 1),
        "pending_kind": col(pending, 2),
        "cell_head": u(cell_head), "cell_next": u(cell_next), "cell_prev": u(cell_prev),
        "cell_column": ints(cell.iter().map(|p| p[0])),
        "cell_row": ints(cell.iter().map(|p| p[1])),
        "scheduled_time": fs(scheduled.iter().map(|s| s.0)),
        "scheduled_seq": ints(scheduled.iter().map(|s| s.1)),
        "scheduled_tag": ints(scheduled.iter().map(|s| s.2)),
        "next_seq": next_seq, "labels": u(labels), "next_reorder": next_reorder,
        "image_x": ints(images.iter().map(|m| m[0])), "image_y": ints(images.iter().map(|m| m[1])),
        "gravity": f(*gravity),
        "growth_rate": f(gp.rate), "growth_target_scale": f(gp.target_scale),
        "growth_kt": f(gp.kt), "growth_rescale_interval": f(gp.rescale_interval),
        "growth_max_reduced_pressure": f(gp.max_reduced_pressure),
        "growth_scale0": f(growth.scale0), "growth_rate_now": f(growth.rate),
        "growth_end": f(growth.end), "growth_next_rescale": f(growth.next_rescale),
        "growth_virial_mark": f(growth.virial_mark), "growth_ended": growth.ended as u8,
        "growth_last_z": f(growth.last_z),
    });
    let (kind, a, b, rng, events, added, origin) = match thermostat {
        None => (0, 0.0, 0.0, 0u128, 0, 0.0, 0.0),
        Some(t) => {
            let (kind, a, b) = match t.thermostat {
                carom_engine::Thermostat::Andersen { kt, rate } => (1, kt, rate),
                carom_engine::Thermostat::Driven { xi2, interval } => (2, xi2, interval),
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
    let thermostat = json!({
        "thermostat_kind": kind, "thermostat_a": f(a), "thermostat_b": f(b),
        "thermostat_rng": ints([(rng >> 64) as u64, rng as u64]),
        "thermostat_events": events, "thermostat_energy_added": f(added),
        "thermostat_origin": f(origin),
        "floor_amplitude": f(floor.map_or(0.0, |fl| fl.amplitude)),
        "floor_omega": f(floor.map_or(0.0, |fl| fl.omega)),
        "floor_origin": f(*floor_origin), "floor_work": f(*floor_work),
        "neighbours": neighbours.name(), "lists_skin": f(skin),
        "lists_centre_x": xs(centres), "lists_centre_y": ys(centres),
    });
    let mut all = state;
    all.as_object_mut()
        .unwrap()
        .extend(per_disc.as_object().unwrap().clone());
    all.as_object_mut()
        .unwrap()
        .extend(thermostat.as_object().unwrap().clone());
    all
}

/// The `/scene` frame carom writes for snapshot `s` (docs/log-format.md, "/scene"):
/// log time `log_time`, one entity, a cylinder per disc, the box as a line loop.
pub fn scene(s: &Snapshot, log_time: u64) -> Value {
    let xyz = |x: f64, y: f64, z: f64| json!({"x": f(x), "y": f(y), "z": f(z)});
    let pose = |x: f64, y: f64| {
        json!({"position": xyz(x, y, 0.0),
               "orientation": {"x": f(0.0), "y": f(0.0), "z": f(0.0), "w": f(1.0)}})
    };
    let rgba = |[r, g, b]: [f64; 3]| json!({"r": f(r), "g": f(g), "b": f(b), "a": f(1.0)});
    let cylinders: Vec<Value> = s
        .positions
        .iter()
        .zip(&s.species)
        .map(|(p, &k)| {
            let d = 2.0 * s.species_radius[k as usize];
            json!({"pose": pose(p.x, p.y), "size": xyz(d, d, d * 0.1),
                   "bottom_scale": f(1.0), "top_scale": f(1.0),
                   "color": rgba(SPECIES_COLORS[k as usize % SPECIES_COLORS.len()])})
        })
        .collect();
    let (lx, ly) = (s.box_size.x, s.box_size.y);
    let corners = [(0.0, 0.0), (lx, 0.0), (lx, ly), (0.0, ly)];
    let sec = u32::try_from(log_time / 1_000_000_000).unwrap();
    json!({"deletions": [], "entities": [{
        "timestamp": {"sec": sec, "nanosec": log_time % 1_000_000_000},
        "frame_id": "box", "id": "discs",
        "lifetime": {"sec": 0, "nanosec": 0}, "frame_locked": false,
        "metadata": [{"key": "time", "value": format!("{:?}", s.time)}],
        "arrows": [], "cubes": [], "spheres": [], "cylinders": cylinders,
        "lines": [{"type": 1, "pose": pose(0.0, 0.0), "thickness": f(2.0),
                   "scale_invariant": true,
                   "points": corners.map(|(x, y)| xyz(x, y, 0.0)),
                   "color": rgba([1.0, 1.0, 1.0]), "colors": [], "indices": []}],
        "triangles": [], "texts": [], "models": [],
    }]})
}

/// The `carom.run` record as the typed reader understood it, key by key (the
/// JSON-valued keys through the reader's own JSON forms).
pub fn run_record(m: &RunMetadata) -> BTreeMap<String, String> {
    let RunMetadata {
        log_format,
        carom_version,
        config,
        seed,
        start_time,
        n_discs,
        stop: _,
        max_time_without_collision,
        log: _,
        resumed_from,
        resumed_at,
        run_facts: _,
    } = m;
    let json = m.to_map();
    let mut r = BTreeMap::new();
    let mut put = |k: &str, v: String| r.insert(k.to_string(), v);
    put("log_format", log_format.clone());
    put("carom_version", carom_version.clone());
    put("config", config.clone());
    put("seed", seed.to_string());
    put("start_time", start_time.clone());
    put("n_discs", n_discs.to_string());
    if let Some(t) = max_time_without_collision {
        put("max_time_without_collision", json!(t).to_string());
    }
    if let Some(p) = resumed_from {
        put("resumed_from", p.clone());
    }
    if let Some(t) = resumed_at {
        put("resumed_at", json!(t).to_string());
    }
    for k in ["stop", "log_options", "run_facts"] {
        if let Some(v) = json.get(k) {
            put(k, v.clone());
        }
    }
    // Its checksum over exactly these fields (log format 2.3).
    carom_log::seal(&mut r);
    r
}

/// The `carom.summary` record as the typed reader understood it, key by key
/// (floats in shortest round-trip form).
pub fn summary_record(s: &SummaryMetadata) -> BTreeMap<String, String> {
    let SummaryMetadata {
        end_time,
        stop_reason,
        error,
        sim_time,
        pair_collisions,
        wall_collisions,
        logged_collisions,
        kinetic_energy,
        energy_lost,
        virial_sum,
        wall_seconds,
        collisions_per_second,
        potential_energy,
    } = s;
    let mut r = BTreeMap::new();
    let mut put = |k: &str, v: String| r.insert(k.to_string(), v);
    put("end_time", end_time.clone());
    put("stop_reason", stop_reason.as_str().to_string());
    if let Some(e) = error {
        put("error", e.clone());
    }
    if let Some(u) = potential_energy {
        put("potential_energy", json!(u).to_string());
    }
    for (k, x) in [
        ("sim_time", sim_time),
        ("kinetic_energy", kinetic_energy),
        ("energy_lost", energy_lost),
        ("virial_sum", virial_sum),
        ("wall_seconds", wall_seconds),
        ("collisions_per_second", collisions_per_second),
    ] {
        put(k, json!(x).to_string());
    }
    for (k, n) in [
        ("pair_collisions", pair_collisions),
        ("wall_collisions", wall_collisions),
        ("logged_collisions", logged_collisions),
    ] {
        put(k, n.to_string());
    }
    carom_log::seal(&mut r);
    r
}

/// Every message of `path` in file order, as `read_carom_log.py --fields` prints
/// them; a `/scene` frame as [`scene`] of the snapshot at its time, taken from
/// `snapshots` (the file itself, or the complete file a cut one was cut from).
pub fn messages(path: &Path, snapshots: &Path) -> Vec<Value> {
    let mut at = BTreeMap::new();
    let mut r = LogReader::open(snapshots).unwrap();
    while let Some(m) = r.next_raw().unwrap() {
        if m.channel == CH_SNAPSHOT {
            at.insert(m.log_time, Snapshot::decode(m.data).unwrap());
        }
    }
    let mut r = LogReader::open(path).unwrap();
    let mut out = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        let (channel, log_time) = (m.channel, m.log_time);
        let mut v = json!({
            "topic": TOPICS[channel], "sequence": m.sequence,
            "log_time": log_time, "publish_time": m.publish_time,
        });
        let data = m.data.to_vec();
        v["fields"] = match channel {
            CH_COLLISIONS if r.compact_collisions() => {
                let mut b = CompactBatch::default();
                b.decode_into(&data).unwrap();
                compact_batch(&b)
            }
            CH_COLLISIONS => {
                let mut b = CollisionBatch::default();
                b.decode_into(&data).unwrap();
                full_batch(&b)
            }
            CH_SNAPSHOT => snapshot(&Snapshot::decode(&data).unwrap()),
            CH_THERMO => thermo(&Thermo::decode(&data).unwrap()),
            CH_CHECKPOINT => checkpoint(&LogCheckpoint::decode(&data).unwrap()),
            CH_SCENE => match at.get(&log_time) {
                Some(s) => scene(s, log_time),
                None => panic!("no /snapshot at the time of the /scene frame {log_time} ns"),
            },
            c => panic!("unknown channel {c}"),
        };
        out.push(v);
    }
    out
}

/// The metadata records of a complete `path` as the typed reader understood them.
pub fn metadata(path: &Path) -> Value {
    let mut r = LogReader::open(path).unwrap();
    while r.next_raw().unwrap().is_some() {}
    let mut m = Map::new();
    m.insert("carom.run".into(), json!(run_record(r.run())));
    if let Some(s) = r.summary().unwrap() {
        m.insert("carom.summary".into(), json!(summary_record(&s)));
    }
    Value::Object(m)
}
