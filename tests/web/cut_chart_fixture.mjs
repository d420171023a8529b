// A chart cut by the frame (issue 48) for the browser tests: the example Passport DNG with its
// sensor rows below 880 cut off (raw_fixtures.withSize: the header says 880 rows, so the chart's
// bottom row D lies outside the 427-row measurement image).
import { step, upload, fileBuffer, setCorners, DNG } from './journey.mjs';
import { ifd0, withSize } from './raw_fixtures.mjs';
import { EXAMPLE } from './image_fixtures.mjs';

const dng = fileBuffer(DNG);
const { dv, entries } = ifd0(dng);
const e = entries[256];
const sensorWidth = e.type === 3 ? dv.getUint16(e.at, true) : dv.getUint32(e.at, true);
export const CUT = withSize(dng, sensorWidth, 880);

/// Loads the cut DNG in step 2, waits for detection to find the chart and name its 6 patches
/// outside (row D), then places the example's corners (rows A–C inside the image, D below it).
export async function openCutChart(page) {
  await step(page, 'images');
  await upload(page, '#step-images input[data-slot="chart"]', 'cut.dng', Buffer.from(CUT));
  await page.waitForFunction(() => window.tristim.derived.image?.height === 427, null, { timeout: 60000 });
  await page.waitForFunction(() => window.tristim.derived.sample?.missing?.length === 6, null, { timeout: 60000 });
  await setCorners(page, EXAMPLE.corners);
}
