//! The command line, declared with clap.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// Where a robot should stop and scan when every scan costs time.
///
/// With no command, runs the main job: the paper's exploration of the built-in office floor,
/// writing `stopscan-out/run.json`, `stopscan-out/scene.svg` and `stopscan-out/report.html`.
#[derive(Debug, Parser)]
#[command(name = "stopscan", version, about, long_about = None)]
pub(crate) struct Cli {
    #[command(flatten)]
    pub(crate) global: Global,
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
}

/// Flags every command accepts.
#[derive(Debug, Args)]
pub(crate) struct Global {
    /// Output format.
    #[arg(long, value_enum, global = true, default_value_t = Format::Table)]
    pub(crate) format: Format,
    /// Seed for everything random (Monte Carlo, random restarts, random benchmark inputs).
    #[arg(long, global = true, default_value_t = 0)]
    pub(crate) seed: u64,
    /// Where results go: the JSON result file (its directory must exist), or a directory for
    /// commands that draw pictures (the main job, `corner demo`, `corner circle`, `corner
    /// policy`, `reproduce`), created if missing (its parent must exist).
    #[arg(long, global = true)]
    pub(crate) out: Option<PathBuf>,
    /// Lift the soft size limits (Monte Carlo samples, UNIREC stops, ROI robots, cells, search
    /// box and camera frames, bench sizes, generated sizes); see the README's "Limits".
    #[arg(long, global = true)]
    pub(crate) allow_large: bool,
}

/// A clap parser for counts: a whole number of at least `min`. Negative numbers reach it (the
/// flags allow them) and get this message instead of clap's "unexpected argument"; a whole
/// number in scientific notation (`1e6`) is accepted.
pub(crate) fn count_at_least(min: usize) -> impl Fn(&str) -> Result<usize, String> + Clone {
    move |s: &str| {
        let t = s.trim();
        let v = t.parse::<usize>().ok().or_else(|| {
            t.parse::<f64>()
                .ok()
                .filter(|x| x.fract() == 0.0 && *x >= 0.0 && *x <= 9.007_199_254_740_992e15)
                .map(|x| x as usize)
        });
        match v {
            Some(n) if n >= min => Ok(n),
            _ => Err(format!("expected a whole number of at least {min}")),
        }
    }
}

/// Parses a point `X,Y` (two finite numbers).
pub(crate) fn parse_point(s: &str) -> anyhow::Result<stopscan::kernel::Point> {
    let v: Vec<&str> = s.split(',').map(str::trim).collect();
    if let [x, y] = v.as_slice()
        && let (Ok(x), Ok(y)) = (x.parse::<f64>(), y.parse::<f64>())
        && x.is_finite()
        && y.is_finite()
    {
        return Ok([x, y]);
    }
    anyhow::bail!("expected X,Y with two finite numbers, got {s:?}")
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// Aligned text for people.
    Table,
    /// One JSON object.
    Json,
    /// An SVG picture (`visibility` only).
    Svg,
}

#[derive(Debug, Subcommand)]
pub(crate) enum Command {
    /// Looking around a corner: circle strategy, competitive ratios, MDP policies.
    Corner {
        #[command(subcommand)]
        command: CornerCommand,
    },
    /// The visibility region of a point in an environment, with labelled boundary pieces.
    Visibility(VisibilityArgs),
    /// Explore an unknown environment with an online strategy: run record and scene.
    Explore(ExploreArgs),
    /// Write a generated instance (spiral, star, comb, office, forest) as GeoJSON.
    Generate(GenerateArgs),
    /// Environment files: convert ROS maps, .pol, WKT and the benchmark format to GeoJSON.
    Map {
        #[command(subcommand)]
        command: MapCommand,
    },
    /// A team of robots explores an unknown region of interest (Algorithm 1 of the ROI paper),
    /// static or drifting; writes a run record and an SVG replay.
    Roi(RoiArgs),
    /// Reproduce a paper table or figure: the paper's value beside ours.
    Reproduce(ReproduceArgs),
    /// Throughput figures as JSON.
    Bench(BenchArgs),
    /// Drive a real robot: speak protocol stopscan/1 (line-delimited JSON, docs/protocol.md) on
    /// standard input and output, or on TCP with --listen; resumable from a journal.
    Serve(ServeArgs),
    /// Join the CSV files of a sharded sweep (`explore --env DIR --shard I/N`) into one, in the
    /// order the whole sweep writes (to --out, default sweep.csv).
    Merge(MergeArgs),
    /// Shell completions (bash, zsh, fish, elvish, powershell) from the same definitions as
    /// --help, on standard output or to --out FILE: `stopscan completions bash >
    /// ~/.local/share/bash-completion/completions/stopscan`.
    Completions(CompletionsArgs),
    /// Man pages from the same definitions as --help: stopscan.1 on standard output, or with
    /// --out DIR one page per command (stopscan.1, stopscan-explore.1, stopscan-corner-circle.1,
    /// ...): `stopscan man --out man && man -l man/stopscan-explore.1`.
    Man,
}

