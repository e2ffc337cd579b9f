// The 2D curve view: Bezier, B-spline and NURBS curves whose control points
// you drag. Every point, parameter, knot and curvature drawn here is an
// answer of CurveService (Tessellate, Evaluate, Split, InsertKnots,
// ElevateDegree, Interpolate, Curvature); the page only turns them into SVG
// elements. The SVG's own transforms place and scale them: the world group
// flips y, and a comb tooth is the server's normal scaled by the server's
// curvature and the comb length you pick.

import {call, pointsMessage, pointsOf} from './rpc.js';
import {Refresher} from './refresher.js';

const SVG = 'http://www.w3.org/2000/svg';
// Samples of the curvature comb.
const COMB_TEETH = 64;
// The first curve: the worked cubic of README.md and examples/cubic_bezier.json.
const FIRST_CURVE = {
  kind: 'bezier',
  points: [[0, 0], [1, 2], [3, 2], [4, 0]],
  weights: [1, 1, 1, 1],
  degree: 3,
  knots: [],
};

function element(name, attributes = {}, parent = null) {
  const node = document.createElementNS(SVG, name);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (parent) parent.appendChild(node);
  return node;
}

function polylinePoints(points) {
  return points.map(([x, y]) => `${x},${y}`).join(' ');
}

function formatNumber(value) {
  return Number.isInteger(value) ? String(value) : value.toPrecision(6).replace(/0+$/, '');
}

// CurveView owns the state of the curve and its SVG drawing.
export class CurveView {
  constructor(root, report) {
    this.root = root;
    this.report = report;
    this.svg = root.querySelector('svg');
    this.world = this.svg.querySelector('.world');
    this.layers = {};
    for (const name of ['before', 'construction', 'comb', 'polygon', 'curve', 'data', 'at', 'handles']) {
      this.layers[name] = element('g', {class: name}, this.world);
    }
    this.controls = Object.fromEntries(
        [...root.querySelectorAll('[data-control]')].map((node) => [node.dataset.control, node]));
    this.state = {...structuredClone(FIRST_CURVE), t: 0.5, selected: 1, before: null,
      data: null, domain: [0, 1]};
    // What the last redraw drew: the polyline's points and parameters, as
    // the server's Tessellate returned them.
    this.drawn = {points: [], parameters: [], curve: null};
    this.refresher = new Refresher(() => this.redraw(), report);
    this.bindControls();
    this.bindPointer();
  }

  // curveMessage returns the state's curve as a freeform.v1.Curve.
  curveMessage() {
    const {kind, points, weights, degree, knots} = this.state;
    const controlPoints = pointsMessage(points);
    if (kind === 'bezier') return {bezier: {controlPoints}};
    const bspline = {degree, controlPoints, knots};
    if (kind === 'nurbs') bspline.weights = weights;
    return {bspline};
  }

  // adopt takes a curve the server answered as the new state.
  adopt(curve, kind = this.state.kind) {
    if (curve.bezier) {
      this.state.points = pointsOf(curve.bezier.controlPoints);
      this.state.degree = this.state.points.length - 1;
      this.state.knots = [];
    } else {
      this.state.points = pointsOf(curve.bspline.controlPoints);
      this.state.degree = curve.bspline.degree ?? 0;
      this.state.knots = curve.bspline.knots ?? [];
    }
    const weights = (curve.bezier ?? curve.bspline).weights;
    this.state.weights = weights ?? this.state.points.map(() => 1);
    this.state.kind = kind;
    this.state.selected = Math.min(this.state.selected, this.state.points.length - 1);
  }

  // uniformKnots asks the server for a clamped knot vector of `degree` for
  // the control points: the knots of the B-spline that interpolates them at
  // uniform parameters with the uniform knot rule.
  async uniformKnots(degree) {
    const answer = await call('CurveService', 'Interpolate', {
      points: pointsMessage(this.state.points),
      bspline: {degree, parameterization: 'PARAMETERIZATION_UNIFORM', knotRule: 'KNOT_RULE_UNIFORM'},
    });
    return answer.curve.bspline.knots;
  }

  async changeKind(kind) {
    this.state.before = null;
    if (kind !== 'bezier') {
      const degree = Math.min(3, this.state.points.length - 1);
      this.state.knots = await this.uniformKnots(degree);
      this.state.degree = degree;
    }
    this.state.kind = kind;
    this.state.t = null;
    this.refresh();
  }

  async changeDegree(degree) {
    this.state.knots = await this.uniformKnots(degree);
    this.state.degree = degree;
    this.state.before = null;
    this.state.t = null;
    this.refresh();
  }

  async insertKnot() {
    const before = this.state.points;
    const answer = await call('CurveService', 'InsertKnots',
        {curve: this.curveMessage(), knots: [this.state.t]});
    this.adopt(answer.curve);
    this.state.before = {what: `knot ${formatNumber(this.state.t)} inserted`, points: before};
    this.refresh();
  }

  async elevateDegree() {
    const before = this.state.points;
    const answer = await call('CurveService', 'ElevateDegree', {curve: this.curveMessage(), by: 1});
    this.adopt(answer.curve);
    this.state.before = {what: `degree elevated to ${this.state.degree}`, points: before};
    this.refresh();
  }

