// Step 2's extra chart images (issue 48, docs/multi-image.md): "Add chart image" — any number of
// further photographs, each in its own panel (extra_panel.js: chart image k = 2, 3, … with its own
// dark frames and flat field, layout or custom grid, light trap and reference), or the second chart
// detection found in step 2's own image ("Use both charts found": chart image 2). The Fit then
// trains on the union of every chart's patches exactly as
// `tristim fit --recipe r.json --raw a --raw b --raw c …` does: withImages() turns the fit's recipe
// into one with an `images` list, chartsOf() gives the worker each image's sample, sourceKeys() the
// files a share link names. Removing image k moves the later ones down (k+1 becomes k).
import { h, field, select } from '../lib/ui.js';
import { mountPanel } from './extra_panel.js';
import { framesCapture } from './extra_frames.js';

const KEYS = ['chart', 'files.chart', 'files.dark', 'files.flat'];   // one session entry per image k: `${key}${k}`

/// The numbers k (2, 3, …) of the extra chart images the session holds, in order.
const storedImages = (app) => Object.keys(app.session).map((key) => /^chart(\d+)$/.exec(key)?.[1])
  .filter((k) => k && Number(k) >= 2 && app.session[`chart${k}`]).map(Number).sort((a, b) => a - b);
/// The extra chart images sampled at their corners: the ones a fit trains on, in order.
const ready = (app) => storedImages(app).filter((k) => app.derived[`sample${k}`] && app.session[`chart${k}`].corners);
const duplicatesOf = (app) => app.session.duplicates ?? app.session.chart2?.duplicates ?? 'once';

/// Mounts the extra images' panels in `parent`; returns {restore, useCandidate, firstChanged, add,
/// remove, panel(k)}. ensureFirst(): step 2's own image is decoded in this worker.
export function mountSecond(parent, app, { ensureFirst }) {
  // How patches of the same colour in several images count (the recipe's `duplicates`).
  const dupSel = select([
    { value: 'once', label: 'once: the same patch of the same chart in several images is one row (mean RGB)' },
    { value: 'each', label: 'each: every image\'s patches are rows of their own' }], duplicatesOf(app));
  dupSel.dataset.role = 'duplicates';
  const box = h('div', { class: 'extra-images' });
  const addBtn = h('button', { type: 'button', class: 'add-image', hidden: true, onclick: () => add() }, 'Add chart image');
  parent.append(box, h('div', { class: 'controls' }, addBtn));
  let panels = [];

  /// An image's sample or reference changed: the fit's data note and the "Add" button follow.
  function changed() {
    addBtn.hidden = panels.some((p) => p.empty());
    app.emit('sample2', app.derived.sample2 ?? null);
  }
  dupSel.addEventListener('change', async () => { await app.save('duplicates', dupSel.value); changed(); });
  function make(k) {
    const p = mountPanel(app, k, { ensureFirst, changed, remove, more: k === 2 ? [field('Patches of the same colour', dupSel)] : [] });
    box.append(p.el);
    panels.push(p);
    return p;
  }
  /// A new empty panel after the last one.
  function add() {
    const p = make(Math.max(1, ...panels.map((x) => x.k)) + 1);
    addBtn.hidden = true;
    p.el.querySelector('input[type=file]')?.focus();
    return p;
  }
  /// Removes chart image k: the later images move down one place (their files decoded again).
  async function remove(k) {
    const moved = panels.filter((p) => p.k >= k).map((p) => p.k);
    for (const p of panels.filter((x) => x.k >= k)) await p.dispose();
    panels = panels.filter((p) => p.k < k);
    const last = Math.max(...moved);
    for (const j of moved) for (const key of KEYS) await app.save(`${key}${j}`, j < last ? app.session[`${key}${j + 1}`] : undefined);
    for (const j of moved.slice(0, -1)) make(j);
    if (!panels.length) make(2);
    changed();
    for (const p of panels.filter((x) => x.k >= k)) await p.restore();
  }
  make(2);

  return {
    /// The session's extra images (a reload): each decoded and sampled at its stored corners.
    async restore() {
      for (const k of storedImages(app)) if (!panels.some((p) => p.k === k)) make(k);
      for (const p of panels) await p.restore();
      changed();
    },
    /// "Use both charts found": detection's candidate c in step 2's own image becomes chart image 2.
    useCandidate: (c) => panels.find((p) => p.k === 2).useCandidate(c),
    /// Step 2's own image or layout changed: its second chart, if chart image 2 is that, is gone.
    firstChanged: () => (app.session.chart2?.sameImage ? remove(2) : null),
    add,
    remove,
    panel: (k) => panels.find((p) => p.k === k),
  };
}

