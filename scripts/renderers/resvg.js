// resvg.js: draw an SVG with @resvg/resvg-js for the resvg adapter (run by
// it, not an adapter itself: it is not executable).
//
//   node resvg.js MODULES SVG W H OUT.png
//
// MODULES is the folder holding node_modules/@resvg/resvg-js.  The SVG is
// drawn at its own size (fitTo original), which must be W x H, over a
// transparent background (the document paints its own), and written as PNG.
'use strict';
const fs = require('fs');
const path = require('path');

function fail(message) {
  process.stderr.write('resvg: ' + message + '\n');
  process.exit(1);
}

const [mods, svgPath, w, h, out] = process.argv.slice(2);
if (!out) fail('usage: node resvg.js MODULES SVG W H OUT.png');
let Resvg;
try {
  ({ Resvg } = require(path.join(mods, 'node_modules', '@resvg', 'resvg-js')));
} catch (e) {
  process.stderr.write('resvg: cannot load @resvg/resvg-js from ' + mods + ': ' + e.message + '\n');
  process.exit(2);
}
try {
  const resvg = new Resvg(fs.readFileSync(svgPath), { fitTo: { mode: 'original' } });
  // the drawing alone, timed in-process (node's start-up, reading the SVG
  // and writing the PNG left out), told to aabench in the last line
  const t0 = process.hrtime.bigint();
  const image = resvg.render();
  const ns = process.hrtime.bigint() - t0;
  if (image.width !== Number(w) || image.height !== Number(h))
    fail('drew ' + image.width + 'x' + image.height + ', not ' + w + 'x' + h);
  fs.writeFileSync(out, image.asPng());
  process.stdout.write('render-seconds: ' + (Number(ns) / 1e9).toFixed(9) + '\n');
} catch (e) {
  fail(e.message);
}
