// The report's parallel coordinates: every objective on its own vertical axis, best at the top,
// one line per design, and brushing: drag along an axis to keep only the designs inside the
// dragged range (several axes: inside all of them); a click on an axis without dragging clears
// its brush. Axes are labelled in display units or, normalised, from 0 (the best feasible value)
// to 1 (the worst).
//   const svg = pkmoptParallel.draw(ctx);
// ctx: {data, shown(q, v), num(v), el(name, attrs, text), brushes (objective index -> [lo, hi]
// in file units), normalisedAxes, scale (pkmoptDecision.frontScale of the feasible designs,
// minimised), selected(d), chosen (id or null), pinned (ids), onBrush()}.
window.pkmoptParallel = (function () {
  'use strict';
  const W0 = 680, H = 420, LEFT = 80, RIGHT = 80, TOP = 60, BOTTOM = 70;

  function draw(ctx) {
    const data = ctx.data, m = data.objectives.length;
    const W = Math.max(W0, 150 * m), spacing = (W - LEFT - RIGHT) / Math.max(m - 1, 1);
    const lo = [], hi = [];
    data.objectives.forEach(function (o, k) {
      const vals = data.designs.map(function (d) { return d.objectives[k]; })
                               .filter(function (v) { return v !== null && isFinite(v); });
      lo.push(vals.length ? Math.min.apply(null, vals) : 0);
      hi.push(vals.length ? Math.max.apply(null, vals) : 1);
    });
    const maximize = function (k) { return data.objectives[k].sense === 'maximize'; };
    // t: 1 at the best value of the axis, 0 at the worst.
    const yOf = function (k, v) {
      let t = hi[k] > lo[k] ? (v - lo[k]) / (hi[k] - lo[k]) : 0.5;
      if (!maximize(k)) t = 1 - t;
      return TOP + (H - TOP - BOTTOM) * (1 - t);
    };
    const valueOf = function (k, y) {
      let t = 1 - (y - TOP) / (H - TOP - BOTTOM);
      t = Math.min(1, Math.max(0, t));
      if (!maximize(k)) t = 1 - t;
      return lo[k] + t * (hi[k] - lo[k]);
    };
    const xOf = function (k) { return LEFT + spacing * k; };
    const svg = ctx.el('svg', {id: 'parallel', width: W, height: H, viewBox: '0 0 ' + W + ' ' + H,
                               'font-family': 'sans-serif', 'font-size': 12});
    svg.appendChild(ctx.el('rect', {width: W, height: H, fill: '#fff'}));
    svg.appendChild(ctx.el('text', {x: LEFT, y: 20, 'font-size': 15},
                           'parallel coordinates, best at the top (drag along an axis to brush)'));
    // Lines: brushed-out designs light grey underneath, then the selected, then the chosen.
    const rank = function (d) {
      return d.id === ctx.chosen ? 3 : d.id === data.knee ? 2 : ctx.selected(d) ? 1 : 0;
    };
    data.designs.slice().sort(function (a, b) { return rank(a) - rank(b); }).forEach(function (d) {
      if (d.objectives.some(function (v) { return v === null || !isFinite(v); })) return;
      const points = d.objectives.map(function (v, k) {
        return xOf(k).toFixed(1) + ',' + yOf(k, v).toFixed(1);
      }).join(' ');
      const inside = ctx.selected(d), chosen = d.id === ctx.chosen, knee = d.id === data.knee;
      const colour = !inside ? '#c8c8c8' : chosen ? '#ff7f0e' : knee ? '#d62728'
                   : d.feasible ? '#1f77b4' : '#8c8c8c';
      svg.appendChild(ctx.el('polyline', {
        'data-id': d.id, points: points, fill: 'none', stroke: colour,
        'stroke-width': chosen || knee ? 3 : 1.5, 'stroke-opacity': inside ? (chosen || knee ? 1 : 0.6) : 0.5,
        class: 'pc' + (inside ? '' : ' out') + (knee ? ' knee' : '') + (chosen ? ' chosen' : '') +
               (ctx.pinned.indexOf(d.id) >= 0 ? ' pin' : '')}));
    });
    data.objectives.forEach(function (o, k) {
      const x = xOf(k);
      svg.appendChild(ctx.el('line', {x1: x, x2: x, y1: TOP, y2: H - BOTTOM, stroke: '#141414'}));
      svg.appendChild(ctx.el('text', {x: x, y: TOP - 22, 'text-anchor': 'middle',
                                      'font-weight': 'bold'}, o.name));
      const best = maximize(k) ? hi[k] : lo[k], worst = maximize(k) ? lo[k] : hi[k];
      let top, bottom;
      if (ctx.normalisedAxes) {
        const sign = maximize(k) ? -1 : 1;
        const n = function (v) {
          const range = ctx.scale.nadir[k] - ctx.scale.ideal[k];
          return range > 0 ? (sign * v - ctx.scale.ideal[k]) / range : 0;
        };
        top = ctx.num(+n(best).toFixed(3));
        bottom = ctx.num(+n(worst).toFixed(3));
      } else {
        top = ctx.num(ctx.shown(o, best));
        bottom = ctx.num(ctx.shown(o, worst));
      }
      svg.appendChild(ctx.el('text', {x: x, y: TOP - 8, 'text-anchor': 'middle', class: 'axis-best'},
                             top));
      svg.appendChild(ctx.el('text', {x: x, y: H - BOTTOM + 16, 'text-anchor': 'middle',
                                      class: 'axis-worst'}, bottom));
      svg.appendChild(ctx.el('text', {x: x, y: H - BOTTOM + 32, 'text-anchor': 'middle'},
                             (ctx.normalisedAxes ? '[0 = best, 1 = worst] '
                                                 : (o.unit ? '[' + o.unit + '] ' : '')) +
                             (maximize(k) ? 'max' : 'min')));
      const b = ctx.brushes[k];
      if (b) {
        const y1 = yOf(k, b[0]), y2 = yOf(k, b[1]);
        svg.appendChild(ctx.el('rect', {x: x - 9, y: Math.min(y1, y2), width: 18,
                                        height: Math.max(Math.abs(y2 - y1), 1), class: 'brush',
                                        'data-axis': k, 'data-lo': b[0], 'data-hi': b[1],
                                        fill: '#ff7f0e', 'fill-opacity': 0.25,
                                        stroke: '#ff7f0e'}));
      }
      // The hit area of the axis for brushing.
      const hit = ctx.el('rect', {x: x - 12, y: TOP, width: 24, height: H - TOP - BOTTOM,
                                  fill: '#000', 'fill-opacity': 0, class: 'axis-hit',
                                  'data-axis': k});
      svg.appendChild(hit);
      hit.addEventListener('mousedown', function (ev) { startBrush(ev, k); });
    });
    const live = ctx.el('rect', {x: 0, y: 0, width: 18, height: 0, fill: '#ff7f0e',
                                 'fill-opacity': 0.25, stroke: '#ff7f0e', display: 'none'});
    svg.appendChild(live);

    function svgY(ev) {
      const p = svg.createSVGPoint();
      p.x = ev.clientX;
      p.y = ev.clientY;
      return p.matrixTransform(svg.getScreenCTM().inverse()).y;
    }
    function clampY(y) { return Math.min(H - BOTTOM, Math.max(TOP, y)); }
    function startBrush(ev, k) {
      ev.preventDefault();
      const y0 = clampY(svgY(ev));
      live.setAttribute('x', xOf(k) - 9);
      function move(e) {
        const y = clampY(svgY(e));
        live.setAttribute('y', Math.min(y0, y));
        live.setAttribute('height', Math.abs(y - y0));
        live.setAttribute('display', 'inline');
      }
      function up(e) {
        window.removeEventListener('mousemove', move);
        window.removeEventListener('mouseup', up);
        const y1 = clampY(svgY(e));
        if (Math.abs(y1 - y0) < 3) {
          delete ctx.brushes[k];
        } else {
          const a = valueOf(k, y0), b = valueOf(k, y1);
          ctx.brushes[k] = [Math.min(a, b), Math.max(a, b)];
        }
        ctx.onBrush();
      }
      window.addEventListener('mousemove', move);
      window.addEventListener('mouseup', up);
    }
    return svg;
  }
  return {draw: draw};
})();
