// Worker handlers of the Share step: a link to a fit (the engine's shareSample: the recipe fitted
// again on the chart sample, encoded with its expected results), opening a link (reproduceLink:
// recomputed and compared; with the source image reproduceLinkImage samples it again), and
// project files (projectFile, openProject). Compression is the module's zlib (deflate-raw), never
// the page's CompressionStream, so the page and the CLI run the same code.
import { reply } from '../lib/reply.js';

/// The reference a fit of `recipe` trains on (as the fit handler chooses it).
const referenceFor = (T, recipe, reference) =>
  (recipe.reference.chart !== 'file' && (recipe.surface?.method ?? 'none') !== 'none' ? T.recipeReference(recipe) : reference);

const sourcesOf = (T, image) => (image ? [{ name: image.name, sha256: T.sha256(image.bytes) }] : []);

export const handlers = {
  shareLink: (T, { recipe, sample, reference, image, base }) => {
    const payload = T.shareSample(recipe, sample, referenceFor(T, recipe, reference), sourcesOf(T, image));
    return reply({ payload, link: T.shareLink(base, payload) });
  },
  shareLimit: (T) => ({ result: T.shareLinkLimit() }),
  /// {text, image?}: the link (or payload) recomputed; with `image` ({name, bytes}) its SHA-256 is
  /// checked against the link's sources and its patches sampled again.
  openLink: (T, { text, image }) => reply(image ? T.reproduceLinkImage(text, image.bytes) : T.reproduceLink(text)),
  projectExport: (T, { recipe, sample, reference, images, session }) => {
    const payload = T.shareSample(recipe, sample, referenceFor(T, recipe, reference), sourcesOf(T, images.find((i) => i.key === 'files.chart')));
    return reply({ bytes: T.projectFile(payload, images.map(({ name, bytes }) => ({ name, bytes })), session) });
  },
  projectOpen: (T, { bytes }) => {
    const project = T.openProject(bytes);
    return reply({ ...project, reproduction: T.reproduceLink(project.payload) });
  },
};
