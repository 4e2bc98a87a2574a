//! The neighbour search in `/checkpoint` (format_version 6 on): the user's
//! setting `neighbours` (auto, cells or lists, by its name) and, when the run is
//! on neighbour lists, their skin and each disc's list centre in internal order.
//! The lists themselves are a function of the centres, which the engine rebuilds
//! on resume; a run on the cell grid stores skin 0 and no centres, and so reads
//! back with `lists` `None`, as every checkpoint before format 6 does.
//!
//! The reader refuses what no engine writes: an unknown setting, centres with
//! skin 0, a skin that is negative or not finite, a number of centres other than
//! the number of discs, and a centre that is not finite.

use crate::format::cdr::{CdrError, CdrReader, CdrWriter};
use carom_core::DVec2;
use carom_engine::{ListsCheckpoint, Neighbours};

/// Append the neighbour search: the setting, then the lists (skin 0 and no
/// centres for none).
pub(super) fn encode_neighbours(
    w: &mut CdrWriter,
    neighbours: Neighbours,
    lists: Option<&ListsCheckpoint>,
) {
    w.string(neighbours.name());
    let (skin, centres) = lists.map_or((0.0, &[][..]), |l| (l.skin, &l.centres[..]));
    w.put(skin);
    w.seq_iter(centres.iter().map(|c| c.x));
    w.seq_iter(centres.iter().map(|c| c.y));
}

/// The setting named `name` ([`Neighbours::name`]), or what is wrong with it
/// (for every record that stores the setting by name).
pub(crate) fn neighbours_named(name: &str) -> Result<Neighbours, String> {
    Neighbours::from_name(name).ok_or_else(|| {
        let allowed =
            [Neighbours::Auto, Neighbours::Cells, Neighbours::Lists].map(Neighbours::name);
        format!("unknown setting {name:?} (allowed: {})", allowed.join(", "))
    })
}

fn invalid(field: &'static str, problem: String) -> CdrError {
    CdrError::Invalid { field, problem }
}

/// Read what [`encode_neighbours`] wrote, for a checkpoint of `discs` discs.
pub(super) fn decode_neighbours(
    r: &mut CdrReader,
    discs: usize,
) -> Result<(Neighbours, Option<ListsCheckpoint>), CdrError> {
    let name = r.string("neighbours")?;
    let neighbours = neighbours_named(&name).map_err(|e| invalid("neighbours", e))?;
    let skin: f64 = r.get("lists_skin")?;
    let x: Vec<f64> = r.seq("lists_centre_x")?;
    let y: Vec<f64> = r.seq("lists_centre_y")?;
    if y.len() != x.len() {
        return Err(invalid(
            "lists_centre_y",
            format!("{} entries, but `lists_centre_x` has {}", y.len(), x.len()),
        ));
    }
    if skin == 0.0 {
        if !x.is_empty() {
            return Err(invalid(
                "lists_centre_x",
                format!(
                    "{} list centres, but `lists_skin` is 0: on the cell grid there are none",
                    x.len()
                ),
            ));
        }
        return Ok((neighbours, None));
    }
    if !(skin.is_finite() && skin > 0.0) {
        return Err(invalid(
            "lists_skin",
            format!("skin {skin} (allowed: 0 on the cell grid, finite and > 0 on lists)"),
        ));
    }
    if x.len() != discs {
        return Err(invalid(
            "lists_centre_x",
            format!(
                "{} list centres for {discs} discs (one per disc on lists)",
                x.len()
            ),
        ));
    }
    for (field, values) in [("lists_centre_x", &x), ("lists_centre_y", &y)] {
        if let Some(k) = values.iter().position(|c| !c.is_finite()) {
            return Err(invalid(
                field,
                format!(
                    "the list centre of slot {k} is {} (allowed: finite)",
                    values[k]
                ),
            ));
        }
    }
    let centres = x
        .into_iter()
        .zip(y)
        .map(|(a, b)| DVec2::new(a, b))
        .collect();
    Ok((neighbours, Some(ListsCheckpoint { skin, centres })))
}
