// The offline survey form (survey_form.hpp). The page carries the key table (survey/schema.hpp) as JSON and builds
// its fields, its checks and its two files from it; nothing about a key is written in the page itself, except how
// each kind of key is typed (a length as a number and a unit, a range as "0.4-0.6" or "[0.4, 0.6]").
#include "topple/output/survey_form.hpp"

#include "topple/solvers/flexible.hpp"
#include "topple/survey/schema.hpp"

namespace topple::io {

nlohmann::ordered_json survey_schema_json() {
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const SurveyKey& k : survey_schema()) {
    nlohmann::ordered_json j;
    j["table"] = k.table;
    j["key"] = k.key;
    j["kind"] = std::string(survey_key_kind_name(k.kind));
    j["unit"] = k.unit;
    const auto bound = [](const std::optional<SurveyKeyBound>& b) {
      return b ? nlohmann::ordered_json{{"value", b->value}, {"inclusive", b->inclusive}} : nlohmann::ordered_json();
    };
    j["low"] = bound(k.low);
    j["high"] = bound(k.high);
    j["range_problem"] = k.range_problem;
    j["choices"] = k.choices;
    j["required"] = k.required;
    j["required_for_shapes"] = k.required_for_shapes;
    j["missing_problem"] = k.missing_problem;
    nlohmann::ordered_json conditions = nlohmann::ordered_json::array();
    for (const SurveyKeyCondition& c : k.conditions) {
      conditions.push_back({{"key", c.key}, {"values", c.values}, {"problem", c.problem}});
    }
    j["conditions"] = conditions;
    j["default"] = k.default_text;
    j["help"] = k.help;
    j["example"] = k.example;
    j["in_form"] = k.in_form;
    keys.push_back(std::move(j));
  }
  nlohmann::ordered_json friction = nlohmann::ordered_json::array();
  for (const FrictionRow& row : friction_table()) {
    friction.push_back({{"surfaces", row.surfaces}, {"mu_low", row.mu_low}, {"mu_high", row.mu_high},
                        {"source", row.source}});
  }
  // The reader's upper limit on a flexible support's frequency (survey_file.cpp's parse_support_filter, the library's
  // SupportOscillator::kMaxFreqHz), which the key table does not carry.
  return {{"keys", keys},
          {"friction", friction},
          {"support_max_freq_hz", SupportOscillator::kMaxFreqHz},
          {"fall_direction_problem", kFallDirectionProblem}};
}

