// Normalises the engine's lists (strings or {id, label, ...}) into [{value, label}] options.
export function options(list, fallback = []) {
  if (!Array.isArray(list) || !list.length) return fallback;
  return list.map((c) => (typeof c === 'string'
    ? { value: c, label: c }
    : { value: String(c.id ?? c.value ?? c.name), label: c.label ?? c.name ?? String(c.id), ...c }));
}
