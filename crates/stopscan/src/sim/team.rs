//! The one stop-scan-plan-go loop, for a team of any size in any world family.
//!
//! Every robot has its own clock. A [`Team::step`] takes the robots whose clock is earliest and
//! who stand on the same place (a *group*: robots that arrived together), lets each tell the
//! others its news ([`Agent::report`]), tells the world they meet there ([`Arena::meet`]; this
//! is the only way robots learn from each other), asks each
//! one for its next action in index order, carries the actions out, and finally lets each leave
//! its note at the place ([`Arena::leave`]). The loop state is plain data (serde), so a mission
//! can be written after every step and resumed after a crash or a battery swap.

use std::fmt::Debug;

use serde::{Deserialize, Serialize};

use super::Observer;
use crate::protocol::{Action, CostModel, Feedback, Tally};

/// A straight move, as a world prices it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// Metres flown or driven (in the world's fixed frame).
    pub metres: f64,
    /// Seconds of travel (without the cost model's per-move time).
    pub seconds: f64,
}

/// Where robots meet: what they learn there from one another (or from what was left there
/// before) and what they leave. The simulator's worlds are meeting places; so is a server's
/// board of records, for robots that report over a protocol.
pub trait Meeting {
    /// A place a robot can stand on.
    type Place: Clone + PartialEq + Debug;
    /// What a scan returns.
    type Observation: Clone;
    /// What robots learn where they stand (from one another, or left there before).
    type Context;
    /// What a robot leaves where it stands (robots of a group often leave equal notes; the
    /// loop passes each distinct note once).
    type Note: PartialEq + Clone;

    /// Robots `group` (indices, ascending) stand together at `at` at time `clock`.
    fn meet(&mut self, at: &Self::Place, clock: f64, group: &[usize]) -> Self::Context;
    /// A robot leaves `note` at `at`.
    fn leave(&mut self, at: &Self::Place, note: Self::Note);
}

/// What the loop needs from a world: moves and scans, besides where robots meet.
pub trait Arena: Meeting {
    /// Checks a straight move that begins at time `clock` and prices it, or refuses it.
    fn travel(
        &self,
        from: &Self::Place,
        to: &Self::Place,
        clock: f64,
        cost: &CostModel,
    ) -> Option<Leg>;
    /// The sensor of robot `robot` at `at`, or `None` if it cannot scan there.
    fn scan(&mut self, robot: usize, at: &Self::Place, clock: f64) -> Option<Self::Observation>;
    /// Whether a scan at a place always sees the same (a static world with an exact sensor):
    /// then a second scan where any scan already stood sees nothing new, and the loop ends
    /// the run as [`SimError::NoProgress`] instead of letting a strategy repeat itself.
    fn is_static(&self) -> bool {
        false
    }
}

/// The feedback a robot of a meeting gets, by its index.
pub type MeetingFeedback<W> = Feedback<<W as Meeting>::Place, <W as Meeting>::Observation>;

/// A strategy as the loop drives it.
pub trait Agent<W: Meeting + ?Sized> {
    /// The registry name.
    fn name(&self) -> &str;
    /// The next action, given the feedback of the last one and what the robot learns here.
    fn act(&mut self, feedback: &MeetingFeedback<W>, context: &W::Context) -> Action<W::Place>;
    /// What the robot leaves where it stands after acting (nothing by default).
    fn note(&mut self) -> Option<&W::Note> {
        None
    }
    /// What the robot tells the robots it meets as it arrives, before anyone acts (nothing by
    /// default): news from where it comes from.
    fn report(&mut self, _feedback: &MeetingFeedback<W>) -> Option<W::Note> {
        None
    }
}

