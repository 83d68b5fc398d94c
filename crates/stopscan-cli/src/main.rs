//! `stopscan`: where to stop and scan. The binary parses arguments, calls the library and
//! writes files and tables; all the work is in the `stopscan` crate.

mod bench;
mod cli;
mod corner;
mod output;

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            // A closed pipe (`stopscan ... | head`) is not a failure.
            if err.chain().any(|e| {
                e.downcast_ref::<std::io::Error>()
                    .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
            }) {
                return ExitCode::SUCCESS;
            }
            let _ = writeln!(std::io::stderr(), "error: {err:#}");
            ExitCode::from(2)
        }
    }
}

fn run(args: &cli::Cli) -> anyhow::Result<()> {
    let g = &args.global;
    match &args.command {
        None => corner::demo(g),
        Some(cli::Command::Corner { command }) => corner::run(command, g),
        Some(cli::Command::Reproduce(r)) => corner::reproduce(r, g),
        Some(cli::Command::Bench(b)) => bench::run(b, g),
    }
}
