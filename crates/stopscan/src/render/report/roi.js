// The replay of a grid mission (render::report::roi_report): the team's robots move along
// their flights in time, and each region cell is marked when a robot first reaches it.
(function () {
  const D = RUN;
  const rec = D.record;
  const env = rec.environment;
  const colours = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"];
  const robots = D.robots || [];

  // The cells drawn: the region, the flights (a search starts outside it) and the map.
  let r0 = Infinity, r1 = -Infinity, c0 = Infinity, c1 = -Infinity;
  const see = (r, c) => { r0 = Math.min(r0, r); r1 = Math.max(r1, r); c0 = Math.min(c0, c); c1 = Math.max(c1, c); };
  for (let i = 0; i < D.runs.length; i += 3) { see(D.runs[i], D.runs[i + 1]); see(D.runs[i], D.runs[i + 2]); }
  for (const rb of robots) for (let i = 0; i < rb.cells.length; i += 2) see(rb.cells[i], rb.cells[i + 1]);
  if (D.mapped) for (let i = 0; i < D.mapped.length; i += 2) see(D.mapped[i], D.mapped[i + 1]);
  if (!Number.isFinite(r0)) { r0 = r1 = c0 = c1 = 0; }
  const rows = r1 - r0 + 3, cols = c1 - c0 + 3;
  const px = Math.max(1, Math.min(40, Math.floor(900 / Math.max(rows, cols))));
  const X = (c) => (c - c0 + 1.5) * px, Y = (r) => (r - r0 + 1.5) * px;

  document.getElementById("subtitle").textContent =
    `${rec.robots.length} robots; ${env.cells} cells of ${fmt(env.cell_size)} m; drift ${fmt(env.drift.speed)} m/s at ${fmt(env.drift.heading_deg)}°; ` +
    `strategy ${rec.strategy.name}; seed ${D.seed}; stopscan ${rec.stopscan_version}`;
  const view = document.getElementById("view");
  const canvas = htmlEl("canvas", { width: cols * px, height: rows * px, id: "grid" }, null, view);
  const g = canvas.getContext("2d");
  const legend = htmlEl("div", { class: "legend" }, null, view);
  const key = (colour, text) => {
    const k = htmlEl("span", {}, null, legend);
    htmlEl("span", { class: "key", style: `background:${colour}` }, null, k);
    k.appendChild(document.createTextNode(text));
  };
  key("#d9e8d2", "region, not yet reached");
  key("#5f9e4a", "cells marked (a robot has stood on them)");
  if (D.shape) key("#1f3fbf", "the true region's outline");
  if (D.mapped) key("#333", "the map (outlined, at the end)");
  robots.forEach((rb) => key(colours[rb.id % colours.length], `robot ${rb.id}`));
  if (!D.robots) htmlEl("p", { class: "note" }, `${D.flown_cells} flown cells: too many to replay, flights left out`, view);

  // When each region cell is first reached (region cells only), and each robot's legs.
  const id = (r, c) => `${r},${c}`;
  const inRegion = new Set();
  for (let i = 0; i < D.runs.length; i += 3) for (let c = D.runs[i + 1]; c <= D.runs[i + 2]; c++) inRegion.add(id(D.runs[i], c));
  const firstReached = new Map();
  for (const rb of robots) {
    for (let i = 0; i < rb.times.length; i++) {
      const [r, c, t] = [rb.cells[2 * i], rb.cells[2 * i + 1], rb.times[i]];
      const k = id(r, c);
      if (!inRegion.has(k)) continue;
      const seen = firstReached.get(k);
      if (!seen || seen[2] > t) firstReached.set(k, [r, c, t]);
    }
  }
  const marked = [...firstReached.values()].sort((a, b) => a[2] - b[2]);
  // A robot stays on a cell for its scan, then flies on: it leaves cell i at
  // max(arrival_i, arrival_{i+1} - flight), flight = move time + distance / speed (cells times size).
  const scanTimes = (rb) => new Set((rec.robots.find((x) => x.id === rb.id) || { scans: [] }).scans.map((s) => s.time));
  const legs = robots.map((rb) => {
    const scans = scanTimes(rb);
    const out = [];
    for (let i = 0; i < rb.times.length; i++) {
      const dwell = scans.has(rb.times[i]) ? rec.cost_model.scan_time : 0;
      out.push(rb.times[i] + dwell);
    }
    return out;
  });

  // Steps: the start, every arrival, every finish; at most 2,000, evenly chosen.
  let times = [0];
  for (const rb of robots) { times.push(...rb.times, rb.finish); }
  times.push(rec.metrics.time);
  times = [...new Set(times.filter(Number.isFinite))].sort((a, b) => a - b);
  if (times.length > 2000) {
    const n = times.length;
    times = Array.from({ length: 2000 }, (_, i) => times[Math.round((i * (n - 1)) / 1999)]);
  }

  const position = (rb, depart, t) => {
    const n = rb.times.length;
    if (n === 0) return null;
    if (t <= rb.times[0]) return [rb.cells[0], rb.cells[1]];
    let lo = 0, hi = n - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (rb.times[mid] <= t) lo = mid; else hi = mid - 1; }
    const i = lo;
    const here = [rb.cells[2 * i], rb.cells[2 * i + 1]];
    if (i === n - 1) return here;
    const next = [rb.cells[2 * i + 2], rb.cells[2 * i + 3]];
    const ti = rb.times[i + 1];
    const dist = Math.hypot(next[0] - here[0], next[1] - here[1]) * env.cell_size;
    const flight = rec.cost_model.move_time + dist / rec.cost_model.speed;
    const leave = Math.min(ti, Math.max(depart[i], ti - flight));
    if (t <= leave) return here;
    const u = ti > leave ? (t - leave) / (ti - leave) : 1;
    return [here[0] + u * (next[0] - here[0]), here[1] + u * (next[1] - here[1])];
  };

  const panel = document.getElementById("panel");
  const m = rec.metrics, b = rec.bounds;
  const now = table(panel, "At this time", [
    ["time (s)", "", null, "time"],
    ["cells marked", "", `of ${env.cells}`, "marked"],
    ["robots home", "", null, "home"],
  ]);
  table(panel, "The mission", [
    ["scans", fmt(m.scans)],
    ["moves", fmt(m.moves)],
    ["distance flown (m)", fmt(m.distance)],
    ["exploration time (s)", fmt(m.time), "when the last robot is back"],
    ["scan time, all robots (s)", fmt(m.scan_time_total)],
    ["move time, all robots (s)", fmt(m.move_time_total)],
    ["travel time, all robots (s)", fmt(m.travel_time_total)],
    ["cells visited", fmt(m.visited_cells), `coverage ${fmt(m.coverage, 6)}`],
    ...(m.mapped_cells !== null && m.mapped_cells !== undefined ? [["cells mapped", fmt(m.mapped_cells), `IoU ${fmt(m.iou, 4)}`]] : []),
  ]);
  const bar = timeBar(panel);
  bar([["scan", m.scan_time_total, "#3b7dd8"], ["move", m.move_time_total, "#9467bd"], ["travel", m.travel_time_total, "#f08c00"]]);
  htmlEl("div", { class: "note" }, "time summed over the robots: scan, move, travel", panel);
  table(panel, "Bounds (ROI paper)", [
    ["d_max", fmt(b.d_max)],
    ["Lemma 1 upper bound (s)", fmt(b.lemma1_upper)],
    ["Lemma 2 lower bound (s)", fmt(b.lemma2_lower)],
    ["within Lemma 1", b.within_lemma1 === null || b.within_lemma1 === undefined ? "–" : String(b.within_lemma1)],
    ["competitive ratio (time / Lemma 2)", fmt(b.competitive_ratio)],
    ["Theorem 1 ratio", fmt(b.theorem1_ratio)],
    ["Theorem 2 ratio", fmt(b.theorem2_ratio)],
    ["lawn mower (s)", fmt(b.lawn_mower)],
    ["eccentricity (cells)", fmt(b.eccentricity)],
  ]);
  if (rec.failures && rec.failures.length) htmlEl("p", { class: "note", style: "color:#b00" }, rec.failures.join("; "), panel);

  const cell = (r, c, inset) => g.fillRect(X(c) - px / 2 + inset, Y(r) - px / 2 + inset, px - 2 * inset, px - 2 * inset);
  const render = (k) => {
    const t = times[k];
    g.fillStyle = "#f4f4f4";
    g.fillRect(0, 0, canvas.width, canvas.height);
    g.fillStyle = "#d9e8d2";
    for (let i = 0; i < D.runs.length; i += 3) {
      const r = D.runs[i];
      g.fillRect(X(D.runs[i + 1]) - px / 2, Y(r) - px / 2, (D.runs[i + 2] - D.runs[i + 1] + 1) * px, px);
    }
    g.fillStyle = "#5f9e4a";
    let n = 0;
    for (const [r, c, tm] of marked) { if (tm > t) break; cell(r, c, px > 4 ? 0.5 : 0); n++; }
    if (D.shape) {
      g.strokeStyle = "#1f3fbf"; g.lineWidth = Math.max(1, px / 8);
      g.beginPath();
      for (const ring of D.shape) {
        for (let i = 0; i < ring.length; i += 2) (i ? g.lineTo : g.moveTo).call(g, X(ring[i]), Y(ring[i + 1]));
        g.closePath();
      }
      g.stroke();
    }
    const end = k === times.length - 1;
    if (D.mapped && end) {
      g.strokeStyle = "#333"; g.lineWidth = Math.max(0.5, px / 10);
      for (let i = 0; i < D.mapped.length; i += 2) g.strokeRect(X(D.mapped[i + 1]) - px / 2, Y(D.mapped[i]) - px / 2, px, px);
    }
    let home = 0;
    robots.forEach((rb, j) => {
      const colour = colours[rb.id % colours.length];
      // The flight so far.
      g.strokeStyle = colour; g.globalAlpha = 0.55; g.lineWidth = Math.max(1, px / 6);
      g.beginPath();
      for (let i = 0; i < rb.times.length && rb.times[i] <= t; i++) (i ? g.lineTo : g.moveTo).call(g, X(rb.cells[2 * i + 1]), Y(rb.cells[2 * i]));
      const p = position(rb, legs[j], t);
      if (p) g.lineTo(X(p[1]), Y(p[0]));
      g.stroke();
      g.globalAlpha = 1;
      if (p) {
        g.fillStyle = colour; g.strokeStyle = "#000"; g.lineWidth = 1;
        g.beginPath(); g.arc(X(p[1]), Y(p[0]), Math.max(3, px / 3), 0, 2 * Math.PI); g.fill(); g.stroke();
      }
      if (t >= rb.finish) home++;
    });
    now.time.textContent = fmt(t);
    now.marked.textContent = String(n);
    now.home.textContent = `${home} of ${robots.length}`;
    canvas.dataset.marked = String(n);
  };
  const label = (k) => `step ${k} of ${times.length - 1}: t = ${fmt(times[k])} s`;
  player(times.length, render, label);
})();
