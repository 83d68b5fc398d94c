//! Online strategies, one family per folder. They see observations only, never the world.
//!
//! - [`corner`]: stop lists: UNIREC, EXPREC, the circle strategy, the MDP policies;
//! - [`polygon`]: the discrete-visibility paper's algorithms and three baselines;
//! - [`grid`]: Algorithm 1 of the ROI paper, with its search and battery wrappers.
//!
//! Each family has one [`Registry`]: the strategies selectable by name, each with the summary
//! that help texts print and the function that builds it, so that names, help and
//! construction cannot drift apart.

pub mod corner;
pub mod grid;
pub mod polygon;

/// One strategy of a family's [`Registry`].
#[derive(Debug, Clone, Copy)]
pub struct Entry<B> {
    /// The name it is selected by (`depth_first`, `unirec`, …).
    pub name: &'static str,
    /// One line for help texts.
    pub summary: &'static str,
    /// How to build it; the signature is the family's.
    pub build: B,
}

/// The strategies of one family, in display order: lookup by name, the list of names and the
/// help text all come from the same entries.
#[derive(Debug, Clone, Copy)]
pub struct Registry<B: 'static> {
    entries: &'static [Entry<B>],
}

/// A name that is not in a registry; the message lists the names that are.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown strategy {name:?}; use one of: {known}")]
pub struct UnknownStrategy {
    /// The name asked for.
    pub name: String,
    /// The registered names, comma-separated.
    pub known: String,
}

impl<B> Registry<B> {
    /// A registry of `entries`, in display order.
    pub const fn new(entries: &'static [Entry<B>]) -> Self {
        Self { entries }
    }

    /// Every entry, in display order.
    pub fn entries(&self) -> &'static [Entry<B>] {
        self.entries
    }

    /// The number of strategies.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the registry is empty (no family's is).
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The names, in display order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + use<B> {
        self.entries.iter().map(|e| e.name)
    }

    /// Whether `name` is registered.
    pub fn contains(&self, name: &str) -> bool {
        self.entries.iter().any(|e| e.name == name)
    }

    /// One line per strategy, `name: summary`, for help texts.
    pub fn help(&self) -> String {
        self.entries
            .iter()
            .map(|e| format!("{}: {}", e.name, e.summary))
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The entry called `name`.
    ///
    /// # Errors
    /// [`UnknownStrategy`] listing the registered names.
    pub fn get(&self, name: &str) -> Result<&'static Entry<B>, UnknownStrategy> {
        self.entries.iter().find(|e| e.name == name).ok_or_else(|| UnknownStrategy {
            name: name.into(),
            known: self.names().collect::<Vec<_>>().join(", "),
        })
    }
}