  // addDataPoint interpolates, with a B-spline, the points clicked so far.
  async addDataPoint(point) {
    this.state.data.push(point);
    if (this.state.data.length < 2) return this.refresh();
    const degree = Math.min(3, this.state.data.length - 1);
    const answer = await call('CurveService', 'Interpolate',
        {points: pointsMessage(this.state.data), bspline: {degree}});
    this.adopt(answer.curve, this.state.kind === 'nurbs' ? 'nurbs' : 'bspline');
    this.state.before = null;
    this.state.t = null;
    this.refresh();
  }

  reset() {
    Object.assign(this.state, structuredClone(FIRST_CURVE),
        {t: 0.5, selected: 1, before: null, data: null});
    this.refresh();
  }

  refresh() {
    this.syncControls();
    this.refresher.request();
  }

  settled() {
    return this.refresher.settled();
  }

  bindControls() {
    const {kind, degree, knots, weight, t, construction, comb, combLength, tolerance} = this.controls;
    const guarded = (action) => (...args) => action(...args).catch((error) => this.report(error));
    kind.addEventListener('change', guarded(() => this.changeKind(kind.value)));
    degree.addEventListener('change', guarded(() => this.changeDegree(Number(degree.value))));
    knots.addEventListener('change', () => {
      this.state.knots = knots.value.split(/[\s,]+/).filter(Boolean).map(Number);
      this.state.before = null;
      this.refresh();
    });
    weight.addEventListener('input', () => {
      this.state.weights[this.state.selected] = Number(weight.value);
      this.refresh();
    });
    t.addEventListener('input', () => {
      this.state.t = Number(t.value);
      this.refresh();
    });
    for (const control of [construction, comb, combLength, tolerance]) {
      control.addEventListener('change', () => this.refresh());
    }
    this.controls.insertKnot.addEventListener('click', guarded(() => this.insertKnot()));
    this.controls.elevate.addEventListener('click', guarded(() => this.elevateDegree()));
    this.controls.interpolate.addEventListener('click', () => {
      this.state.data = this.state.data ? null : [];
      this.refresh();
    });
    this.controls.reset.addEventListener('click', () => this.reset());
  }

