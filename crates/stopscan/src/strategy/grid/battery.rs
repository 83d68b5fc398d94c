//! A battery that lasts a limited flight time (the field experiment's 12 minutes): before
//! every action the robot checks that it could still fly home afterwards; if not, it flies
//! home, the battery is swapped, it flies back to the vertex it left and carries on with the
//! action it was about to take. The inner strategy never notices.

use serde::{Deserialize, Serialize};

use super::{GridFeedback, GridStrategy};
use crate::protocol::Action;
use crate::protocol::grid::{Cell, GridContext, Record, TimeModel};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "leg", rename_all = "snake_case")]
enum Detour {
    None,
    /// Flying home to swap; then back to `resume`, then `then`.
    Home {
        resume: Cell,
        then: Action<Cell>,
    },
    /// Flying back to the vertex it left; then `then`.
    Back {
        then: Action<Cell>,
    },
}

/// A flight-time limit around an inner strategy. With no limit it passes everything through.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Battery<S> {
    inner: S,
    /// Flight seconds per battery (`None`: unlimited).
    capacity: Option<f64>,
    times: TimeModel,
    scan_time: f64,
    move_time: f64,
    used: f64,
    at: Option<Cell>,
    home: Option<Cell>,
    detour: Detour,
    inner_acted: bool,
    /// Batteries swapped so far.
    pub swaps: u32,
    /// Why the robot gave up, if it did (a battery too small to reach a vertex and return).
    pub failure: Option<Box<str>>,
}

impl<S> Battery<S> {
    /// A battery of `capacity` flight seconds (`None`: unlimited) for a robot flying under
    /// `times`, scanning for `scan_time` and paying `move_time` per move.
    pub fn new(
        inner: S,
        capacity: Option<f64>,
        times: TimeModel,
        scan_time: f64,
        move_time: f64,
    ) -> Self {
        Self {
            inner,
            capacity,
            times,
            scan_time,
            move_time,
            used: 0.0,
            at: None,
            home: None,
            detour: Detour::None,
            inner_acted: false,
            swaps: 0,
            failure: None,
        }
    }

    /// The inner strategy.
    pub fn inner(&self) -> &S {
        &self.inner
    }

    /// Flight seconds used from the current battery.
    pub fn used(&self) -> f64 {
        self.used
    }

    fn fly(&self, from: Cell, to: Cell) -> f64 {
        if from == to {
            return 0.0;
        }
        self.move_time + self.times.seconds(from, to).unwrap_or(f64::INFINITY)
    }

    /// Seconds an action takes from `at`, and where it leaves the robot.
    fn cost_of(&self, at: Cell, a: &Action<Cell>) -> (f64, Cell) {
        match a {
            Action::MoveTo { to } => (self.fly(at, *to), *to),
            Action::Scan => (self.scan_time, at),
            Action::Done => (0.0, at),
        }
    }

    /// Lets an action through if the battery allows it and the flight home after it;
    /// otherwise starts a detour home.
    fn gate(&mut self, a: Action<Cell>) -> Action<Cell> {
        let (Some(cap), Some(at), Some(home)) = (self.capacity, self.at, self.home) else {
            return self.commit(a);
        };
        if matches!(a, Action::Done) {
            return a;
        }
        let (cost, end) = self.cost_of(at, &a);
        if self.used + cost + self.fly(end, home) <= cap {
            return self.commit(a);
        }
        if at == home {
            // Swap here and try again with a full battery.
            self.swap();
            return self.after_swap(at, a);
        }
        self.detour = Detour::Home { resume: at, then: a };
        self.used += self.fly(at, home);
        self.at = Some(home);
        Action::MoveTo { to: home }
    }

    fn swap(&mut self) {
        self.used = 0.0;
        self.swaps += 1;
    }

    /// With a fresh battery at home: back to `resume`, then `then`, if one battery can.
    fn after_swap(&mut self, resume: Cell, then: Action<Cell>) -> Action<Cell> {
        let home = self.home.unwrap_or(resume);
        let (cost, end) = self.cost_of(resume, &then);
        let need = self.fly(home, resume) + cost + self.fly(end, home);
        if need > self.capacity.unwrap_or(f64::INFINITY) {
            self.failure = Some(Box::from(format!(
                "a battery of {:.1} s cannot reach cell (row {}, col {}) and return: that needs {need:.1} s",
                self.capacity.unwrap_or_default(),
                end[0],
                end[1]
            )));
            return Action::Done;
        }
        if resume == home {
            return self.commit(then);
        }
        self.detour = Detour::Back { then };
        self.used += self.fly(home, resume);
        self.at = Some(resume);
        Action::MoveTo { to: resume }
    }

    fn commit(&mut self, a: Action<Cell>) -> Action<Cell> {
        if self.capacity.is_none() {
            return a;
        }
        if let Some(at) = self.at {
            let (cost, end) = self.cost_of(at, &a);
            self.used += cost;
            self.at = Some(end);
        }
        a
    }
}

impl<S: GridStrategy> GridStrategy for Battery<S> {
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn act(&mut self, feedback: &GridFeedback, context: &GridContext) -> Action<Cell> {
        self.inner_acted = false;
        if let GridFeedback::Start { at: c } = feedback {
            self.home.get_or_insert(*c);
            self.at.get_or_insert(*c);
        }
        match self.detour {
            Detour::Home { resume, then } => {
                self.detour = Detour::None;
                self.swap();
                self.after_swap(resume, then)
            }
            Detour::Back { then } => {
                self.detour = Detour::None;
                self.commit(then)
            }
            Detour::None => {
                self.inner_acted = true;
                let a = self.inner.act(feedback, context);
                self.gate(a)
            }
        }
    }

    fn report(&mut self, feedback: &GridFeedback) -> Option<Record> {
        if self.detour == Detour::None { self.inner.report(feedback) } else { None }
    }

    fn note(&mut self) -> Option<&Record> {
        if self.inner_acted { self.inner.note() } else { None }
    }
}
