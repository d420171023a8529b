// Exports a plot's SVG as a standalone .svg file or a rasterised .png (2x), all in the page.
import { download } from '../lib/ui.js';

export function svgString(svg) {
  const clone = svg.cloneNode(true);
  clone.setAttribute('xmlns', 'http://www.w3.org/2000/svg');
  if (!clone.getAttribute('style')?.includes('background')) clone.setAttribute('style', `${clone.getAttribute('style') ?? ''};background:white`);
  return new XMLSerializer().serializeToString(clone);
}

export function exportSvg(svg, name) {
  download(`${name}.svg`, svgString(svg), 'image/svg+xml');
}

export function pngBlob(svg, scale = 2) {
  const w = svg.width?.baseVal?.value || svg.getBoundingClientRect().width;
  const hgt = svg.height?.baseVal?.value || svg.getBoundingClientRect().height;
  const url = URL.createObjectURL(new Blob([svgString(svg)], { type: 'image/svg+xml' }));
  return new Promise((resolve, reject) => {
    const img = new Image();
    img.onload = () => {
      const c = document.createElement('canvas');
      c.width = Math.round(w * scale); c.height = Math.round(hgt * scale);
      const ctx = c.getContext('2d');
      ctx.fillStyle = 'white'; ctx.fillRect(0, 0, c.width, c.height);
      ctx.drawImage(img, 0, 0, c.width, c.height);
      URL.revokeObjectURL(url);
      c.toBlob((b) => (b ? resolve(b) : reject(new Error('PNG encoding failed'))), 'image/png');
    };
    img.onerror = () => { URL.revokeObjectURL(url); reject(new Error('could not rasterise the SVG')); };
    img.src = url;
  });
}

export async function exportPng(svg, name) {
  download(`${name}.png`, await pngBlob(svg), 'image/png');
}
