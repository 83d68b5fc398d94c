//! The corner papers' experiments: the four-strategy lineup, Monte Carlo through the real
//! simulator, and the reproductions of their tables and figures.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::{ExperimentError, MonteCarlo, Reproduction, Row, sample_seed};
use crate::offline::corner::{expected, optimal::optimal_scans, worst_case};
use crate::protocol::CostModel;
use crate::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use crate::render::{LineChart, Series};
use crate::sim::{NoObserver, corner::run};
use crate::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use crate::strategy::corner::{ExprecReading, StopList, circle, exprec, unirec};
use crate::world::corner::CornerWorld;

/// The reproductions this module knows.
pub const IDS: &[&str] = &[
    "corner-table-2",
    "corner-table-3",
    "corner-table-4",
    "corner-fig-4",
    "corner-fig-6",
    "corner-fig-7",
    "corner-fig-8",
    "circle-table-1",
    "circle-fig-7",
];

/// A named strategy reduced to its stop list.
#[derive(Debug, Clone, PartialEq)]
pub struct Contender {
    /// Display name, with its reading (`UNIREC [nominal last step]`).
    pub name: String,
    /// The stops.
    pub list: StopList,
}

/// How the lineup reads the ambiguous parts of the corner paper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineupOptions {
    /// Last-step charge for UNIREC and EXPREC.
    pub last_step: LastStep,
    /// Which EXPREC.
    pub exprec: ExprecReading,
    /// Transition reading of both MDPs.
    pub reading: Reading,
    /// The MDPs' sampling step, radians.
    pub mdp_step: f64,
}

impl Default for LineupOptions {
    fn default() -> Self {
        Self {
            last_step: LastStep::Capped,
            exprec: ExprecReading::TableI,
            reading: Reading::Conditional,
            mdp_step: 5f64.to_radians(),
        }
    }
}

fn model_err(e: impl std::fmt::Display) -> ExperimentError {
    ExperimentError::Model(e.to_string())
}

/// UNIREC, EXPREC, POLICY1 and POLICY2 for one setup and belief.
///
/// # Errors
/// [`ExperimentError::Model`] if a piece of the model is invalid.
pub fn lineup(
    setup: &CornerSetup,
    belief: &AngleDistribution,
    o: LineupOptions,
) -> Result<Vec<Contender>, ExperimentError> {
    let delta = setup.delta();
    let mdp = |memory| CornerMdp {
        setup: *setup,
        step: o.mdp_step,
        memory,
        reading: o.reading,
        belief: belief.clone(),
    };
    Ok(vec![
        Contender {
            name: "UNIREC".into(),
            list: unirec(delta, Route::Arc, o.last_step).map_err(model_err)?,
        },
        Contender {
            name: "EXPREC".into(),
            list: exprec(delta, o.exprec, Route::Arc, o.last_step).map_err(model_err)?,
        },
        Contender {
            name: "POLICY1".into(),
            list: mdp(Memory::None).solve().map_err(model_err)?.stop_list,
        },
        Contender {
            name: "POLICY2".into(),
            list: mdp(Memory::Last).solve().map_err(model_err)?.stop_list,
        },
    ])
}

/// Monte Carlo: draws θ from `truth`, runs the stop list's strategy through the simulator,
/// and averages the time. Sample `i` uses its own generator seeded from `(seed, i)`.
///
/// # Errors
/// [`ExperimentError::Sim`] if the strategy misbehaves (it cannot for a stop list).
pub fn monte_carlo(
    list: &StopList,
    setup: &CornerSetup,
    truth: &AngleDistribution,
    samples: usize,
    seed: u64,
) -> Result<MonteCarlo, ExperimentError> {
    let last_step = if list.charged_last() > crate::protocol::corner::CORNER {
        LastStep::Nominal
    } else {
        LastStep::Capped
    };
    let times: Result<Vec<f64>, _> = (0..samples as u64)
        .into_par_iter()
        .map(|i| {
            let mut rng = ChaCha8Rng::seed_from_u64(sample_seed(seed, i));
            let world = CornerWorld { setup: *setup, theta: truth.sample(&mut rng), last_step };
            let mut strategy = list.clone().into_strategy("stops");
            run(&world, &mut strategy, &mut NoObserver).map(|r| r.time.total())
        })
        .collect();
    let times = times?;
    let n = times.len().max(1) as f64;
    let mean = times.iter().sum::<f64>() / n;
    let var = times.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    Ok(MonteCarlo { mean, std_err: (var / n).sqrt(), samples })
}

