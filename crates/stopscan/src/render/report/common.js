"use strict";
// The run's data, embedded by stopscan (render::report).
const RUN = JSON.parse(document.getElementById("run-data").textContent);
const SVGNS = "http://www.w3.org/2000/svg";

/** An SVG element with attributes, appended to parent when given. */
function svgEl(tag, attrs, parent) {
  const e = document.createElementNS(SVGNS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}

/** An HTML element with attributes and text, appended to parent when given. */
function htmlEl(tag, attrs, text, parent) {
  const e = document.createElement(tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (text !== undefined && text !== null) e.textContent = text;
  if (parent) parent.appendChild(e);
  return e;
}

/** A number as the summary table prints it: integers whole, others with `digits` decimals. */
function fmt(v, digits) {
  if (v === null || v === undefined) return "–";
  if (typeof v !== "number") return String(v);
  if (!Number.isFinite(v)) return String(v);
  if (Number.isInteger(v) && digits === undefined) return String(v);
  return v.toFixed(digits === undefined ? 3 : digits);
}

/** A table of [label, value, note] rows under a heading; returns the value cells by key. */
function table(parent, heading, rows) {
  htmlEl("h2", {}, heading, parent);
  const t = htmlEl("table", {}, null, parent);
  const cells = {};
  for (const [label, value, note, key] of rows) {
    const tr = htmlEl("tr", {}, null, t);
    const l = htmlEl("td", {}, label, tr);
    if (note) htmlEl("div", { class: "note" }, note, l);
    cells[key || label] = htmlEl("td", { class: "v" }, value, tr);
  }
  return cells;
}

/** The stacked bar of a time split: [[name, seconds, colour], ...]. */
function timeBar(parent) {
  const bar = htmlEl("div", { class: "bar", title: "time split into its terms" }, null, parent);
  return (terms) => {
    const total = terms.reduce((s, t) => s + t[1], 0);
    bar.replaceChildren();
    for (const [name, v, colour] of terms) {
      const w = total > 0 ? (100 * v) / total : 0;
      htmlEl("span", { style: `width:${w}%;background:${colour}`, title: `${name}: ${fmt(v)} s` }, null, bar);
    }
  };
}

/** Options from the address: "#step=5&play". */
function hashParams() {
  const out = {};
  for (const part of location.hash.replace(/^#/, "").split("&")) {
    if (!part) continue;
    const [k, v] = part.split("=");
    out[decodeURIComponent(k)] = v === undefined ? true : decodeURIComponent(v);
  }
  return out;
}

/**
 * The controls: first, back, play/pause, forward, last, a slider over steps 0..count-1, the
 * step's label and the speed. render(k) draws step k. Space plays or pauses; the arrow keys
 * step; Home and End jump.
 */
function player(count, render, label) {
  const nav = document.getElementById("controls");
  const button = (text, title) => htmlEl("button", { type: "button", title }, text, nav);
  const first = button("|◀", "first step (Home)");
  const back = button("◀", "step back (←)");
  const play = button("Play", "play / pause (space)");
  play.id = "play";
  const fwd = button("▶", "step forward (→)");
  const last = button("▶|", "last step (End)");
  const slider = htmlEl("input", { type: "range", min: 0, max: Math.max(count - 1, 0), step: 1, value: 0, id: "slider", "aria-label": "step" }, null, nav);
  const text = htmlEl("span", { id: "step-label" }, "", nav);
  const speed = htmlEl("select", { id: "speed", title: "playback speed" }, null, nav);
  for (const s of [0.25, 0.5, 1, 2, 4, 8]) {
    const o = htmlEl("option", { value: s }, `×${s}`, speed);
    if (s === 1) o.selected = true;
  }
  // The whole run plays in about 20 s at ×1, and never faster than 30 steps a second.
  const baseRate = Math.min(30, Math.max(2, count / 20));
  let at = -1;
  let timer = null;
  const show = (k) => {
    k = Math.max(0, Math.min(count - 1, k | 0));
    if (k === at) return;
    at = k;
    render(k);
    slider.value = k;
    text.textContent = label(k);
    document.body.dataset.step = String(k);
  };
  const stop = () => {
    if (timer !== null) clearInterval(timer);
    timer = null;
    play.textContent = "Play";
    document.body.dataset.playing = "false";
  };
  const start = () => {
    if (at >= count - 1) show(0);
    stop();
    play.textContent = "Pause";
    document.body.dataset.playing = "true";
    timer = setInterval(() => {
      if (at >= count - 1) stop();
      else show(at + 1);
    }, 1000 / (baseRate * Number(speed.value)));
  };
  play.onclick = () => (timer === null ? start() : stop());
  first.onclick = () => { stop(); show(0); };
  last.onclick = () => { stop(); show(count - 1); };
  back.onclick = () => { stop(); show(at - 1); };
  fwd.onclick = () => { stop(); show(at + 1); };
  slider.oninput = () => { stop(); show(Number(slider.value)); };
  speed.onchange = () => { if (timer !== null) start(); };
  document.addEventListener("keydown", (e) => {
    if (e.target && e.target.tagName === "SELECT") return;
    const keys = { " ": () => play.onclick(), ArrowLeft: () => back.onclick(), ArrowRight: () => fwd.onclick(), Home: () => first.onclick(), End: () => last.onclick() };
    if (keys[e.key]) { e.preventDefault(); keys[e.key](); }
  });
  const h = hashParams();
  // Opens on the finished run; play starts again from the first step.
  show(h.step !== undefined ? Number(h.step) : count - 1);
  document.body.dataset.firstFrameMs = performance.now().toFixed(1);
  if (h.play) start();
  return { show, start, stop };
}
