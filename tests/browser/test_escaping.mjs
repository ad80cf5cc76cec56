// Names that are HTML in the pages minksum writes: a --title, an operand's
// file name and a VRML DEF name holding "<!--<script>", "</script>", "&amp;",
// U+2028 and U+2029 ('minksum view' of a polytope, of a sum and of a scene,
// 'minksum cgm --html'), and a title of control characters.
//   node test_escaping.mjs data|page --minksum BIN --out DIR
// data (no browser): in each page the embedded JSON holds none of < > & U+2028
// U+2029 (each written \uXXXX), so no name ends the <script> element or makes
// the HTML parser read on past it; JSON.parse gives back every name exactly;
// the <title> element holds the title as character references (control
// characters as U+FFFD).
// page: each page in the browser: no page error, the canvas drawn, the
// document's title and the title shown on the page equal to the title given,
// every name read back exactly.
import { check, checkPage, launch, minksum, open, options } from './lib.mjs';
import { mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const mode = process.argv[2];
process.argv.splice(2, 1);
check(mode === 'data' || mode === 'page', `unknown mode '${mode}' (data, page)`);
const o = options();
const root = join(o.out, `escaping-${mode}`);
rmSync(root, { recursive: true, force: true });

// A file name with every one of them: a directory "<!--<script>&amp; U+2028 U+2029",
// in it the directories "<" and "script>" (a file name cannot hold '/'), and the file.
const NASTY = '<!--<script>&amp; \u2028 \u2029';
const dir = join(root, NASTY, '<', 'script>');
mkdirSync(dir, { recursive: true });
const file = join(dir, 'cube <!--<script>.off');
check(file.includes('</script>') && file.includes('<!--<script>'), `the file name ${file} lacks the markup it is for`);
writeFileSync(file, 'OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n' +
                    '4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n');
const CONTROLS = 'bell \x07 escape \x1b[31m delete \x7f csi \x9b end';
const TITLE = 'T <!--<script> </script><b>x</b> &amp; & \u2028 \u2029 "q" \'s\' é ⊕';

// The scene: 'minksum cgm P Q -o' with the names P and Q replaced by DEF names
// that are HTML (a VRML identifier may hold < > ! - / & ; and UTF-8).
const DEF_P = '<!--<script>P</script>&amp;\u2028', DEF_Q = '<b>Q</b>\u2029&lt;';
const wrlPlain = join(root, 'plain.wrl'), wrl = join(root, 'scene.wrl');
minksum(o.minksum, ['cgm', 'tetra', 'cube@rot:2', '-o', wrlPlain]);
const plain = readFileSync(wrlPlain, 'utf8');
check(/\bDEF P\b/.test(plain) && /\bDEF Q\b/.test(plain), `${wrlPlain}: no DEF P and DEF Q to rename`);
writeFileSync(wrl, plain.replace(/\b(DEF|USE) P\b/g, `$1 ${DEF_P}`).replace(/\b(DEF|USE) Q\b/g, `$1 ${DEF_Q}`));

const PAGES = [
  { name: 'sum', args: ['view', file, 'octahedron', '--title', TITLE], title: TITLE,
    names: (d) => [[d.solids[0].name, file]] },
  { name: 'polytope', args: ['view', file], title: file, names: (d) => [[d.solids[0].name, file]] },
  { name: 'cgm', args: ['cgm', file, 'tetra', '--html'], title: `${file} + tetra`,
    names: (d) => [[d.operands[0], file], [d.operands[1], 'tetra']] },
  { name: 'scene', args: ['view', wrl, '--title', TITLE], title: TITLE,
    names: (d) => [[d.solids[0].name, DEF_P], [d.solids[1].name, DEF_Q]] },
  // Control characters: kept in the data (JSON escapes them), U+FFFD in the <title> element.
  { name: 'controls', args: ['view', 'tetra', '--title', CONTROLS], title: CONTROLS,
    htmlTitle: CONTROLS.replace(/[\x00-\x08\x0b-\x1f\x7f-\x9f]/g, '\ufffd'), names: () => [] },
];

function decodeHtml(text) {
  return text.replace(/&(lt|gt|amp|quot|#39);/g, (_, e) => ({ lt: '<', gt: '>', amp: '&', quot: '"', '#39': "'" })[e]);
}

for (const p of PAGES) {
  const html = join(root, `${p.name}.html`);
  const args = p.args[0] === 'cgm' ? [...p.args, html] : [...p.args, '-o', html];
  minksum(o.minksum, args);
  p.html = html;
  const text = readFileSync(html, 'utf8');
  const marker = '<script type="application/json" id="minksum-data">';
  const start = text.indexOf(marker);
  check(start >= 0, `${p.name}: no data element`);
  const end = text.indexOf('</script>', start);
  const body = text.slice(start + marker.length, end);
  for (const [c, shown] of [['<', '<'], ['>', '>'], ['&', '&'], ['\u2028', 'U+2028'], ['\u2029', 'U+2029']])
    check(!body.includes(c), `${p.name}: the embedded data holds a raw ${shown} at ${body.indexOf(c)}: …${body.slice(Math.max(0, body.indexOf(c) - 40), body.indexOf(c) + 40)}…`);
  const after = text.slice(end, end + 60);
  check(after.startsWith('</script>\n<script>\n/* The viewer of minksum'), `${p.name}: the data element is not followed by the viewer's script: ${after}`);
  const d = JSON.parse(body);
  check(d.title === p.title, `${p.name}: the data's title is ${JSON.stringify(d.title)}, not ${JSON.stringify(p.title)}`);
  for (const [got, want] of p.names(d)) check(got === want, `${p.name}: a name came back as ${JSON.stringify(got)}, not ${JSON.stringify(want)}`);
  const t = /<title>([^<]*)<\/title>/.exec(text);
  check(t, `${p.name}: no <title> element without markup in it`);
  const htmlTitle = p.htmlTitle ?? p.title;
  check(decodeHtml(t[1]) === htmlTitle, `${p.name}: the <title> element reads ${JSON.stringify(decodeHtml(t[1]))}, not ${JSON.stringify(htmlTitle)}`);
}
if (mode === 'data') {
  console.log(`PASS: escaping in the data of ${PAGES.length} pages (${PAGES.map((p) => p.name).join(', ')})`);
  process.exit(0);
}

const browser = await launch();
try {
  for (const p of PAGES) {
    const { page, log } = await open(browser.context, p.html);
    await checkPage(page, log, p.name);
    const shown = await page.evaluate(() => ({
      documentTitle: document.title,
      heading: document.getElementById('title').textContent,
      data: window.minksum.data,
      scripts: document.scripts.length,
      injected: [...document.querySelectorAll('b')].filter((e) => ['x', 'P', 'Q'].includes(e.textContent)).length,
    }));
    const htmlTitle = p.htmlTitle ?? p.title;
    check(shown.documentTitle === htmlTitle, `${p.name}: document.title is ${JSON.stringify(shown.documentTitle)}, not ${JSON.stringify(htmlTitle)}`);
    check(shown.heading === p.title, `${p.name}: the page shows the title ${JSON.stringify(shown.heading)}, not ${JSON.stringify(p.title)}`);
    check(shown.scripts === 2, `${p.name}: ${shown.scripts} script elements, not 2 (the data and the viewer)`);
    check(shown.injected === 0, `${p.name}: the markup of a name became ${shown.injected} <b> elements`);
    for (const [got, want] of p.names(shown.data)) check(got === want, `${p.name}: the page read a name as ${JSON.stringify(got)}, not ${JSON.stringify(want)}`);
    await page.screenshot({ path: join(root, `${p.name}.png`) });
    await page.close();
  }
} finally {
  await browser.close();
}
console.log(`PASS: ${PAGES.length} pages with names that are HTML (${PAGES.map((p) => p.name).join(', ')}) drawn, their titles shown as given`);
