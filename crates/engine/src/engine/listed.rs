//! The neighbour-list path: each disc tests only the discs of its list.
//!
//! A disc's next event is the earliest of its pair collisions with its list's
//! members (physics.md (2.2)), its wall hit (2.6) and its skin exit, the instant
//! it is s from its list centre (2.7). At a skin exit the disc is renewed: its
//! path is brought back into the box if it left through a periodic edge, it
//! leaves its old partners' lists, its centre moves to where it is, and the
//! 3 × 3 block of the grid of centres (cells at least R wide) gives its new
//! list, which it joins on both sides; then it predicts. Its partners' events
//! stand: their paths did not change. There are no cell crossings. Lists are
//! chosen once at construction (`choose`), never by timing; a list that would
//! overflow sends the run back to cells for good (`leave_lists`). See
//! crates/engine/src/lists.rs and docs/performance.md, "neighbour lists".

use super::body::{Face, Image, Pending};
use super::motion::{Listed, Motion};
use super::predict::{neighbour, test_pair, Found, Scanner};
use super::Engine;
use crate::classes::Grids;
use crate::lists::{
    list_radius, mirror, skin_for, Line, Lists, Neighbours, CAPACITY, LISTS_FROM_PACKING, MAX_DISCS,
};
use crate::{EngineError, EngineParams, NO_DISC};
use carom_core::kinematics::exit_time;
use carom_core::{DVec2, SimBox, Species};

/// Why the engine cannot run `params` on lists for `n` discs of `species` in
/// `sim_box`, with the grids `grids` the cell path would build; `None` if it can.
fn refusal(
    params: &EngineParams,
    sim_box: &SimBox,
    species: &[Species],
    grids: &Grids,
    n: usize,
) -> Option<String> {
    let sigma = grids.largest_sigma();
    let r = list_radius(sigma, skin_for(sigma));
    let narrow = (0..2).find(|&k| {
        sim_box.boundary[k].is_periodic() && crate::cells::CellGrid::shape(sim_box, r, n)[k] < 3
    });
    if params.gravity != 0.0 {
        Some("with gravity (lists need straight flights)".into())
    } else if params.floor.is_some() {
        Some("with a vibrating floor (lists need straight flights)".into())
    } else if params.growth.rate != 0.0 {
        Some("with compression (growing discs would need a growth margin in every list)".into())
    } else if !grids.single() {
        Some("for this mixture: its sizes need a cell grid each".into())
    } else if n > MAX_DISCS {
        Some(format!("for {n} discs (at most {MAX_DISCS})"))
    } else if species.is_empty() || sigma <= 0.0 {
        Some("without discs".into())
    } else {
        narrow.map(|k| {
            format!(
                "in a periodic box {} = {} wide: fewer than three list cells of {r} (σ + 2 skin)",
                ["Lx", "Ly"][k],
                sim_box.size[k]
            )
        })
    }
}

/// Whether an engine for `params` runs on lists: [`Neighbours::Auto`] for equal
/// discs where lists can be used and the packing fraction η = Σ π a²/(L_x L_y)
/// is at least [`LISTS_FROM_PACKING`]; an error where [`Neighbours::Lists`] was
/// asked for and cannot be used.
pub(super) fn choose(
    params: &EngineParams,
    sim_box: &SimBox,
    species: &[Species],
    species_of: &[u16],
    grids: &Grids,
) -> Result<bool, EngineError> {
    let n = species_of.len();
    let refused = refusal(params, sim_box, species, grids, n);
    match params.neighbours {
        Neighbours::Cells => Ok(false),
        Neighbours::Lists => match refused {
            Some(why) => Err(EngineError::ListsRefused(why)),
            None => Ok(true),
        },
        Neighbours::Auto => {
            let area: f64 = species_of
                .iter()
                .map(|&s| std::f64::consts::PI * species[s as usize].radius.powi(2))
                .sum();
            let eta = area / (sim_box.size.x * sim_box.size.y);
            // Equal discs only: in a mixture the lists are sized for the largest
            // contact distance, and small discs crowd them past their capacity.
            let mut radii = species_of.iter().map(|&s| species[s as usize].radius);
            let first = radii.next();
            let equal = radii.all(|r| Some(r) == first);
            Ok(refused.is_none() && equal && eta >= LISTS_FROM_PACKING)
        }
    }
}

impl Engine {
    /// Put the engine on lists with skin `skin` and centres `centres` (internal
    /// order; the discs' positions at their last update): the grid of centres,
    /// every disc in the cell of its centre, and every list from the centres.
    /// `Err` (the engine unchanged) if a list would overflow.
    pub(super) fn enter_lists(&mut self, skin: f64, centres: &[DVec2]) -> Result<(), String> {
        let sigma = self.grids.largest_sigma();
        let mut grids = centre_grid(&self.sim_box, self.species.len(), sigma, skin, self.len())?;
        let mut bodies = self.bodies.clone();
        for i in (0..self.len()).rev() {
            let c = grids.first.coords_of(centres[i]);
            grids.first.insert(&mut bodies, i as u32, c);
        }
        let lists = lists_from(&grids, &bodies, centres, skin, self.sim_box.size)?;
        self.bodies = bodies;
        self.take_lists(grids, lists);
        Ok(())
    }