#[derive(Debug, Args)]
pub(crate) struct MergeArgs {
    /// The parts' CSV files, in any order.
    #[arg(required = true)]
    pub(crate) parts: Vec<PathBuf>,
}

#[derive(Debug, Args)]
pub(crate) struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    pub(crate) shell: clap_complete::Shell,
}

#[derive(Debug, Args)]
pub(crate) struct ServeArgs {
    /// Listen on this TCP address (`127.0.0.1:7878`; port 0 picks a free one, printed on
    /// standard error) instead of standard input and output. One session per server; a robot
    /// may reconnect and go on; the server exits once the session is done and the robot
    /// has closed the connection.
    #[arg(long)]
    pub(crate) listen: Option<String>,
    /// Append every step to this new journal file, written before each reply.
    #[arg(long, conflicts_with = "resume")]
    pub(crate) journal: Option<PathBuf>,
    /// Go on from this journal after a crash: its steps are replayed (each reply checked),
    /// then new steps are appended to it.
    #[arg(long)]
    pub(crate) resume: Option<PathBuf>,
    /// Also sync each journal line to the disk before replying (safe against a power cut;
    /// about a millisecond per step).
    #[arg(long)]
    pub(crate) fsync: bool,
    /// The most scans a session may take; then it is done with reason "limit".
    #[arg(long, default_value_t = stopscan::sim::lidar::MAX_SCANS, value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_scans: u64,
    /// When the session ends, write it here as an MCAP recording for Foxglove: every pose
    /// the robot reported and its localisation (transforms), every laser scan, every goal,
    /// and every step in words. With --resume, the recording holds the whole session (after
    /// a crash, `serve --resume JOURNAL --mcap FILE < /dev/null` writes it).
    #[arg(long)]
    pub(crate) mcap: Option<PathBuf>,
}

#[derive(Debug, Subcommand)]
pub(crate) enum CornerCommand {
    /// The corner demo: the circle strategy at a few distances and the four corner-paper
    /// strategies on one belief; writes a chart.
    Demo,
    /// The 2-competitive circle strategy at distance D: ratio c(D), steps, scan points.
    Circle {
        /// Distance to the corner in units of v·τ (scan cost 1, speed 1).
        #[arg(long, allow_negative_numbers = true)]
        distance: f64,
    },
    /// Distances at which the circle strategy needs one more scan (the circle paper's Table 1).
    Thresholds {
        /// How many thresholds (0 to count−1 intermediate scans), at most 60.
        #[arg(long, default_value_t = 6, allow_negative_numbers = true, value_parser = count_at_least(1))]
        count: usize,
    },
    /// Globally optimal scan points for at most K intermediate scans, anywhere in the plane.
    Optimal {
        /// Distance to the corner in units of v·τ.
        #[arg(long, allow_negative_numbers = true)]
        distance: f64,
        /// The most intermediate scans (at most 12; the search takes seconds per scan).
        #[arg(long, allow_negative_numbers = true, value_parser = count_at_least(0))]
        scans: usize,
    },
    /// Theorem 1: run the circle recursion with a ratio below 2 and watch it collapse.
    Collapse {
        /// The ratio c to try.
        #[arg(long, allow_negative_numbers = true)]
        ratio: f64,
        /// Distance (default 10/(2 − c), far beyond the proof's 1/(2 − c)).
        #[arg(long, allow_negative_numbers = true)]
        distance: Option<f64>,
    },
    /// The exact worst-case competitive ratio of a strategy at step δ = τv/D.
    Ratio(RatioArgs),
    /// The optimal MDP policy for a belief, its stops, expected time and image.
    Policy(PolicyArgs),
    /// Run strategies against edges drawn from a true distribution.
    Simulate(SimulateArgs),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum RatioStrategy {
    /// Scans at δ, 2δ, 3δ, … (corner paper, Table I).
    Unirec,
    /// Scans at exponentially spaced stops (corner paper, Table I).
    Exprec,
    /// The circle paper's strategy at distance d = 1/δ.
    Circle,
    /// The stops given with --stops-deg.
    Stops,
}

#[derive(Debug, Args)]
pub(crate) struct RatioArgs {
    /// The strategy.
    #[arg(long, value_enum)]
    pub(crate) strategy: RatioStrategy,
    /// δ = τ·v/D: the angle (radians) travelled on the circle in one scan time.
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) delta: f64,
    /// Stop angles in degrees for --strategy stops, comma-separated, increasing.
    #[arg(long, allow_negative_numbers = true, value_delimiter = ',')]
    pub(crate) stops_deg: Vec<f64>,
    #[command(flatten)]
    pub(crate) readings: Readings,
}