/// One meeting: robots `group` (indices into `agents`, ascending) stand together at `at` at
/// time `clock`. Each tells the others its news (left at the place), they learn what the place
/// holds, each decides its next action in index order, and each leaves its note. Returns the
/// actions in the order of `group`.
///
/// The simulator's loop holds every meeting through here, and so does a server whose robots
/// report over a protocol: both make the same decisions from the same feedback.
pub fn confer<'f, W, A>(
    world: &mut W,
    agents: &mut [A],
    feedback: impl Fn(usize) -> &'f MeetingFeedback<W>,
    at: &W::Place,
    clock: f64,
    group: &[usize],
) -> Vec<Action<W::Place>>
where
    W: Meeting + ?Sized,
    W::Place: 'f,
    W::Observation: 'f,
    A: Agent<W>,
{
    let mut notes: Vec<W::Note> = Vec::new();
    for &i in group {
        if let Some(n) = agents[i].report(feedback(i))
            && notes.last() != Some(&n)
        {
            notes.push(n);
        }
    }
    for n in notes.drain(..) {
        world.leave(at, n);
    }
    let context = world.meet(at, clock, group);
    let mut actions = Vec::with_capacity(group.len());
    for &i in group {
        let agent = &mut agents[i];
        actions.push(agent.act(feedback(i), &context));
        if let Some(n) = agent.note()
            && notes.last() != Some(n)
        {
            notes.push(n.clone());
        }
    }
    for n in notes {
        world.leave(at, n);
    }
    actions
}

/// Why a run was cut short.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SimError<P: Debug> {
    /// A strategy asked for a move the world refuses (it leaves the free space) or for a scan
    /// where it cannot scan.
    #[error(
        "strategy {strategy} (robot {robot}) asked to move from {from:?} to {to:?}, which the world refuses"
    )]
    Blocked {
        /// The strategy.
        strategy: String,
        /// The robot.
        robot: usize,
        /// Where the robot was.
        from: P,
        /// Where it wanted to go (`from` for a scan).
        to: P,
    },
    /// The team did not finish within the step limit.
    #[error("strategy {0} did not finish within {1} steps")]
    TooLong(String, u64),
    /// The run was stopped at the scan limit the user set, before the strategy was done.
    #[error(
        "strategy {strategy} was stopped at the scan limit ({scans} scans, --max-scans) before it was done"
    )]
    ScanLimit {
        /// The strategy.
        strategy: String,
        /// The scans taken.
        scans: u64,
    },
    /// A strategy asked to scan, in a static world, where a scan already stood: it would see
    /// nothing new, so it has stopped making progress.
    #[error(
        "strategy {strategy} (robot {robot}) asked to scan at {at:?}, where scan {earlier} already stood: it would see nothing new, so the run was ended after {scans} scans"
    )]
    NoProgress {
        /// The strategy.
        strategy: String,
        /// The robot.
        robot: usize,
        /// Where it asked to scan again.
        at: P,
        /// The number (from 1, over the team) of the earlier scan there.
        earlier: u64,
        /// Scans taken by the team so far.
        scans: u64,
    },
}

impl<P: Debug> SimError<P> {
    fn blocked(strategy: &str, robot: usize, from: P, to: P) -> Self {
        Self::Blocked { strategy: strategy.into(), robot, from, to }
    }

    /// The same error with its places moved by `f` (a change of frame).
    pub fn map_places<Q: Debug>(self, f: impl Fn(P) -> Q) -> SimError<Q> {
        match self {
            Self::Blocked { strategy, robot, from, to } => {
                SimError::Blocked { strategy, robot, from: f(from), to: f(to) }
            }
            Self::TooLong(s, n) => SimError::TooLong(s, n),
            Self::ScanLimit { strategy, scans } => SimError::ScanLimit { strategy, scans },
            Self::NoProgress { strategy, robot, at, earlier, scans } => {
                SimError::NoProgress { strategy, robot, at: f(at), earlier, scans }
            }
        }
    }
}

/// Records a scan at `at` as the team's scan `scans + 1`, or, when a scan already stood there,
/// returns its number and `scans`.
fn revisit<P: Clone + PartialEq + Spot>(
    scanned: &mut std::collections::HashMap<u64, Vec<(P, u64)>>,
    scans: u64,
    at: &P,
) -> Option<(u64, u64)> {
    let here = scanned.entry(at.spot()).or_default();
    if let Some(&(_, earlier)) = here.iter().find(|(p, _)| p == at) {
        return Some((earlier, scans));
    }
    here.push((at.clone(), scans + 1));
    None
}

