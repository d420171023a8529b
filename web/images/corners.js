// The preview with four draggable corner handles (pointer and keyboard) and the patch grid drawn
// over it. Coordinates are those of the measurement image (half resolution), as sampleChart wants.
// The grid is the engine's: its chart layout placed by its homography while the corners move,
// then the sampled areas of the engine's sampling once it belongs to these corners. A detected
// chart (setDetected) is drawn as a dashed proposal with its own patch grid until it is used,
// and labelled with its confidence. Corners outside the image (a chart cut by the frame) are
// shown in a padded view: the preview is letterboxed in a dark margin that holds every handle,
// so the handles stay visible and draggable and never spill over what follows the editor.

const NS = 'http://www.w3.org/2000/svg';
const svgEl = (tag, attrs = {}) => {
  const e = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  return e;
};
const CORNER_NAMES = ['top-left (first patch)', 'top-right', 'bottom-right (last patch)', 'bottom-left'];

/// The patch cells of a layout placed by a homography (row-major 3 × 3, unit square -> image): [{id, quad}].
export function gridCells({ layout, homography: H }) {
  const map = (u, v) => { const w = H[6] * u + H[7] * v + H[8]; return [(H[0] * u + H[1] * v + H[2]) / w, (H[3] * u + H[4] * v + H[5]) / w]; };
  return layout.patches.map((p) => ({ id: p.id, quad: [[p.u0, p.v0], [p.u1, p.v0], [p.u1, p.v1], [p.u0, p.v1]].map(([u, v]) => map(u, v)) }));
}
const cornersText = (c) => [0, 1, 2, 3].map((i) => `${c[2 * i]},${c[2 * i + 1]}`).join(' ');

export class CornerEditor {
  /// onChange(corners, final); grid(layout, corners) -> Promise<{layout: ChartLayout, homography}>.
  /// clipId: the id of the image's clip path (unique per editor on the page).
  constructor({ onChange, grid, clipId = 'image-clip' }) {
    this.onChange = onChange;
    this.gridOf = grid;
    this.width = 0; this.height = 0;
    this.corners = new Float64Array(8);
    this.layout = { chart: 'passport' };
    this.grid = null;          // {layout, homography, key} of the last placed grid
    this.sample = null;
    this.refused = null;       // the code of the last refused sampling of these corners
    this.detected = null;      // {candidate, proposal}: a detected chart, drawn as a proposal or labelled in use
    this.trap = null;          // the light trap {x, y, w, h} (measurement-image pixels), or null
    this.onTrapDrawn = null;   // while marking a light trap: called with the rectangle dragged out
    this.onHelp = null;        // while asking where the chart is: called with {seed: [x, y]} (a click) or {box: [x0, y0, x1, y1]} (a drag)
    this.el = document.createElement('div');
    this.el.className = 'corner-editor';
    this.el.tabIndex = -1;
    this.canvas = document.createElement('canvas');
    this.canvas.setAttribute('aria-hidden', 'true');
    this.svg = svgEl('svg', { class: 'overlay', role: 'group', 'aria-label': 'Chart corners on the preview' });
    this.gridLayer = svgEl('g', { class: 'grid', 'clip-path': `url(#${clipId})` });
    const clip = svgEl('clipPath', { id: clipId });
    this.clipRect = svgEl('rect', { x: 0, y: 0, width: 1, height: 1 });
    clip.append(this.clipRect);
    const defs = svgEl('defs');
    defs.append(clip);
    this.outline = svgEl('polygon', { class: 'outline' });
    this.handleLayer = svgEl('g', { class: 'handles' });
    this.detectLayer = svgEl('g', { class: 'detected', 'clip-path': `url(#${clipId})` });
    this.detectLabel = svgEl('text', { class: 'detect-label' });
    this.trapRect = svgEl('rect', { class: 'light-trap' });
    this.trapLabel = svgEl('text', { class: 'light-trap-label' });
    this.trapLabel.textContent = 'light trap';
    this.helpRect = svgEl('rect', { class: 'detect-help', fill: 'rgba(80, 160, 255, .12)', stroke: '#4da3ff', 'stroke-width': 2, 'stroke-dasharray': '4 3', 'vector-effect': 'non-scaling-stroke' });
    this.helpRect.style.display = 'none';
    this.frame = svgEl('rect', { class: 'image-frame', x: 0, y: 0, width: 1, height: 1 });   // the image's edge in a padded view
    this.view = null;          // [x0, y0, x1, y1]: the area shown (the image, or more when a corner lies outside it)
    this.dragging = false;     // the view stays put while a handle is dragged (it would move under the pointer)
    this.svg.append(defs, this.frame, this.detectLayer, this.outline, this.gridLayer, this.detectLabel, this.trapRect, this.trapLabel, this.helpRect, this.handleLayer);
    // Marking a light trap: a drag on the image (not on a handle) draws its rectangle.
    this.svg.addEventListener('pointerdown', (e) => {
      if (!this.onTrapDrawn && this.onHelp && !e.target.closest('.handle')) { this.pointAtChart(e); return; }
      if (!this.onTrapDrawn || e.target.closest('.handle')) return;
      e.preventDefault();
      this.svg.setPointerCapture(e.pointerId);
      const [x0, y0] = this.toImage(e);
      const rectOf = (ev) => {
        const [x1, y1] = this.toImage(ev);
        const r = (v) => Math.round(v * 10) / 10;
        return { x: r(Math.min(x0, x1)), y: r(Math.min(y0, y1)), w: r(Math.abs(x1 - x0)), h: r(Math.abs(y1 - y0)) };
      };
      const move = (ev) => this.setLightTrap(rectOf(ev));
      const up = (ev) => {
        this.svg.releasePointerCapture(ev.pointerId);
        this.svg.removeEventListener('pointermove', move);
        this.svg.removeEventListener('pointerup', up);
        const done = this.onTrapDrawn;
        this.onTrapDrawn = null;
        this.el.classList.remove('marking');
        done(rectOf(ev));
      };
      this.svg.addEventListener('pointermove', move);
      this.svg.addEventListener('pointerup', up);
    });
    this.el.append(this.canvas, this.svg);
    this.el.hidden = true;
    this.handles = CORNER_NAMES.map((name, i) => this.makeHandle(i, name));
  }