/// The two readings of the corner paper's stop lists.
#[derive(Debug, Args, Clone, Copy)]
pub(crate) struct Readings {
    /// How a last step past the corner is charged.
    #[arg(long, value_enum, default_value_t = LastStepArg::Capped)]
    pub(crate) last_step: LastStepArg,
    /// Which EXPREC: Table I (δ, 2δ, 4δ, …) or the appendix (δ, 3δ, 7δ, …).
    #[arg(long, value_enum, default_value_t = ExprecArg::TableI)]
    pub(crate) exprec: ExprecArg,
    /// Route between stops (the circle strategy always drives chords).
    #[arg(long, value_enum, default_value_t = RouteArg::Arc)]
    pub(crate) route: RouteArg,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum LastStepArg {
    /// Stop at the corner; charge what was driven.
    Capped,
    /// Charge the nominal angle, as the paper's formula does (arc route only).
    Nominal,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ExprecArg {
    /// Stops at δ, 2δ, 4δ, 8δ, …
    TableI,
    /// Stops at δ, 3δ, 7δ, 15δ, …
    Appendix,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum RouteArg {
    /// Along the circle.
    Arc,
    /// Along straight chords.
    Chord,
}

/// The robot and its cost model (the corner paper's experiment by default).
#[derive(Debug, Args, Clone, Copy)]
pub(crate) struct SetupArgs {
    /// Distance to the corner, metres.
    #[arg(long, allow_negative_numbers = true, default_value_t = 10.0)]
    pub(crate) distance: f64,
    /// Seconds per scan (τ).
    #[arg(long, allow_negative_numbers = true, default_value_t = 2.0)]
    pub(crate) scan_time: f64,
    /// Seconds per move between stops.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0)]
    pub(crate) move_time: f64,
    /// Metres per second (v).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.5)]
    pub(crate) speed: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum MemoryArg {
    /// MDP1: states s_i, s'_i.
    None,
    /// MDP2: states s_ij (last scan at stop j).
    Last,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ReadingArg {
    /// Bayes-correct P(θ ≤ iδ | θ > jδ).
    Conditional,
    /// The printed P(jδ ≤ θ ≤ iδ).
    Literal,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum SolverArg {
    /// Exact backward induction (acyclic once the self-loop is removed).
    Backward,
    /// General sparse policy iteration on the full MDP.
    General,
}

#[derive(Debug, Args)]
pub(crate) struct PolicyArgs {
    /// Belief in degrees: uniform:0,180 | normal:60,5 | mix:0.5*normal:30,3+0.5*normal:90,3 |
    /// histogram:FILE | observed:FILE[,BUCKET_DEG].
    #[arg(long)]
    pub(crate) belief: String,
    /// MDP1 (none) or MDP2 (last).
    #[arg(long, value_enum, default_value_t = MemoryArg::Last)]
    pub(crate) memory: MemoryArg,
    /// The distribution the expected time is computed under (defaults to the belief).
    #[arg(long)]
    pub(crate) truth: Option<String>,
    /// Stop spacing on the circle, degrees.
    #[arg(long, allow_negative_numbers = true, default_value_t = 5.0)]
    pub(crate) step_deg: f64,
    /// How the transition probabilities are read.
    #[arg(long, value_enum, default_value_t = ReadingArg::Conditional)]
    pub(crate) reading: ReadingArg,
    /// Which solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Backward)]
    pub(crate) solver: SolverArg,
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
}

#[derive(Debug, Args)]
pub(crate) struct SimulateArgs {
    /// Strategies from the registry, comma-separated, or all (see --help).
    #[arg(long, value_delimiter = ',', default_value = "all")]
    pub(crate) strategy: Vec<String>,
    /// What the robot believes (degrees, as for `corner policy`).
    #[arg(long, default_value = "uniform:0,180")]
    pub(crate) belief: String,
    /// What the world draws θ from (defaults to the belief).
    #[arg(long)]
    pub(crate) truth: Option<String>,
    /// Monte Carlo samples per strategy (soft limit 10^7).
    #[arg(long, default_value_t = 1000, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) samples: usize,
    /// MDP stop spacing, degrees.
    #[arg(long, allow_negative_numbers = true, default_value_t = 5.0)]
    pub(crate) step_deg: f64,
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    #[command(flatten)]
    pub(crate) readings: Readings,
}

#[derive(Debug, Args)]
pub(crate) struct ExploreArgs {
    /// The environment (GeoJSON with a "start" property, WKT, .pol, ROS map, benchmark format),
    /// or a folder of them: a sweep in parallel that writes CSV (to --out, default sweep.csv).
    #[arg(long)]
    pub(crate) env: PathBuf,
    /// With --env DIR: run only part I of N of the sweep (every N-th file from the I-th, files
    /// sorted by name), so that N machines or jobs share it; `stopscan merge` joins the parts'
    /// CSV files into the whole sweep's.
    #[arg(long, value_name = "I/N", value_parser = stopscan::pipeline::sweep::Shard::parse)]
    pub(crate) shard: Option<stopscan::pipeline::sweep::Shard>,
    /// The strategy (the help lists the polygon registry: `main::command`).
    #[arg(long, default_value = "depth_first")]
    pub(crate) strategy: String,
    /// The start "X,Y" (default: the file's start, its first query point, or a point inside the
    /// first triangle of its triangulation).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) start: Option<String>,
    /// Seconds per scan.
    #[arg(long, allow_negative_numbers = true, default_value_t = 1.0)]
    pub(crate) scan_time: f64,
    /// Seconds per move.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0)]
    pub(crate) move_time: f64,
    /// Metres per second.
    #[arg(long, allow_negative_numbers = true, default_value_t = 1.0)]
    pub(crate) speed: f64,
    /// Write the scene (domain, regions, path, numbered scans) as SVG.
    #[arg(long)]
    pub(crate) svg: Option<PathBuf>,
    /// Write report.html here: one self-contained page (no network) that replays the run
    /// step by step in the browser (each scan's region, the path, the frontiers left open)
    /// beside the metrics, the time's terms, the bounds and the certified ratio.
    #[arg(long)]
    pub(crate) report: Option<PathBuf>,
    /// Write an MCAP recording of the run here, for Foxglove (JSON messages with Foxglove's
    /// schemas: the map, each scan's region, the frontiers open, the path, the robot's
    /// transforms, the raw laser scans with --sensor lidar, a log; the cost model, seed and
    /// version as metadata).
    #[arg(long)]
    pub(crate) mcap: Option<PathBuf>,
    /// Limit the sensor to R metres (the paper's restricted visibility polygons); the bound
    /// becomes Lemma 4's and the lower bound area / (πR²).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) range: Option<f64>,
    /// The robot's radius in metres: viewpoints and moves stay in the configuration space
    /// (the free space shrunk by the robot), scans still see the whole free space, and space
    /// no reachable viewpoint can see is reported as unreachable area.
    #[arg(long, allow_negative_numbers = true, conflicts_with = "footprint")]
    pub(crate) robot_radius: Option<f64>,
    /// A convex footprint polygon around the robot's reference point, as nav2 writes it:
    /// "[[x, y], [x, y], ...]" in metres (kept at a fixed heading).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) footprint: Option<String>,
    /// The sensor's beams per revolution: a window shorter than the beam spacing at its
    /// distance (d·2π/beams) is not worth a trip.
    #[arg(long, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) beams: Option<usize>,
    /// The smallest feature the sensor resolves, metres (windows shorter are not worth a trip).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0)]
    pub(crate) min_feature: f64,
    /// The shortest window worth a trip, metres [default: the robot's width, and at least two
    /// cells of an occupancy map; 0 for a point robot on a polygon].
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) min_window: Option<f64>,
    /// The smallest pocket of unseen space enclosed by what was seen (the back of a pillar,
    /// a desk's hidden face) worth a trip, as a share of the area seen so far [default:
    /// 0.005 where --min-window has a default above 0; 0 for a point robot on a polygon].
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) min_pocket: Option<f64>,
    /// The largest pocket --min-pocket may leave unvisited, square metres (keeps a small room
    /// in a large building a room).
    #[arg(
        long,
        allow_negative_numbers = true,
        default_value_t = stopscan::pipeline::explore::DEFAULT_POCKET_CAP
    )]
    pub(crate) pocket_cap: f64,
    /// The most the pockets --min-pocket leaves may hold in all, as a share of the area seen
    /// so far: a part into a small pocket is closed only while the pockets left, with it,
    /// hold less (so the backs of many desks cannot add up).
    #[arg(
        long,
        allow_negative_numbers = true,
        default_value_t = stopscan::pipeline::explore::DEFAULT_POCKET_BUDGET
    )]
    pub(crate) pocket_budget: f64,
    /// Compute the offline greedy reference for domains up to this many vertices.
    #[arg(long, default_value_t = 1000, allow_negative_numbers = true, value_parser = count_at_least(0))]
    pub(crate) greedy_max_vertices: usize,
    /// Search for the exact offline optimum (integer programming over candidate viewpoints)
    /// for domains up to this many vertices.
    #[arg(long, default_value_t = 400, allow_negative_numbers = true, value_parser = count_at_least(0))]
    pub(crate) optimum_max_vertices: usize,
    /// Seconds for the optimum's search; when they run out, the best set found, the best
    /// proven lower bound and the gap are reported (0: skip the search).
    #[arg(long, default_value_t = 5.0, allow_negative_numbers = true)]
    pub(crate) optimum_seconds: f64,
    /// Branch-and-bound nodes for the optimum's search (microlp): a budget that gives the
    /// same result on every machine, unlike --optimum-seconds (which still applies).
    #[arg(long, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) optimum_nodes: Option<usize>,
    /// Seconds for the lower bounds (valid when cut short, only weaker).
    #[arg(long, default_value_t = 5.0, allow_negative_numbers = true)]
    pub(crate) bounds_seconds: f64,
    /// Steps for the lower bounds instead of --bounds-seconds: a budget that cuts them at
    /// the same place on every machine and under any load, so that a sweep split across
    /// machines gives the same rows. A step is one check of the budget: 100 to 1,000 steps
    /// a second here, depending on the stage (a forest of 20 pillars needs 518).
    #[arg(long, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) bounds_steps: Option<usize>,
    /// The integer-programming solver: microlp (built in); cbc and highs when built with the
    /// cargo features of those names.
    #[arg(long, default_value = "microlp")]
    pub(crate) solver: String,
    /// Write every move and scan as it happens, one JSON object per line (flushed per event).
    #[arg(long)]
    pub(crate) trace: Option<PathBuf>,
    /// ROS maps: simplify the boundary traced along cell edges, preserving its topology, by
    /// moving it at most TOL metres (default 1.5 cells; 0 keeps the traced boundary). Other
    /// formats are read as they are.
    #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
    pub(crate) simplify: Option<f64>,
    /// Drive from simulated raw laser scans instead of exact visibility regions:
    /// `lidar[:beams=720,max=20,sigma=0.02,dropout=0.01,spurious=0,min=0.05]`. Scans are
    /// cleaned, segmented and aligned by ICP; the run is measured on the ground truth, with
    /// the pose error at each stop (seeded by --seed).
    #[arg(long, value_name = "SPEC", value_parser = parse_lidar)]
    pub(crate) sensor: Option<stopscan::world::lidar::Lidar>,
    /// With --sensor lidar: odometry's drift, the position error per metre driven (standard
    /// deviation per axis; a tenth of it in radians of heading per metre).
    #[arg(
        long,
        value_name = "SHARE",
        allow_negative_numbers = true,
        default_value_t = 0.0,
        requires = "sensor"
    )]
    pub(crate) odometry_drift: f64,
    /// With --sensor lidar: relays. When the scan where a trip ends is predicted not to be
    /// placed by ICP along some direction (the far end of a featureless corridor, or of a hall
    /// seen from one side), and odometry may be off there by more than M metres (one standard
    /// deviation), the robot stops on the way where a scan can be placed, and scans to place
    /// itself. Relays count as scans; the strategy is not told of them. 0 never relays
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        default_value_t = stopscan::sim::lidar::RELAY,
        requires = "sensor"
    )]
    pub(crate) relay: f64,
    /// Stop the run after N scans, done or not: a run stopped before the strategy is done is
    /// recorded with the reason (exit code 2), its record written as for any run cut short
    /// [default: no limit but the simulator's, 20,000 scans from raw scans, a million steps].
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) max_scans: Option<usize>,
}

