// site/frame.mjs — what every page of the course site has around its text: the title, the
// navigation bar, the student edition's banner, the contents sidebar of a long page, the
// previous/next links, the footer. site/build.mjs calls page() for each page.
import path from 'node:path';

const posix = path.posix;
export const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]);

// A site path as seen from a page (hash kept).
export function relative(fromPage, to) {
  const [file, hash] = to.split('#');
  const rel = posix.relative(posix.dirname(fromPage), file) || posix.basename(file);
  return hash === undefined ? rel : `${rel}#${hash}`;
}

// The browser tab's title: the page's own, then the site's name unless the page's title starts with it.
export function fullTitle(title, site) {
  return title.startsWith(site) ? title : `${title} — ${site}`;
}

// The h2/h3 headings of a page's HTML (markdown-it-anchor gave them ids): the contents sidebar.
export function headings(html) {
  const list = [];
  for (const m of html.matchAll(/<h([23]) id="([^"]+)"[^>]*>([\s\S]*?)<\/h\1>/g)) {
    const text = m[3].replace(/<[^>]+>/g, '').trim();
    if (text) list.push({ level: Number(m[1]), id: m[2], text });
  }
  return list;
}
const TOC_FROM = 5;  // a page with this many headings or more gets the sidebar

// The whole HTML of one page. nav: [[href, label]]; prev/next: { href, label } or null.
export function page(name, { site, title, body, nav, section, source, wide, scripts, prev, next, edition }) {
  const up = (p) => relative(name, p);
  const links = nav.map(([href, label]) =>
    `<a href="${up(href)}"${href === section ? ' class="current" aria-current="page"' : ''}>${esc(label)}</a>`).join('\n    ');
  const toc = wide ? [] : headings(body);
  const tocList = toc.length >= TOC_FROM
    ? `<ul>\n${toc.map((h) => `<li class="h${h.level}"><a href="#${h.id}">${h.text}</a></li>`).join('\n')}\n</ul>` : '';
  const pager = prev || next ? `<nav class="pager" aria-label="previous and next">
  ${prev ? `<a rel="prev" href="${up(prev.href)}"><small>previous</small><br>← ${esc(prev.label)}</a>` : '<span></span>'}
  ${next ? `<a rel="next" href="${up(next.href)}"><small>next</small><br>${esc(next.label)} →</a>` : '<span></span>'}
</nav>` : '';
  return `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>${esc(fullTitle(title, site))}</title>
<link rel="icon" href="data:,">
<link rel="stylesheet" href="${up('assets/katex/katex.min.css')}">
<link rel="stylesheet" href="${up('assets/hljs/github.min.css')}">
<link rel="stylesheet" href="${up('assets/diff2html/diff2html.min.css')}">
<link rel="stylesheet" href="${up('assets/style.css')}">
</head>
<body>
<nav class="site-nav">
  <a class="brand" href="${up('index.html')}">${esc(site)}</a>
  <div class="links">
    ${links}
  </div>
</nav>
${edition ? `<div class="edition">${edition}</div>\n` : ''}<div class="layout${tocList ? ' with-toc' : ''}${wide ? ' wide' : ''}">
${tocList ? `<aside class="toc-side" aria-label="contents"><p>On this page</p>\n${tocList}\n</aside>\n` : ''}<main class="${wide ? 'wide' : 'text'}">
${tocList ? `<details class="toc-inline"><summary>On this page</summary>\n${tocList}\n</details>\n` : ''}${body}
${pager}
</main>
</div>
<footer>Built by <code>scripts/make_site.sh</code>${source ? ` from <code>${esc(source)}</code>` : ''}.</footer>
${scripts.map((s) => `<script src="${up(s)}"></script>`).join('\n')}
</body>
</html>
`;
}
