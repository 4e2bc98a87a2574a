//! # carom-io
//!
//! Configuration, MCAP logging and reading, and analysis input for carom.