/// Chart image k's capture stage, when it needs its own: its frames, its light trap and flare
/// (Abed 2013 App. C steps 1-2); left out (the recipe's own) when it has neither and the first
/// image has no light trap (else that trap would be measured on this image too).
function captureOf(app, k, s, capture) {
  const frames = framesCapture(app, k);
  if (!Object.keys(frames).length && !s.lightTrap && !capture.light_trap) return {};
  return { capture: { dark_frames: 0, dark_mode: 'per_pixel', flat_field: false, falloff: false, ...frames,
    ...(s.lightTrap ? { light_trap: s.lightTrapCorners, flare: Array.from(s.lightTrap.mean) } : {}) } };
}

/// The recipe of a fit on the chart images of step 2: `recipe` itself with one image, or with an
/// `images` list — the first image's stages, then each extra image's (its layout or custom grid,
/// its chart's or its file's reference under step 1's illuminant and observer, its own frames and
/// light trap; the second chart of the first image: that image's file and stages, its own corners)
/// — and `duplicates`. Every image leaves out the patches the recipe's flag rule names
/// (`sampling.exclude_flags` / `exclude_flagged`, applied by the engine).
export async function withImages(app, recipe) {
  const ks = ready(app);
  if (!ks.length) return recipe;
  const first = app.session['files.chart'];
  const sha = (app.derived.chartDigest ??= { bytes: null, sha256: '' });
  if (sha.bytes !== first.bytes) Object.assign(sha, { bytes: first.bytes, sha256: await app.engine.call('digest', { bytes: first.bytes }) });
  const { reference, capture, sampling } = recipe;
  const rule = { exclude_flagged: sampling.exclude_flagged, ...(sampling.exclude_flags ? { exclude_flags: sampling.exclude_flags } : {}) };
  const entry = (k) => {
    const s = app.derived[`sample${k}`], c = app.session[`chart${k}`];
    const own = { corners: s.corners, area: sampling.area, exclude: [], ...rule };
    if (c.sameImage) return { name: first.name, sha256: sha.sha256, reference, capture, sampling: { ...sampling, ...own } };
    const name = app.session[`files.chart${k}`].name;
    if (c.chart === 'custom' && !c.referenceFile) {
      throw Object.assign(new Error(`chart image ${k} (${name}): a custom grid has no built-in colours — give its reference file in step 2`), { code: 'INVALID_ARGUMENT' });
    }
    return { name, sha256: c.sha256,
      reference: { chart: c.referenceFile ? 'file' : c.chart, data_digest: c.referenceFile ? app.derived[`reference${k}`]?.data_digest ?? '' : '',
        illuminant: reference.illuminant, observer: reference.observer }, ...captureOf(app, k, s, capture),
      sampling: { layout: c.chart === 'custom' ? c.layout : { chart: c.chart }, ...own } };
  };
  return {
    ...recipe,
    images: [{ name: first.name, sha256: sha.sha256, reference, capture, sampling }, ...ks.map(entry)],
    duplicates: duplicatesOf(app),
  };
}

/// What the worker's fit pairs each image of `recipe.images` with: its sample (the engine's
/// ChartSample) and, for a reference file, the page's reference (the second chart of the first
/// image shares the first's).
export function chartsOf(app, recipe, sample, reference) {
  if (!recipe.images?.length) return undefined;
  return [{ sample, reference }, ...ready(app).map((k) => {
    const { layout, homography, patches, missing = [] } = app.derived[`sample${k}`];   // missing: a cut chart's
    const c = app.session[`chart${k}`], file = app.derived[`reference${k}`];
    const { data_digest, ...own } = file ?? {};
    return { sample: { layout, homography, patches, missing }, reference: c.sameImage ? reference : (c.referenceFile && file ? own : null) };
  })];
}

/// The extra charts' patch count in all, and what the page's text calls them (secondName).
export function extraCharts(app) {
  const ks = ready(app);
  return { count: ks.length, patches: ks.reduce((n, k) => n + app.derived[`sample${k}`].ids.length, 0), names: secondName(app) };
}

/// What the extra charts are called in the page's text: their files, or the first image's second chart.
export function secondName(app) {
  return ready(app).map((k) => (app.session[`chart${k}`].sameImage ? `${app.session['files.chart']?.name}: its second chart`
    : app.session[`files.chart${k}`]?.name)).join(', ');
}

/// The source files of a fit on `recipe` in its `images` order (a share link's `sources`).
export function sourceKeys(app, recipe) {
  if (!recipe.images?.length) return ['files.chart'];
  return ['files.chart', ...ready(app).map((k) => (app.session[`chart${k}`].sameImage ? 'files.chart' : `files.chart${k}`))];
}
