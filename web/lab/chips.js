// The engine's Munsell matte chip ids (labMunsell), asked once per page and shared by the Lab's
// pickers (the metamerism explorer's chip, the renderer's chart of chips).
let ids = null;

/// The ids, in the engine's order (a promise; the worker is asked once).
export function munsellIds(app) {
  ids ??= app.engine.call('labMunsell', {}).catch((e) => { ids = null; throw e; });
  return ids;
}

/// Fills `sel` with the chips (option text = id) once: a multiple picker with none selected, a
/// single one keeping its choice when the list has it (else the first chip).
export async function fillChips(app, sel) {
  if (sel.dataset.loaded) return;
  const list = await munsellIds(app);
  const keep = sel.value;
  sel.replaceChildren(...list.map((id) => {
    const o = document.createElement('option');
    o.value = id;
    o.textContent = id;
    return o;
  }));
  if (!sel.multiple) sel.value = list.includes(keep) ? keep : list[0];
  sel.dataset.loaded = '1';
}