  /// Where the chart is, from the user: a click (moving less than 6 screen px) gives a seed point,
  /// a drag a rough box, drawn while it is dragged; both in measurement-image pixels.
  pointAtChart(e) {
    e.preventDefault();
    this.svg.setPointerCapture(e.pointerId);
    const [x0, y0] = this.toImage(e);
    const r = (v) => Math.round(v * 10) / 10;
    const isClick = (ev) => Math.hypot(ev.clientX - e.clientX, ev.clientY - e.clientY) < 6;
    const move = (ev) => {
      const [x1, y1] = this.toImage(ev);
      this.helpRect.style.display = isClick(ev) ? 'none' : '';
      for (const [k, v] of Object.entries({ x: Math.min(x0, x1), y: Math.min(y0, y1), width: Math.abs(x1 - x0), height: Math.abs(y1 - y0) })) this.helpRect.setAttribute(k, v);
    };
    const up = (ev) => {
      this.svg.releasePointerCapture(ev.pointerId);
      this.svg.removeEventListener('pointermove', move);
      this.svg.removeEventListener('pointerup', up);
      this.helpRect.style.display = 'none';
      const [x1, y1] = this.toImage(ev);
      const done = this.onHelp;
      if (done) done(isClick(ev) ? { seed: [r(x0), r(y0)] } : { box: [r(Math.min(x0, x1)), r(Math.min(y0, y1)), r(Math.max(x0, x1)), r(Math.max(y0, y1))] });
    };
    this.svg.addEventListener('pointermove', move);
    this.svg.addEventListener('pointerup', up);
  }

  /// Arms (a function) or disarms (null) pointAtChart: a click or drag on the image, not on a handle.
  askWhereTheChartIs(onHelp) {
    this.onHelp = onHelp;
    this.el.classList.toggle('pointing', !!onHelp);
    this.svg.style.cursor = onHelp ? 'crosshair' : '';
  }

