//! The wire layout of `/checkpoint`: the schema text every log stores and
//! `docs/log-format.md` shows verbatim, and the format version it describes.

/// `ros2msg` text of the schema `carom_msgs/msg/Checkpoint`.
pub const CHECKPOINT_MSG: &str = "\
# The complete state of a carom run, from which it resumes bit-identically.
# Per-disc arrays have one entry per disc; units are the run's.
uint32 format_version             # 6 (5: without the neighbour search at the end; 4: nor growth; 3: nor gravity and the thermostat; 2: nor the images)
# --- run driver ---
float64 run_start_time            # simulated time at which the run started (time)
uint64 logged_collisions          # collisions written to /collisions so far
uint32[4] next_sequence           # next MCAP sequence number of /collisions, /snapshot, /thermo, /checkpoint
# --- box and species ---
float64 box_x                     # box edge lengths (length)
float64 box_y
uint8 boundary_x                  # 0 = periodic, 1 = hard walls
uint8 boundary_y
float64 wall_restitution_x        # wall restitution (1 when periodic)
float64 wall_restitution_y
uint64[] species_count
float64[] species_radius          # (length)
float64[] species_mass            # (mass)
uint16[] species                  # per disc: species index
# --- dynamics ---
uint8 restitution_kind            # 0 = elastic, 1 = centre-of-mass R, 2 = normal e
float64 restitution               # R or e (1 when elastic)
float64 tc                        # TC-model duration (time)
uint64 max_events_without_time_advance
# --- clock and running totals ---
float64 now                       # current time (time)
float64 epoch                     # time of the internal clock's zero (time)
float64 clock                     # internal clock now (time since epoch); per-disc times below are on it
uint64 same_time_collisions
uint64 pair_collisions
uint64 wall_collisions
uint64 cell_crossings
uint64 stale_events
float64 virial_sum                # sum r_ij . dp_i (length*momentum)
float64[4] wall_impulse           # momentum given to walls x-low, x-high, y-low, y-high
float64 energy_lost               # (energy)
# --- per-disc delayed states ---
float64[] x                       # position at time t on the disc's straight path (length)
float64[] y
float64[] vx                      # velocity (length/time)
float64[] vy
float64[] t                       # time of that position (time); carom writes 0: x, y are the path's origin
uint32[] collision_count
float64[] last_collision          # time of last collision, pair or wall (-inf if none or TC off)
float64[] event_time              # time of the pending event (+inf if none)
float64[] pair_time               # time of the pair candidate where it is the pending event, else +inf (not needed to resume)
uint32[] pending_partner          # the pair candidate's partner (4294967295 = none)
uint32[] pending_partner_count    # the partner's collision_count when the candidate was found
uint32[] pending_kind             # the pending event: kind and details (engine-internal)
# --- neighbour grid (engine-internal) ---
uint32[] cell_head                # first disc per cell (4294967295 = none)
uint32[] cell_next
uint32[] cell_prev
uint32[] cell_column
uint32[] cell_row
# --- events scheduled by the caller (any tag), then, with a thermostat, its next event ---
float64[] scheduled_time
uint64[] scheduled_seq
uint64[] scheduled_tag
uint64 next_seq
# --- internal disc order ---
uint32[] labels                   # per internal slot: the disc's external index (the per-disc arrays above are in internal order)
uint64 next_reorder               # pair-collision count at which the engine next renumbers its discs
# --- periodic images (format_version 3 on) ---
int32[] image_x                   # net periodic edges crossed since the run began, per disc in internal order:
int32[] image_y                   #   the unwrapped position now is x + vx * (clock - t) + image_x * box_x
# --- uniform gravity (format_version 4 on) ---
float64 gravity                   # g along -y (length/time^2; 0: none); then x, y, vx, vy are a path: the
                                  #   position at clock is (x + vx c, y + vy c - g c^2/2), velocity (vx, vy - g c), c = clock - t
# --- thermostat (format_version 4 on; its next event is the last scheduled entry of tag 18446744073709551614, time +inf for none) ---
uint8 thermostat_kind             # 0 = none, 1 = Andersen, 2 = driven
float64 thermostat_a              # Andersen: kT (energy); driven: xi2 (length^2/time^3); 0 for none
float64 thermostat_b              # Andersen: rate per disc (1/time); driven: interval (time); 0 for none
uint64[2] thermostat_rng          # the Pcg64Mcg generator's 128-bit state: high, low 64 bits
uint64 thermostat_events          # thermostat events so far
float64 thermostat_energy_added   # kinetic energy the thermostat added so far (energy)
float64 thermostat_origin         # time the thermostat was set: driving kick k comes at origin + k * interval (time)
# --- growing discs, compression (format_version 5 on; physics.md section 16) ---
float64 growth_rate               # configured relative growth rate (1/time; 0: none); radii are a0 * scale, a0 the species radii
float64 growth_target_scale       # scale at which growth stops
float64 growth_kt                 # kT the velocities are rescaled to (energy)
float64 growth_rescale_interval   # time between rescales (time)
float64 growth_max_reduced_pressure # jamming bound on Z
float64 growth_scale0             # engine-internal: scale at clock 0
float64 growth_rate_now           # engine-internal: rate now (0 once ended)
float64 growth_end                # engine-internal: clock time of the target scale (+inf once ended)
float64 growth_next_rescale       # engine-internal: clock time of the next rescale (+inf once ended)
float64 growth_virial_mark        # engine-internal: virial sum at the last rescale
uint8 growth_ended                # 0 growing (or none), 1 target reached, 2 jammed
float64 growth_last_z             # Z over the last interval between rescales
# --- vibrating floor (format_version 5 on; physics.md section 18) ---
float64 floor_amplitude           # A (length; 0: no floor): the floor is at A (1 - cos(omega t')), t' = time - floor_origin
float64 floor_omega               # angular frequency omega = 2 pi f (1/time; 0: no floor)
float64 floor_origin              # time the floor was set, its phase origin (time)
float64 floor_work                # kinetic energy the floor gave the discs so far (energy)
# --- neighbour search (format_version 6 on; performance.md: neighbour lists) ---
string neighbours                 # the setting: auto, cells or lists (the engine chooses, or is told)
float64 lists_skin                # on neighbour lists: their skin s (length, > 0); 0: on the cell grid
float64[] lists_centre_x          # on lists, per disc in internal order: the list centre, the disc's position
float64[] lists_centre_y          #   (in the box) at its last list update (length); empty on the cell grid
";

/// Format version written in `format_version`.
pub const CHECKPOINT_FORMAT_VERSION: u32 = 6;
