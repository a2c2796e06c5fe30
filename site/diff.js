// diff.js — the lesson diffs' syntax colouring, in the browser and offline: diff2html's UI bundle
// (highlight.js inside) colours the side-by-side tables site/build.mjs rendered into each page.
/* global Diff2HtmlUI */
const languages = { h: 'cpp', cpp: 'cpp', vert: 'glsl', frag: 'glsl', comp: 'glsl', glsl: 'glsl', json: 'json', txt: 'cmake' };
document.querySelectorAll('.lesson-diff').forEach((el) => {
  new Diff2HtmlUI(el, undefined, {
    highlight: true, highlightLanguages: languages, synchronisedScroll: true,
    fileListToggle: false, fileContentToggle: true, stickyFileHeaders: false,
  }).draw();
});