namespace {

// The page, before the schema is put in its place (@SCHEMA@). Plain ES2017 that Chromium, Firefox and Safari on
// phones run; no external resource of any kind (the test checks the page names no http(s) URL it loads).
constexpr const char* kPage = R"PAGE(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>topple survey form</title>
<style>
body { font-family: system-ui, sans-serif; margin: 0 auto; max-width: 60rem; padding: 0.5rem 1rem 4rem; color: #222; }
h1 { font-size: 1.4rem; } h2 { font-size: 1.15rem; margin-top: 1.6rem; border-bottom: 1px solid #ccc; }
.fields { display: grid; grid-template-columns: repeat(auto-fill, minmax(17rem, 1fr)); gap: 0.5rem 1rem; }
.field label { display: block; font-weight: 600; font-family: ui-monospace, monospace; font-size: 0.95rem; }
.field input, .field select { font-size: 1rem; padding: 0.25rem; max-width: 100%; box-sizing: border-box; }
.field input.n { width: 6.5rem; } .field input.t { width: 100%; }
.field small { display: block; color: #555; font-size: 0.8rem; }
.field .error { color: #b00020; font-size: 0.85rem; }
.field.bad input, .field.bad select { border: 2px solid #b00020; }
.object { border: 1px solid #bbb; border-radius: 6px; padding: 0.5rem 0.8rem; margin: 0.8rem 0; }
.object h3 { margin: 0.2rem 0 0.5rem; font-size: 1rem; }
.population { border-color: #7a9; }
button { font-size: 1rem; padding: 0.4rem 0.9rem; margin: 0.2rem 0.4rem 0.2rem 0; }
#errors li { color: #b00020; } #status { font-weight: 600; }
textarea { width: 100%; height: 12rem; font-family: ui-monospace, monospace; font-size: 0.85rem; }
.hidden { display: none; }
</style>
</head>
<body>
<h1>topple: field survey</h1>
<p>This page works offline: nothing leaves this device. Fill in the site, the earthquake if known, and every object
you observed, one by one or as populations of similar objects counted together ("71 of 212 stones toppled",
their sizes as ranges or a measured sample); the checks below each field are those of <code>topple invert</code>'s
reader. Save the survey as TOML
or CSV and run <code>topple invert survey.toml</code>. Lengths take their unit; a friction coefficient, restitution or
amplification may be a value (<code>0.5</code>) or a range (<code>0.4-0.6</code> or <code>[0.4, 0.6]</code>).
A population's sizes are a value or a range (<code>40-50</code>) in the unit beside them, or a measured sample, one
member per line. An object's or a population's <code>support</code> is a text ("furniture") or, with its natural
frequency and damping ratio given beside it, a flexible support (its text then names it). Keys not offered here
(meshes, record files, a site's default flexible support) are written in the file: docs/survey.md.</p>
<h2>Site</h2><div id="site" class="fields"></div>
<h2>Earthquake (optional)</h2><div id="event" class="fields"></div>
<h2>Inversion settings (optional)</h2><div id="inversion" class="fields"></div>
<h2>Objects</h2><div id="objects"></div>
<button type="button" id="add-object">Add an object</button>
<h2>Populations (optional)</h2><div id="populations"></div>
<button type="button" id="add-population">Add a population</button>
<h2>Save</h2>
<button type="button" id="save-toml">Save TOML</button><button type="button" id="save-csv">Save CSV</button>
<p id="status"></p>
<ul id="errors"></ul>
<label for="toml-out">survey.toml</label><textarea id="toml-out" readonly></textarea>
<label for="csv-out">survey.csv</label><textarea id="csv-out" readonly></textarea>
<details><summary>Keys written in the file, not in this form</summary><ul id="not-in-form"></ul></details>
<div id="runs" class="hidden"></div>
<script type="application/json" id="schema">@SCHEMA@</script>
<script>
'use strict';
const SCHEMA = JSON.parse(document.getElementById('schema').textContent);
const KEYS = SCHEMA.keys;
const LENGTH_UNITS = {mm: 0.001, cm: 0.01, m: 1.0, in: 0.0254, ft: 0.3048};  // core/units.cpp, parse_length_m
const AREA_UNITS = ['cm2', 'mm2', 'm2'];
const NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;
const RANGE = /^\[?\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(?:,|-|–|to)\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*\]?$/;
const FORM_TABLES = ['site', 'event', 'inversion', 'object', 'population'];
// family = "records" needs its record files, which are written in the file: the form offers the other families.
const NOT_OFFERED = {'inversion.family': ['records']};

function keysOf(table) { return KEYS.filter(k => k.table === table && k.in_form); }
function schemaKey(table, key) { return KEYS.find(k => k.table === table && k.key === key); }
function el(tag, attrs, children) {
  const e = document.createElement(tag);
  for (const [a, v] of Object.entries(attrs || {})) {
    if (a === 'text') e.textContent = v; else e.setAttribute(a, v);
  }
  for (const c of children || []) e.appendChild(c);
  return e;
}
// A number as the reader prints it: fmt's "{}" and JavaScript's String() both give the shortest round-trip form.
function show(v) { return String(v); }
function fill(problem, values) {
  let i = 0;
  return problem.replace(/\{\}/g, () => show(values[Math.min(i++, values.length - 1)]));
}
function outside(k, v) {
  if (k.low && (k.low.inclusive ? v < k.low.value : !(v > k.low.value))) return true;
  if (k.high && (k.high.inclusive ? v > k.high.value : !(v < k.high.value))) return true;
  return false;
}

// ---- fields ----
function makeField(k, scope) {
  const inputs = [];
  const add = (node) => { inputs.push(node); return node; };
  const box = el('div', {class: 'field', 'data-key': k.key});
  const id = scope + '-' + k.key;
  const unit = k.unit ? ' (' + k.unit + ')' : '';
  box.appendChild(el('label', {for: id, text: k.key + unit + (k.required ? ' *' : '')}));
  const text = (cls, ph) => add(el('input', {id: inputs.length ? id + '-' + inputs.length : id, class: cls,
                                           type: 'text', placeholder: ph || '', autocomplete: 'off'}));
  if (k.kind === 'choice') {
    const s = add(el('select', {id: id}));
    s.appendChild(el('option', {value: '', text: k.default ? '(default: ' + k.default + ')' : '(not given)'}));
    const skip = NOT_OFFERED[k.table + '.' + k.key] || [];
    for (const c of k.choices) if (!skip.includes(c)) s.appendChild(el('option', {value: c, text: c}));
    box.appendChild(s);
  } else if (k.kind === 'tables') {
    // A population's measured sample: one member per line, its two sizes (width and height; a cylinder's diameter
    // and height), each a number with the unit beside or its own ("45, 100" or "45cm 1m").
    box.appendChild(add(el('textarea', {id: id, class: 'sample', rows: '4', placeholder: '45, 100\n48, 105'})));
    const s = add(el('select', {id: id + '-unit', 'aria-label': k.key + ' unit'}));
    for (const u of Object.keys(LENGTH_UNITS)) s.appendChild(el('option', {value: u, text: u}));
    s.value = 'cm';
    box.appendChild(s);
  } else if (k.kind === 'length' || k.kind === 'area') {
    box.appendChild(text(k.table === 'population' ? 't' : 'n', k.table === 'population' ? '45 or 40-50' : 'number'));
    const s = add(el('select', {id: id + '-unit', 'aria-label': k.key + ' unit'}));
    for (const u of (k.kind === 'length' ? Object.keys(LENGTH_UNITS) : AREA_UNITS)) {
      s.appendChild(el('option', {value: u, text: u}));
    }
    s.value = k.kind === 'length' ? 'cm' : 'cm2';
    box.appendChild(s);
  } else if (k.kind === 'support') {
    // Free text; with freq_hz and damping a flexible support (docs/survey.md, "Flexible supports"), the text its name.
    box.appendChild(text('t', 'text, e.g. furniture'));
    for (const name of ['freq_hz', 'damping']) {
      const sk = schemaKey('support', name);
      box.appendChild(el('small', {text: 'flexible: ' + name + (sk.unit ? ' (' + sk.unit + ')' : '')}));
      box.appendChild(text('n', sk.example.replace(/[\[\]]/g, '').replace(', ', '-')));
    }
  } else if (k.kind === 'axis') {
    for (const ph of ['min', 'max', 'count']) box.appendChild(text('n', ph));
  } else if (k.kind === 'lat_lon') {
    for (const ph of ['lat', 'lon']) box.appendChild(text('n', ph));
  } else if (k.kind === 'value_or_range') {
    box.appendChild(text('t', k.choices.length ? k.choices[0] + ', 0.5 or 0.4-0.6' : '0.5 or 0.4-0.6'));
  } else {
    box.appendChild(text(k.kind === 'number' || k.kind === 'integer' ? 'n' : 't', ''));
  }
  if (k.key === 'mu' && (k.table === 'object' || k.table === 'population')) {
    // The friction table of docs/survey.md: choosing a pair of surfaces fills mu with its range.
    const s = el('select', {id: id + '-material', 'aria-label': 'surfaces'});
    s.appendChild(el('option', {value: '', text: '(surfaces: fill mu from the table)'}));
    SCHEMA.friction.forEach((row, i) => s.appendChild(el('option', {value: String(i),
        text: row.surfaces + ': ' + row.mu_low + '–' + row.mu_high})));
    s.addEventListener('change', () => {
      if (s.value === '') return;
      const row = SCHEMA.friction[Number(s.value)];
      inputs[0].value = '[' + row.mu_low + ', ' + row.mu_high + ']';
      validate();
    });
    box.appendChild(s);
    box.material = s;
  }
  box.appendChild(el('small', {text: k.help}));
  box.appendChild(el('div', {class: 'error'}));
  box.inputs = inputs;
  box.initial = inputs.map(i => i.value);  // what clearForm() puts back
  box.schema = k;
  for (const i of inputs) i.addEventListener(i.tagName === 'SELECT' ? 'change' : 'input', validate);
  return box;
}

// What a field holds: {given, toml, csv, value (a number or the choice's text), problem}.
function readField(box) {
  const k = box.schema;
  const raw = box.inputs.map(i => i.value.trim());
  if (raw.every(v => v === '') || (k.kind === 'length' || k.kind === 'area' || k.kind === 'tables') && raw[0] === '') {
    return {given: false};
  }
  const num = (t) => NUMBER.test(t) ? Number(t) : null;
  const bad = (problem) => ({given: true, problem: problem});
  switch (k.kind) {
    case 'text': return {given: true, toml: quoted(raw[0]), csv: raw[0], value: raw[0]};
    case 'support': return supportOf(raw);
    case 'choice': {
      const n = num(raw[0]);
      const toml = n !== null ? raw[0] : JSON.stringify(raw[0]);
      return {given: true, toml: toml, csv: raw[0], value: raw[0]};
    }
    case 'number': case 'integer': {
      const v = num(raw[0]);
      if (v === null) return bad('expected a number');
      if (k.table === 'population' && k.kind === 'integer') {
        // A population's counts as survey_file.cpp's population_count words them, before the key's own range.
        if (v !== Math.floor(v)) return bad('a count is a whole number');
        if (v < 0) return bad(fill(COUNT_PROBLEM, [v]));
      }
      const whole = k.kind === 'integer' && v !== Math.floor(v);
      if (whole || outside(k, v)) return bad(fill(k.range_problem, [v]));
      return {given: true, toml: show(v), csv: show(v), value: v};
    }
    case 'value_or_range': {
      if (k.choices.includes(raw[0])) return {given: true, toml: JSON.stringify(raw[0]), csv: raw[0], value: raw[0]};
      return rangeOf(k, raw[0]);
    }
    case 'length': case 'area': {
      if (k.table === 'population' && SIZES.includes(k.key)) return populationLength(k, raw[0], raw[1]);
      const v = num(raw[0]);
      if (v === null) return bad('expected a number');
      if (k.kind === 'length' && outside(k, v * LENGTH_UNITS[raw[1]])) {
        return bad(fill(k.range_problem, [v * LENGTH_UNITS[raw[1]]]));
      }
      if (k.kind === 'area' && !(v > 0)) return bad('is not a positive area with unit m2, cm2 or mm2');
      const text = show(v) + raw[1];
      return {given: true, toml: JSON.stringify(text), csv: text, value: v, unit: raw[1]};
    }
    case 'axis': {
      const [lo, hi, count] = raw.map(num);
      if (lo === null || hi === null || count === null) return bad('expected [min, max, count]');
      if (!(lo > 0) || !(hi > lo)) return bad(fill(k.range_problem, [lo, hi]));
      if (count < 2 || count > 1000 || count !== Math.floor(count)) {
        return bad('count must be a whole number from 2 to 1000, got ' + show(count));
      }
      const toml = '[' + show(lo) + ', ' + show(hi) + ', ' + show(count) + ']';
      return {given: true, toml: toml, csv: toml, value: lo};
    }
    case 'tables': return populationSample(raw[0], raw[1]);
    case 'numbers': {
      const parts = raw[0].replace(/[\[\]]/g, '').split(/[,;\s]+/).filter(t => t !== '');
      const vs = parts.map(num);
      if (vs.some(v => v === null)) return bad('expected a list of numbers');
      const list = '[' + vs.map(show).join(', ') + ']';
      return {given: true, toml: list, csv: list, value: vs.length, list: vs};
    }
    case 'lat_lon': {
      const [lat, lon] = raw.map(num);
      if (lat === null || lon === null) return bad('expected [lat, lon]');
      const latKey = schemaKey('site', 'lat'), lonKey = schemaKey('site', 'lon');
      if (outside(latKey, lat)) return bad(fill(latKey.range_problem, [lat]));
      if (outside(lonKey, lon)) return bad(fill(lonKey.range_problem, [lon]));
      const toml = '[' + show(lat) + ', ' + show(lon) + ']';
      return {given: true, toml: toml, csv: toml, value: lat};
    }
  }
  return bad('unsupported');
}

function quoted(text) { return JSON.stringify(text).replace(/\x7f/g, '\\u007F'); }
// A value or a range [low, high] of `k` ("0.5", "0.4-0.6", "[0.4, 0.6]"), each end held to k's range.
function rangeOf(k, text) {
  const bad = (problem) => ({given: true, problem: problem});
  let lo, hi;
  if (NUMBER.test(text)) { lo = hi = Number(text); } else {
    const m = RANGE.exec(text);
    if (!m) return bad(k.choices.length ? 'write "' + k.choices[0] + '", a value or a range' : 'expected a number');
    lo = Number(m[1]); hi = Number(m[2]);
    if (lo > hi) return bad('range [' + show(lo) + ', ' + show(hi) + '] has low > high');
  }
  for (const end of [lo, hi]) if (outside(k, end)) return bad(fill(k.range_problem, [end]));
  const toml = lo === hi ? show(lo) : '[' + show(lo) + ', ' + show(hi) + ']';
  return {given: true, toml: toml, csv: toml, value: lo, lo: lo, hi: hi};
}
// An object's or a population's support: free text, or a flexible support {freq_hz, damping, name} when either
// number is given (survey_file.cpp's parse_support_filter: both required; its words, at support.freq_hz or
// support.damping). A problem names its key in `at`.
function supportOf(raw) {
  const [name, freqText, dampingText] = raw;
  if (freqText === '' && dampingText === '') return {given: true, toml: quoted(name), csv: name, value: name};
  const parts = {};
  for (const [key, text] of [['freq_hz', freqText], ['damping', dampingText]]) {
    const k = schemaKey('support', key);
    if (text === '') return {given: true, problem: k.missing_problem, at: key};
    // The range's words; the reader says the damping ratio's with the range read ("..., got [0.05, 1]").
    const r = rangeOf(k, text);
    const typed = rangeOf({low: null, high: null, choices: []}, text);
    if (r.problem && key === 'damping' && !typed.problem) {
      return {given: true, at: key,
              problem: k.range_problem + ', got [' + show(typed.lo) + ', ' + show(typed.hi) + ']'};
    }
    if (r.problem) return {given: true, problem: r.problem, at: key};
    if (key === 'freq_hz' && r.hi > SCHEMA.support_max_freq_hz) {
      return {given: true, at: key, problem: show(r.hi) + ' Hz is above ' + show(SCHEMA.support_max_freq_hz) +
              ' Hz, where no shelf or floor is: a support that stiff moves with the ground (give the support as ' +
              'text for a rigid one)'};
    }
    parts[key] = r.toml;
  }
  const toml = '{freq_hz = ' + parts.freq_hz + ', damping = ' + parts.damping +
               (name ? ', name = ' + quoted(name) : '') + '}';
  return {given: true, toml: toml, csv: toml, value: name, flexible: true};
}

// ---- populations (survey/population.hpp; the reader's words of check_population, held against the reader by
// tests/cli/test_cli_survey_form.cpp) ----
const COUNT_PROBLEM = schemaKey('population', 'overturned').range_problem;  // "a count cannot be negative, got {}"
const SIZES = ['width', 'height', 'diameter'];  // a population's sizes: a length or a range (depth is one length)
// survey.cpp's check_object_fall_direction's words (schema.hpp), of a population's fall directions.
const FALL_PROBLEM = SCHEMA.fall_direction_problem;
// fmt's "{:.4g}" (population.cpp words a size outside the stated range so): 4 significant digits, no trailing zeros.
function g4(v) { return String(Number(v.toPrecision(4))); }
// A size: a length "45" or a range "40-50" / "[40, 50]", in the unit beside it. {lo, hi} as typed, {loM, hiM} in m.
function populationLength(k, text, unit) {
  const bad = (problem) => ({given: true, problem: problem});
  const factor = LENGTH_UNITS[unit];
  let lo, hi;
  if (NUMBER.test(text)) { lo = hi = Number(text); } else {
    const m = RANGE.exec(text);
    if (!m) return bad('expected a length or a range [low, high] of lengths');
    lo = Number(m[1]); hi = Number(m[2]);
  }
  const loM = lo * factor, hiM = hi * factor;
  if (loM > hiM) return bad('range [' + show(loM) + ', ' + show(hiM) + '] m has low > high');
  if (outside(k, loM)) return bad(fill(k.range_problem, [loM]));
  const one = (v) => JSON.stringify(show(v) + unit);
  return {given: true, toml: lo === hi ? one(lo) : '[' + one(lo) + ', ' + one(hi) + ']',
          csv: lo === hi ? show(lo) + unit : null, value: lo, lo: lo, hi: hi, unit: unit, loM: loM, hiM: hiM,
          range: lo !== hi};
}
// The measured sample: one member per line (or separated by ';'), two sizes each; a number takes the unit beside
// the list unless it carries its own. The members' sizes are checked against the ranges in validate().
function populationSample(text, unit) {
  const members = [];
  const lines = text.split(/[\n;]+/).map(t => t.trim()).filter(t => t !== '');
  for (let i = 0; i < lines.length; ++i) {
    const parts = lines[i].split(/[,\s]+/).filter(t => t !== '');
    const sizes = parts.map(p => /^([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([a-z]*)$/.exec(p));
    if (parts.length !== 2 || sizes.some(m => !m || m[2] !== '' && !(m[2] in LENGTH_UNITS))) {
      return {given: true, problem: 'member ' + (i + 1) + ': expected two lengths (width and height; a cylinder: ' +
                                    'diameter and height), e.g. "45, 100"'};
    }
    members.push(sizes.map(m => ({value: Number(m[1]), unit: m[2] || unit, m: Number(m[1]) * LENGTH_UNITS[m[2] || unit]})));
  }
  if (!members.length) {  // survey_file.cpp's population_sample, of sample = []
    return {given: true, problem: 'the measured sample is empty: give its members, or leave sample out and state the ' +
                                  'sizes as ranges'};
  }
  return {given: true, value: members.length, members: members};
}

// ---- the form ----
const objects = [];
const populations = [];
function addPopulation() {
  const box = el('div', {class: 'object population'});
  const title = el('h3', {text: 'population ' + (populations.length + 1)});
  const remove = el('button', {type: 'button', text: 'Remove'});
  remove.addEventListener('click', () => {
    populations.splice(populations.indexOf(box), 1);
    box.remove();
    populations.forEach((p, i) => { p.heading.textContent = 'population ' + (i + 1); });
    validate();
  });
  const fields = el('div', {class: 'fields'});
  box.fields = keysOf('population').map(k => makeField(k, 'population' + (populations.length + 1)));
  for (const f of box.fields) fields.appendChild(f);
  box.appendChild(title);
  box.appendChild(fields);
  box.appendChild(remove);
  box.heading = title;
  populations.push(box);
  document.getElementById('populations').appendChild(box);
  validate();
  return box;
}
function addObject() {
  const n = objects.length + 1;
  const box = el('div', {class: 'object'});
  const title = el('h3', {text: 'object ' + n});
  const remove = el('button', {type: 'button', text: 'Remove'});
  remove.addEventListener('click', () => {
    objects.splice(objects.indexOf(box), 1);
    box.remove();
    objects.forEach((o, i) => { o.heading.textContent = 'object ' + (i + 1); });
    validate();
  });
  const fields = el('div', {class: 'fields'});
  box.fields = keysOf('object').map(k => makeField(k, 'object' + n));
  for (const f of box.fields) fields.appendChild(f);
  box.appendChild(title);
  box.appendChild(fields);
  box.appendChild(remove);
  box.heading = title;
  objects.push(box);
  document.getElementById('objects').appendChild(box);
  validate();
  return box;
}
const tables = {};
for (const t of ['site', 'event', 'inversion']) {
  tables[t] = keysOf(t).map(k => makeField(k, t));
  for (const f of tables[t]) document.getElementById(t).appendChild(f);
}
// A flexible support's keys are offered beside an object's or a population's support (its text is the name); the
// site's default support, meshes and record files are not.
for (const k of KEYS.filter(k => !k.in_form && k.table !== 'support')) {
  document.getElementById('not-in-form').appendChild(el('li', {text: '[' + k.table + '] ' + k.key + ': ' + k.help}));
}
document.getElementById('add-object').addEventListener('click', addObject);
document.getElementById('add-population').addEventListener('click', addPopulation);

function fieldOf(boxes, key) { return boxes.find(b => b.schema.key === key); }

// The shape whose dimensions apply: an object's shape (default block); a general body with b1, b2 or inertia is the
// asymmetric one (docs/survey.md, "Asymmetric bodies").
function shapeOf(fields, read) {
  const shape = read.get('shape').given ? read.get('shape').value : 'block';
  if (shape === 'general' && ['b1', 'b2', 'inertia'].some(k => read.get(k) && read.get(k).given)) {
    return 'general asymmetric';
  }
  return shape;
}
function applies(k, shape) {
  return !k.required_for_shapes.length || k.required_for_shapes.some(s => s === shape || s.split(' ')[0] === shape);
}

// Checks everything; returns {toml, csv, errors}. Each error is "field: problem", the field named as the reader
// names it (site.lat, object[2](vase).mu, inversion.pga_g).
function validate() {
  const errors = [];
  const said = (box, field, problem) => {
    errors.push(field + ': ' + problem);
    if (box) { box.classList.add('bad'); box.querySelector('.error').textContent = problem; }
  };
  const readAll = (boxes) => {
    const m = new Map();
    for (const b of boxes) {
      b.classList.remove('bad');
      b.querySelector('.error').textContent = '';
      m.set(b.schema.key, readField(b));
    }
    return m;
  };
  const read = {site: readAll(tables.site), event: readAll(tables.event), inversion: readAll(tables.inversion)};
  // A condition on another key (schema.hpp, SurveyKeyCondition): "table.key" or a key of the same table; its value
  // as given, or its default when absent; "<absent>": it must not be given; no values: it must be given.
  const holds = (table, own, c) => {
    const [t, name] = c.key.includes('.') ? c.key.split('.') : [table, c.key];
    const m = t === table ? own : read[t];
    const r = m ? m.get(name) : undefined;
    if (r && r.given && r.problem) return true;  // that key's own problem is said there
    const isGiven = Boolean(r && r.given);
    if (c.values.length === 0) return isGiven;
    if (c.values.includes('<absent>')) return !isGiven;
    const k = schemaKey(t, name);
    const v = isGiven ? String(r.value) : (k && k.default ? k.default : null);
    return v !== null && c.values.includes(v);
  };
  const check = (table, boxes, own, path) => {
    for (const b of boxes) {
      const k = b.schema, r = own.get(k.key);
      if (!r.given) continue;
      if (r.problem) { said(b, path(r.at ? k.key + '.' + r.at : k.key), r.problem); continue; }
      const failed = k.conditions.find(c => !holds(table, own, c));
      if (failed) said(b, path(k.key), failed.problem);
    }
  };
  for (const t of ['site', 'event', 'inversion']) check(t, tables[t], read[t], key => t + '.' + key);
  const objs = objects.map(o => ({box: o, read: readAll(o.fields)}));
  const ids = new Map();
  objs.forEach((o, i) => {
    const idr = o.read.get('id');
    const id = idr.given ? idr.value : '';
    const named = (key) => 'object[' + (i + 1) + '](' + id + ').' + key;
    if (!id) said(fieldOf(o.box.fields, 'id'), 'object[' + (i + 1) + '].id', schemaKey('object', 'id').missing_problem);
    else if (ids.has(id)) said(fieldOf(o.box.fields, 'id'), 'object[' + (i + 1) + '].id', "duplicate object id '" + id + "'");
    ids.set(id, i);
    const shape = shapeOf(o.box.fields, o.read);
    for (const b of o.box.fields) {
      const k = b.schema;
      b.classList.toggle('hidden', !applies(k, shape.split(' ')[0]) && !applies(k, shape));
      if (k.key !== 'id' && !o.read.get(k.key).given && (k.required || k.required_for_shapes.includes(shape))) {
        said(b, named(k.key), k.missing_problem.replace('{shape}', shape.split(' ')[0]));
      }
    }
    check('object', o.box.fields.filter(b => b.schema.key !== 'id' && !b.classList.contains('hidden')), o.read, named);
  });
  const pops = populations.map(p => ({box: p, read: readAll(p.fields)}));
  pops.forEach((p, i) => checkPopulation(p, i, ids, said, check));
  if (objs.length === 0 && pops.length === 0) {
    const station = read.site.get('pga_g').given;
    errors.push('object: ' + (station ? 'the survey has no site with observed objects to invert'
                                      : 'a site needs at least one observed object (or an instrument: pga_g or record)'));
  }
  const list = document.getElementById('errors');
  list.textContent = '';
  for (const e of errors) list.appendChild(el('li', {text: e}));
  document.getElementById('status').textContent = errors.length ? errors.length + ' problem(s): not saved yet' : 'ready to save';
  if (errors.length) return {errors: errors};
  const csv = csvText(read, objs, pops);
  return {errors: errors, toml: tomlText(read, objs, pops), csv: csv.text, csvProblem: csv.problem};
}

// A population's checks (survey_file.cpp's parse_population, population.cpp's check_population), each problem in the
// reader's words at the field the reader names: population[2](stones).overturned.
function checkPopulation(p, i, ids, said, check) {
  const idr = p.read.get('id');
  const id = idr.given ? idr.value : '';
  const named = (key) => 'population[' + (i + 1) + '](' + id + ').' + key;
  const field = (key) => fieldOf(p.box.fields, key);
  if (!id) said(field('id'), 'population[' + (i + 1) + '].id', schemaKey('population', 'id').missing_problem);
  else if (ids.has(id)) {
    said(field('id'), 'population[' + (i + 1) + '].id', "duplicate id '" + id + "' (objects and populations share " +
                                                         'one list of ids)');
  }
  ids.set(id, i);
  const shape = p.read.get('shape').given ? p.read.get('shape').value : 'block';
  for (const b of p.box.fields) {
    // A key whose shape condition fails (a block's diameter, a cylinder's width or bearing) is not offered.
    const byShape = b.schema.conditions.find(c => c.key === 'shape');
    b.classList.toggle('hidden', Boolean(byShape) && !byShape.values.includes(shape));
    if (b.schema.key !== 'id' && b.schema.required && !p.read.get(b.schema.key).given) {
      said(b, named(b.schema.key), b.schema.missing_problem);
    }
  }
  check('population', p.box.fields.filter(b => b.schema.key !== 'id' && !b.classList.contains('hidden')), p.read, named);
  // What check_population says of the keys together, for keys that are fine alone.
  const fine = (key) => {
    const r = p.read.get(key), b = field(key);
    return r && r.given && !r.problem && !b.classList.contains('hidden') && !b.classList.contains('bad');
  };
  const val = (key) => fine(key) ? p.read.get(key).value : null;
  const count = val('count'), over = val('overturned');
  if (count !== null && over !== null) {
    if (over > count) {
      said(field('overturned'), named('overturned'), over + ' overturned of ' + count + ' counted: more than the count');
    } else {
      const rocked = val('rocked'), slid = val('slid');
      const moved = over + (rocked || 0) + (slid || 0);
      if (moved > count) {
        const key = slid !== null ? 'slid' : 'rocked';
        said(field(key), named(key), 'overturned + rocked + slid = ' + moved + ' is more than the count, ' + count);
      }
    }
  }
  if (fine('fallen_azimuths_deg')) {
    const list = p.read.get('fallen_azimuths_deg').list;
    const wrong = list.find(a => !(a >= 0 && a < 360));
    if (over !== null && list.length > over) {
      said(field('fallen_azimuths_deg'), named('fallen_azimuths_deg'), list.length + ' fall directions for ' + over +
                                                                       ' overturned');
    } else if (wrong !== undefined) {
      said(field('fallen_azimuths_deg'), named('fallen_azimuths_deg'), 'a direction lies in [0, 360) deg, got ' +
                                                                       show(wrong));
    } else if (shape === 'block' && !p.read.get('depth').given) {
      said(field('fallen_azimuths_deg'), named('fallen_azimuths_deg'), FALL_PROBLEM);
    }
  }
  const base = shape === 'cylinder' ? 'diameter' : 'width';
  const sample = p.read.get('sample');
  if (!sample.given) {
    const missing = !p.read.get('height').given ? 'height' : !p.read.get(base).given ? base : null;
    if (missing) {
      said(field(missing), named(missing), 'a population needs its sizes: a range for height and ' + base +
                                           ' (or a measured sample = [{...}, ...])');
    }
  } else if (!sample.problem) {
    sample.members.forEach((m, j) => {
      for (const [key, size] of [['height', m[1]], [base, m[0]]]) {
        const where = named('sample[' + (j + 1) + '].' + key);
        if (!(size.m > 0)) {
          said(field('sample'), where, 'must be positive, got ' + show(size.m) + ' m');
          continue;
        }
        if (fine(key)) {
          const r = p.read.get(key);
          if (size.m < r.loM || size.m > r.hiM) {
            said(field('sample'), where, g4(size.m) + " m is outside the population's stated range [" + g4(r.loM) +
                                         ', ' + g4(r.hiM) + '] m');
          }
        }
      }
    });
  }
}

function given(m, boxes) { return boxes.filter(b => m.get(b.schema.key).given && !b.classList.contains('hidden')); }
function tomlText(read, objs, pops) {
  let out = '# survey written by topple survey-form (docs/survey.md)\n';
  for (const t of ['site', 'event', 'inversion']) {
    const g = given(read[t], tables[t]);
    if (!g.length) continue;
    out += '\n[' + t + ']\n';
    for (const b of g) out += b.schema.key + ' = ' + read[t].get(b.schema.key).toml + '\n';
  }
  for (const o of objs) {
    out += '\n[[object]]\n';
    for (const b of given(o.read, o.box.fields)) out += b.schema.key + ' = ' + o.read.get(b.schema.key).toml + '\n';
  }
  for (const p of pops) {
    out += '\n[[population]]\n';
    const base = baseOf(p);
    for (const b of given(p.read, p.box.fields)) {
      const r = p.read.get(b.schema.key);
      if (b.schema.kind === 'tables') {
        const size = (s) => JSON.stringify(show(s.value) + s.unit);
        out += 'sample = [' + r.members.map(m => '{' + base + ' = ' + size(m[0]) + ', height = ' + size(m[1]) + '}')
                                      .join(', ') + ']\n';
      } else {
        out += b.schema.key + ' = ' + r.toml + '\n';
      }
    }
  }
  return out;
}
function baseOf(p) { return p.read.get('shape').given && p.read.get('shape').value === 'cylinder' ? 'diameter' : 'width'; }
// RFC 4180: a cell with a separator, a quote, a line break or spaces at its ends is quoted, its quotes doubled.
function cell(text) { return /[",\n\r;#]|^\s|\s$/.test(text) ? '"' + text.replace(/"/g, '""') + '"' : text; }
function csvText(read, objs, pops) {
  let out = '# survey written by topple survey-form (docs/survey.md, "CSV surveys")\n';
  for (const t of ['site', 'event', 'inversion']) {
    for (const b of given(read[t], tables[t])) out += cell(t + '.' + b.schema.key) + ',' + cell(read[t].get(b.schema.key).csv) + '\n';
  }
  // A population's size range is written in a column whose header names the unit ("width_cm", cells "[40, 50]"), so
  // every size in that column (objects', populations', measured members') must be in that one unit.
  const unitOf = {};
  for (const key of ['width', 'height', 'diameter']) {
    const units = new Set();
    let range = false;
    for (const o of objs) if (given(o.read, o.box.fields).some(b => b.schema.key === key)) units.add(o.read.get(key).unit);
    for (const p of pops) {
      if (given(p.read, p.box.fields).some(b => b.schema.key === key)) {
        units.add(p.read.get(key).unit);
        range = range || p.read.get(key).range;
      }
      const sample = p.read.get('sample');
      if (sample.given) for (const m of sample.members) units.add((key === 'height' ? m[1] : key === baseOf(p) ? m[0] : m[2] || {}).unit);
    }
    units.delete(undefined);
    if (!range) continue;
    if (units.size > 1) {
      return {problem: 'CSV not saved: a population\'s ' + key + ' range is written in a column whose header names ' +
                       'one unit (e.g. ' + key + '_cm), but the ' + key + 's are given in ' + [...units].join(' and ') +
                       ': give them all in one unit, or save TOML'};
    }
    unitOf[key] = [...units][0];
  }
  const used = (entries, key) => entries.some(e => given(e.read, e.box.fields).some(b => b.schema.key === key));
  const columns = keysOf('object').map(k => k.key).filter(key => used(objs, key));
  for (const k of keysOf('population')) {
    if (k.kind !== 'tables' && !columns.includes(k.key) && used(pops, k.key)) columns.push(k.key);
  }
  // A measured member's two sizes need their columns even where no object or range uses them.
  for (const p of pops) {
    if (!p.read.get('sample').given) continue;
    for (const key of [baseOf(p), 'height']) if (!columns.includes(key)) columns.push(key);
  }
  const members = pops.some(p => p.read.get('sample').given);
  if (members) columns.push('population');
  const header = columns.map(key => unitOf[key] ? key + '_' + unitOf[key] : key);
  out += header.join(',') + '\n';
  const sized = (key, r) => unitOf[key] ? (r.range ? '[' + show(r.lo) + ', ' + show(r.hi) + ']' : show(r.lo !== undefined ? r.lo : r.value))
                                        : r.csv;
  for (const o of objs) {
    const g = given(o.read, o.box.fields).map(b => b.schema.key);
    out += columns.map(key => g.includes(key) ? cell(sized(key, o.read.get(key))) : '').join(',') + '\n';
  }
  for (const p of pops) {
    const g = given(p.read, p.box.fields).map(b => b.schema.key);
    out += columns.map(key => g.includes(key) && key !== 'population' ? cell(sized(key, p.read.get(key))) : '').join(',') + '\n';
  }
  // The measured members: a row each, its population's id in the population column and its two sizes.
  for (const p of pops) {
    const sample = p.read.get('sample');
    if (!sample.given) continue;
    const base = baseOf(p);
    for (const m of sample.members) {
      const size = (s, key) => unitOf[key] ? show(s.value) : show(s.value) + s.unit;
      out += columns.map(key => key === 'population' ? cell(p.read.get('id').value) : key === base ? size(m[0], key)
                                : key === 'height' ? size(m[1], key) : '').join(',') + '\n';
    }
  }
  return {text: out};
}

function save(kind, download) {
  const r = validate();
  const area = document.getElementById(kind + '-out');
  // Both the text (what the page's DOM holds, and what a test reads) and the value (what is shown).
  const text = r.errors.length || !r[kind] ? '' : r[kind];
  area.textContent = text;
  area.value = text;
  if (kind === 'csv' && !r.errors.length && r.csvProblem) {
    document.getElementById('status').textContent = r.csvProblem;
    return false;
  }
  if (r.errors.length) return false;
  if (download) {
    const blob = new Blob([r[kind]], {type: kind === 'toml' ? 'application/toml' : 'text/csv'});
    const a = el('a', {href: URL.createObjectURL(blob), download: 'survey.' + kind});
    document.body.appendChild(a);
    a.click();
    setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
  }
  return true;
}
document.getElementById('save-toml').addEventListener('click', () => save('toml', true));
document.getElementById('save-csv').addEventListener('click', () => save('csv', true));

// ---- filling the form from data: a query string ?prefill=JSON (what the test drives), or this device's last entry ----
// {"site": {"name": "kitchen"}, "inversion": {"pga_g": "0.05,2,8"}, "objects": [{"id": "vase", "diameter": "8cm",
//  "material": "wood on wood", ...}], "populations": [{"id": "stones", "count": "40", "width": "40-50cm",
//  "sample": "45, 100; 48, 105", "sample_unit": "cm", ...}], "save": true}: each value as typed (a length with its
// unit, a range "40-50cm", an axis or [lat, lon] with commas, a sample's members separated by ';'); "save" fills both
// text areas as the buttons do (without downloading).
function setField(box, value) {
  const k = box.schema, v = String(value);
  if (k.kind === 'length' || k.kind === 'area') {
    const m = /^\s*([^a-zA-Z]*?)\s*([a-zA-Z][a-zA-Z0-9]*)\s*$/.exec(v);
    if (m) { box.inputs[0].value = m[1]; box.inputs[1].value = m[2]; } else box.inputs[0].value = v;
  } else if (k.kind === 'tables') {
    box.inputs[0].value = v.replace(/;\s*/g, '\n');
  } else if (k.kind === 'support') {
    // "furniture", or {"name": ..., "freq_hz": "3-6", "damping": "0.05"} for a flexible support.
    const f = typeof value === 'object' ? value : {name: v};
    box.inputs[0].value = f.name || ''; box.inputs[1].value = f.freq_hz || ''; box.inputs[2].value = f.damping || '';
  } else if (k.kind === 'axis' || k.kind === 'lat_lon') {
    v.replace(/[\[\]]/g, '').split(',').forEach((p, i) => { if (box.inputs[i]) box.inputs[i].value = p.trim(); });
  } else {
    box.inputs[0].value = v;
  }
}
function fillFrom(data) {
  for (const t of ['site', 'event', 'inversion']) {
    for (const [key, value] of Object.entries(data[t] || {})) {
      const box = fieldOf(tables[t], key);
      if (box) setField(box, value);
    }
  }
  const fillEntry = (box, entry) => {
    for (const [key, value] of Object.entries(entry)) {
      if (key === 'material') {
        const mu = fieldOf(box.fields, 'mu');
        mu.material.value = String(SCHEMA.friction.findIndex(r => r.surfaces === value));
        mu.material.dispatchEvent(new Event('change'));
        continue;
      }
      if (key === 'sample_unit') {  // the unit of a measured sample's bare numbers
        fieldOf(box.fields, 'sample').inputs[1].value = value;
        continue;
      }
      const f = fieldOf(box.fields, key);
      if (f) setField(f, value);
    }
  };
  for (const o of data.objects || []) fillEntry(addObject(), o);
  for (const p of data.populations || []) fillEntry(addPopulation(), p);
  validate();
}
function stateOf() {
  const grab = (boxes) => Object.fromEntries(boxes.filter(b => b.inputs.some(i => i.tagName !== 'SELECT' && i.value)
      || b.schema.kind === 'choice' && b.inputs[0].value).flatMap(b => b.schema.kind === 'tables'
      ? [[b.schema.key, b.inputs[0].value.replace(/\n/g, ';')], ['sample_unit', b.inputs[1].value]]
      : b.schema.kind === 'support' ? [[b.schema.key, {name: b.inputs[0].value, freq_hz: b.inputs[1].value,
                                                       damping: b.inputs[2].value}]]
      : [[b.schema.key, b.schema.kind === 'length' || b.schema.kind === 'area' ? b.inputs[0].value + b.inputs[1].value
                                                                              : b.inputs.map(i => i.value).join(',')]]));
  return {site: grab(tables.site), event: grab(tables.event), inversion: grab(tables.inversion),
          objects: objects.map(o => grab(o.fields)), populations: populations.map(p => grab(p.fields))};
}
// An empty form: every field as made, no object, no population.
function clearForm() {
  for (const t of ['site', 'event', 'inversion']) {
    for (const b of tables[t]) b.inputs.forEach((i, j) => { i.value = b.initial[j]; });
  }
  for (const list of [objects, populations]) { for (const b of list) b.remove(); list.length = 0; }
  validate();
}
// A list of prefills is several surveys entered one after the other in this one page (what the test drives): each
// is filled into a cleared form and saved, and what the page showed is kept under #runs as run-N-toml, run-N-csv,
// run-N-status and run-N-errors.
function keepRun(n) {
  const runs = document.getElementById('runs');
  const pre = (what, text) => runs.appendChild(el('pre', {id: 'run-' + n + '-' + what, text: text}));
  pre('toml', document.getElementById('toml-out').value);
  pre('csv', document.getElementById('csv-out').value);
  pre('status', document.getElementById('status').textContent);
  pre('errors', [...document.getElementById('errors').children].map(li => li.textContent).join('\n'));
}
const query = new URLSearchParams(location.search);
if (query.has('prefill')) {
  const data = JSON.parse(query.get('prefill'));
  (Array.isArray(data) ? data : [data]).forEach((d, i) => {
    if (i > 0) clearForm();
    fillFrom(d);
    if (d.save) { save('toml', false); save('csv', false); }
    if (Array.isArray(data)) keepRun(i + 1);
  });
} else {
  let saved = null;
  try { saved = JSON.parse(localStorage.getItem('topple-survey-form') || 'null'); } catch (e) { saved = null; }
  if (saved) fillFrom(saved); else addObject();
  // Kept on this device as it is typed, so that a closed tab or a flat battery loses nothing.
  document.body.addEventListener('input', () => {
    try { localStorage.setItem('topple-survey-form', JSON.stringify(stateOf())); } catch (e) { /* private mode */ }
  });
}
</script>
</body>
</html>
)PAGE";

}  // namespace

std::string survey_form_html() {
  std::string schema = survey_schema_json().dump();
  // Inside <script>, "</" would end the element: JSON allows "<\/" for it.
  for (std::size_t at = schema.find("</"); at != std::string::npos; at = schema.find("</", at + 3)) {
    schema.replace(at, 2, "<\\/");
  }
  std::string page = kPage;
  const std::string marker = "@SCHEMA@";
  page.replace(page.find(marker), marker.size(), schema);
  return page;
}

}  // namespace topple::io
