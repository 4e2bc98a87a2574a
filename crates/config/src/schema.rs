//! The JSON Schema of a configuration, generated from the types of `model`
//! (`#[derive(JsonSchema)]`): draft 2020-12, one `$defs` entry per section,
//! `additionalProperties: false` wherever the reader refuses unknown fields, the
//! enumerated spellings, the defaults and the simple bounds. Editors read the
//! shipped copy, `data/config.schema.json`, through the examples'
//! `"$schema": "./config.schema.json"`; a test keeps it equal to this one:
//!
//! ```sh
//! cargo run -p carom-config --example write_schema > data/config.schema.json
//! ```
//!
//! The descriptions are the fields' doc comments, reflowed to one line per
//! paragraph; schemars' `format` annotations (`double`, `uint64`) are dropped.

use super::Config;
use schemars::generate::SchemaSettings;
use schemars::transform::RecursiveTransform;
use schemars::Schema;

/// The JSON Schema of [`Config`] (draft 2020-12).
pub fn config_schema() -> Schema {
    SchemaSettings::draft2020_12()
        .with_transform(RecursiveTransform(tidy))
        .into_generator()
        .into_root_schema_for::<Config>()
}

/// [`config_schema`] as the text of `data/config.schema.json`: pretty-printed,
/// with a final newline.
pub fn config_schema_json() -> String {
    let mut text = serde_json::to_string_pretty(&config_schema()).expect("a schema serialises");
    text.push('\n');
    text
}

/// One schema node: its description on one line per paragraph (doc comments
/// are wrapped for the source, not for an editor's tooltip), no `format`.
fn tidy(schema: &mut Schema) {
    schema.remove("format");
    if let Some(serde_json::Value::String(d)) = schema.get_mut("description") {
        *d = d
            .split("\n\n")
            .map(|paragraph| paragraph.replace('\n', " "))
            .collect::<Vec<_>>()
            .join("\n\n");
    }
}