/// A `--sensor` specification.
fn parse_lidar(s: &str) -> Result<stopscan::world::lidar::Lidar, String> {
    s.parse().map_err(|e: stopscan::world::lidar::InvalidLidar| e.to_string())
}

#[derive(Debug, Args)]
pub(crate) struct RoiArgs {
    /// The region: a text grid (# region, . outside, S start), a PGM/PNG mask (grey ≥ 128 is
    /// region), or a polygon (GeoJSON, WKT, .pol) explored through its outer grid approximation.
    #[arg(long, conflicts_with_all = ["random", "resume"])]
    pub(crate) grid: Option<PathBuf>,
    /// A random region of this many 4-connected cells (seeded by --seed; soft limit 4·10^6).
    #[arg(long, conflicts_with = "resume", allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) random: Option<usize>,
    /// Robots (R; soft limit 10,000).
    #[arg(long, default_value_t = 1, conflicts_with = "resume", allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) robots: usize,
    /// Robot speed S_r, m/s.
    #[arg(long, allow_negative_numbers = true, default_value_t = 1.0, conflicts_with = "resume")]
    pub(crate) robot_speed: f64,
    /// Speed S_p at which the region translates, m/s (must be below S_r).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0, conflicts_with = "resume")]
    pub(crate) roi_speed: f64,
    /// Heading of the region's drift, degrees counter-clockwise from east (the grid's +x).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, conflicts_with = "resume")]
    pub(crate) roi_heading_deg: f64,
    /// Flight seconds per battery: a robot flies home to swap before it would run out, then
    /// resumes from the vertex it left (the field experiment).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "resume")]
    pub(crate) battery_s: Option<f64>,
    /// Journal the mission here, for --resume: the state it starts from, then one line per
    /// step, each written before the next step.
    #[arg(long, conflicts_with = "resume")]
    pub(crate) state: Option<PathBuf>,
    /// Carry on with the mission journaled in STATE (and keep journaling there); the mission's
    /// settings, and its --trace, come from STATE, so only --out, --svg, --report, --mcap,
    /// --trace and --format may be given with it.
    #[arg(long, value_name = "STATE")]
    pub(crate) resume: Option<PathBuf>,
    /// Side of a cell, metres (for polygons, the grid's cell; otherwise the scale).
    #[arg(long, allow_negative_numbers = true, default_value_t = 1.0, conflicts_with = "resume")]
    pub(crate) cell_m: f64,
    /// Pixels per cell side, for masks.
    #[arg(long, default_value_t = 1, conflicts_with = "resume", allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) cell_px: usize,
    /// For masks: the region is dark (grey below 128) instead of light.
    #[arg(long, conflicts_with = "resume")]
    pub(crate) invert_mask: bool,
    /// The start cell ROW,COL for masks and grids without S (default: the first region cell).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "resume")]
    pub(crate) start: Option<String>,
    /// Sense with the field pipeline in simulation: a synthetic camera, the frame classifier
    /// and a vote over --frames frames per scan (conservative marking).
    #[arg(long, conflicts_with = "resume")]
    pub(crate) camera: bool,
    /// Frames per scan with --camera, 1 to 99 (the paper: 5, voted 3 of 5).
    #[arg(long, default_value_t = 5, conflicts_with = "resume", requires = "camera", allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) frames: usize,
    /// Sweep this box of cells ROW0,COL0,ROW1,COL1 lawn-mower fashion until the region is first
    /// seen (needs --launch).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "resume")]
    pub(crate) search_box: Option<String>,
    /// Where the robots take off and land, ROW,COL (with --search-box).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "resume")]
    pub(crate) launch: Option<String>,
    /// Seconds per scan (the paper's model: 0).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0, conflicts_with = "resume")]
    pub(crate) scan_time: f64,
    /// Seconds per move (the paper's model: 0).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0, conflicts_with = "resume")]
    pub(crate) move_time: f64,
    /// Write every move and scan to this file as it happens, one JSON object per line with the
    /// robot's index (flushed per event). The state file remembers it: a resumed mission cuts
    /// the trace back to the last state written and carries it on, so no event appears twice.
    #[arg(long)]
    pub(crate) trace: Option<PathBuf>,
    /// Leave each robot's cells, times and scans out of the run record (large regions: the
    /// record of 10^6 cells and 64 robots is about 0.5 GB with them).
    #[arg(long, conflicts_with = "resume")]
    pub(crate) no_paths: bool,
    /// Where to write the SVG replay (default: --out with .svg).
    #[arg(long)]
    pub(crate) svg: Option<PathBuf>,
    /// Write report.html here: one self-contained page (no network) that replays the mission
    /// in the browser, the robots moving and the cells being marked, beside the metrics and
    /// bounds.
    #[arg(long)]
    pub(crate) report: Option<PathBuf>,
    /// Write an MCAP recording of the mission here, for Foxglove (JSON messages with
    /// Foxglove's schemas: the region, the cells as they are first reached, each robot's
    /// transform, the flights, a log; the cost model, seed and version as metadata).
    #[arg(long)]
    pub(crate) mcap: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Family {
    /// A spiral corridor that needs r + 1 views (the paper's Fig. 9).
    Spiral,
    /// A star whose optimum is 2 views (the paper's Fig. 11).
    Star,
    /// A corridor with rooms opening on one side.
    Comb,
    /// An office floor: rooms with doors on both sides of a corridor, desks as holes.
    Office,
    /// A rectangle with random convex pillars.
    Forest,
}

#[derive(Debug, Args)]
pub(crate) struct GenerateArgs {
    /// The family.
    #[arg(value_enum)]
    pub(crate) family: Family,
    /// Size: spiral turns, star spikes, comb teeth, office rooms per side, forest pillars (soft
    /// limits in the README).
    #[arg(long, default_value_t = 6, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) size: usize,
    /// Office desks.
    #[arg(long, default_value_t = 0, allow_negative_numbers = true, value_parser = count_at_least(0))]
    pub(crate) desks: usize,
    /// The GeoJSON to write (with the start as its "start" property); `--out` works too.
    #[arg(short = 'o', long = "output")]
    pub(crate) output: Option<PathBuf>,
}

#[derive(Debug, Subcommand)]
pub(crate) enum MapCommand {
    /// Read any supported environment and write it as GeoJSON.
    Import(ImportArgs),
}

#[derive(Debug, Args)]
pub(crate) struct ImportArgs {
    /// The input: ROS map .yaml, GeoJSON, WKT, .pol, or the visibility benchmark format.
    pub(crate) file: PathBuf,
    /// The GeoJSON to write; `--out` works too.
    #[arg(short = 'o', long = "output")]
    pub(crate) output: Option<PathBuf>,
    /// ROS maps: the start "X,Y" in metres; the free region containing it is kept (default:
    /// the largest free region).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) start: Option<String>,
    /// ROS maps: enclosed obstacle specks below this area (square metres) are dropped.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.05)]
    pub(crate) min_speck_area: f64,
    /// ROS maps: simplify the boundary traced along cell edges, preserving its topology, by
    /// moving it at most TOL metres (default 1.5 cells; 0 keeps the traced boundary).
    #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
    pub(crate) simplify: Option<f64>,
}

#[derive(Debug, Args)]
pub(crate) struct VisibilityArgs {
    /// The environment file (the visibility benchmark format).
    #[arg(long)]
    pub(crate) env: PathBuf,
    /// The viewpoint, "X,Y".
    #[arg(long, allow_hyphen_values = true, conflicts_with = "queries")]
    pub(crate) at: Option<String>,
    /// Many viewpoints, one "x y" per line: one JSON object per line on output.
    #[arg(long)]
    pub(crate) queries: Option<PathBuf>,
    /// Sensor range R (metres): the region within R, with exact arcs.
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) range: Option<f64>,
    /// Largest distance between an arc and its chords in the output polygon (default R/10⁴).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) arc_tolerance: Option<f64>,
}