/// The corner paper's experimental setup: the robot on the wall 10 m from the corner,
/// speed 0.5 m/s, reconstruction time τ (2 s or 10 s), free moves.
pub fn paper_setup(tau: f64) -> CornerSetup {
    CornerSetup::new(10.0, CostModel { scan_time: tau, move_time: 0.0, speed: 0.5 })
        .expect("the paper's setup is valid")
}

/// Distribution `k` (1–4) of the corner paper's Fig. 5, on 5° buckets.
///
/// 1: N(60°, 5°) (the mean survives in the text; σ = 5° is the N(60, 5) of Table IV).
/// 2: cut from the text; fitted by [`fit_distribution_2`].
/// 3: uniform on [0, π]. 4: 0.5·N(30°, 3°) + 0.5·N(90°, 3°) ("means π/6 and π/2, variance of
/// 3 degrees", read as a standard deviation of 3°, the same unit as N(60, 5)).
///
/// # Errors
/// [`ExperimentError::Model`] for `k` outside 1–4.
pub fn fig5(k: usize) -> Result<AngleDistribution, ExperimentError> {
    let spec = match k {
        1 => "normal:60,5".to_string(),
        2 => {
            let (m, s, _) = fit_distribution_2();
            format!("normal:{m},{s}")
        }
        3 => "uniform:0,180".to_string(),
        4 => "mix:0.5*normal:30,3+0.5*normal:90,3".to_string(),
        _ => {
            return Err(ExperimentError::Model(format!(
                "Fig. 5 has distributions 1 to 4, not {k}"
            )));
        }
    };
    AngleDistribution::parse(&spec).and_then(|d| d.bucketed(5f64.to_radians())).map_err(model_err)
}

const TABLE_2: [[f64; 4]; 4] = [
    [43.98, 39.40, 26.72, 28.93],
    [57.22, 39.42, 41.77, 35.16],
    [48.17, 34.88, 48.53, 34.82],
    [43.06, 37.63, 37.69, 27.39],
];
const TABLE_3: [[f64; 4]; 4] = [
    [53.96, 40.94, 36.99, 37.43],
    [68.64, 46.49, 47.86, 53.63],
    [61.30, 40.82, 76.21, 46.95],
    [56.92, 35.24, 68.25, 43.16],
];
const TABLE_4: [f64; 4] = [47.44, 34.43, 38.16, 50.87];

/// Fits Distribution 2, whose description is cut from the text: a Gaussian N(µ, σ) on 5°
/// buckets (µ from 40° to 140°, σ from 5° to 60°, steps of 5°) minimising the squared relative
/// error against the paper's policy-independent numbers for it: UNIREC at τ = 2 and τ = 10
/// and EXPREC at τ = 2 (Table III's EXPREC column matches no reading for any distribution).
/// Returns `(µ°, σ°, residual)`.
pub fn fit_distribution_2() -> (f64, f64, f64) {
    let mut best = (0.0, 0.0, f64::INFINITY);
    let lists: Vec<(CornerSetup, StopList, StopList)> = [2.0, 10.0]
        .iter()
        .map(|&tau| {
            let s = paper_setup(tau);
            let u = unirec(s.delta(), Route::Arc, LastStep::Nominal).expect("valid δ");
            let e = exprec(s.delta(), ExprecReading::TableI, Route::Arc, LastStep::Nominal)
                .expect("valid δ");
            (s, u, e)
        })
        .collect();
    for m in (40..=140).step_by(5) {
        for sd in (5..=60).step_by(5) {
            let Ok(t) =
                AngleDistribution::normal(f64::from(m).to_radians(), f64::from(sd).to_radians())
                    .and_then(|d| d.bucketed(5f64.to_radians()))
            else {
                continue;
            };
            let u2 = expected(&lists[0].1, &lists[0].0, &t).time;
            let e2 = expected(&lists[0].2, &lists[0].0, &t).time;
            let u10 = expected(&lists[1].1, &lists[1].0, &t).time;
            let r = ((u2 - TABLE_2[1][0]) / TABLE_2[1][0]).powi(2)
                + ((e2 - TABLE_2[1][1]) / TABLE_2[1][1]).powi(2)
                + ((u10 - TABLE_3[1][0]) / TABLE_3[1][0]).powi(2);
            if r < best.2 {
                best = (f64::from(m), f64::from(sd), r);
            }
        }
    }
    best
}