  // toWorld returns the world point under a pointer event, as the SVG's
  // own transform maps it.
  toWorld(event) {
    const matrix = this.world.getScreenCTM().inverse();
    const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix);
    return [point.x, point.y];
  }

  // toScreen returns the client coordinates of a world point (for tests).
  toScreen([x, y]) {
    const point = new DOMPoint(x, y).matrixTransform(this.world.getScreenCTM());
    return {x: point.x, y: point.y};
  }

  bindPointer() {
    let dragging = null;
    this.svg.addEventListener('pointerdown', (event) => {
      const handle = event.target.closest('.handle');
      if (handle) {
        dragging = Number(handle.dataset.index);
        this.state.selected = dragging;
        this.svg.setPointerCapture(event.pointerId);
        this.refresh();
      } else if (this.state.data) {
        this.addDataPoint(this.toWorld(event)).catch((error) => this.report(error));
      }
    });
    this.svg.addEventListener('pointermove', (event) => {
      if (dragging === null) return;
      this.state.points[dragging] = this.toWorld(event);
      this.state.before = null;
      this.refresh();
    });
    const release = () => {
      dragging = null;
    };
    this.svg.addEventListener('pointerup', release);
    this.svg.addEventListener('pointercancel', release);
  }

  syncControls() {
    const {kind, degree, knots, weight, weightValue, interpolate} = this.controls;
    const {state} = this;
    kind.value = state.kind;
    this.root.dataset.kind = state.kind;
    degree.value = String(state.degree);
    knots.value = state.knots.map(String).join(', ');
    weight.value = String(state.weights[state.selected] ?? 1);
    weightValue.textContent = formatNumber(state.weights[state.selected] ?? 1);
    interpolate.classList.toggle('active', Boolean(state.data));
    interpolate.textContent = state.data ? 'Stop interpolating' : 'Interpolate clicks';
  }

  // redraw asks the server for everything the drawing shows, then draws it.
  async redraw() {
    const curve = this.curveMessage();
    const tolerance = Number(this.controls.tolerance.value);
    const tessellation = await call('CurveService', 'Tessellate', {curve, tolerance});
    const parameters = tessellation.parameters ?? [];
    // The domain runs from the tessellation's first vertex to its last.
    this.state.domain = [parameters[0], parameters.at(-1)];
    const {domain} = this.state;
    if (this.state.t === null || !(this.state.t >= domain[0] && this.state.t <= domain[1])) {
      this.state.t = parameters[parameters.length >> 1];
    }
    const {t} = this.state;
    const [atT, construction, comb] = await Promise.all([
      call('CurveService', 'Evaluate', {curve, parameters: {list: {values: [t]}}}),
      this.controls.construction.checked ? this.construction(curve, t) : [],
      this.controls.comb.checked ? this.comb(curve) : null,
    ]);
    if (this.refresher.superseded) return;
    this.drawn = {points: pointsOf(tessellation.points), parameters, curve, t};
    this.draw(pointsOf(atT.derivatives[0])[0], construction, comb);
  }

  // construction returns the polygons of the construction at t: for a
  // Bezier curve the levels of the de Casteljau triangle (level r point i is
  // the last control point of the left piece of P_i..P_n split at t, the
  // same point as the server's split gives); for a B-spline or NURBS curve
  // the control polygons after inserting t once, twice, ... up to the
  // degree (de Boor's construction).
  async construction(curve, t) {
    const {domain, points, degree, knots} = this.state;
    if (!(t > domain[0] && t < domain[1])) return [];
    if (curve.bezier) {
      const lefts = await Promise.all(points.slice(0, -1).map(async (_, first) => {
        const bezier = {controlPoints: pointsMessage(points.slice(first))};
        const answer = await call('CurveService', 'Split', {curve: {bezier}, parameters: [t]});
        return pointsOf(answer.pieces[0].bezier.controlPoints);
      }));
      return points.slice(1).map((_, level) =>
          lefts.slice(0, points.length - level - 1).map((left) => left[level + 1]));
    }
    const multiplicity = knots.filter((knot) => knot === t).length;
    const insertions = [];
    for (let times = 1; times <= degree - multiplicity; times++) {
      insertions.push(Array(times).fill(t));
    }
    return Promise.all(insertions.map(async (inserted) => {
      const answer = await call('CurveService', 'InsertKnots', {curve, knots: inserted});
      return pointsOf(answer.curve.bspline.controlPoints);
    }));
  }

  // comb returns the points, normals and curvatures of the comb's teeth.
  async comb(curve) {
    const parameters = {range: {count: COMB_TEETH}};
    const [positions, curvature] = await Promise.all([
      call('CurveService', 'Evaluate', {curve, parameters}),
      call('CurveService', 'Curvature', {curve, parameters}),
    ]);
    return {
      points: pointsOf(positions.derivatives[0]),
      normals: pointsOf(curvature.normals),
      curvatures: curvature.curvatures ?? [],
    };
  }

  draw(pointAtT, construction, comb) {
    const {layers, state} = this;
    for (const layer of Object.values(layers)) layer.replaceChildren();
    if (state.before) {
      element('polyline', {points: polylinePoints(state.before.points)}, layers.before);
      for (const [x, y] of state.before.points) {
        element('circle', {cx: x, cy: y, r: 0.05}, layers.before);
      }
    }
    construction.forEach((level, index) => {
      element('polyline', {points: polylinePoints(level), class: `level level-${index % 4}`},
          layers.construction);
      for (const [x, y] of level) element('circle', {cx: x, cy: y, r: 0.03}, layers.construction);
    });
    if (comb) this.drawComb(comb);
    element('polyline', {points: polylinePoints(state.points)}, layers.polygon);
    element('polyline', {points: polylinePoints(this.drawn.points), id: 'curve-line'}, layers.curve);
    for (const [x, y] of state.data ?? []) {
      element('rect', {x, y, width: 0.08, height: 0.08, transform: 'translate(-0.04 -0.04)'},
          layers.data);
    }
    element('circle', {cx: pointAtT[0], cy: pointAtT[1], r: 0.06}, layers.at);
    state.points.forEach(([x, y], index) => {
      element('circle', {cx: x, cy: y, r: 0.08, class: index === state.selected ? 'handle selected' : 'handle',
        'data-index': index}, layers.handles);
    });
    this.drawReadout(pointAtT);
  }

  // drawComb draws each tooth as the server's normal at the server's point,
  // scaled by minus the curvature and the comb length (SVG transforms do
  // the scaling), so that the teeth point away from the centre of
  // curvature.
  drawComb({points, normals, curvatures}) {
    const length = this.controls.combLength.value;
    points.forEach(([x, y], index) => {
      const [nx, ny] = normals[index] ?? [0, 0];
      element('line', {x1: 0, y1: 0, x2: nx, y2: ny,
        transform: `translate(${x} ${y}) scale(-${length}) scale(${curvatures[index] ?? 0})`},
      this.layers.comb);
    });
  }

  drawReadout(pointAtT) {
    const {state, controls} = this;
    controls.t.min = String(state.domain[0]);
    controls.t.max = String(state.domain[1]);
    controls.t.value = String(this.drawn.t);
    controls.tValue.textContent = formatNumber(this.drawn.t);
    controls.pointAtT.textContent = `(${pointAtT.map(formatNumber).join(', ')})`;
    controls.drawnCount.textContent = String(this.drawn.points.length);
    controls.controlPoints.textContent = state.points
        .map((point, index) => `P${index} = (${point.map(formatNumber).join(', ')})` +
            (state.kind === 'nurbs' ? `  w = ${formatNumber(state.weights[index])}` : ''))
        .join('\n');
    controls.before.textContent = state.before ?
      `${state.before.what}: ${state.before.points.length} control points before (dashed), ` +
      `${state.points.length} after` : '';
  }
}
