//! Print the JSON Schema of a carom configuration, generated from the Rust types;
//! the shipped copy is made with
//!
//! ```sh
//! cargo run -p carom-config --example write_schema > data/config.schema.json
//! ```

fn main() {
    print!("{}", carom_config::config_schema_json());
}