/// The variants compared in Tables II–IV: each strategy under each reading.
fn variants(
    setup: &CornerSetup,
    belief: &AngleDistribution,
) -> Result<Vec<(usize, Contender)>, ExperimentError> {
    let mut out = Vec::new();
    for (last, tag) in
        [(LastStep::Nominal, "nominal last step"), (LastStep::Capped, "capped last step")]
    {
        let o = LineupOptions { last_step: last, ..LineupOptions::default() };
        let l = lineup(setup, belief, o)?;
        out.push((0, Contender { name: format!("UNIREC [{tag}]"), list: l[0].list.clone() }));
    }
    for (r, tag) in [
        (ExprecReading::TableI, "Table I stops, nominal"),
        (ExprecReading::Appendix, "appendix stops, capped"),
    ] {
        let last = if r == ExprecReading::TableI { LastStep::Nominal } else { LastStep::Capped };
        let list = exprec(setup.delta(), r, Route::Arc, last).map_err(model_err)?;
        out.push((1, Contender { name: format!("EXPREC [{tag}]"), list }));
    }
    for (reading, tag1, tag2) in [
        (Reading::Literal, "printed probabilities", "printed probabilities"),
        (Reading::Conditional, "conditional probabilities", "exact optimum"),
    ] {
        let l = lineup(setup, belief, LineupOptions { reading, ..LineupOptions::default() })?;
        out.push((2, Contender { name: format!("POLICY1 [{tag1}]"), list: l[2].list.clone() }));
        out.push((3, Contender { name: format!("POLICY2 [{tag2}]"), list: l[3].list.clone() }));
    }
    Ok(out)
}

fn table_rows(
    prefix: &str,
    setup: &CornerSetup,
    belief: &AngleDistribution,
    truth: &AngleDistribution,
    paper: [f64; 4],
    samples: usize,
    seed: u64,
) -> Result<Vec<Row>, ExperimentError> {
    let mut rows = Vec::new();
    for (k, (col, c)) in variants(setup, belief)?.into_iter().enumerate() {
        let exact = expected(&c.list, setup, truth).time;
        let mc = monte_carlo(&c.list, setup, truth, samples, sample_seed(seed, k as u64))?;
        rows.push(
            Row::new(format!("{prefix}{}", c.name), Some(paper[col]), exact).with_monte_carlo(mc),
        );
    }
    Ok(rows)
}

fn common_model(tau: f64) -> Vec<String> {
    let s = paper_setup(tau);
    vec![
        format!("D = 10 m, v = 0.5 m/s, τ = {tau} s, no per-move time; δ = τv/D = {} for UNIREC and EXPREC", s.delta()),
        "θ ranges over [0°, 180°]; θ ≥ 90° is seen only from the corner; travel is along the circle (D·Δφ), as the paper's formula charges it".into(),
        "MDP stops every 5° (the bucket size of Fig. 5); distributions are the Fig. 5 histograms (5° buckets, uniform inside)".into(),
        "'ours' is the exact expected time (integrated over θ); 'monte_carlo' is the mean of the paper's 1000 samples, seeded".into(),
        "UNIREC/EXPREC 'nominal last step' charge ⌈θ/δ⌉δ·D/v as the paper's formula does even past the corner; 'capped' stops at the corner".into(),
        "POLICY 'printed probabilities' use P(F|s_ij,Rec) = P(jδ ≤ θ ≤ iδ) as printed (MDP1, whose formulas are cut: P(θ ≤ iδ)); POLICY2 'exact optimum' uses the Bayes-correct P(θ ≤ iδ | θ > jδ), which makes the MDP value the true expected time, hence the optimum over all stop lists on the 5° grid; POLICY1 'conditional' conditions on the previous stop, P(θ ≤ iδ | θ > (i−1)δ), the best a memoryless state can do".into(),
    ]
}

