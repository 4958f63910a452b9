// The report's decision rules, the same as optimizer/decision.hpp and `pkmopt choose` (the
// report's page test checks that both choose the same design): every objective minimised (a
// maximised one negated by the caller), normalised by the candidates' ideal and nadir points.
//   pkmoptDecision.choose(F, rule, values) -> {index, normalised, weights}
//   rule: 'knee' | 'compromise' | 'weights' (values: preference >= 0) | 'reference' (values:
//   aspiration levels in the units of F)
window.pkmoptDecision = (function () {
  'use strict';
  const AUGMENTATION = 1e-6;  // rho of the augmented achievement scalarizing function

  function frontScale(F) {
    const m = F[0].length, ideal = F[0].slice(), nadir = F[0].slice();
    F.forEach(function (f) {
      for (let i = 0; i < m; i++) {
        ideal[i] = Math.min(ideal[i], f[i]);
        nadir[i] = Math.max(nadir[i], f[i]);
      }
    });
    return {ideal: ideal, nadir: nadir};
  }
  function normalised(scale, f) {
    return f.map(function (v, i) {
      const range = scale.nadir[i] - scale.ideal[i];
      return range > 0 ? (v - scale.ideal[i]) / range : 0;
    });
  }
  function pseudoWeights(fn) {
    const w = fn.map(function (v) { return 1 - v; });
    let total = 0;
    w.forEach(function (v) { total += v; });
    return w.map(function (v) { return total > 0 ? v / total : 1 / w.length; });
  }
  function squaredDistance(a, b) {
    let s = 0;
    for (let i = 0; i < a.length; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
    return s;
  }
  function smallest(values) {
    let best = 0;
    for (let k = 1; k < values.length; k++) if (values[k] < values[best]) best = k;
    return best;
  }
  function choose(F, rule, values) {
    const scale = frontScale(F);
    const N = F.map(function (f) { return normalised(scale, f); });
    let score;
    if (rule === 'knee') {
      score = N.map(function (fn) {
        let s = 0;
        fn.forEach(function (v) { s += v; });
        return s;
      });
    } else if (rule === 'compromise') {
      score = N.map(function (fn) { return squaredDistance(fn, fn.map(function () { return 0; })); });
    } else if (rule === 'weights') {
      let total = 0;
      values.forEach(function (v) { total += v; });
      const preference = values.map(function (v) { return v / total; });
      score = N.map(function (fn) { return squaredDistance(pseudoWeights(fn), preference); });
    } else {
      const zn = normalised(scale, values);
      score = N.map(function (fn) {
        let worst = -Infinity, sum = 0;
        for (let i = 0; i < fn.length; i++) {
          const term = fn[i] - zn[i];
          worst = Math.max(worst, term);
          sum += term;
        }
        return worst + AUGMENTATION * sum;
      });
    }
    const index = smallest(score);
    return {index: index, normalised: N[index], weights: pseudoWeights(N[index])};
  }
  return {frontScale: frontScale, normalised: normalised, pseudoWeights: pseudoWeights,
          choose: choose};
})();
