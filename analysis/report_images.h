// The report's figures inside index.html (analysis/report.h), so that the
// page is one file: gnuplot's SVG inline, its hover labels turned into
// native tooltips, and a PNG as a data URI where a figure has no SVG.
// Internal to the analysis library.
//
// gnuplot 5.4's `set terminal svg mouse standalone` writes a script and,
// for a hypertext label (`with labels hypertext`), a group
//   <g onmousemove="gnuplot_svg.showHypertext(evt,'case nc100\nreplicate 2')"
//      onmouseout="gnuplot_svg.hideHypertext()"><title> </title> ... </g>
// whose text its script shows. Inline, without scripts, the group's <title>
// carries that text instead: browsers show a <title> as a tooltip.
#pragma once

#include <string>

namespace granasym::analysis::report {

struct InlineSvg {
  std::string markup;  // the <svg> element, ready to be placed in HTML
  int tooltips = 0;    // hypertext labels turned into <title> tooltips
};

// `svg` (the text of an SVG file, `origin` its name in messages) made fit to
// sit inline among other SVGs: the XML declaration, doctype, comments and
// every <script> dropped, and so are the elements only the script uses (the
// hidden hover boxes, the grid button); every on* attribute (its handlers)
// and every javascript: link dropped; every id, href="#id" and url(#id)
// prefixed with `prefix` (ids are per document, and the page holds many
// SVGs); each hypertext group marked class="hover" and its <title> filled
// with its text (gnuplot's
// JavaScript escapes \n, \', \" and \\ undone); the root's own <title>
// replaced by `label`. InputError naming `origin` when the text is not an
// SVG document (no <svg> element, a tag or comment left open).
InlineSvg MakeInlineSvg(const std::string& svg, const std::string& prefix, const std::string& label,
                        const std::string& origin);

// `bytes` as a data URI: "data:<mime>;base64,...".
std::string DataUri(const std::string& mime, const std::string& bytes);

}  // namespace granasym::analysis::report