/// One robot's state in the loop and what it has done so far.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Track<P, O> {
    /// Its clock: seconds since the start.
    pub clock: f64,
    /// Where it stands.
    pub at: P,
    /// The feedback it gets next.
    pub feedback: Feedback<P, O>,
    /// Whether it has answered done.
    pub done: bool,
    /// Its scans, moves and metres.
    pub tally: Tally,
    /// The places it stood on, in order (starts at its start), when the team records paths.
    pub path: Vec<P>,
    /// When each of its scans began.
    pub scan_times: Vec<f64>,
    /// Where each of its scans was taken, when the team records paths.
    pub scan_places: Vec<P>,
    /// Its tally as each scan was taken (that scan counted), when the team records paths.
    #[serde(default)]
    pub scan_tallies: Vec<Tally>,
    /// What each of its scans returned (kept when the team records observations).
    pub observations: Vec<O>,
}

/// What a team's tracks keep besides tallies and clocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Recording {
    /// Every place each robot stood on.
    pub paths: bool,
    /// Every observation.
    pub observations: bool,
}

impl Recording {
    /// Paths and observations.
    pub const ALL: Self = Self { paths: true, observations: true };
    /// Paths only.
    pub const PATHS: Self = Self { paths: true, observations: false };
    /// Neither (the fastest: a benchmark, or a sweep that needs only times).
    pub const NONE: Self = Self { paths: false, observations: false };
}

/// How a step ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// More to do.
    Continue,
    /// Every robot is done.
    Finished,
    /// An observer stopped the run.
    Interrupted,
}

/// The loop's state: every robot's track.
///
/// # Example
/// Two robots explore a 3 × 3 region of interest from its corner cell with the ROI paper's
/// Algorithm 1 ([`RecursiveDfs`](crate::strategy::grid::RecursiveDfs)), at 1 m/s with free
/// scans and moves, and come home.
/// ```
/// use stopscan::protocol::CostModel;
/// use stopscan::sim::{Flow, NoObserver, Recording, Team};
/// use stopscan::strategy::grid::RecursiveDfs;
/// use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};
///
/// let cells = (0..3).flat_map(|row| (0..3).map(move |col| [row, col]));
/// let roi = GridRoi::new("square", cells, [0, 0], 1.0)?;
/// let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, 7);
/// let cost = CostModel::new(0.0, 0.0, 1.0)?;
/// let mut robots = [RecursiveDfs::new(0), RecursiveDfs::new(1)];
/// let mut team = Team::new(vec![[0, 0]; 2], Recording::NONE);
/// let flow = team.run(&mut world, &cost, &mut robots, &mut NoObserver, 1_000)?;
/// assert_eq!(flow, Flow::Finished);
/// assert_eq!(world.visited().len(), 9); // every cell
/// assert!(team.robots.iter().all(|r| r.done && r.at == [0, 0])); // everyone home
/// assert_eq!(team.makespan(), 10.0); // seconds, the last robot home
/// assert_eq!((team.tally().moves, team.tally().distance), (20, 20.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Team<P, O> {
    /// The robots, by index.
    pub robots: Vec<Track<P, O>>,
    /// Steps taken so far.
    pub steps: u64,
    /// What the tracks keep.
    pub recording: Recording,
    /// The robots not done, by (clock, index); rebuilt from the tracks after loading.
    /// Every robot's clock as an ordered key (`u64::MAX` once done) and place as a number: a
    /// compact copy of the tracks that the loop scans to find the next group. Rebuilt after
    /// loading.
    #[serde(skip)]
    clocks: Vec<u64>,
    #[serde(skip)]
    spots: Vec<u64>,
    /// The group acting now.
    #[serde(skip)]
    group: Vec<usize>,
    /// Scans taken by the team so far.
    #[serde(skip)]
    tally_scans: u64,
    /// In a static world, every place scanned so far (by spot), with the team's scan number.
    #[serde(skip)]
    scanned: std::collections::HashMap<u64, Vec<(P, u64)>>,
}

