// site/check_static.mjs — what site/check.mjs learns from a page's HTML without a browser: the
// pages are site/build.mjs's own output (frame.mjs's frame around markdown-it, KaTeX, highlight.js
// and diff2html output), read here by a small HTML tree builder that follows the browser's parser
// where these pages need it (void elements, raw-text <script>/<style>, RCDATA <title>, entities,
// the implied ends of <p>, <li>, <dd>/<dt>, table cells and rows, self-closing tags in SVG/MathML).
// check.mjs compares this reading with Chromium's on every page it opens (ids, links, pictures,
// navigation bar, KaTeX, the text): a page this parser reads otherwise fails the check there.
import { decodeHTML } from 'entities';

const VOID = new Set(['area', 'base', 'br', 'col', 'embed', 'hr', 'img', 'input', 'link', 'meta', 'source', 'track', 'wbr', 'param']);
const RAW = new Set(['script', 'style', 'xmp', 'iframe', 'noembed', 'noframes']);
const RCDATA = new Set(['title', 'textarea']);
const CLOSES_P = new Set(['address', 'article', 'aside', 'blockquote', 'details', 'dialog', 'div', 'dl', 'fieldset', 'figcaption', 'figure',
  'footer', 'form', 'h1', 'h2', 'h3', 'h4', 'h5', 'h6', 'header', 'hgroup', 'hr', 'main', 'menu', 'nav', 'ol', 'p', 'pre', 'section',
  'summary', 'table', 'ul', 'li', 'dd', 'dt', 'center', 'dir', 'listing', 'xmp', 'search', 'plaintext']);
