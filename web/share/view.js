// Step 7: Share — a link that recomputes the selected profile (docs/link-format.md: recipe, patch
// RGB, reference, source SHA-256 and the expected results, compressed into the URL fragment;
// nothing is uploaded), opening one (recomputed in the worker: "reproduced", or both results side
// by side — never silently the new one), the source RAW dropped on an opened link (its SHA-256
// checked, its patches sampled again), and project files (.tristim: the whole session).
// Opening a link or a bad link changes nothing in the session; every text from a link is shown as
// text, never as HTML.
import { h, field, showError, clearError, download, fileBytes } from '../lib/ui.js';
import { encodeSession, decodeSession, resultRows, linkOffer } from './project.js';
import { chartsOf, sourceKeys } from '../images/second.js';

export function mount(section, app) {
  const { engine } = app;
  const selected = () => (app.session.results ?? []).find((r) => r.key === app.session.selected) ?? app.session.results?.[0];
  const fitInputs = (recipe) => {
    const { source, settings, data_digest, ...reference } = app.derived.reference ?? {};
    const { layout, homography, patches, missing = [] } = app.derived.sample ?? {};   // missing: a cut chart's, in the link's recipe
    if (!app.derived.reference || !patches) throw Object.assign(new Error('no chart sample yet: set the reference and sample the chart first'), { code: 'NO_PROFILE' });
    const sample = { layout, homography, patches, missing };
    return { reference, sample, charts: several(recipe) ? chartsOf(app, recipe, sample, reference) : undefined };
  };
  // A fit on several chart images (the recipe's `images`): the link is made on the union of their
  // patches, so the second image must still be sampled.
  const several = (recipe) => {
    if (!recipe.images?.length) return false;
    if (!app.derived.sample2?.patches) throw Object.assign(new Error('this profile was fitted on two chart images: load and sample the second image in step 2 again'), { code: 'NO_PROFILE' });
    return true;
  };
  const fileOf = (key) => {
    const file = app.session[key];
    return file?.bytes ? { name: file.name, bytes: new Uint8Array(file.bytes).slice() } : null;
  };

  // --- make a link
  const makeBtn = h('button', { type: 'button', class: 'primary', id: 'share-make' }, 'Make a link to the selected profile');
  const linkOut = h('input', { type: 'text', readonly: true, id: 'share-link', 'aria-label': 'Link to the selected profile', size: 60 });
  const copyBtn = h('button', { type: 'button', id: 'share-copy', disabled: true }, 'Copy');
  const makeNote = h('p', { class: 'summary', id: 'share-note' });
  makeBtn.addEventListener('click', async () => {
    clearError(makeBtn);
    const r = selected();
    try {
      if (!r) throw Object.assign(new Error('no profile yet: fit one in step 3'), { code: 'NO_PROFILE' });
      const images = sourceKeys(app, r.recipe).map(fileOf);
      makeNote.textContent = 'Making the link (the fit runs again in the worker)…';
      const [{ link }, limit] = await Promise.all([
        engine.call('shareLink', { recipe: r.recipe, ...fitInputs(r.recipe), images, base: location.href.split('#')[0] }),
        engine.call('shareLimit')]);
      const offer = linkOffer(link, limit, r.label ?? r.recipe.characterisation.model);
      linkOut.value = offer.link;
      copyBtn.disabled = !offer.link;
      makeNote.textContent = offer.note;
    } catch (e) {
      makeNote.textContent = '';
      showError(makeBtn, e, 'Share');
    }
  });
  copyBtn.addEventListener('click', () => { linkOut.select(); navigator.clipboard?.writeText(linkOut.value).catch(() => {}); });

  // --- open a link
  const openIn = h('input', { type: 'text', id: 'share-open-text', 'aria-label': 'A tristim link or payload', placeholder: 'paste a tristim link', size: 60 });
  const openBtn = h('button', { type: 'button', id: 'share-open' }, 'Open');
  const verdictBox = h('div', { id: 'share-verdict', 'aria-live': 'polite' });
  const imageIn = h('input', { type: 'file', id: 'share-image' });
  const imageField = field('Check with the source image (its SHA-256 must match; its patches are sampled again)', imageIn);
  imageField.hidden = true;
  let opened = null;   // the link shown in verdictBox

  async function open(text, image = null) {
    const control = image ? imageIn : openBtn;
    clearError(openBtn); clearError(imageIn);
    section.dataset.opening = 'true';
    delete section.dataset.linkError;
    try {
      const r = await engine.call('openLink', { text, image });
      opened = text;
      render(r);
    } catch (e) {
      section.dataset.linkError = e.code ?? 'ERROR';
      showError(control, e, image ? image.name : 'Link');
    } finally {
      delete section.dataset.opening;
    }
  }
  openBtn.addEventListener('click', () => open(openIn.value.trim()));
  imageIn.addEventListener('change', async () => {
    const f = imageIn.files[0];
    if (!f || !opened) return;
    let bytes;
    try { bytes = await fileBytes(f); } catch (e) { showError(imageIn, e, f.name); return; }
    await open(opened, { name: f.name, bytes });
  });

  function render(r) {
    const payload = JSON.parse(r.payload);
    const expected = resultRows(r.expected.text), actual = new Map(resultRows(r.actual.text));
    const names = [...expected.map(([n]) => n), ...[...actual.keys()].filter((n) => !expected.some(([e]) => e === n))];
    const exp = new Map(expected);
    const same = r.verdict === 'reproduced';
    const title = same
      ? `Reproduced${r.resampled ? ' from the source image (sampled again)' : ''}: the link's ${r.kind} profile, recomputed here, gives the same results.`
      : `Differs: recomputed here, the link's ${r.kind} profile does not give the results it was shared with. Both are shown; the link's are not replaced.`;
    const rows = names.map((n) => {
      const a = exp.get(n) ?? '', b = actual.get(n) ?? '';
      const differs = a !== b;
      return h('tr', { class: differs ? 'differs' : '', dataset: { name: n }, style: differs ? { background: '#fdecea' } : null },
        h('th', { scope: 'row' }, differs ? `${n} ≠` : n), h('td', {}, a || '(absent)'), h('td', {}, b || '(absent)'));
    });
    const sources = (payload.sources ?? []).map((s) => h('li', {}, `${s.name} — SHA-256 ${s.sha256}`));
    // A fit on several chart images: the link's patches are their union (ids "k:A1"); one source
    // image cannot be sampled again for it.
    const charts = (payload.recipe?.images ?? []).map((e, k) => h('li', {}, `${k + 1}: ${e.name}`));
    imageField.hidden = !(payload.kind === 'relative' && sources.length && !charts.length);
    verdictBox.replaceChildren(
      h('h3', { id: 'share-verdict-title', dataset: { verdict: r.verdict } }, title),
      h('p', { class: 'summary' }, `Made with tristim ${r.expected_version}; recomputed with tristim ${r.actual_version}. `,
        `Digest of the link's results: ${r.expected.digest}; here: ${r.actual.digest}.`),
      sources.length ? h('div', {}, h('p', {}, 'Source images (not in the link):'), h('ul', {}, sources)) : null,
      charts.length ? h('div', { class: 'share-charts' }, h('p', {}, `Fitted on the union of ${charts.length} chart images' patches:`), h('ol', {}, charts)) : null,
      h('table', { class: 'share-results' },
        h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, 'result'), h('th', { scope: 'col' }, 'in the link'), h('th', { scope: 'col' }, 'recomputed here'))),
        h('tbody', {}, rows)),
      h('p', { class: 'hint' }, 'Coefficients to 10 significant digits, metrics to 6 (docs/link-format.md); the ΔE00 rows: mean, median, 95th percentile, max.'));
  }

  /// Opens the link in the address bar (#tristim=…): the step is shown and the link recomputed.
  function openFromHash() {
    if (!location.hash.startsWith('#tristim=')) return null;
    app.goto('share');
    openIn.value = location.href;
    return open(location.href);
  }
  window.addEventListener('hashchange', openFromHash);

  // --- project files
  const exportBtn = h('button', { type: 'button', id: 'share-export' }, 'Export the session as a project file (.tristim)');
  const importIn = h('input', { type: 'file', id: 'share-import', accept: '.tristim' });
  const projectNote = h('p', { class: 'summary', id: 'share-project-note' });
  exportBtn.addEventListener('click', async () => {
    clearError(exportBtn);
    try {
      const r = selected();
      if (!r) throw Object.assign(new Error('no profile yet: fit one in step 3'), { code: 'NO_PROFILE' });
      const { json, images } = encodeSession(app.session);
      const { bytes } = await engine.call('projectExport', { recipe: r.recipe, ...fitInputs(r.recipe), images, session: json,
        sources: sourceKeys(app, r.recipe) });
      download('session.tristim', bytes, 'application/octet-stream');
      projectNote.textContent = `Project file: ${bytes.length} bytes (recipe, patch data, reference, ${images.length} image(s) and the page's settings). tristim reproduce session.tristim checks it from the command line.`;
    } catch (e) { showError(exportBtn, e, 'Project'); }
  });
  importIn.addEventListener('change', async () => {
    const f = importIn.files[0];
    if (!f) return;
    clearError(importIn);
    try {
      const bytes = await fileBytes(f);
      const project = await engine.call('projectOpen', { bytes });
      const session = decodeSession(project.session, project.images);
      render(project.reproduction);
      opened = project.payload;
      if (!confirm(`Replace this session with the project's (${f.name})? Every file, corner, setting and result kept in this browser is replaced.`)) return;
      await app.store.clear();
      for (const [k, v] of Object.entries(session)) await app.store.set(k, v);
      location.hash = '';
      location.reload();
    } catch (e) { showError(importIn, e, f.name); }
  });

  section.append(
    h('p', {}, 'A link holds everything needed to recompute the selected profile — its recipe, the patches\' camera RGB, the reference (a built-in chart by name, or your data) and a digest of the results — in the part of the address after #, which is never sent to a server. A colleague opening it sees whether the profile comes out the same.'),
    h('div', { class: 'controls' }, field('Share', makeBtn), linkOut, copyBtn), makeNote,
    h('h3', {}, 'Open a link'),
    h('div', { class: 'controls' }, openIn, field('Recompute', openBtn)),
    verdictBox, imageField,
    h('h3', {}, 'Project files'),
    h('div', { class: 'controls' }, field('Export', exportBtn), field('Import a project file (replaces this session)', importIn)), projectNote);
  return { openFromHash, open };
}
