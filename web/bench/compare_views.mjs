// One view of the viewer under two URL queries, for docs/BENCHMARKS.md: `hexlod serve --scene
// S`, chromium (the browser test's setup), each query's view once everything it wants is loaded
// (harness.settledView); prints one JSON object with each view's terminals and trees per LOD
// and how far apart the two images are (PSNR, pixels that differ, pixels more than 24 of 255
// apart), and saves the two canvases as PNGs when OUT_DIR is given. The canvas has no samples
// unless a query says `aa=1`. For example, occlusion
// culling on and off:
//   node web/bench/compare_views.mjs build/apps/hexlod configs/default.json 640x360 \
//       'camera=0,-700,1.7,90,0&mode=walk&occlusion=1' 'camera=0,-700,1.7,90,0&mode=walk&occlusion=0'
//   node web/bench/compare_views.mjs HEXLOD_BINARY SCENE WIDTHxHEIGHT QUERY_A QUERY_B [OUT_DIR]
import fs from 'node:fs';
import path from 'node:path';

import { imageDifference, launchChromium, settledView, startServer } from '../test-browser/harness.mjs';

const [binary, scene, size, ...rest] = process.argv.slice(2);
const [queryA, queryB, out] = rest;
if (!binary || !scene || !size || queryA === undefined || queryB === undefined) {
    console.error('usage: node web/bench/compare_views.mjs HEXLOD_BINARY SCENE WIDTHxHEIGHT QUERY_A QUERY_B [OUT_DIR]');
    process.exit(2);
}
const [width, height] = size.split('x').map(Number);
const server = startServer(binary, scene);
const browser = await launchChromium({ width, height });
try {
    const base = await server.url;
    const views = [];
    // Without multisampling unless a query asks for it (`aa=1`: the viewer reads the first aa).
    for (const query of [queryA, queryB]) views.push(await settledView(browser.page, `${base}?${query ? `${query}&` : ''}aa=0`, 600000));
    const difference = await imageDifference(browser.page, views[0].image, views[1].image);
    if (out) {
        fs.mkdirSync(out, { recursive: true });
        views.forEach((v, i) => fs.writeFileSync(path.join(out, `view-${'ab'[i]}.png`), v.image));
    }
    const summary = (v, query) => ({ query, terminals: v.state.streamer.terminals, trees: v.state.streamer.trees, occlusion: v.state.occlusion });
    console.log(JSON.stringify({ scene, viewport: size, a: summary(views[0], queryA), b: summary(views[1], queryB), ...difference }, null, 1));
} finally {
    await browser.close();
    server.stop();
}
