// The replay of a polygon exploration (render::report::polygon_report).
(function () {
  const D = RUN;
  const rec = D.record;
  const [x0, y0, x1, y1] = D.bounds;
  const extent = Math.max(x1 - x0, y1 - y0, 1e-9);
  const pad = extent * 0.02;
  const W = x1 - x0 + 2 * pad, H = y1 - y0 + 2 * pad;
  // Picture coordinates: x to the right, y down (the map's y up).
  const X = (x) => (x - x0 + pad).toFixed(5) * 1;
  const Y = (y) => (y1 - y + pad).toFixed(5) * 1;
  const ringD = (flat) => {
    let d = "";
    for (let i = 0; i < flat.length; i += 2) d += (i ? "L" : "M") + X(flat[i]) + "," + Y(flat[i + 1]);
    return d + "Z";
  };

  document.getElementById("subtitle").textContent =
    `${rec.environment.vertices} vertices, ${rec.environment.holes} holes, r = ${rec.environment.reflex_vertices} reflex; ` +
    `strategy ${rec.strategy.name}; seed ${D.seed}; stopscan ${rec.stopscan_version}`;

  const view = document.getElementById("view");
  const svg = svgEl("svg", { viewBox: `0 0 ${W} ${H}`, id: "map", "font-family": "sans-serif" }, view);
  const stroke = (px) => ({ "stroke-width": px, "vector-effect": "non-scaling-stroke" });
  svgEl("rect", { x: 0, y: 0, width: W, height: H, fill: "#9a9a9a" }, svg);
  svgEl("path", { d: D.domain.map(ringD).join(""), fill: "#fff", "fill-rule": "evenodd", stroke: "#222", ...stroke(1.2), class: "domain" }, svg);
  // Seen space is one colour however often it was seen; each scan's outline shows faintly.
  const scans = svgEl("g", { id: "scans", fill: "#cfe0f7", stroke: "#3b7dd8", "stroke-opacity": 0.3 }, svg);
  if (D.cspace) {
    svgEl("path", { d: D.cspace.map(ringD).join(""), fill: "#2e9e44", "fill-opacity": 0.1, "fill-rule": "evenodd", stroke: "#2e9e44", "stroke-opacity": 0.5, ...stroke(0.6), "stroke-dasharray": "3 2", class: "cspace" }, svg);
  }
  const latest = svgEl("path", { fill: "#3b7dd8", "fill-opacity": 0.25, stroke: "#1d4f9a", ...stroke(1.4), id: "latest" }, svg);
  const open = svgEl("g", { id: "open" }, svg);
  const path = svgEl("polyline", { fill: "none", stroke: "#f08c00", ...stroke(1.6), id: "path" }, svg);
  const stops = svgEl("g", { id: "stops", fill: "#7a1fa2", stroke: "#fff" }, svg);
  const rMarker = extent / 160;
  if (D.path.length >= 2) {
    const s = rMarker * 1.6;
    svgEl("rect", { x: X(D.path[0]) - s / 2, y: Y(D.path[1]) - s / 2, width: s, height: s, fill: "#111", class: "start" }, svg);
  }
  const robot = svgEl("circle", { r: rMarker * 1.5, fill: "#f08c00", stroke: "#000", ...stroke(1), id: "robot" }, svg);
  const legend = htmlEl("div", { class: "legend" }, null, view);
  const key = (colour, text, extra) => {
    const k = htmlEl("span", {}, null, legend);
    htmlEl("span", { class: "key", style: `background:${colour};${extra || ""}` }, null, k);
    k.appendChild(document.createTextNode(text));
  };
  key("#fff", "free space");
  key("#cfe0f7", "seen by the scans so far");
  key("rgba(59,125,216,.6)", "the latest scan's region", "border-color:#1d4f9a");
  key("#e0301e", "frontiers left open");
  key("#f08c00", "path driven; robot");
  key("#7a1fa2", "scan points");
  key("#111", "start");
  if (D.cspace) key("rgba(46,158,68,.25)", "configuration space (where the robot may stand)");

  // The panel: this step's tally and time, then the run's results beside its bounds.
  const panel = document.getElementById("panel");
  const m = rec.metrics, b = rec.bounds, c = rec.cost_model;
  const step = table(panel, "At this step", [
    ["scans", "", null, "scans"],
    ["moves", "", null, "moves"],
    ["distance (m)", "", null, "distance"],
    ["scan time (s)", "", `${fmt(c.scan_time)} s per scan`, "scan_time_total"],
    ["move time (s)", "", `${fmt(c.move_time)} s per move`, "move_time_total"],
    ["travel time (s)", "", `distance / ${fmt(c.speed)} m/s`, "travel_time_total"],
    ["total time (s)", "", null, "time"],
    ["frontiers left open", "", "red on the map", "open"],
  ]);
  const bar = timeBar(panel);
  const barKey = htmlEl("div", { class: "note" }, null, panel);
  barKey.innerHTML = '<span class="key" style="background:#3b7dd8"></span>scan <span class="key" style="background:#9467bd"></span>move <span class="key" style="background:#f08c00"></span>travel';
  const ratio = (v) => (v === null || v === undefined ? "–" : fmt(v));
  table(panel, "The run", [
    ["scans", fmt(m.scans)],
    ["total time (s)", fmt(m.time), `${fmt(m.scan_time_total)} scan + ${fmt(m.move_time_total)} move + ${fmt(m.travel_time_total)} travel`],
    ["coverage", fmt(m.coverage, 6), `${fmt(m.covered_area)} of ${fmt(rec.environment.free_area)} m²`],
    ["windows left open", fmt(m.open_windows)],
    ["lower bound: scans", fmt(b.scans_lower), b.scans_lower_rule],
    ["upper bound (paper)", fmt(b.scans_upper), b.scans_upper_rule],
    ["lower bound: distance (m)", fmt(b.distance_lower)],
    ["lower bound: time (s)", fmt(b.time_lower)],
    ["certified ratio (time / lower bound)", ratio(b.certified_ratio), b.bounds_complete === false ? "bounds cut short by their budget" : null],
    ["offline greedy reference (views)", fmt(b.greedy_reference)],
    ["offline optimum (views)", fmt(b.optimum), b.optimum_note || null],
  ]);
  // A record's object as rows: numbers and flags as values, words and nested objects as notes.
  const rows = (o) => Object.keys(o).map((k) => {
    const v = o[k], label = k.replace(/_/g, " ");
    if (typeof v === "number" || typeof v === "boolean") return [label, fmt(v)];
    if (typeof v === "string" && v.length <= 20) return [label, v];
    return [label, "", typeof v === "string" ? v : JSON.stringify(v)];
  });
  if (rec.robot) table(panel, "The footprint", rows(rec.robot));
  if (rec.raw_scans) {
    const r = rec.raw_scans;
    table(panel, "Raw scans", rows(Object.fromEntries(Object.entries(r).filter(([, v]) => !Array.isArray(v)))));
  }
  if (rec.error) htmlEl("p", { class: "note", style: "color:#b00" }, `The run ended early: ${rec.error}`, panel);
  table(panel, "Set-up", [
    ...rows({ cost_model: `${fmt(c.scan_time)} s per scan, ${fmt(c.move_time)} s per move, ${fmt(c.speed)} m/s` }),
    ...rows({ ...rec.sensor, range: rec.sensor.range === null ? "unlimited" : rec.sensor.range }),
    ...rows({ strategy_parameters: rec.strategy.params, seed: D.seed }),
  ]);

  // Which frontiers' parts are open at step k: the last entry of each history at or before k.
  const openAt = (k) => {
    let d = "", n = 0;
    for (const f of D.frontiers) {
      if (f.scan + 1 > k) continue;
      let e = null;
      for (const o of f.open) { if (o[0] <= k) e = o; else break; }
      if (!e) continue;
      const [ax, ay] = f.a, [bx, by] = f.b;
      for (let i = 1; i + 1 < e.length; i += 2) {
        const t0 = e[i], t1 = e[i + 1];
        d += `M${X(ax + t0 * (bx - ax))},${Y(ay + t0 * (by - ay))}L${X(ax + t1 * (bx - ax))},${Y(ay + t1 * (by - ay))}`;
        n += 1;
      }
    }
    return [d, n];
  };
  // vector-effect is not inherited: every stroked element carries its own.
  const openPath = svgEl("path", { d: "", stroke: "#e0301e", fill: "none", "stroke-linecap": "round", ...stroke(3.5) }, open);
  const scanD = D.scans.map(() => null);

  const render = (k) => {
    const f = D.frames[k];
    // One <path class="scan"> per scan taken so far.
    while (scans.childElementCount > f.scans) scans.lastChild.remove();
    while (scans.childElementCount < f.scans) {
      const i = scans.childElementCount;
      scanD[i] = scanD[i] || ringD(D.scans[i].poly);
      svgEl("path", { d: scanD[i], class: "scan", "data-scan": i + 1, ...stroke(0.5) }, scans);
    }
    while (stops.childElementCount > f.scans) stops.lastChild.remove();
    while (stops.childElementCount < f.scans) {
      const i = stops.childElementCount, s = D.scans[i];
      const c = svgEl("circle", { cx: X(s.at[0]), cy: Y(s.at[1]), r: rMarker, class: "stop", ...stroke(0.8) }, stops);
      c.appendChild(svgEl("title", {})).textContent = `scan ${i + 1}`;
    }
    latest.setAttribute("d", f.scans > 0 ? scanD[f.scans - 1] : "");
    let pts = "";
    for (let i = 0; i < f.path && 2 * i + 1 < D.path.length; i++) pts += `${X(D.path[2 * i])},${Y(D.path[2 * i + 1])} `;
    path.setAttribute("points", pts);
    const last = Math.max(0, Math.min(f.path, D.path.length / 2) - 1);
    robot.setAttribute("cx", X(D.path[2 * last] || 0));
    robot.setAttribute("cy", Y(D.path[2 * last + 1] || 0));
    const [d, n] = openAt(k);
    openPath.setAttribute("d", d);
    for (const key of ["scans", "moves"]) step[key].textContent = fmt(f[key]);
    for (const key of ["distance", "scan_time_total", "move_time_total", "travel_time_total", "time"]) step[key].textContent = fmt(f[key]);
    step.open.textContent = String(n);
    bar([["scan", f.scan_time_total, "#3b7dd8"], ["move", f.move_time_total, "#9467bd"], ["travel", f.travel_time_total, "#f08c00"]]);
  };
  const label = (k) => {
    const f = D.frames[k];
    const end = k === D.frames.length - 1 && f.scans === D.scans.length ? " (end)" : "";
    return `step ${k} of ${D.frames.length - 1}: ${f.scans} scans, ${fmt(f.time)} s${end}`;
  };
  player(D.frames.length, render, label);
})();