fn table_notes(rows: &[Row]) -> Vec<String> {
    let mut notes = vec![noise_note(rows)];
    let find = |label: &str| rows.iter().find(|r| r.label == label);
    for d in 1..=4 {
        let p = format!("dist {d} / ");
        if let (Some(opt), Some(paper)) = (
            find(&format!("{p}POLICY2 [exact optimum]")),
            find(&format!("{p}POLICY2 [printed probabilities]")),
        ) && let Some(pub_v) = opt.paper
            && opt.ours < pub_v - 3.0 * opt.monte_carlo.map_or(0.0, |m| m.std_err).max(0.01)
        {
            notes.push(format!(
                "dist {d}: the exact optimal POLICY2 takes {:.2} s, below the published {:.2} s by more than Monte Carlo noise: the published policy was suboptimal for its own model (the printed-probability reading gives {:.2} s)",
                opt.ours, pub_v, paper.ours
            ));
        }
        for c in ["UNIREC", "EXPREC", "POLICY1", "POLICY2"] {
            let best =
                rows.iter().filter(|r| r.label.starts_with(&format!("{p}{c} "))).min_by(|a, b| {
                    a.rel_diff.unwrap_or(9.0).abs().total_cmp(&b.rel_diff.unwrap_or(9.0).abs())
                });
            if let Some(b) = best {
                notes.push(format!(
                    "dist {d} {c}: closest reading is {} ({:+.1}%)",
                    b.label.trim_start_matches(&p),
                    100.0 * b.rel_diff.unwrap_or(0.0)
                ));
            }
        }
    }
    notes
}

/// How many published values lie within four Monte Carlo standard errors of ours: the
/// paper's numbers are 1000-sample means, so only larger gaps are real disagreements.
fn noise_note(rows: &[Row]) -> String {
    let mut within = 0;
    let mut far = Vec::new();
    for r in rows {
        if let (Some(p), Some(mc)) = (r.paper, r.monte_carlo) {
            // The published values are rounded to 0.01 s.
            let se = mc.std_err.hypot(0.005);
            let z = (p - r.ours) / se;
            if z.abs() <= 4.0 {
                within += 1;
            } else {
                let z = if z.abs() > 99.0 {
                    format!("{}99", if z > 0.0 { ">+" } else { "<-" })
                } else {
                    format!("{z:+.0}")
                };
                far.push(format!(
                    "{} (paper {:+.1}%, {z} s.e.)",
                    r.label,
                    100.0 * (p - r.ours) / r.ours
                ));
            }
        }
    }
    format!(
        "{within} of {} rows lie within 4 Monte Carlo standard errors of the published value; beyond that: {}",
        within + far.len(),
        if far.is_empty() { "none".to_string() } else { far.join("; ") }
    )
}

/// Runs one reproduction.
///
/// # Errors
/// [`ExperimentError::UnknownId`] for an unknown identifier; model errors otherwise.
pub fn reproduce(id: &str, samples: usize, seed: u64) -> Result<Reproduction, ExperimentError> {
    match id {
        "corner-table-2" | "corner-table-3" => {
            corner_table(id, if id.ends_with('2') { 2.0 } else { 10.0 }, samples, seed)
        }
        "corner-table-4" => corner_table_4(samples, seed),
        "corner-fig-4" | "corner-fig-6" => corner_policy_figure(id),
        "corner-fig-7" => corner_fig_7(),
        "corner-fig-8" => corner_fig_8(),
        "circle-table-1" => Ok(circle_table_1()),
        "circle-fig-7" => Ok(circle_fig_7(seed)),
        _ => Err(ExperimentError::UnknownId(id.into(), IDS.join(", "))),
    }
}

