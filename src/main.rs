//! The `carom` command: `run`, `resume`, `analyze`, `info` (see `carom --help`).

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