/// Two teams are equal when their tracks, steps and recording are (the scan caches are
/// derived data).
impl<P: PartialEq, O: PartialEq> PartialEq for Team<P, O> {
    fn eq(&self, other: &Self) -> bool {
        self.robots == other.robots
            && self.steps == other.steps
            && self.recording == other.recording
    }
}

/// A clock as an ordered key: non-negative floats order as their bits do.
fn key(clock: f64) -> u64 {
    clock.max(0.0).to_bits()
}

/// A place as a number, so that the loop compares places cheaply when it looks for robots
/// standing together (equal places give equal numbers; unequal places rarely do, and are told
/// apart anyway).
pub trait Spot {
    /// The number.
    fn spot(&self) -> u64;
}

impl Spot for [f64; 2] {
    fn spot(&self) -> u64 {
        self[0].to_bits().rotate_left(32) ^ self[1].to_bits()
    }
}

impl Spot for [i32; 2] {
    fn spot(&self) -> u64 {
        (u64::from(self[0] as u32) << 32) | u64::from(self[1] as u32)
    }
}

impl<P: Clone + PartialEq + Debug + Spot, O: Clone> Team<P, O> {
    /// A team whose robot `i` starts at `starts[i]` at time 0.
    pub fn new(starts: Vec<P>, recording: Recording) -> Self {
        let robots = starts
            .into_iter()
            .map(|s| Track {
                clock: 0.0,
                at: s.clone(),
                feedback: Feedback::Start { at: s.clone() },
                done: false,
                tally: Tally::default(),
                path: vec![s],
                scan_times: Vec::new(),
                scan_places: Vec::new(),
                scan_tallies: Vec::new(),
                observations: Vec::new(),
            })
            .collect();
        Self {
            robots,
            steps: 0,
            recording,
            clocks: Vec::new(),
            spots: Vec::new(),
            group: Vec::new(),
            tally_scans: 0,
            scanned: std::collections::HashMap::new(),
        }
    }

    /// The time the last robot finished (the makespan), or the latest clock so far.
    pub fn makespan(&self) -> f64 {
        self.robots.iter().map(|r| r.clock).fold(0.0, f64::max)
    }

    /// The team's scans, moves and metres together.
    pub fn tally(&self) -> Tally {
        self.robots.iter().fold(Tally::default(), |mut t, r| {
            t.scans += r.tally.scans;
            t.moves += r.tally.moves;
            t.distance += r.tally.distance;
            t
        })
    }

    /// Whether every robot is done.
    pub fn finished(&self) -> bool {
        self.robots.iter().all(|r| r.done)
    }

    /// The robots that act next: the robot with the earliest clock (the lowest index among
    /// equals) and every robot standing with it at that time. Fills `self.group`.
    fn next_group(&mut self) -> bool {
        if self.clocks.len() != self.robots.len() {
            self.clocks = self.robots.iter().map(|r| Self::key_of(r).0).collect();
            self.spots = self.robots.iter().map(|r| Self::key_of(r).1).collect();
            self.tally_scans = self.robots.iter().map(|r| r.tally.scans).sum();
        }
        let mut first = 0;
        let mut best = u64::MAX;
        for (i, &c) in self.clocks.iter().enumerate() {
            if c < best {
                best = c;
                first = i;
            }
        }
        self.group.clear();
        if best == u64::MAX {
            return false;
        }
        let spot = self.spots[first];
        let at = &self.robots[first].at;
        for i in first..self.clocks.len() {
            if self.clocks[i] == best && self.spots[i] == spot && self.robots[i].at == *at {
                self.group.push(i);
            }
        }
        true
    }

    fn key_of(r: &Track<P, O>) -> (u64, u64) {
        if r.done { (u64::MAX, u64::MAX) } else { (key(r.clock), r.at.spot()) }
    }

