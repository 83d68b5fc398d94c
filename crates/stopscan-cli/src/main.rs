//! `stopscan`: where to stop and scan. The binary parses arguments, calls the library and
//! writes files and tables; all the work is in the `stopscan` crate.

mod bench;
mod cli;
mod corner;
mod explore;
mod output;
mod roi;
mod visibility;

use std::io::Write;
use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

fn main() -> ExitCode {
    // The strategy registry writes the help of `--strategy`.
    let command = cli::Cli::command().mut_subcommand("corner", |c| {
        c.mut_subcommand("simulate", |s| {
            s.mut_arg("strategy", |a| {
                a.long_help(format!(
                    "Strategies, comma-separated, or all:\n{}",
                    stopscan::strategy::corner::registry::help()
                ))
            })
        })
    });
    let args = match cli::Cli::from_arg_matches(&command.get_matches()) {
        Ok(a) => a,
        Err(e) => e.exit(),
    };
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
            // Each cause once: library errors often repeat their source in their own message.
            let mut msg = err.to_string();
            for cause in err.chain().skip(1) {
                let c = cause.to_string();
                if !msg.contains(&c) {
                    msg = format!("{msg}: {c}");
                }
            }
            let _ = writeln!(std::io::stderr(), "error: {msg}");
            ExitCode::from(2)
        }
    }
}

fn run(args: &cli::Cli) -> anyhow::Result<()> {
    let g = &args.global;
    if g.format == cli::Format::Svg && !matches!(args.command, Some(cli::Command::Visibility(_))) {
        anyhow::bail!("--format svg is only available for `stopscan visibility`");
    }
    match &args.command {
        None => explore::main_job(g),
        Some(cli::Command::Explore(a)) => explore::run(a, g),
        Some(cli::Command::Generate(a)) => explore::generate(a, g),
        Some(cli::Command::Corner { command }) => corner::run(command, g),
        Some(cli::Command::Visibility(v)) => visibility::run(v, g),
        Some(cli::Command::Map { command: cli::MapCommand::Import(a) }) => visibility::import(a, g),
        Some(cli::Command::Roi(a)) => roi::run(a, g),
        Some(cli::Command::Reproduce(r)) => corner::reproduce(r, g),
        Some(cli::Command::Bench(b)) => bench::run(b, g),
    }
}
