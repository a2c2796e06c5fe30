// site/source_pages.mjs — a file shown whole: highlight.js colours it at build time, each line has
// an anchor (#L42) in the gutter, so an exercise row or a doc can link to a line.
import hljs from 'highlight.js';
import { esc } from './frame.mjs';

export const languageOf = (p) => ({ h: 'cpp', cpp: 'cpp', vert: 'glsl', frag: 'glsl', comp: 'glsl', glsl: 'glsl', json: 'json',
  sh: 'bash', py: 'python', cmake: 'cmake', txt: 'cmake', md: 'markdown' })[p.split('.').pop()] ?? 'plaintext';

// The body of a source page: its heading, where it belongs (HTML given), the code with line anchors.
export function sourceBody(repoPath, text, about = '') {
  const code = hljs.highlight(text, { language: languageOf(repoPath) }).value;
  const count = text.split('\n').length - (text.endsWith('\n') ? 1 : 0);
  const gutter = Array.from({ length: count }, (_, i) => `<a id="L${i + 1}" href="#L${i + 1}">${i + 1}</a>`).join('\n');
  return `<h1 class="source-title"><code>${esc(repoPath)}</code></h1>
${about ? `<p class="source-about">${about}</p>\n` : ''}<div class="source"><pre class="gutter">${gutter}</pre><pre class="code"><code class="hljs">${code}</code></pre></div>`;
}
