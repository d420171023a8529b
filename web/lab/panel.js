// One shape for every tab of the Lab: heading, explanation, controls, buttons (each with its error
// slot), the command line that does the same, then what the tab shows.
import { h, errorSlot } from '../lib/ui.js';

/// id names the heading (h-lab-<id>); `explain` may be empty; `shown` follows the command line.
export function labPanel({ id, title, explain, controls, buttons, cli, hint = 'The same on the command line:' }, ...shown) {
  return h('section', { class: 'lab-panel', 'aria-labelledby': `h-lab-${id}` },
    h('h3', { id: `h-lab-${id}` }, title),
    explain ? h('p', { class: 'explain' }, explain) : null,
    h('div', { class: 'controls' }, ...controls),
    h('p', {}, ...buttons.flatMap((b, i) => (i ? [' ', b] : [b]))), ...buttons.map((b) => errorSlot(b)),
    h('p', { class: 'hint' }, hint), cli, ...shown);
}