fn corner_table(
    id: &str,
    tau: f64,
    samples: usize,
    seed: u64,
) -> Result<Reproduction, ExperimentError> {
    let setup = paper_setup(tau);
    let paper = if tau == 2.0 { TABLE_2 } else { TABLE_3 };
    let mut rows = Vec::new();
    for d in 1..=4 {
        let dist = fig5(d)?;
        rows.extend(table_rows(
            &format!("dist {d} / "),
            &setup,
            &dist,
            &dist,
            paper[d - 1],
            samples,
            sample_seed(seed, d as u64),
        )?);
    }
    let (m, s, r) = fit_distribution_2();
    let mut model = common_model(tau);
    model.push(format!(
        "Distribution 2 is cut from the text; fitted as N({m}°, {s}°) to its UNIREC (τ = 2, 10) and EXPREC (τ = 2) values (squared relative residual {r:.5}); the fit is a flat ridge (wide Gaussians leaning to large θ), so dist 2 rows carry that uncertainty"
    ));
    let mut notes = table_notes(&rows);
    // Evidence for numbers no reading can match: a fine-grid exact optimum is a lower bound.
    for d in 1..=4 {
        let dist = fig5(d)?;
        let fine = CornerMdp {
            setup,
            step: 0.1f64.to_radians(),
            memory: Memory::Last,
            reading: Reading::Conditional,
            belief: dist.clone(),
        };
        let opt = expected(&fine.solve().map_err(model_err)?.stop_list, &setup, &dist).time;
        for (c, name) in ["UNIREC", "EXPREC", "POLICY1", "POLICY2"].iter().enumerate() {
            if paper[d - 1][c] < opt * (1.0 - 0.03) {
                notes.push(format!(
                    "dist {d} {name}: the published {:.2} s is more than 3% below {opt:.2} s, the exact optimum over all stop lists on a 0.1° grid; no strategy can achieve it in this model, so the published number comes from a different model or a different run",
                    paper[d - 1][c]
                ));
            }
        }
    }
    Ok(Reproduction { id: id.into(), model, rows, notes, charts: vec![], images: vec![] })
}

fn corner_table_4(samples: usize, seed: u64) -> Result<Reproduction, ExperimentError> {
    let setup = paper_setup(2.0);
    let belief = fig5(1)?;
    let truth = AngleDistribution::uniform(0.0, std::f64::consts::PI).map_err(model_err)?;
    let rows = table_rows("", &setup, &belief, &truth, TABLE_4, samples, seed)?;
    let mut model = common_model(2.0);
    model.push("belief N(60°, 5°) on 5° buckets; truth uniform on [0°, 180°] (Table IV)".into());
    let notes = vec![
        noise_note(&rows),
        "belief and truth differ here, so no policy is optimal for the truth; the rows measure what a wrong belief costs".into(),
    ];
    Ok(Reproduction {
        id: "corner-table-4".into(),
        model,
        rows,
        notes,
        charts: vec![],
        images: vec![],
    })
}

fn corner_policy_figure(id: &str) -> Result<Reproduction, ExperimentError> {
    let setup = paper_setup(2.0);
    let (dist_no, memories): (usize, &[Memory]) = if id == "corner-fig-4" {
        (4, &[Memory::Last])
    } else {
        (3, &[Memory::None, Memory::Last])
    };
    let belief = fig5(dist_no)?;
    let mut rows = Vec::new();
    let mut images = Vec::new();
    for &memory in memories {
        let m = CornerMdp {
            setup,
            step: 5f64.to_radians(),
            memory,
            reading: Reading::Conditional,
            belief: belief.clone(),
        };
        let p = m.solve().map_err(model_err)?;
        let name = if memory == Memory::Last { "MDP2" } else { "MDP1" };
        rows.push(Row::new(
            format!("{name}: scans if never seen"),
            None,
            p.scan_stops.len() as f64,
        ));
        rows.push(Row::new(
            format!("{name}: expected time (s)"),
            None,
            expected(&p.stop_list, &setup, &belief).time,
        ));
        images.push((
            format!("{id}-{}", name.to_lowercase()),
            format!("{name} optimal policy, distribution {dist_no}, δ = 5°"),
            p.image,
        ));
    }
    Ok(Reproduction {
        id: id.into(),
        model: vec![
            format!(
                "D = 10 m, v = 0.5 m/s, τ = 2 s, δ = 5°, distribution {dist_no} of Fig. 5, exact (conditional) transition probabilities"
            ),
            "image rows are the robot's stop i (downwards), columns the last scan's stop j".into(),
        ],
        rows,
        notes: vec!["the paper prints no numbers for this figure; compare the images".into()],
        charts: vec![],
        images,
    })
}