  makeHandle(i, name) {
    const g = svgEl('g', { class: 'handle', tabindex: 0, role: 'slider', 'aria-label': `Corner ${i + 1}, ${name}` });
    g.dataset.corner = i;
    const hit = svgEl('circle', { r: 16, class: 'hit' });   // a larger target for fingers and mice
    const ring = svgEl('circle', { r: 9, class: 'ring' });
    const dot = svgEl('circle', { r: 2, class: 'dot' });
    const label = svgEl('text', { dx: 11, dy: -9 });
    label.textContent = String(i + 1);
    g.append(hit, ring, dot, label);
    this.handleLayer.append(g);
    g.addEventListener('pointerdown', (e) => {
      e.preventDefault();
      g.setPointerCapture(e.pointerId);
      g.focus();
      this.dragging = true;
      this.el.classList.add('dragging');
      const move = (ev) => { const [x, y] = this.toImage(ev); this.moveCorner(i, x, y, false); };
      const up = (ev) => {
        g.releasePointerCapture(ev.pointerId);
        g.removeEventListener('pointermove', move);
        g.removeEventListener('pointerup', up);
        this.dragging = false;
        this.el.classList.remove('dragging');
        this.draw();   // the view takes in where the handle was dropped
        this.onChange(this.corners, true);
      };
      g.addEventListener('pointermove', move);
      g.addEventListener('pointerup', up);
    });
    g.addEventListener('keydown', (e) => {
      const step = e.shiftKey ? 10 : 1;
      const d = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, -step], ArrowDown: [0, step] }[e.key];
      if (!d) return;
      e.preventDefault();
      this.moveCorner(i, this.corners[2 * i] + d[0], this.corners[2 * i + 1] + d[1], false);
      this.onChange(this.corners, false);
    });
    return g;
  }

  toImage(ev) {
    const pt = this.svg.createSVGPoint();
    pt.x = ev.clientX; pt.y = ev.clientY;
    const p = pt.matrixTransform(this.svg.getScreenCTM().inverse());
    return [p.x, p.y];
  }

  moveCorner(i, x, y, notify = true) {
    this.corners[2 * i] = Math.round(x * 10) / 10;
    this.corners[2 * i + 1] = Math.round(y * 10) / 10;
    this.draw();
    if (notify) this.onChange(this.corners, true);
  }

  /// r: {width, height, preview: {width, height, rgba}} from the worker's decode.
  setImage(r) {
    this.width = r.width; this.height = r.height;
    this.el.hidden = false;
    this.view = null;
    const p = r.preview;
    if (p) {
      this.canvas.width = p.width; this.canvas.height = p.height;
      this.canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(p.rgba), p.width, p.height), 0, 0);
    } else {
      this.canvas.width = r.width; this.canvas.height = r.height;
    }
    this.draw();
  }

  /// The area shown: the image, padded to hold every handle when a corner lies outside it (or so
  /// near its edge that the handle would be cut), at most one image size beyond each edge. The
  /// canvas (the image) is placed inside it in percent; the element's aspect ratio follows.
  fitView(scale) {
    const w = this.width, hh = this.height, c = this.corners, r = 12 * scale, pad = 30 * scale;
    const xs = [0, 1, 2, 3].map((i) => c[2 * i]), ys = [0, 1, 2, 3].map((i) => c[2 * i + 1]);
    const out = xs.some((x) => x - r < 0 || x + r > w) || ys.some((y) => y - r < 0 || y + r > hh);
    const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
    const v = out ? [clamp(Math.min(0, ...xs.map((x) => x - pad)), -w, 0), clamp(Math.min(0, ...ys.map((y) => y - pad)), -hh, 0),
      clamp(Math.max(w, ...xs.map((x) => x + pad)), w, 2 * w), clamp(Math.max(hh, ...ys.map((y) => y + pad)), hh, 2 * hh)]
      : [0, 0, w, hh];
    if (this.view && v.every((x, i) => x === this.view[i])) return;
    this.view = v;
    const [x0, y0, x1, y1] = v, vw = x1 - x0, vh = y1 - y0;
    this.svg.setAttribute('viewBox', `${x0} ${y0} ${vw} ${vh}`);
    this.el.style.aspectRatio = `${vw} / ${vh}`;
    this.el.classList.toggle('padded', out);
    Object.assign(this.canvas.style, { left: `${(-x0 / vw) * 100}%`, top: `${(-y0 / vh) * 100}%`, width: `${(w / vw) * 100}%`, height: `${(hh / vh) * 100}%` });
    this.frame.setAttribute('width', w);
    this.frame.setAttribute('height', hh);
  }

  setCorners(c) { this.corners = Float64Array.from(c); this.draw(); }

  /// Default corners: a centred rectangle over 60 % of the image.
  reset() {
    const w = this.width, hh = this.height;
    this.setCorners([0.2 * w, 0.2 * hh, 0.8 * w, 0.2 * hh, 0.8 * w, 0.8 * hh, 0.2 * w, 0.8 * hh]);
    if (w) this.onChange(this.corners, true);
  }

  setLayout(layout) { this.layout = layout; this.draw(); }
  /// The light trap's rectangle {x, y, w, h} drawn over the image (null: none).
  setLightTrap(rect) { this.trap = rect; this.draw(); }
  /// The next drag on the image marks the light trap; onDone(rect) gets it.
  markLightTrap(onDone) { this.onTrapDrawn = onDone; this.el.classList.add('marking'); }
  /// The engine's sampling of the current corners, or null and the code it refused them with.
  setSample(s, refused = null) { this.sample = s; this.refused = refused; this.draw(); }

  /// Asks the engine for the grid of the current layout and corners (one request at a time).
  placeGrid(key) {
    if (this.placing || this.requested === key) return;
    this.requested = key;
    this.placing = this.gridOf(this.layout, Array.from(this.corners))
      .then((g) => { this.grid = { ...g, key }; }, () => { this.grid = null; })
      .finally(() => { this.placing = null; this.draw(); });
  }

  /// A detected chart (ChartCandidate with its `grid` {layout, homography}) drawn as a proposal
  /// (dashed outline and patch grid) or, once its corners are used, only its confidence label.
  /// null: nothing detected.
  setDetected(candidate, { proposal = false } = {}) {
    this.detected = candidate ? { candidate, proposal } : null;
    this.draw();
  }

  drawDetected(scale) {
    const d = this.detected;
    this.detectLabel.style.display = d ? '' : 'none';   // (SVG elements have no `hidden`)
    this.detectLayer.replaceChildren();
    if (!d) return;
    const c = d.candidate;
    if (d.proposal) {
      const residual = new Map(c.patches.map((p) => [p.id, p.residual]));
      const outline = svgEl('polygon', { class: 'detected-outline', points: cornersText(c.corners) });
      this.detectLayer.append(outline, ...gridCells(c.grid).map((cell) => {
        const r = residual.get(cell.id);
        const poly = svgEl('polygon', { points: cell.quad.map((p) => p.join(',')).join(' '), class: `detected-cell${r > 0.1 ? ' poor' : ''}` });
        const t = svgEl('title');
        t.textContent = `${cell.id} (detected): ${Number.isFinite(r) ? `${(100 * r).toFixed(1)} % from the reference after a 3×3 fit` : ''}`;
        poly.append(t);
        poly.dataset.id = cell.id;
        return poly;
      }));
    }
    // The label sits above the chart's top edge (the edge nearer the image's top).
    const xs = [0, 1, 2, 3].map((i) => c.corners[2 * i]), ys = [0, 1, 2, 3].map((i) => c.corners[2 * i + 1]);
    this.detectLabel.setAttribute('x', Math.min(...xs));
    this.detectLabel.setAttribute('y', Math.max(14 * scale, Math.min(...ys) - 22 * scale));
    this.detectLabel.setAttribute('font-size', 13 * scale);
    this.detectLabel.textContent = `${d.proposal ? 'detected' : 'in use: detected'} ${c.chart} · confidence ${c.confidence.toFixed(2)}`;
  }

  draw() {
    const c = this.corners;
    this.outline.setAttribute('points', cornersText(c));
    this.outline.classList.toggle('crossed', this.refused === 'CORNERS_CROSSED');
    this.clipRect.setAttribute('width', this.width);
    this.clipRect.setAttribute('height', this.height);
    this.handles.forEach((g, i) => {
      g.setAttribute('transform', `translate(${c[2 * i]},${c[2 * i + 1]})`);
      g.setAttribute('aria-valuetext', `x ${c[2 * i].toFixed(1)}, y ${c[2 * i + 1].toFixed(1)}`);
    });
    const flagsById = new Map();
    const s = this.sample && this.sample.corners?.every((v, i) => v === c[i]) ? this.sample : null;
    if (s) s.ids.forEach((id, i) => flagsById.set(id, s.flags[i]));
    const scale = Math.max(1, this.width / 900);
    if (this.width && !this.dragging) this.fitView(scale);
    this.svg.style.setProperty('--stroke', `${1.2 * scale}px`);
    // The engine's sample areas when they belong to these corners; its placed grid while dragging.
    const key = JSON.stringify([this.layout, Array.from(c)]);
    if (!s && this.grid?.key !== key && this.width) this.placeGrid(key);
    const cells = s ? s.ids.map((id, i) => ({ id, quad: [0, 1, 2, 3].map((k) => [s.sample_quads[8 * i + 2 * k], s.sample_quads[8 * i + 2 * k + 1]]) }))
      : this.refused || !this.grid ? [] : gridCells(this.grid);
    this.gridLayer.replaceChildren(...cells.map((cell) => {
      const id = cell.id;
      const flags = flagsById.get(id);
      const poly = svgEl('polygon', { points: cell.quad.map((p) => p.join(',')).join(' '), class: `cell${flags?.includes('saturated') ? ' saturated' : flags?.length ? ' warn' : ''}` });
      const t = svgEl('title');
      t.textContent = `${id}${flags?.length ? ': ' + flags.join(', ') : ''}`;
      poly.append(t);
      poly.dataset.id = id;
      return poly;
    }));
    this.drawDetected(scale);
    const t = this.trap;
    this.trapRect.style.display = this.trapLabel.style.display = t ? '' : 'none';
    if (t) {
      for (const [k, v] of Object.entries({ x: t.x, y: t.y, width: t.w, height: t.h })) this.trapRect.setAttribute(k, v);
      this.trapLabel.setAttribute('x', t.x);
      this.trapLabel.setAttribute('y', Math.max(12 * scale, t.y - 4 * scale));
      this.trapLabel.setAttribute('font-size', 12 * scale);
    }
    for (const g of this.handles) {
      g.querySelector('circle.ring').setAttribute('r', 9 * scale);
      g.querySelector('circle.hit').setAttribute('r', 16 * scale);
    }
  }
}