#[derive(Debug, Args)]
pub(crate) struct ReproduceArgs {
    /// The reproduction, or all (the help lists `experiment::ids()`: `main::command`).
    pub(crate) id: String,
    /// Monte Carlo samples where the paper used sampling (roi-fig-7: trials per point, at
    /// most the paper's 100; soft limit 10^7).
    #[arg(long, default_value_t = 1000, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) samples: usize,
    /// The folder of benchmark environments (*.pol, ROS *.yaml) for views-benchmarks (default:
    /// $STOPSCAN_DATA, else the shared data beside the checkout stopscan was built from, else
    /// beside the executable, else ../shared/data).
    #[arg(long)]
    pub(crate) data: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum BenchTarget {
    /// MDP2 backward induction (or policy iteration with --solver general).
    Mdp,
    /// c(d) for many random distances.
    Circle,
    /// The exact worst-case ratio of a long stop list.
    Ratio,
    /// Visibility queries on an environment (needs --env).
    Visibility,
    /// Exploration of --n generated office floors in parallel (the paper's algorithm).
    Explore,
    /// Every strategy side by side on the ROS maps of --data and --offices generated office
    /// floors, for a robot with a footprint: scans, mission time, coverage, unreachable area,
    /// certified ratio (JSON to --out, chart to --chart).
    Floors,
    /// A random region of --n cells (default 10^6) explored by --robots robots (default 64),
    /// then the three Fig. 7 sweeps of the ROI paper (100 trials per point).
    Roi,
    /// The raw-scan pipeline: reading a lidar scan and aligning it by ICP, per scan, and ICP's
    /// convergence on --n scan pairs (default 1,000) within 3 m of each other, from up to
    /// 0.3 m and 10° of odometry error, on --env (default: the built-in office).
    Scans,
    /// `stopscan serve`: a simulated robot explores --env (default: the built-in office)
    /// through the server with the first of --strategies (default cost_aware): the server's
    /// work and the TCP round trip per step, the journal's write per step (flushed, and with
    /// fsync), resuming from the journal, and `roi --state`'s journal write per step.
    Serve,
}

#[derive(Debug, Args)]
pub(crate) struct BenchArgs {
    /// What to measure.
    #[arg(value_enum)]
    pub(crate) target: BenchTarget,
    /// Problem size: stops (mdp, ratio), distances (circle), floors (explore) or cells (roi).
    #[arg(long, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) n: Option<usize>,
    /// Timed repetitions; the median is reported (at most 1,000).
    #[arg(long, default_value_t = 15, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) repeat: usize,
    /// MDP solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Backward)]
    pub(crate) solver: SolverArg,
    /// The environment for `bench visibility` (its own queries are used unless --queries).
    #[arg(long)]
    pub(crate) env: Option<PathBuf>,
    /// Query points for `bench visibility`, one "x y" per line.
    #[arg(long)]
    pub(crate) queries: Option<PathBuf>,
    /// Sensor range for `bench visibility` (range-limited queries).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) range: Option<f64>,
    /// Robots for `bench roi`.
    #[arg(long, default_value_t = 64, allow_negative_numbers = true, value_parser = count_at_least(1))]
    pub(crate) robots: usize,
    /// `bench floors`: a folder of ROS map .yaml files (searched one level deep).
    #[arg(long, default_value = "../shared/data/ros-maps")]
    pub(crate) data: PathBuf,
    /// `bench floors`: generated office floors added to the maps.
    #[arg(long, default_value_t = 12, allow_negative_numbers = true, value_parser = count_at_least(0))]
    pub(crate) offices: usize,
    /// `bench floors`: the strategies, comma-separated (default: all but range_limited).
    #[arg(long)]
    pub(crate) strategies: Option<String>,
    /// `bench floors`: the robot's radius, metres.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.2)]
    pub(crate) robot_radius: f64,
    /// `bench floors`: seconds per scan.
    #[arg(long, allow_negative_numbers = true, default_value_t = 30.0)]
    pub(crate) scan_time: f64,
    /// `bench floors`: metres per second.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.5)]
    pub(crate) speed: f64,
    /// `bench floors`: write the mission-time chart (SVG and PNG beside it).
    #[arg(long)]
    pub(crate) chart: Option<PathBuf>,
    /// `bench scans`: the second scan of a pair is taken within this many metres of the
    /// first (in sight of it); long drives between stops are where walls seen from afar
    /// must place a scan.
    #[arg(long, value_name = "M", allow_negative_numbers = true, default_value_t = 3.0)]
    pub(crate) pairs_within: f64,
}