const BUTTON_SCOPE = new Set(['applet', 'caption', 'html', 'table', 'td', 'th', 'marquee', 'object', 'template', 'button', 'svg', 'math']);
// The open elements an element's start tag ends (the innermost of the first set, not beyond the second).
const P = new Set(['p']);
const LI = new Set(['li']);
const LIST_SCOPE = new Set([...BUTTON_SCOPE, 'ol', 'ul']);
const DD_DT = new Set(['dd', 'dt']);
const DL_SCOPE = new Set([...BUTTON_SCOPE, 'dl']);
const CELL = new Set(['td', 'th']);
const ROW_SCOPE = new Set(['table', 'tr', 'html']);
const ROW = new Set(['tr', 'td', 'th']);
const SECTION = new Set(['thead', 'tbody', 'tfoot', 'tr', 'td', 'th']);
const TABLE_SCOPE = new Set(['table', 'html']);
const OPTION = new Set(['option']);
const SELECT_SCOPE = new Set(['select', 'html']);
const ATTR = /[\s/]*([^\s"'>/=]+)(?:\s*=\s*(?:"([^"]*)"|'([^']*)'|([^\s>]+)))?/y;
const END_TAG = /<\/([a-zA-Z][^\s/>]*)[^>]*>/y;
const START_TAG = /<([a-zA-Z][^\s/>]*)/y;
const TAG_CLOSE = /\s*(\/?)>/y;
const decode = (s) => (s.includes('&') ? decodeHTML(s) : s);

// The element tree of an HTML document: { tag, attrs: Map, classes, children: [element | string], parent }.
export function parseHtml(html) {
  html = html.replace(/\r\n?/g, '\n');
  const root = { tag: '#document', attrs: new Map(), children: [], parent: null, classes: [] };
  const stack = [root];
  const top = () => stack[stack.length - 1];
  const foreign = () => stack.some((e) => e.tag === 'svg' || e.tag === 'math');
  const popTo = (i) => { stack.length = i; };
  // The innermost open element named one of `names`, not beyond one of `boundary`: its index, or -1.
  const inScope = (names, boundary) => {
    for (let i = stack.length - 1; i > 0; i--) {
      if (names.has(stack[i].tag)) return i;
      if (boundary.has(stack[i].tag)) return -1;
    }
    return -1;
  };
  const text = (s) => { if (s) top().children.push(decode(s)); };
  let i = 0;
  const n = html.length;
  while (i < n) {
    const lt = html.indexOf('<', i);
    if (lt < 0) { text(html.slice(i)); break; }
    if (lt > i) text(html.slice(i, lt));
    i = lt;
    if (html.startsWith('<!--', i)) { const end = html.indexOf('-->', i + 4); i = end < 0 ? n : end + 3; continue; }
    if (html[i + 1] === '!' || html[i + 1] === '?') { const end = html.indexOf('>', i); i = end < 0 ? n : end + 1; continue; }
    if (html[i + 1] === '/') {
      END_TAG.lastIndex = i;
      const m = END_TAG.exec(html);
      if (!m) { text('<'); i++; continue; }
      i = END_TAG.lastIndex;
      const tag = m[1].toLowerCase();
      for (let k = stack.length - 1; k > 0; k--) if (stack[k].tag === tag) { popTo(k); break; }
      continue;
    }
    START_TAG.lastIndex = i;
    const m = START_TAG.exec(html);
    if (!m) { text('<'); i++; continue; }
    const tag = m[1].toLowerCase();
    i = START_TAG.lastIndex;
    const attrs = new Map();
    for (;;) {
      ATTR.lastIndex = i;
      const a = ATTR.exec(html);
      if (!a) break;
      const name = a[1].toLowerCase();
      if (!attrs.has(name)) attrs.set(name, decode(a[2] ?? a[3] ?? a[4] ?? ''));
      i = ATTR.lastIndex;
    }
    TAG_CLOSE.lastIndex = i;
    const close = TAG_CLOSE.exec(html);
    const selfClosing = close?.[1] === '/';
    if (close) i = TAG_CLOSE.lastIndex;
    // The ends the parser implies before this element.
    if (/^h[1-6]$/.test(tag) && /^h[1-6]$/.test(top().tag)) stack.pop();
    if (CLOSES_P.has(tag)) { const p = inScope(P, BUTTON_SCOPE); if (p > 0) popTo(p); }
    if (tag === 'li') { const li = inScope(LI, LIST_SCOPE); if (li > 0) popTo(li); }
    if (tag === 'dd' || tag === 'dt') { const d = inScope(DD_DT, DL_SCOPE); if (d > 0) popTo(d); }
    if (tag === 'td' || tag === 'th') { const c = inScope(CELL, ROW_SCOPE); if (c > 0) popTo(c); }
    if (tag === 'tr') { const r = inScope(ROW, TABLE_SCOPE); if (r > 0) popTo(r); }
    if (tag === 'thead' || tag === 'tbody' || tag === 'tfoot') { const t = inScope(SECTION, TABLE_SCOPE); if (t > 0) popTo(t); }
    if (tag === 'option') { const o = inScope(OPTION, SELECT_SCOPE); if (o > 0) popTo(o); }
    const el = { tag, attrs, children: [], parent: top(), classes: attrs.has('class') ? attrs.get('class').split(/\s+/).filter(Boolean) : [] };
    top().children.push(el);
    if (VOID.has(tag) || selfClosing && (foreign() || tag === 'svg' || tag === 'math')) continue;
    if (RAW.has(tag) || RCDATA.has(tag)) {
      const endTag = new RegExp(`</${tag}[\\s/>]`, 'ig');
      endTag.lastIndex = i;
      const end = endTag.exec(html)?.index ?? -1;
      const body = html.slice(i, end < 0 ? n : end);
      if (body) el.children.push(RCDATA.has(tag) ? decode(body) : body);
      i = end < 0 ? n : html.indexOf('>', end) + 1 || n;
      continue;
    }
    stack.push(el);
  }
  return root;
}

export const hasClass = (el, c) => el.classes.includes(c);
export function* elements(node) {
  for (const c of node.children) if (typeof c !== 'string') { yield c; yield* elements(c); }
}
export const textOf = (node) => node.children.map((c) => (typeof c === 'string' ? c : textOf(c))).join('');
const closest = (el, test) => { for (let e = el; e && e.tag !== '#document'; e = e.parent) if (test(e)) return e; return null; };

const PROSE_SKIP = (e) => ['code', 'pre', 'script', 'style'].includes(e.tag) || ['katex', 'katex-error', 'lesson-diff'].some((c) => hasClass(e, c));
const BLOCK = new Set(['p', 'li', 'td', 'th', 'h1', 'h2', 'h3', 'h4', 'h5', 'h6', 'dd', 'dt', 'blockquote', 'main']);
const FRAME_STYLES = /^assets\/(katex\/katex\.min|hljs\/github\.min|diff2html\/diff2html\.min|style)\.css$/;

// What check.mjs needs to know of one page: the same facts it reads from Chromium's DOM (see the
// evaluate() there), and what the page makes a browser load or run (`loads`, `active`).
export function pageFacts(html) {
  const doc = parseHtml(html);
  const all = [...elements(doc)];
  const main = all.find((e) => e.tag === 'main');
  const prose = new Map();
  if (main) {
    const walk = (node, skipped, block) => {
      for (const c of node.children) {
        if (typeof c === 'string') {
          if (!skipped) prose.set(block, (prose.get(block) ?? '') + c);
        } else walk(c, skipped || PROSE_SKIP(c), BLOCK.has(c.tag) ? c : block);
      }
    };
    walk(main, PROSE_SKIP(main), main);
  }
  const navs = all.filter((e) => e.tag === 'nav' && hasClass(e, 'site-nav'));
  const rel = (r) => all.find((e) => e.tag === 'a' && e.attrs.get('rel') === r)?.attrs.get('href') ?? null;
  // What loads by itself: stylesheets, icons, scripts, pictures, frames, media; what runs or styles
  // the page beyond the frame's own stylesheets (a script, a handler, a <style>, a style attribute
  // outside KaTeX's output): such a page is opened in the browser whatever its kind.
  const loads = [];
  const active = [];
  for (const e of all) {
    const a = e.attrs;
    if (e.tag === 'link' && a.has('href')) {
      const kinds = (a.get('rel') ?? '').toLowerCase().split(/\s+/);
      if (kinds.some((k) => ['stylesheet', 'icon', 'preload', 'prefetch', 'modulepreload', 'manifest', 'import'].includes(k))) {
        loads.push({ what: `<link rel="${a.get('rel')}">`, raw: a.get('href') });
        if (!(kinds.includes('stylesheet') && FRAME_STYLES.test(a.get('href').replace(/^(\.\.\/)+/, ''))) && a.get('href') !== 'data:,') active.push(`<link rel="${a.get('rel')}" href="${a.get('href')}">`);
      }
    }
    if (e.tag === 'img') {
      if (a.has('src')) loads.push({ what: '<img>', raw: a.get('src'), image: true });
      if (a.has('srcset')) { loads.push({ what: '<img srcset>', raw: a.get('srcset').trim().split(/\s+/)[0] }); active.push('<img srcset>'); }
    }
    for (const [tag, attr] of [['script', 'src'], ['iframe', 'src'], ['frame', 'src'], ['embed', 'src'], ['object', 'data'], ['video', 'src'],
      ['video', 'poster'], ['audio', 'src'], ['source', 'src'], ['track', 'src'], ['input', 'src']]) {
      if (e.tag === tag && a.has(attr)) { loads.push({ what: `<${tag} ${attr}>`, raw: a.get(attr) }); active.push(`<${tag} ${attr}="${a.get(attr)}">`); }
    }
    if (e.tag === 'script' && !a.has('src') && textOf(e).trim()) active.push('an inline <script>');
    if (['style', 'base', 'iframe', 'object', 'embed', 'video', 'audio', 'frame', 'frameset', 'template', 'canvas'].includes(e.tag)) active.push(`<${e.tag}>`);
    if (e.tag === 'meta' && a.has('http-equiv')) active.push(`<meta http-equiv="${a.get('http-equiv')}">`);
    for (const name of a.keys()) if (name.startsWith('on')) active.push(`an ${name} handler`);
    // (markdown-it's table alignment, text-align alone, lays nothing out wider)
    const style = a.get('style');
    if (style !== undefined && !/^\s*text-align:\s*(left|center|right);?\s*$/.test(style) &&
        (/url\s*\(|@import|expression/i.test(style) || !closest(e, (x) => hasClass(x, 'katex') || hasClass(x, 'katex-display')))) {
      active.push(`a style attribute on <${e.tag}> ("${style.slice(0, 40)}")`);
    }
  }
  const prosePieces = [...prose.values()];
  return {
    title: textOf(all.find((e) => e.tag === 'title') ?? { children: [] }).replace(/\s+/g, ' ').trim(),
    nav: navs.flatMap((n) => [...elements(n)].filter((e) => e.tag === 'a').map((e) => textOf(e).trim())),
    prev: rel('prev'),
    next: rel('next'),
    links: all.filter((e) => e.tag === 'a' && e.attrs.has('href')).map((e) => e.attrs.get('href')),
    images: all.filter((e) => e.tag === 'img' && e.attrs.has('src')).map((e) => e.attrs.get('src')),
    ids: all.filter((e) => e.attrs.has('id')).map((e) => e.attrs.get('id')),
    rawMath: prosePieces.map((t) => t.match(/\$\$[^$]+\$\$|\$[^$\s][^$]*\$/)?.[0]).find(Boolean) ?? null,
    katex: all.filter((e) => hasClass(e, 'katex')).length,
    katexErrors: all.filter((e) => hasClass(e, 'katex-error')).length,
    prose: prosePieces.join('\n'),
    lessonFiles: all.filter((e) => e.tag === 'section' && hasClass(e, 'lesson-file')).map((s) => {
      const inside = [...elements(s)];
      const guide = inside.find((e) => hasClass(e, 'guide'));
      return {
        path: s.attrs.get('data-path'),
        guide: guide ? textOf(guide).trim() : '',
        shown: inside.filter((e) => hasClass(e, 'd2h-file-name')).map((e) => textOf(e).trim()),
        sides: inside.filter((e) => hasClass(e, 'd2h-file-side-diff')).length,
        columns: inside.filter((e) => hasClass(e, 'd2h-file-diff')).length,
        lines: inside.filter((e) => hasClass(e, 'd2h-code-side-line') || hasClass(e, 'd2h-code-line')).length,
      };
    }),
    loads,
    active: [...new Set(active)],
  };
}

// The page without what differs between editions around the same text: the navigation bar (the
// edition's labs) and the student edition's banner. Two pages equal by this run alike in a browser,
// given the same bytes for everything they load (check.mjs: "twins").
export const withoutFrame = (html) => html.replace(/<nav class="site-nav">[\s\S]*?<\/nav>/, '').replace(/<div class="edition">[^<]*<\/div>\n?/, '');
