//! `stopscan merge`: the CSV files of a sharded sweep (`explore --env DIR --shard I/N`) joined
//! into the one the whole sweep writes: the same columns, rows in file-name order and, within
//! a file, in the strategy registry's order.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use stopscan::io::atomic;
use stopscan::strategy::polygon::REGISTRY;

use crate::cli::{Global, MergeArgs};

/// One row and where it came from.
struct Row {
    environment: String,
    strategy: usize,
    record: csv::StringRecord,
}

pub(crate) fn run(a: &MergeArgs, g: &Global) -> anyhow::Result<()> {
    let order: Vec<&str> = REGISTRY.names().collect();
    let mut header: Option<(csv::StringRecord, &Path)> = None;
    let mut rows: Vec<Row> = Vec::new();
    // (environment, strategy) → the part and line it was read from.
    let mut seen: HashMap<(String, usize), (PathBuf, u64)> = HashMap::new();
    for part in &a.parts {
        let file =
            std::fs::File::open(part).with_context(|| format!("cannot read {}", part.display()))?;
        let mut reader = csv::Reader::from_reader(std::io::BufReader::new(file));
        let columns =
            reader.headers().with_context(|| format!("{}: not CSV", part.display()))?.clone();
        if columns.is_empty() {
            // A shard that had no files wrote nothing.
            continue;
        }
        match &header {
            None => header = Some((columns.clone(), part)),
            Some((first, from)) if *first != columns => bail!(
                "{}: its columns differ from {}'s: not parts of one sweep (first {:?}, then {:?})",
                part.display(),
                from.display(),
                first.iter().collect::<Vec<_>>(),
                columns.iter().collect::<Vec<_>>()
            ),
            Some(_) => {}
        }
        let column = |name: &str| {
            columns.iter().position(|c| c == name).with_context(|| {
                format!(
                    "{}: no {name} column: not a sweep's CSV (explore --env DIR)",
                    part.display()
                )
            })
        };
        let (env_at, strategy_at) = (column("environment")?, column("strategy")?);
        for record in reader.records() {
            let record = record.with_context(|| format!("{}: a malformed row", part.display()))?;
            let line = record.position().map_or(0, csv::Position::line);
            let environment = record[env_at].to_string();
            let name = &record[strategy_at];
            let Some(strategy) = order.iter().position(|s| *s == name) else {
                bail!("{}: line {line}: unknown strategy {name:?}", part.display());
            };
            if let Some((other, other_line)) =
                seen.insert((environment.clone(), strategy), (part.clone(), line))
            {
                bail!(
                    "{}: line {line}: {environment} with {name} is also in {}, line {other_line}: a part given twice, or parts of different sweeps",
                    part.display(),
                    other.display()
                );
            }
            rows.push(Row { environment, strategy, record });
        }
    }
    // The whole sweep's order: files by name, then strategies in registry order.
    rows.sort_by(|a, b| (&a.environment, a.strategy).cmp(&(&b.environment, b.strategy)));
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("sweep.csv"));
    let files = rows
        .iter()
        .map(|r| r.environment.as_str())
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    atomic::write(&out, |w| {
        let mut csv = csv::Writer::from_writer(w);
        if let Some((columns, _)) = &header {
            csv.write_record(columns)?;
        }
        for r in &rows {
            csv.write_record(&r.record)?;
        }
        csv.flush()
    })?;
    println!(
        "merged {} rows ({files} environments) from {} parts into {}",
        rows.len(),
        a.parts.len(),
        out.display()
    );
    Ok(())
}