fn lineup_times(
    setup: &CornerSetup,
    belief: &AngleDistribution,
    truth: &AngleDistribution,
) -> Result<Vec<f64>, ExperimentError> {
    let o = LineupOptions { last_step: LastStep::Nominal, ..LineupOptions::default() };
    Ok(lineup(setup, belief, o)?.iter().map(|c| expected(&c.list, setup, truth).time).collect())
}

const NAMES: [&str; 4] = ["UNIREC", "EXPREC", "POLICY1", "POLICY2"];

fn corner_fig_7() -> Result<Reproduction, ExperimentError> {
    let belief = fig5(3)?;
    let taus = [0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 7.5, 10.0, 12.5, 15.0, 20.0];
    let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 4];
    let mut rows = Vec::new();
    let mut p2_wins = 0;
    for &tau in &taus {
        let t = lineup_times(&paper_setup(tau), &belief, &belief)?;
        for (k, v) in t.iter().enumerate() {
            series[k].push((tau, *v));
            rows.push(Row::new(format!("τ = {tau} s / {}", NAMES[k]), None, *v));
        }
        if t[3] <= t[2] + 1e-9 {
            p2_wins += 1;
        }
    }
    let chart = LineChart {
        title: "Expected time vs reconstruction time (distribution 3)".into(),
        x_label: "reconstruction time τ (s)".into(),
        y_label: "expected time to see the edge (s)".into(),
        series: series
            .into_iter()
            .zip(NAMES)
            .map(|(p, n)| Series::line(n, p).with_markers())
            .collect(),
    };
    Ok(Reproduction {
        id: "corner-fig-7".into(),
        model: vec![
            "Fig. 7's caption is cut; we keep distribution 3 (uniform, no prior knowledge) and vary τ from 0.5 s to 20 s".into(),
            "D = 10 m, v = 0.5 m/s, δ = τv/D, MDP step 5°, exact transition probabilities, nominal last step".into(),
        ],
        rows,
        notes: vec![format!("POLICY2 ≤ POLICY1 at {p2_wins} of {} reconstruction times (the paper: POLICY2 outperforms POLICY1 as scans get costly)", taus.len())],
        charts: vec![("corner-fig-7".into(), chart)],
        images: vec![],
    })
}

fn corner_fig_8() -> Result<Reproduction, ExperimentError> {
    let setup = paper_setup(2.0);
    let truths = [
        ("left", fig5(1)?, "truth N(60°, 5°)"),
        (
            "right",
            AngleDistribution::uniform(0.0, std::f64::consts::FRAC_PI_2)
                .map_err(model_err)?
                .bucketed(5f64.to_radians())
                .map_err(model_err)?,
            "truth uniform on [0°, 90°]",
        ),
    ];
    let mut rows = Vec::new();
    let mut charts = Vec::new();
    let mut notes = Vec::new();
    for (side, truth, what) in truths {
        let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 4];
        for mu in (30..=90).step_by(5) {
            let belief = AngleDistribution::normal(f64::from(mu).to_radians(), 5f64.to_radians())
                .and_then(|d| d.bucketed(5f64.to_radians()))
                .map_err(model_err)?;
            for (k, v) in lineup_times(&setup, &belief, &truth)?.into_iter().enumerate() {
                series[k].push((f64::from(mu), v));
                rows.push(Row::new(format!("{side}: belief N({mu}°, 5°) / {}", NAMES[k]), None, v));
            }
        }
        let spread = |s: &[(f64, f64)]| {
            s.iter().map(|p| p.1).fold(f64::MIN, f64::max)
                - s.iter().map(|p| p.1).fold(f64::MAX, f64::min)
        };
        let (p1, p2) = (spread(&series[2]), spread(&series[3]));
        let verdict = if p2 > p1 + 1e-9 {
            "holds here"
        } else if (p2 - p1).abs() <= 1e-9 {
            "is not visible here (equal spread)"
        } else {
            "does not hold here"
        };
        notes.push(format!(
            "{what}: over the beliefs POLICY1 varies by {p1:.2} s and POLICY2 by {p2:.2} s; the paper's claim that MDP2 is more sensitive to wrong beliefs {verdict}"
        ));
        charts.push((
            format!("corner-fig-8-{side}"),
            LineChart {
                title: format!("Wrong beliefs: policies for N(µ, 5°), {what}"),
                x_label: "belief mean µ (degrees)".into(),
                y_label: "expected time to see the edge (s)".into(),
                series: series
                    .into_iter()
                    .zip(NAMES)
                    .map(|(p, n)| Series::line(n, p).with_markers())
                    .collect(),
            },
        ));
    }
    Ok(Reproduction {
        id: "corner-fig-8".into(),
        model: vec![
            "D = 10 m, v = 0.5 m/s, τ = 2 s, δ = 0.1, MDP step 5°, beliefs N(µ, 5°) for µ = 30°..90° on 5° buckets".into(),
            "exact expected times under the truth instead of 1000-sample averages".into(),
        ],
        rows,
        notes,
        charts,
        images: vec![],
    })
}

