//! `stopscan`: where to stop and scan. The binary parses arguments, shows progress and prints
//! tables; the work, the pipelines included, is in the `stopscan` crate
//! (`stopscan::pipeline`).
//!
//! - `cli`: the command line (clap), with help texts from the library's registries;
//! - one module per command: `explore` (and the main job), `generate`, `corner`, `reproduce`,
//!   `visibility`, `map` (`map import`), `roi`, `bench`, `serve`;
//! - `output`: tables, JSON, the progress spinner and bars; `limits`: the soft size limits.

mod bench;
mod cli;
mod corner;
mod explore;
mod generate;
mod limits;
mod map;
mod merge;
mod output;
mod reproduce;
mod roi;
mod serve;
mod visibility;

use std::io::Write;
use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

fn main() -> ExitCode {
    let command = command();
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
            let _ = writeln!(std::io::stderr(), "error: {}", error_chain(&err));
            ExitCode::from(2)
        }
    }
}

/// The command line, with the help texts that come from the library: each family's strategy
/// registry and the reproduction IDs.
fn command() -> clap::Command {
    use stopscan::strategy::{corner, polygon};
    let polygon_names: Vec<&str> = polygon::REGISTRY.names().collect();
    cli::Cli::command()
        .mut_subcommand("corner", |c| {
            c.mut_subcommand("simulate", |s| {
                s.mut_arg("strategy", |a| {
                    a.long_help(format!(
                        "Strategies, comma-separated, or all:\n{}",
                        corner::registry::help()
                    ))
                })
            })
        })
        .mut_subcommand("explore", |c| {
            c.mut_arg("strategy", |a| {
                a.help(format!(
                    "The strategy: {}; `all` in a sweep (see --help)",
                    polygon_names.join(", ")
                ))
                .long_help(format!(
                    "The strategy, or `all` in a sweep (a folder given to --env):\n{}",
                    polygon::REGISTRY.help()
                ))
            })
        })
        .mut_subcommand("reproduce", |c| {
            c.mut_arg("id", |a| {
                a.help(format!("{}, or all", stopscan::experiment::ids().join(", ")))
            })
        })
}