    /// Put the engine on `lists`, its discs in the grid of centres `grids`.
    pub(super) fn take_lists(&mut self, grids: Grids, lists: Lists) {
        self.grids = grids;
        self.lists = Some(Box::new(lists));
        self.origin_limit = super::clock::origin_limit(self.sim_box.size, self.grids.first.width);
    }

    /// Put a new engine on lists if `choose` says so, centred where the discs are.
    pub(super) fn start_lists(&mut self) -> Result<(), EngineError> {
        let on = choose(
            &self.params,
            &self.sim_box,
            &self.species,
            &self.species_of,
            &self.grids,
        )?;
        if on {
            let centres: Vec<DVec2> = self.bodies.iter().map(|b| b.at(self.clock)).collect();
            let skin = skin_for(self.grids.largest_sigma());
            // Lists too full to start (a crystal squeezed past their capacity) keep
            // the run on cells.
            let _ = self.enter_lists(skin, &centres);
        }
        Ok(())
    }

    /// Disc `i`'s earliest event from now on lists: its pair candidate among its
    /// list's members, its wall hit or its skin exit, whichever comes first.
    #[inline(always)]
    pub(super) fn predict_listed<M: Motion>(&mut self, i: usize) {
        count!(FullPredictions);
        let lists = self.lists.as_ref().expect("on lists");
        let now = self.clock;
        let bi = self.bodies[i];
        let ri = bi.at(now);
        let radius = self.species[bi.species as usize].radius;
        let mut found = Found::NOTHING;
        let law = M::scan(self);
        for (j, code) in lists.lines[i].members() {
            // Seeing j's image at r_j + s L is seeing i at r_i − s L.
            let me = Scanner {
                bi: &bi,
                radius,
                ri: ri - lists.shifts[code as usize],
            };
            let bj = &self.bodies[j as usize];
            test_pair::<M>(
                &me,
                &self.species,
                j,
                bj,
                now,
                law,
                Image::from_code(code),
                &mut found,
            );
        }
        let boundary = M::boundary_event(self, i, ri, bi.v);
        self.file_event::<M>(i, &found, boundary);
    }

    /// Disc `i`'s earliest wall hit or skin exit from now: (time from now, kind,
    /// face). `p` is its position now, `v` its velocity.
    #[inline(always)]
    pub(super) fn boundary_event_listed(
        &self,
        i: usize,
        p: DVec2,
        v: DVec2,
    ) -> (f64, Pending, Face) {
        let lists = self.lists.as_ref().expect("on lists");
        let mut best = exit_time(p - lists.lines[i].centre, v, lists.skin);
        let (mut kind, mut face) = (Pending::Skin, Face::new(0, false));
        for k in 0..2 {
            self.earlier_wall(i, k, p[k], v[k], (&mut best, &mut kind, &mut face));
        }
        (best, kind, face)
    }

    /// Disc `i` left its skin: renew its list (see the module documentation) and
    /// predict; or, if a list would overflow, leave the lists for good.
    #[inline(never)]
    pub(super) fn renew_list(&mut self, i: usize) {
        count!(ListUpdates);
        self.stats.cell_crossings += 1;
        let now = self.clock;
        if self.wrap_into_box(i) {
            self.keep_origin_near([i]);
        }
        let centre = self.bodies[i].at(now);
        let lists = self.lists.as_mut().expect("on lists");
        let old = lists.lines[i];
        for (j, _) in old.members() {
            lists.lines[j as usize].remove(i as u32);
        }
        lists.lines[i] = Line::empty(centre);
        let grid = &mut self.grids.first;
        grid.remove(&mut self.bodies, i as u32);
        let c = grid.coords_of(centre);
        grid.insert(&mut self.bodies, i as u32, c);
        let Some(found) = block_members(&self.grids, &self.bodies, lists, i) else {
            return self.leave_lists();
        };
        for &(j, code) in found.iter() {
            let lines = &mut lists.lines;
            lines[i].insert(j, code);
            if !lines[j as usize].insert(i as u32, mirror(code)) {
                return self.leave_lists();
            }
        }
        self.predict_listed::<Listed>(i);
    }