    /// Runs one group of robots one action each (see the module documentation).
    ///
    /// # Errors
    /// [`SimError::Blocked`] if a strategy asks for a move or a scan the world refuses.
    pub fn step<W, A>(
        &mut self,
        world: &mut W,
        cost: &CostModel,
        agents: &mut [A],
        observer: &mut dyn Observer<P, O>,
    ) -> Result<Flow, SimError<P>>
    where
        W: Arena<Place = P, Observation = O>,
        A: Agent<W>,
    {
        if !self.next_group() {
            return Ok(Flow::Finished);
        }
        let group = std::mem::take(&mut self.group);
        self.steps += 1;
        let (clock, at) = (self.robots[group[0]].clock, self.robots[group[0]].at.clone());
        let robots = &self.robots;
        let actions = confer(world, agents, |i| &robots[i].feedback, &at, clock, &group);
        let mut stop = false;
        // Robots of a group often fly the same leg: price it once.
        let mut last_leg: Option<(P, Leg)> = None;
        for (&i, action) in group.iter().zip(actions) {
            let agent = &agents[i];
            let r = &mut self.robots[i];
            match action {
                Action::MoveTo { to } => {
                    let priced = match &last_leg {
                        Some((t, leg)) if *t == to => Some(*leg),
                        _ => world.travel(&r.at, &to, r.clock, cost),
                    };
                    let Some(leg) = priced else {
                        return Err(SimError::blocked(agent.name(), i, r.at.clone(), to));
                    };
                    last_leg = Some((to.clone(), leg));
                    r.tally.moves += 1;
                    r.tally.distance += leg.metres;
                    r.clock += cost.move_time + leg.seconds;
                    r.at = to.clone();
                    if self.recording.paths {
                        r.path.push(to.clone());
                    }
                    r.feedback = Feedback::Arrived;
                    stop |= observer.on_move(i, &to, leg.metres).is_break();
                }
                Action::Scan => {
                    if world.is_static()
                        && let Some(earlier) = revisit(&mut self.scanned, self.tally_scans, &r.at)
                    {
                        let (strategy, at, scans) = (agent.name().into(), r.at.clone(), earlier.1);
                        return Err(SimError::NoProgress {
                            strategy,
                            robot: i,
                            at,
                            earlier: earlier.0,
                            scans,
                        });
                    }
                    let Some(obs) = world.scan(i, &r.at, r.clock) else {
                        return Err(SimError::blocked(agent.name(), i, r.at.clone(), r.at.clone()));
                    };
                    r.tally.scans += 1;
                    self.tally_scans += 1;
                    r.scan_times.push(r.clock);
                    if self.recording.paths {
                        r.scan_places.push(r.at.clone());
                        r.scan_tallies.push(r.tally);
                    }
                    r.clock += cost.scan_time;
                    stop |= observer.on_scan(i, &r.at, &obs).is_break();
                    if self.recording.observations {
                        r.observations.push(obs.clone());
                    }
                    r.feedback = Feedback::Scanned(obs);
                }
                Action::Done => r.done = true,
            }
        }
        for &i in &group {
            (self.clocks[i], self.spots[i]) = Self::key_of(&self.robots[i]);
        }
        let any_done = group.iter().any(|&i| self.robots[i].done);
        self.group = group;
        if stop {
            observer.on_finish(&self.tally());
            return Ok(Flow::Interrupted);
        }
        // Done robots have the largest key; the team is finished when the next one is done.
        if any_done && self.finished() {
            observer.on_finish(&self.tally());
            return Ok(Flow::Finished);
        }
        Ok(Flow::Continue)
    }

    /// Steps until every robot is done, an observer stops the run, or `limit` steps in all
    /// have been taken.
    ///
    /// # Errors
    /// [`SimError::Blocked`] as in [`Team::step`]; [`SimError::TooLong`] past the limit.
    pub fn run<W, A>(
        &mut self,
        world: &mut W,
        cost: &CostModel,
        agents: &mut [A],
        observer: &mut dyn Observer<P, O>,
        limit: u64,
    ) -> Result<Flow, SimError<P>>
    where
        W: Arena<Place = P, Observation = O>,
        A: Agent<W>,
    {
        loop {
            if self.steps >= limit {
                let name = agents.first().map_or_else(String::new, |a| a.name().to_string());
                return Err(SimError::TooLong(name, limit));
            }
            match self.step(world, cost, agents, observer)? {
                Flow::Continue => {}
                f => return Ok(f),
            }
        }
    }
}