/// An error and its causes on one line, each cause once ([`stopscan::pipeline::error_message`]).
fn error_chain(err: &anyhow::Error) -> String {
    let err: &(dyn std::error::Error + 'static) = err.as_ref();
    stopscan::pipeline::error_message(err)
}

fn run(args: &cli::Cli) -> anyhow::Result<()> {
    let g = &args.global;
    if g.format == cli::Format::Svg && !matches!(args.command, Some(cli::Command::Visibility(_))) {
        anyhow::bail!("--format svg is only available for `stopscan visibility`");
    }
    check_targets(args)?;
    match &args.command {
        None => explore::main_job(g),
        Some(cli::Command::Explore(a)) => explore::run(a, g),
        Some(cli::Command::Generate(a)) => generate::run(a, g),
        Some(cli::Command::Corner { command }) => corner::run(command, g),
        Some(cli::Command::Visibility(v)) => visibility::run(v, g),
        Some(cli::Command::Map { command: cli::MapCommand::Import(a) }) => map::import(a, g),
        Some(cli::Command::Roi(a)) => roi::run(a, g),
        Some(cli::Command::Reproduce(r)) => reproduce::run(r, g),
        Some(cli::Command::Bench(b)) => bench::run(b, g),
        Some(cli::Command::Serve(a)) => serve::run(a, g),
        Some(cli::Command::Merge(a)) => merge::run(a, g),
        Some(cli::Command::Completions(a)) => completions(a.shell, g),
        Some(cli::Command::Man) => man(g),
    }
}

/// Writes the shell's completions to standard output, or to `--out FILE`.
fn completions(shell: clap_complete::Shell, g: &cli::Global) -> anyhow::Result<()> {
    let mut text = Vec::new();
    clap_complete::generate(shell, &mut command(), "stopscan", &mut text);
    match &g.out {
        Some(path) => Ok(stopscan::io::atomic::write_bytes(path, &text)?),
        None => Ok(std::io::stdout().write_all(&text)?),
    }
}

/// Writes `stopscan.1` to standard output, or every command's page into the directory `--out`.
fn man(g: &cli::Global) -> anyhow::Result<()> {
    let top = command();
    let Some(dir) = &g.out else {
        let mut page = Vec::new();
        clap_mangen::Man::new(top).render(&mut page)?;
        return Ok(std::io::stdout().write_all(&page)?);
    };
    // Every command and subcommand, named as its page is: stopscan-corner-circle.
    let mut pending = vec![(String::from("stopscan"), top)];
    let mut written = 0usize;
    while let Some((name, cmd)) = pending.pop() {
        for sub in cmd.get_subcommands() {
            pending.push((format!("{name}-{}", sub.get_name()), sub.clone()));
        }
        let mut page = Vec::new();
        clap_mangen::Man::new(cmd.name(name.clone()).bin_name(name.replace('-', " ")))
            .render(&mut page)?;
        stopscan::io::atomic::write_bytes(&dir.join(format!("{name}.1")), &page)?;
        written += 1;
    }
    eprintln!("wrote {written} man pages to {}", dir.display());
    Ok(())
}

/// Checks every output before any work (a long sweep must not fail at its end): a file output
/// needs an existing directory and must not be a directory; a directory output is created
/// (one level) now. `roi --resume` checks the outputs its state names once it has read it.
fn check_targets(args: &cli::Cli) -> anyhow::Result<()> {
    use cli::{Command, CornerCommand};
    use std::path::{Path, PathBuf};
    use stopscan::io::atomic;
    let check_file = |p: &Path| -> anyhow::Result<()> { Ok(atomic::check_file(p)?) };
    let ensure_dir = |p: &Path| -> anyhow::Result<()> { Ok(atomic::ensure_dir(p)?) };
    let g = &args.global;
    let out = g.out.as_deref();
    let file = |p: Option<&Path>| p.map_or(Ok(()), check_file);
    let unused = |what: &str| -> anyhow::Result<()> {
        match out {
            Some(_) => anyhow::bail!("{what} writes to -o FILE; --out is not used"),
            None => Ok(()),
        }
    };
    match &args.command {
        None => ensure_dir(out.unwrap_or(Path::new("stopscan-out"))),
        Some(Command::Explore(a)) => {
            if a.env.is_dir() {
                check_file(out.unwrap_or(Path::new("sweep.csv")))
            } else {
                check_file(out.unwrap_or(Path::new("run.json")))?;
                file(a.svg.as_deref())?;
                file(a.trace.as_deref())
            }
        }
        Some(Command::Generate(a)) => check_file(output::geojson_output(a.output.as_deref(), g)?),
        Some(Command::Map { command: cli::MapCommand::Import(a) }) => {
            check_file(output::geojson_output(a.output.as_deref(), g)?)
        }
        Some(Command::Corner { command }) => match command {
            CornerCommand::Demo => ensure_dir(out.unwrap_or(Path::new("stopscan-out"))),
            CornerCommand::Circle { .. } | CornerCommand::Policy(_) => {
                out.map_or(Ok(()), ensure_dir)
            }
            _ => file(out),
        },
        Some(Command::Visibility(_) | Command::Bench(_) | Command::Completions(_)) => file(out),
        Some(Command::Merge(_)) => check_file(out.unwrap_or(Path::new("sweep.csv"))),
        Some(Command::Reproduce(_) | Command::Man) => out.map_or(Ok(()), ensure_dir),
        Some(Command::Serve(a)) => {
            unused("serve")?;
            file(a.journal.as_deref())
        }
        Some(Command::Roi(a)) => {
            file(a.trace.as_deref())?;
            if a.resume.is_some() {
                file(out)?;
                return file(a.svg.as_deref());
            }
            let o = out.map_or_else(|| PathBuf::from("roi-run.json"), Path::to_path_buf);
            check_file(&o)?;
            check_file(&a.svg.clone().unwrap_or_else(|| o.with_extension("svg")))?;
            file(a.state.as_deref())
        }
    }
}