const TABLE_1: [(f64, f64); 6] = [
    (0.618_034, 1.618_034),
    (1.530_414, 2.040_287),
    (2.799_395, 2.155_363),
    (4.400_876, 2.168_544),
    (6.316_892, 2.147_994),
    (8.514_200, 2.118_498),
];

fn circle_table_1() -> Reproduction {
    let mut rows = Vec::new();
    for (t, (d, c)) in circle::thresholds(TABLE_1.len()).iter().zip(TABLE_1) {
        rows.push(Row::new(format!("{} scans: maximal d", t.scans), Some(d), t.distance));
        rows.push(Row::new(format!("{} scans: c at upper bound", t.scans), Some(c), t.ratio));
    }
    Reproduction {
        id: "circle-table-1".into(),
        model: vec![
            "units: scan cost 1, speed 1; 'scans' counts intermediate scans (the scan at the corner is extra), as Table 1 does".into(),
            "c(d) by bisection of recursion (1) to adjacent floats; thresholds by bisection in d of the scan count".into(),
        ],
        rows,
        notes: vec!["the paper rounds to six digits; every row agrees to all printed digits".into()],
        charts: vec![],
        images: vec![],
    }
}

/// `c(d)` on `n` evenly spaced distances in `(0, d_max]`.
pub fn ratio_curve(d_max: f64, n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .into_par_iter()
        .map(|i| {
            let d = d_max * i as f64 / n as f64;
            (d, circle::ratio(d))
        })
        .collect()
}

