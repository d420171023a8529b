// Worker handlers of the Share step: a link to a fit (the engine's shareSample: the recipe fitted
// again on the chart sample, encoded with its expected results; a recipe with several chart `images`
// through shareTraining on the union of their training sets, as the fit handler fits it), opening a link (reproduceLink:
// recomputed and compared; with the source image reproduceLinkImage samples it again), and
// project files (projectFile, openProject). Compression is the module's zlib (deflate-raw), never
// the page's CompressionStream, so the page and the CLI run the same code.
import { reply } from '../lib/reply.js';
import { unionOf } from '../fit/handlers.js';

/// The reference a fit of `recipe` trains on (as the fit handler chooses it).
const referenceFor = (T, recipe, reference) =>
  (recipe.reference.chart !== 'file' && (recipe.surface?.method ?? 'none') !== 'none' ? T.recipeReference(recipe) : reference);

const sourcesOf = (T, images) => images.filter(Boolean).map((image) => ({ name: image.name, sha256: T.sha256(image.bytes) }));

/// The payload of a fit of `recipe`: with an `images` list (several chart images, `charts` one
/// {sample, reference} per entry) the fit on their union, else on the one sample.
const payloadOf = (T, { recipe, sample, reference, charts }, images) => (recipe.images?.length
  ? T.shareTraining(recipe, unionOf(T, recipe, charts), sourcesOf(T, images))
  : T.shareSample(recipe, sample, referenceFor(T, recipe, reference), sourcesOf(T, images)));

export const handlers = {
  /// `images`: the source files ({name, bytes}) in the recipe's order (their SHA-256 go in the link).
  shareLink: (T, { images, base, ...fit }) => {
    const payload = payloadOf(T, fit, images);
    return reply({ payload, link: T.shareLink(base, payload) });
  },
  shareLimit: (T) => ({ result: T.shareLinkLimit() }),
  /// {text, image?}: the link (or payload) recomputed; with `image` ({name, bytes}) its SHA-256 is
  /// checked against the link's sources and its patches sampled again.
  openLink: (T, { text, image }) => reply(image ? T.reproduceLinkImage(text, image.bytes) : T.reproduceLink(text)),
  projectExport: (T, { images, session, sources, ...fit }) => {
    const payload = payloadOf(T, fit, sources.map((key) => images.find((i) => i.key === key)));
    return reply({ bytes: T.projectFile(payload, images.map(({ name, bytes }) => ({ name, bytes })), session) });
  },
  projectOpen: (T, { bytes }) => {
    const project = T.openProject(bytes);
    return reply({ ...project, reproduction: T.reproduceLink(project.payload) });
  },
};