    /// Bring disc `i`'s path back into the box if it left through periodic edges
    /// since its last renewal: its position moves by whole box lengths, its images
    /// count them, and its counter is bumped (its partners saw it through other
    /// images, so their candidates are obsolete). Whether it moved.
    fn wrap_into_box(&mut self, i: usize) -> bool {
        let p = self.bodies[i].at(self.clock);
        let size = self.sim_box.size;
        let mut moved = false;
        for k in 0..2 {
            let w = (p[k] / size[k]).floor();
            if self.sim_box.boundary[k].is_periodic() && w != 0.0 {
                self.bodies[i].r0[k] -= w * size[k];
                self.images[self.label[i] as usize][k] += w as i32;
                moved = true;
            }
        }
        if moved {
            self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
        }
        moved
    }

    /// Go back to the cell path for the rest of the run: every disc into the box
    /// and into the grids the cell path builds, and every event predicted again.
    /// Deterministic, so a run that overflows a list is still reproducible.
    #[cold]
    #[inline(never)]
    fn leave_lists(&mut self) {
        self.lists = None;
        let now = self.clock;
        let size = self.sim_box.size;
        for i in 0..self.len() {
            self.wrap_into_box(i);
        }
        let internal: Vec<u16> = self.bodies.iter().map(|b| b.species).collect();
        self.grids = Grids::new(&self.sim_box, &self.species, &internal, true);
        for i in (0..self.len()).rev() {
            let grid = self.grids.get_mut(self.grids.class(self.bodies[i].species));
            let c = grid.coords_of(self.bodies[i].at(now));
            grid.insert(&mut self.bodies, i as u32, c);
        }
        self.origin_limit = super::clock::origin_limit(size, self.grids.first.width);
        for i in 0..self.len() {
            self.predict_any(i);
        }
        self.queue.retune(self.bodies.as_slice(), self.clock);
    }
}

/// The empty grid of list centres for `n` discs of `species` species and
/// largest contact distance `sigma` with skin `skin` (cells at least the list
/// radius wide), or why there is none.
pub(super) fn centre_grid(
    sim_box: &SimBox,
    species: usize,
    sigma: f64,
    skin: f64,
    n: usize,
) -> Result<Grids, String> {
    if !(skin.is_finite() && skin > 0.0) {
        return Err(format!("skin {skin} (allowed: finite, > 0)"));
    }
    let width = list_radius(sigma, skin);
    Ok(Grids::one(sim_box, species, sigma / 2.0, width, n))
}

/// Every disc's list from the centres `centres` (internal order), the discs
/// threaded through the grid of centres `grids` by their records `bodies`;
/// `Err` if a list would hold more than [`CAPACITY`].
pub(super) fn lists_from(
    grids: &Grids,
    bodies: &[super::body::Body],
    centres: &[DVec2],
    skin: f64,
    size: DVec2,
) -> Result<Lists, String> {
    let mut lists = Lists::new(centres, grids.largest_sigma(), skin, size);
    for i in 0..centres.len() {
        let full = || format!("the list of disc {i} would hold more than {CAPACITY} discs");
        let found = block_members(grids, bodies, &lists, i).ok_or_else(full)?;
        for &(j, code) in found.iter() {
            lists.lines[i].insert(j, code);
        }
    }
    Ok(lists)
}

/// The discs a list gets, each with the image code through which it is seen
/// (at most [`CAPACITY`]).
struct Members {
    len: usize,
    found: [(u32, u8); CAPACITY],
}

impl Members {
    fn iter(&self) -> impl Iterator<Item = &(u32, u8)> {
        self.found[..self.len].iter()
    }
}

/// The discs whose centres lie within the list radius of disc `i`'s centre, each
/// with the image code through which it is seen: the discs of the 3 × 3 block of
/// cells around `i`'s cell in the grid of centres, tested with d = (c_j − c_i) +
/// shift, which is exactly −d seen from j, so that the lists are symmetric;
/// `None` if there are more than [`CAPACITY`].
fn block_members(
    grids: &Grids,
    bodies: &[super::body::Body],
    lists: &Lists,
    i: usize,
) -> Option<Members> {
    let grid = &grids.first;
    let c = bodies[i].link.coords();
    let ci = lists.lines[i].centre;
    let r2 = lists.radius * lists.radius;
    let mut out = Members {
        len: 0,
        found: [(0, 0); CAPACITY],
    };
    for oy in -1..=1 {
        let Some((cy, sy)) = neighbour(c[1], oy, grid.n[1], grid.periodic[1]) else {
            continue;
        };
        for ox in -1..=1 {
            let Some((cx, sx)) = neighbour(c[0], ox, grid.n[0], grid.periodic[0]) else {
                continue;
            };
            let code = Image::new(sx, sy);
            let shift = lists.shifts[code.code() as usize];
            let mut j = grid.head[grid.index([cx, cy])];
            while j != NO_DISC {
                if j as usize != i {
                    let d = (lists.lines[j as usize].centre - ci) + shift;
                    if d.length_squared() < r2 {
                        if out.len == CAPACITY {
                            return None;
                        }
                        out.found[out.len] = (j, code.code());
                        out.len += 1;
                    }
                }
                j = bodies[j as usize].link.next;
            }
        }
    }
    Some(out)
}