fn circle_fig_7(seed: u64) -> Reproduction {
    let small = ratio_curve(10.0, 2000);
    let large = ratio_curve(100.0, 2000);
    // The maximum sits on a cusp (a threshold); refine around the sampled maximum.
    let &(d0, _) = small.iter().max_by(|a, b| a.1.total_cmp(&b.1)).expect("non-empty");
    let (mut lo, mut hi) = (d0 - 0.01, d0 + 0.01);
    for _ in 0..200 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if circle::ratio(m1) < circle::ratio(m2) { lo = m1 } else { hi = m2 }
    }
    let d_star = 0.5 * (lo + hi);
    let by_scans: Vec<_> = (1..=6).map(|k| optimal_scans(4.4, k, seed)).collect();
    let best = by_scans.iter().min_by(|a, b| a.ratio.total_cmp(&b.ratio)).expect("six runs");
    let mut rows = vec![
        Row::new("max c(d)", Some(2.168_544), circle::ratio(d_star)),
        Row::new("argmax d", Some(4.400_875), d_star),
        Row::new("c(40)", Some(2.001_525), circle::ratio(40.0)),
        Row::new("c(4.4), circle strategy", Some(2.1685), circle::ratio(4.4)),
        Row::new(
            "c(4.4), global optimum with 3 scans, the circle strategy's count",
            Some(2.12),
            by_scans[2].ratio,
        ),
        Row::new(
            format!("c(4.4), global optimum over 1–6 scans (best: {} scans)", best.scans),
            Some(2.12),
            best.ratio,
        ),
        Row::new(
            "c(1), global optimum with 1 scan",
            Some(1.808_201),
            optimal_scans(1.0, 1, seed).ratio,
        ),
    ];
    for c in [1.9, 1.99, 1.999] {
        let r = circle::collapse(10.0 / (2.0 - c), c);
        rows.push(Row::new(
            format!("Theorem 1, c = {c}: farthest distance reached at d = {:.0}", r.distance),
            None,
            r.farthest,
        ));
        rows.push(Row::new(format!("Theorem 1, c = {c}: bound 1/(2 − c)"), None, r.bound));
    }
    for d in [100.0, 1000.0, 10000.0] {
        rows.push(Row::new(format!("c({d}) − 2 (→ 0, Theorem 2)"), None, circle::ratio(d) - 2.0));
    }
    let lb = |pts: &[(f64, f64)]| pts.iter().map(|&(d, _)| (d, 2.0)).collect::<Vec<_>>();
    let charts = vec![
        (
            "circle-fig-7-small".into(),
            LineChart {
                title: "Circle strategy: c(d) for small d".into(),
                x_label: "distance d (units of v·τ)".into(),
                y_label: "competitive ratio c".into(),
                series: vec![
                    Series::line("c(d)", small.clone()),
                    Series::line("lower bound 2 (Theorem 1)", lb(&small)).dashed(),
                ],
            },
        ),
        (
            "circle-fig-7-large".into(),
            LineChart {
                title: "Circle strategy: c(d) for larger d".into(),
                x_label: "distance d (units of v·τ)".into(),
                y_label: "competitive ratio c".into(),
                series: vec![
                    Series::line("c(d)", large.clone()),
                    Series::line("lower bound 2 (Theorem 1)", lb(&large)).dashed(),
                ],
            },
        ),
    ];
    Reproduction {
        id: "circle-fig-7".into(),
        model: vec![
            "units: scan cost 1, speed 1; c(d) on 2000 distances in (0, 10] and in (0, 100]".into(),
            "the global optimum places the scan points anywhere in the plane (restarted Nelder–Mead over 2k coordinates, exact worst-case ratio)".into(),
        ],
        rows,
        notes: vec![
            format!(
                "global optimum at d = 4.4 by number of intermediate scans: {}; the paper's Fig. 6 solution (≈ 2.12) is not the global optimum of its own model, and the circle strategy is {:.1}% above the optimum there, not 'within about 2%'",
                by_scans.iter().map(|o| format!("{} → {:.6}", o.scans, o.ratio)).collect::<Vec<_>>().join(", "),
                100.0 * (circle::ratio(4.4) / best.ratio - 1.0)
            ),
            "every worst-case ratio of the optimiser is exact (breakpoint enumeration); a brute-force sweep over 200,000 edge angles agrees to 2e-6 (tests/corner.rs)".into(),
            "Theorem 1: with c < 2 the recursion collapses before the corner and never gets further than 1/(2 − c) from the start".into(),
        ],
        charts,
        images: vec![],
    }
}

/// What the built-in demo computes.
#[derive(Debug, Clone, PartialEq)]
pub struct Demo {
    /// The circle strategy at a few distances.
    pub circles: Vec<circle::CircleSolution>,
    /// `(name, expected time, worst-case ratio)` of the four corner-paper strategies.
    pub strategies: Vec<(String, f64, f64)>,
    /// The `c(d)` chart.
    pub chart: LineChart,
}

/// The built-in demo: the circle strategy at a few distances and the four corner-paper
/// strategies on one belief (Table II's setup, distribution 4).
///
/// # Errors
/// Model errors (none for the built-in values).
pub fn demo() -> Result<Demo, ExperimentError> {
    let circles = [0.5, 1.0, 2.0, 4.4, 10.0, 40.0].iter().map(|&d| circle::solve(d)).collect();
    let setup = paper_setup(2.0);
    let belief = fig5(4)?;
    let mut four = Vec::new();
    for c in lineup(&setup, &belief, LineupOptions::default())? {
        let e = expected(&c.list, &setup, &belief).time;
        four.push((c.name, e, worst_case(&c.list, &setup).worst_ratio));
    }
    let chart = LineChart {
        title: "Circle strategy: competitive ratio c(d)".into(),
        x_label: "distance d (units of v·τ)".into(),
        y_label: "competitive ratio c".into(),
        series: vec![
            Series::line("c(d)", ratio_curve(20.0, 800)),
            Series::line("lower bound 2", vec![(0.0, 2.0), (20.0, 2.0)]).dashed(),
        ],
    };
    Ok(Demo { circles, strategies: four, chart })
}
