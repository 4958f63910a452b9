// The report's script: the scatter of the chosen objectives, the parallel coordinates with
// brushing (report_parallel.js), choosing a design by a rule (report_decision.js), pinning and
// comparing designs, the designs table (sort, filter), the knee table, hover. Data: #report-data
// (file units, with each quantity's display unit and scale).
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const byId = {};
  data.designs.forEach(function (d, k) { d.index = k; byId[d.id] = d; });
  const tip = document.getElementById('tip');
  const pinned = [];
  const MAX_PINNED = 4;
  const brushes = {};  // objective index -> [lo, hi] in file units (report_parallel.js)
  let normalisedAxes = false;
  let chosen = null;   // the id the choice panel's rule chose

  // Objectives minimised (maximised ones negated) and their scale over the feasible designs with
  // every objective finite: the frame of the rules and of the normalised axes.
  const sign = data.objectives.map(function (o) { return o.sense === 'maximize' ? -1 : 1; });
  function complete(d) {
    return d.objectives.every(function (v) { return v !== null && isFinite(v); });
  }
  function minimised(d) { return d.objectives.map(function (v, k) { return sign[k] * v; }); }
  const feasibleAll = data.designs.filter(function (d) { return d.feasible && complete(d); });
  const scale = feasibleAll.length ? pkmoptDecision.frontScale(feasibleAll.map(minimised)) : null;
  function normalisedValue(d, k) {
    const v = d.objectives[k];
    if (v === null || !scale) return null;
    const range = scale.nadir[k] - scale.ideal[k];
    return range > 0 ? (sign[k] * v - scale.ideal[k]) / range : 0;
  }
  function selected(d) {
    return Object.keys(brushes).every(function (k) {
      const v = d.objectives[k];
      return v !== null && isFinite(v) && v >= brushes[k][0] && v <= brushes[k][1];
    });
  }
  // The SVG namespace, from the inline scatter the page was written with (no URL in the page).
  const SVG = document.querySelector('#scatter-box svg').namespaceURI;

  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return {'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c];
    });
  }
  // Five significant digits; exponent form only for very large or small magnitudes.
  function num(v) {
    if (v === null || v === undefined || !isFinite(v)) return '-';
    const a = Math.abs(v);
    if (a !== 0 && (a >= 1e7 || a < 1e-4)) return v.toExponential(4);
    return String(+v.toPrecision(5));
  }
  function shown(q, v) { return (v === null || v === undefined) ? null : v * q.scale; }
  function withUnit(q, v) { return num(shown(q, v)) + (q.unit ? ' ' + esc(q.unit) : ''); }

  // ---- quantities of a design, in display units -------------------------------------------
  // Each: {key, label, unit, value(d) in display units, bound: 'upper'|'lower'|'', kind}.
  const columns = [];
  data.parameters.forEach(function (p, k) {
    columns.push({key: p.name, label: p.name, unit: p.unit, kind: 'parameter',
                  value: function (d) { return shown(p, d.parameters[k]); },
                  bound: function (d) {
                    const v = d.parameters[k], span = p.max - p.min;
                    if (v === null || !(span > 0)) return '';
                    if (v >= p.max - 0.01 * span) return 'upper';
                    if (v <= p.min + 0.01 * span) return 'lower';
                    return '';
                  },
                  range: num(p.min * p.scale) + ' .. ' + num(p.max * p.scale)});
  });
  if (!data.home_free) {
    columns.push({key: 'home_height', label: 'home_height', unit: data.home.unit,
                  kind: 'parameter', value: function (d) { return shown(data.home, d.home_height); },
                  bound: function () { return ''; }});
  }
  data.objectives.forEach(function (o, k) {
    columns.push({key: o.name, label: o.name + (o.sense === 'maximize' ? ' (max)' : ' (min)'),
                  unit: o.unit, kind: 'objective',
                  value: function (d) { return shown(o, d.objectives[k]); },
                  bound: function () { return ''; }});
  });
  data.constraints.forEach(function (c, k) {
    columns.push({key: c.name, label: c.name, unit: c.unit, kind: 'constraint',
                  value: function (d) { return shown(c, d.constraints[k]); },
                  bound: function () { return ''; }});
  });

  function cell(col, d) {
    const b = col.bound(d);
    const mark = b === 'upper' ? ' <span class="atbound" title="at its upper bound">&#9650;</span>'
               : b === 'lower' ? ' <span class="atbound" title="at its lower bound">&#9660;</span>'
               : '';
    return num(col.value(d)) + mark;
  }

  // One design's details (hover, knee, pinned): a two-column table.
  function detailRows(d) {
    let h = '';
    let kind = '';
    columns.forEach(function (col) {
      if (col.kind !== kind) {
        kind = col.kind;
        h += '<tr><td colspan="2" class="sec">' + kind + 's' +
             (kind === 'constraint' ? ' (g &le; 0 satisfied)' : '') + '</td></tr>';
      }
      h += '<tr><th>' + esc(col.label) + '</th><td>' + cell(col, d) +
           (col.unit ? ' ' + esc(col.unit) : '') + '</td></tr>';
    });
    if (data.fixed.length) {
      h += '<tr><td colspan="2" class="sec">fixed parameters</td></tr>';
      data.fixed.forEach(function (f) {
        h += '<tr><th>' + esc(f.name) + '</th><td>' + withUnit(f, f.value) + '</td></tr>';
      });
    }
    if (d.actuator !== undefined) {
      h += '<tr><td colspan="2" class="sec">actuator</td></tr>' +
           (d.actuator ? '<tr><th>' + esc(d.actuator.name) + '</th><td>' +
                         num(d.actuator.max_force / 1000) + ' kN, stroke ' +
                         num(d.actuator.stroke * 1000) + ' mm</td></tr>'
                       : '<tr><td colspan="2" class="bad">no entry carries the legs</td></tr>');
    }
    return h;
  }
  function describe(d) {
    return '<b>' + esc(d.id) + '</b>' + (d.id === data.knee ? ' (knee)' : '') +
           (d.feasible ? '' : ' <span class="bad">infeasible</span>') + '<table>' +
           detailRows(d) + '</table>';
  }

  // ---- scatter of the chosen pair ---------------------------------------------------------
  function niceTicks(lo, hi, target) {
    if (!(hi > lo)) return [lo];
    const raw = (hi - lo) / target, p = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map(function (f) { return f * p; })
                              .find(function (s) { return s >= raw; });
    const out = [];
    for (let t = Math.ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) {
      out.push(Math.abs(t) < 1e-12 * step ? 0 : t);
    }
    return out;
  }
  const xSel = document.getElementById('x-axis'), ySel = document.getElementById('y-axis');
  data.objectives.forEach(function (o, k) {
    const label = o.name + (o.unit ? ' [' + o.unit + ']' : '');
    xSel.add(new Option(label, k));
    ySel.add(new Option(label, k));
  });
  xSel.value = '0';
  ySel.value = data.objectives.length > 1 ? '1' : '0';

  function el(name, attrs, text) {
    const e = document.createElementNS(SVG, name);
    Object.keys(attrs).forEach(function (a) { e.setAttribute(a, attrs[a]); });
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function axisLabel(sel, k, o) {
    return (normalisedAxes && scale ? o.name + ' [0 = best, 1 = worst]' : sel.options[k].text) +
           (o.sense === 'maximize' ? ' (max)' : ' (min)');
  }
  function drawScatter() {
    const xi = +xSel.value, yi = +ySel.value;
    const ox = data.objectives[xi], oy = data.objectives[yi];
    const W = 680, H = 520, L = 100, T = 40, R = 30, B = 70;
    const pts = data.designs.filter(function (d) {
      return isFinite(d.objectives[xi]) && isFinite(d.objectives[yi]) &&
             d.objectives[xi] !== null && d.objectives[yi] !== null;
    });
    function range(vals) {
      let lo = Math.min.apply(null, vals), hi = Math.max.apply(null, vals);
      if (!(hi > lo)) { const w = lo === 0 ? 1 : Math.abs(lo) * 0.05; lo -= w; hi += w; }
      const pad = 0.05 * (hi - lo);
      return [lo - pad, hi + pad];
    }
    const vx = normalisedAxes && scale ? function (d) { return normalisedValue(d, xi); }
                                       : function (d) { return shown(ox, d.objectives[xi]); };
    const vy = normalisedAxes && scale ? function (d) { return normalisedValue(d, yi); }
                                       : function (d) { return shown(oy, d.objectives[yi]); };
    const xs = pts.map(vx), ys = pts.map(vy);
    const xr = pts.length ? range(xs) : [0, 1], yr = pts.length ? range(ys) : [0, 1];
    const sx = function (v) { return L + (W - L - R) * (v - xr[0]) / (xr[1] - xr[0]); };
    const sy = function (v) { return T + (H - T - B) * (1 - (v - yr[0]) / (yr[1] - yr[0])); };
    const svg = el('svg', {id: 'scatter', width: W, height: H, viewBox: '0 0 ' + W + ' ' + H,
                           'font-family': 'sans-serif', 'font-size': 12});
    svg.appendChild(el('rect', {width: W, height: H, fill: '#fff'}));
    niceTicks(xr[0], xr[1], 6).forEach(function (t) {
      svg.appendChild(el('line', {x1: sx(t), x2: sx(t), y1: T, y2: H - B, stroke: '#e6e6e6'}));
      svg.appendChild(el('text', {x: sx(t), y: H - B + 16, 'text-anchor': 'middle'}, num(t)));
    });
    niceTicks(yr[0], yr[1], 6).forEach(function (t) {
      svg.appendChild(el('line', {x1: L, x2: W - R, y1: sy(t), y2: sy(t), stroke: '#e6e6e6'}));
      svg.appendChild(el('text', {x: L - 6, y: sy(t) + 4, 'text-anchor': 'end'}, num(t)));
    });
    svg.appendChild(el('rect', {x: L, y: T, width: W - L - R, height: H - T - B, fill: 'none',
                                stroke: '#141414'}));
    const xLabel = el('text', {id: 'x-label', x: L + (W - L - R) / 2, y: H - 24,
                               'text-anchor': 'middle', 'font-size': 14},
                      axisLabel(xSel, xi, ox));
    svg.appendChild(xLabel);
    svg.appendChild(el('text', {id: 'y-label', x: 8, y: T - 14, 'font-size': 14},
                       axisLabel(ySel, yi, oy)));
    const rank = function (d) {  // brushed-out below, the knee and the chosen design on top
      return d.id === chosen ? 3 : d.id === data.knee ? 2 : selected(d) ? 1 : 0;
    };
    const order = pts.slice().sort(function (a, b) { return rank(a) - rank(b); });
    order.forEach(function (d) {
      const knee = d.id === data.knee, isChosen = d.id === chosen, inside = selected(d);
      const colour = isChosen ? '#ff7f0e' : knee ? '#d62728' : '#1f77b4';
      const c = el('circle', {cx: sx(vx(d)), cy: sy(vy(d)),
                              r: knee || isChosen ? 6.5 : 4.5, 'data-id': d.id,
                              class: 'pt' + (pinned.indexOf(d.id) >= 0 ? ' pin' : '') +
                                     (inside ? '' : ' out') + (isChosen ? ' chosen' : ''),
                              fill: d.feasible ? colour : 'none',
                              stroke: d.feasible ? colour : '#8c8c8c',
                              'stroke-width': d.feasible ? 1 : 1.5});
      svg.appendChild(c);
      const p = pinned.indexOf(d.id);
      if (p >= 0 || knee || isChosen) {
        svg.appendChild(el('text', {x: +c.getAttribute('cx') + 8, y: +c.getAttribute('cy') - 8,
                                    fill: isChosen ? '#c25e00' : knee ? '#d62728' : '#000',
                                    'font-weight': p >= 0 ? 'bold' : 'normal'},
                           (p >= 0 ? (p + 1) + ': ' : '') + d.id + (knee ? ' knee' : '') +
                           (isChosen ? ' chosen' : '')));
      }
    });
    const box = document.getElementById('scatter-box');
    box.innerHTML = '';
    box.appendChild(svg);
    bindHover(box);
  }

  // ---- pinning ----------------------------------------------------------------------------
  function togglePin(id) {
    const at = pinned.indexOf(id);
    if (at >= 0) pinned.splice(at, 1);
    else {
      if (pinned.length === MAX_PINNED) pinned.shift();  // the oldest gives way
      pinned.push(id);
    }
    drawScatter();
    drawParallel();
    drawPinned();
    document.querySelectorAll('#designs tr[data-id], polyline[data-id]').forEach(function (e) {
      e.classList.toggle('pin', pinned.indexOf(e.getAttribute('data-id')) >= 0);
    });
  }
  function drawPinned() {
    const box = document.getElementById('pinned');
    if (!pinned.length) {
      box.innerHTML = '<p class="hint">No design pinned yet: click a point, a line or a row.</p>';
      return;
    }
    const ds = pinned.map(function (id) { return byId[id]; });
    let h = '<table class="compare"><tr><th></th>' + ds.map(function (d, k) {
      return '<th>' + (k + 1) + ': ' + esc(d.id) + (d.id === data.knee ? ' (knee)' : '') +
             ' <button class="unpin" data-unpin="' + esc(d.id) + '">unpin</button></th>';
    }).join('') + '</tr>';
    let kind = '';
    columns.forEach(function (col) {
      if (col.kind !== kind) {
        kind = col.kind;
        h += '<tr><td class="sec" colspan="' + (ds.length + 1) + '">' + kind + 's</td></tr>';
      }
      h += '<tr><th>' + esc(col.label) + (col.unit ? ' [' + esc(col.unit) + ']' : '') + '</th>' +
           ds.map(function (d) { return '<td class="num">' + cell(col, d) + '</td>'; }).join('') +
           '</tr>';
    });
    data.fixed.forEach(function (f) {
      h += '<tr><th>' + esc(f.name) + ' [' + esc(f.unit) + '] (fixed)</th>' +
           ds.map(function () { return '<td class="num">' + num(f.value * f.scale) + '</td>'; })
             .join('') + '</tr>';
    });
    h += '<tr><td class="sec" colspan="' + (ds.length + 1) + '">the machine at the task centre ' +
         '(level platform; dashed green: the task box)</td></tr><tr><th></th>' +
         ds.map(function (d) {
           return '<td class="drawing">' + (data.drawings[d.id] ||
                  '<span class="bad">no drawing (no machine file)</span>') + '</td>';
         }).join('') + '</tr></table>';
    box.innerHTML = h;
    box.querySelectorAll('[data-unpin]').forEach(function (b) {
      b.addEventListener('click', function () { togglePin(b.getAttribute('data-unpin')); });
    });
  }

  // ---- the designs table ------------------------------------------------------------------
  let sortColumn = -1, sortAscending = true;
  function parseFilter(text) {
    const conditions = [], words = [];
    const re = /([A-Za-z_][A-Za-z0-9_]*)\s*(<=|>=|<|>|=)\s*(-?[0-9.eE+-]+)/g;
    let m, rest = text;
    while ((m = re.exec(text)) !== null) {
      const col = columns.find(function (c) { return c.key === m[1]; });
      if (col) conditions.push({col: col, op: m[2], value: +m[3]});
      rest = rest.replace(m[0], ' ');
    }
    rest.split(/[\s,]+/).forEach(function (w) { if (w) words.push(w.toLowerCase()); });
    return {conditions: conditions, words: words};
  }
  function passes(d, f) {
    for (const c of f.conditions) {
      const v = c.col.value(d);
      if (v === null || !isFinite(v)) return false;
      if ((c.op === '<' && !(v < c.value)) || (c.op === '>' && !(v > c.value)) ||
          (c.op === '<=' && !(v <= c.value)) || (c.op === '>=' && !(v >= c.value)) ||
          (c.op === '=' && num(v) !== num(c.value))) return false;
    }
    return f.words.every(function (w) { return d.id.toLowerCase().indexOf(w) >= 0; });
  }
  function drawTable() {
    const f = parseFilter(document.getElementById('filter').value);
    let rows = data.designs.filter(function (d) { return passes(d, f) && selected(d); });
    if (sortColumn >= 0) {
      const col = columns[sortColumn];
      rows = rows.slice().sort(function (a, b) {
        const va = col.value(a), vb = col.value(b);
        const x = (va === null ? Infinity : va) - (vb === null ? Infinity : vb);
        return sortAscending ? x : -x;
      });
    }
    let h = '<table id="designs"><tr><th data-sort="-1">id</th>' + columns.map(function (c, k) {
      return '<th data-sort="' + k + '" title="click to sort">' + esc(c.label) +
             (c.unit ? ' [' + esc(c.unit) + ']' : '') +
             (k === sortColumn ? (sortAscending ? ' &#8593;' : ' &#8595;') : '') + '</th>';
    }).join('') + (data.designs.length && data.designs[0].actuator !== undefined ? '<th>actuator</th>' : '') +
        '<th>feasible</th></tr>';
    rows.forEach(function (d) {
      h += '<tr data-id="' + esc(d.id) + '" class="' + (pinned.indexOf(d.id) >= 0 ? 'pin' : '') +
           (d.id === chosen ? ' chosen' : '') + '"><td>' + esc(d.id) +
           (d.id === data.knee ? ' (knee)' : '') + (d.id === chosen ? ' (chosen)' : '') + '</td>' +
           columns.map(function (c) { return '<td class="num">' + cell(c, d) + '</td>'; }).join('') +
           (d.actuator !== undefined ? '<td>' + (d.actuator ? esc(d.actuator.name) : '-') + '</td>' : '') +
           '<td>' + (d.feasible ? 'yes' : '<span class="bad">no</span>') + '</td></tr>';
    });
    h += '</table>';
    const box = document.getElementById('designs-box');
    box.innerHTML = h;
    const brushed = Object.keys(brushes).length;
    document.getElementById('shown').textContent =
        rows.length + ' of ' + data.designs.length + ' designs shown' +
        (brushed ? ' (' + brushed + ' brushed ' + (brushed > 1 ? 'axes' : 'axis') + ')' : '');
    box.querySelectorAll('th[data-sort]').forEach(function (th) {
      th.addEventListener('click', function () {
        const k = +th.getAttribute('data-sort');
        if (k === sortColumn) sortAscending = !sortAscending;
        else { sortColumn = k; sortAscending = true; }
        drawTable();
      });
    });
    bindHover(box);
  }

  // ---- hover and click on anything with data-id ---------------------------------------------
  function mark(id, on) {
    document.querySelectorAll('[data-id="' + id + '"]').forEach(function (e) {
      e.classList.toggle('hl', on);
    });
  }
  function bindHover(root) {
    root.querySelectorAll('[data-id]').forEach(function (e) {
      const id = e.getAttribute('data-id');
      if (!byId[id]) return;
      e.addEventListener('mouseenter', function () {
        tip.innerHTML = describe(byId[id]);
        tip.style.display = 'block';
        mark(id, true);
      });
      e.addEventListener('mousemove', function (ev) {
        tip.style.left = (ev.pageX + 14) + 'px';
        tip.style.top = (ev.pageY + 14) + 'px';
      });
      e.addEventListener('mouseleave', function () {
        tip.style.display = 'none';
        mark(id, false);
      });
      e.addEventListener('click', function () { togglePin(id); });
    });
  }

  // ---- parallel coordinates (report_parallel.js) --------------------------------------------
  function drawParallel() {
    const old = document.getElementById('parallel');
    if (!old) return;  // fewer than three objectives
    const svg = pkmoptParallel.draw({
      data: data, shown: shown, num: num, el: el, brushes: brushes, scale: scale,
      normalisedAxes: normalisedAxes && !!scale, selected: selected, chosen: chosen,
      pinned: pinned, onBrush: redraw});
    old.replaceWith(svg);
    bindHover(svg);
  }

  // ---- choosing a design (report_decision.js; the rules of `pkmopt choose`) ------------------
  const ruleSel = document.getElementById('rule');
  function candidates() {
    return data.designs.filter(function (d) { return d.feasible && complete(d) && selected(d); });
  }
  function ruleValues() {
    const rule = ruleSel.value;
    if (rule !== 'weights' && rule !== 'reference') return {ok: true, values: []};
    const values = [];
    let ok = true, total = 0;
    document.querySelectorAll('#choose-inputs input.' + (rule === 'weights' ? 'w' : 'z'))
      .forEach(function (input) {
        const k = +input.getAttribute('data-k');
        const text = input.value.trim();
        let v = text === '' && rule === 'weights' ? 0 : Number(text);
        if (text === '' && rule === 'reference') v = NaN;
        if (!isFinite(v) || (rule === 'weights' && v < 0)) ok = false;
        input.classList.toggle('bad-input', !isFinite(v) || (rule === 'weights' && v < 0));
        // Aspiration levels are typed in display units: back to file units.
        values[k] = rule === 'reference' ? v / data.objectives[k].scale : v;
        total += rule === 'weights' && isFinite(v) ? v : 0;
      });
    if (rule === 'weights' && !(total > 0)) ok = false;
    return {ok: ok, values: values};
  }
  function fileNumber(v) { return String(+v.toPrecision(12)); }
  function commandLine(rule, values) {
    if (rule === 'knee' || rule === 'compromise') return 'pkmopt choose DIR --' + rule;
    const items = data.objectives.map(function (o, k) {
      return o.name + '=' + fileNumber(values[k]);
    }).filter(function (item, k) { return rule === 'reference' || values[k] > 0; });
    return 'pkmopt choose DIR --' + rule + ' ' + items.join(',');
  }
  function computeChoice() {
    const rule = ruleSel.value;
    document.querySelectorAll('#choose-inputs .w, #choose-inputs .z').forEach(function (e) {
      e.disabled = !((rule === 'weights' && e.classList.contains('w')) ||
                     (rule === 'reference' && e.classList.contains('z')));
    });
    const box = document.getElementById('chosen');
    const pool = candidates();
    const input = ruleValues();
    chosen = null;
    if (!pool.length) {
      box.innerHTML = '<p class="bad">No feasible design inside the brushes: nothing to choose ' +
                      'from.</p>';
      return;
    }
    if (!input.ok) {
      box.innerHTML = '<p class="bad">' + (rule === 'weights'
          ? 'Weights: numbers of at least 0, not all 0.'
          : 'Aspiration levels: a number for every objective, in the units shown.') + '</p>';
      return;
    }
    const values = rule === 'reference'
        ? input.values.map(function (v, k) { return sign[k] * v; }) : input.values;
    const c = pkmoptDecision.choose(pool.map(minimised), rule, values);
    const d = pool[c.index];
    chosen = d.id;
    const brushed = Object.keys(brushes).length > 0;
    let h = '<p><b id="chosen-id">' + esc(d.id) + '</b>, one of ' + pool.length +
            ' feasible designs' + (brushed ? ' inside the brushes' : '') +
            ' <button data-pin-chosen="1">pin</button></p><table><tr><th>objective</th>' +
            '<th>value</th><th>normalised</th><th>pseudo-weight</th></tr>';
    data.objectives.forEach(function (o, k) {
      h += '<tr><th>' + esc(o.name) + (o.sense === 'maximize' ? ' (max)' : ' (min)') +
           '</th><td class="num">' + withUnit(o, d.objectives[k]) + '</td><td class="num">' +
           c.normalised[k].toFixed(3) + '</td><td class="num">' + c.weights[k].toFixed(3) +
           '</td></tr>';
    });
    h += '</table><p>The same choice on the command line, writing the design\'s machine file' +
         (brushed ? ' (without the brushes: it chooses among all feasible designs)' : '') +
         ':<br><code id="chosen-command">' + esc(commandLine(rule, input.values)) +
         '</code></p>';
    box.innerHTML = h;
    box.querySelector('[data-pin-chosen]').addEventListener('click', function () {
      togglePin(d.id);
    });
  }
  function buildChoosePanel() {
    let h = '<tr><th>objective</th><th>weight</th><th>aspiration level</th></tr>';
    data.objectives.forEach(function (o, k) {
      h += '<tr><th>' + esc(o.name) + (o.sense === 'maximize' ? ' (max)' : ' (min)') + '</th>' +
           '<td><input class="w" data-k="' + k + '" size="6" value="1"></td>' +
           '<td><input class="z" data-k="' + k + '" size="10" value="' +
           (scale ? num(shown(o, sign[k] * scale.ideal[k])) : '') + '"> ' + esc(o.unit) +
           '</td></tr>';
    });
    document.getElementById('choose-inputs').innerHTML = h;
    document.querySelectorAll('#choose-inputs input').forEach(function (e) {
      e.addEventListener('input', redraw);
    });
    ruleSel.addEventListener('change', redraw);
    const look = [], roles = {};
    function role(id, what) {
      if (!id) return;
      if (!roles[id]) { roles[id] = []; look.push(id); }
      roles[id].push(what);
    }
    role(data.knee, 'the knee');
    role(data.compromise, 'the compromise, nearest the ideal point');
    (data.high_trade_off || []).forEach(function (id) {
      role(id, 'high trade-off: leaving it costs much for little');
    });
    document.getElementById('look-first').innerHTML = look.length
        ? 'Designs to look at first: ' + look.map(function (id) {
            return '<a href="#" data-look="' + esc(id) + '">' + esc(id) + '</a> (' +
                   roles[id].join('; ') + ')';
          }).join(', ') + '. Click one to pin it.'
        : '';
    document.querySelectorAll('[data-look]').forEach(function (a) {
      a.addEventListener('click', function (ev) {
        ev.preventDefault();
        togglePin(a.getAttribute('data-look'));
      });
    });
  }

  function redraw() {
    computeChoice();
    drawScatter();
    drawParallel();
    drawTable();
  }

  xSel.addEventListener('change', drawScatter);
  ySel.addEventListener('change', drawScatter);
  document.getElementById('filter').addEventListener('input', drawTable);
  document.getElementById('normalised').addEventListener('change', function (ev) {
    normalisedAxes = ev.target.checked;
    redraw();
  });
  document.getElementById('clear-brushes').addEventListener('click', function () {
    Object.keys(brushes).forEach(function (k) { delete brushes[k]; });
    redraw();
  });
  const kneeBox = document.getElementById('knee-table');
  if (kneeBox && data.knee) kneeBox.innerHTML = '<table>' + detailRows(byId[data.knee]) + '</table>';
  buildChoosePanel();
  redraw();
})();
