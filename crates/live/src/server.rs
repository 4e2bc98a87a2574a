//! [`Live`]: the Foxglove WebSocket server of a run and the run's
//! [`Observer`]. It asks for a frame at most [`LiveOptions::frame_rate`] times a
//! wall second, and only while a client listens to `/scene` or `/progress`; a
//! client that subscribes gets a frame at once (at the next look between events).
//! The frame's state goes through the single slot of `handoff` to a sender thread
//! that builds the `foxglove.SceneUpdate` and logs it; the server queues at most
//! [`LiveOptions::backlog`] messages per client and drops the oldest beyond (the
//! SDK's lossy send), so neither a slow client nor a large frame holds up the run.

use std::net::{SocketAddr, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use carom_engine::{Engine, State};
use carom_log::Thermo;
use carom_run::{Observer, Progress};
use foxglove::websocket::{ChannelView, Client, ServerListener};
use foxglove::{Context, WebSocketServer, WebSocketServerHandle};

use crate::channels::Channels;
use crate::colour::Colouring;
use crate::handoff::Handoff;
use crate::scene::scene_update;

/// Where `carom run --live` serves without an address: Foxglove's usual port on
/// this machine only.
pub const DEFAULT_ADDR: &str = "127.0.0.1:8765";
/// Frames per wall second by default.
pub const DEFAULT_FRAME_RATE: f64 = 10.0;

/// What can go wrong starting a live server.
#[derive(Debug, thiserror::Error)]
pub enum LiveError {
    /// The address is not one.
    #[error("live address {addr:?}: {problem}; give HOST:PORT (such as {DEFAULT_ADDR}) or a port (0: any free port)")]
    Address {
        /// The address as given.
        addr: String,
        /// What was wrong with it.
        problem: String,
    },
    /// The server could not listen there.
    #[error("live address {addr}: cannot serve there: {problem}; give another address or port (0: any free port)")]
    Serve {
        /// The address.
        addr: SocketAddr,
        /// Why (the SDK's words).
        problem: String,
    },
    /// A channel could not be made.
    #[error("live channel {topic}: {problem}")]
    Channel {
        /// Its topic.
        topic: String,
        /// The SDK's words.
        problem: String,
    },
    /// A frame rate that is not a positive number.
    #[error("live frame rate {0}: give a number of frames per second > 0 (such as {DEFAULT_FRAME_RATE})")]
    Rate(f64),
}

/// How a live server serves.
#[derive(Debug, Clone, PartialEq)]
pub struct LiveOptions {
    /// Where to listen (port 0: any free port; [`Live::addr`] tells which).
    pub addr: SocketAddr,
    /// The most frames per second of wall time (default [`DEFAULT_FRAME_RATE`]).
    pub frame_rate: f64,
    /// What colours the discs.
    pub colouring: Colouring,
    /// Messages queued per client before the oldest are dropped (a few frames:
    /// a frame of N discs is about 100 N bytes).
    pub backlog: usize,
}

impl LiveOptions {
    /// Options to serve at `addr` (`HOST:PORT`, or a port alone on 127.0.0.1),
    /// with the defaults otherwise.
    pub fn at(addr: &str) -> Result<Self, LiveError> {
        let bad = |problem: String| LiveError::Address {
            addr: addr.into(),
            problem,
        };
        let addr = match addr.parse::<u16>() {
            Ok(port) => SocketAddr::from(([127, 0, 0, 1], port)),
            Err(_) => addr
                .to_socket_addrs()
                .map_err(|e| bad(e.to_string()))?
                .next()
                .ok_or_else(|| bad("no such address".into()))?,
        };
        Ok(LiveOptions {
            addr,
            frame_rate: DEFAULT_FRAME_RATE,
            colouring: Colouring::Species,
            backlog: 16,
        })
    }
}

impl Default for LiveOptions {
    fn default() -> Self {
        LiveOptions::at(DEFAULT_ADDR).expect("the default address is one")
    }
}

/// Raises `wanted` when a client subscribes: it gets a frame at once.
struct Subscribed {
    wanted: Arc<AtomicBool>,
}

impl ServerListener for Subscribed {
    fn on_subscribe(&self, _client: Client, _channel: ChannelView) {
        self.wanted.store(true, Ordering::Relaxed);
    }
}

/// A live server of a run: hand it to the run as its `Control::observer`.
pub struct Live {
    /// The channels' and the server's context (they hold it weakly).
    _context: Arc<Context>,
    server: Option<WebSocketServerHandle>,
    channels: Arc<Channels>,
    handoff: Handoff,
    addr: SocketAddr,
    interval: Duration,
    last_frame: Option<Instant>,
    /// A client subscribed since the last frame.
    wanted: Arc<AtomicBool>,
}

impl Live {
    /// Start serving; clients may connect at once, and at any time after.
    pub fn start(options: &LiveOptions) -> Result<Live, LiveError> {
        if !(options.frame_rate > 0.0 && options.frame_rate.is_finite()) {
            return Err(LiveError::Rate(options.frame_rate));
        }
        let ctx = Context::new();
        let channels = Arc::new(Channels::new(&ctx)?);
        let wanted = Arc::new(AtomicBool::new(false));
        let server = WebSocketServer::new()
            .name(format!("carom {}", env!("CARGO_PKG_VERSION")))
            .context(&ctx)
            .bind(options.addr.ip().to_string(), options.addr.port())
            .message_backlog_size(options.backlog.max(1))
            .listener(Arc::new(Subscribed {
                wanted: Arc::clone(&wanted),
            }))
            .start_blocking()
            .map_err(|e| LiveError::Serve {
                addr: options.addr,
                problem: e.to_string(),
            })?;
        let addr = SocketAddr::new(options.addr.ip(), server.port());
        let (theirs, colouring) = (Arc::clone(&channels), options.colouring);
        let handoff = Handoff::new(move |state: &State| {
            if theirs.scene_wanted() {
                theirs.scene(&scene_update(state, colouring), state.time);
            }
        });
        Ok(Live {
            _context: ctx,
            server: Some(server),
            channels,
            handoff,
            addr,
            interval: Duration::from_secs_f64(1.0 / options.frame_rate),
            last_frame: None,
            wanted,
        })
    }

    /// The address served (with the port the system chose for port 0).
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The address as a client opens it: `ws://HOST:PORT`.
    pub fn url(&self) -> String {
        format!("ws://{}", self.addr)
    }

    /// Send the last frame and stop serving: clients still connected are
    /// disconnected. (Dropping a `Live` does the same.)
    pub fn finish(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        self.handoff.close();
        if let Some(server) = self.server.take() {
            server.stop().wait_blocking();
        }
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        self.stop();
    }
}

impl Observer for Live {
    fn frame_due(&mut self) -> bool {
        if !self.channels.frames_wanted() {
            return false;
        }
        self.wanted.load(Ordering::Relaxed)
            || self.last_frame.is_none_or(|t| t.elapsed() >= self.interval)
    }

    fn frame(&mut self, engine: &Engine, progress: &Progress) {
        self.last_frame = Some(Instant::now());
        self.wanted.store(false, Ordering::Relaxed);
        if self.channels.scene_wanted() {
            self.handoff.give(|spare| match spare {
                Some(mut s) => {
                    engine.state_into(&mut s);
                    s
                }
                None => engine.state(),
            });
        }
        self.channels.progress(progress);
    }

    fn thermo(&mut self, record: &Thermo) {
        self.channels.thermo(record);
    }
}

impl std::fmt::Debug for Live {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Live")
            .field("addr", &self.addr)
            .field("interval", &self.interval)
            .finish()
    }
}
