// The report's document (analysis/report.h): sections of blocks, rendered
// once as HTML and once as Markdown, so that both files carry the same
// content; every text is escaped by the renderers, in one place.
// Internal to the analysis library.
#pragma once

#include <string>
#include <vector>

namespace granasym::analysis::report {

// A piece of inline text: plain, code, or a link (a relative path or an anchor).
struct Span {
  std::string text, href;
  bool code = false;
};
using Inline = std::vector<Span>;

inline Inline Plain(const std::string& text) { return {Span{text, "", false}}; }
inline Inline Code(const std::string& text) { return {Span{text, "", true}}; }
inline Inline Link(const std::string& text, const std::string& href, bool code = false) {
  return {Span{text, href, code}};
}
inline Inline operator+(Inline a, const Inline& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
std::string PlainText(const Inline& content);

struct Cell {
  Inline content;
  std::string css;  // classes of the cell (HTML only)
};

struct Block {
  enum class Type { kParagraph, kNote, kTable, kFigure, kDetails, kList };
  Type type = Type::kParagraph;
  Inline text;                          // paragraph, note, details' summary, figure's alt text
  std::vector<std::string> header;      // table
  std::vector<std::vector<Cell>> rows;  // table
  std::vector<std::string> row_css;     // table: classes of each row (may be empty)
  std::string image;                    // figure: relative path of the PNG (report.md links it)
  // figure, in index.html: the SVG inline (report_images.h made it safe to
  // place as it is), else the PNG as a data URI; the page links no image.
  std::string svg_markup, data_uri;
  std::string preformatted;     // details: shown as a code block
  std::vector<Block> children;  // details: blocks inside
  std::vector<Inline> items;    // list
};

Block Paragraph(Inline text);
Block Note(Inline text);

struct Section {
  std::string id;  // the anchor: set from the title when the document is complete
  std::string title;
  int level = 2;
  std::vector<Block> blocks;
};

struct Document {
  std::string title;
  Inline subtitle;
  std::vector<Section> sections;
};

// The anchor of a heading as forges derive it (lower case, blanks to '-',
// other ASCII punctuation dropped), so that report.md's contents work there
// too; a repeated anchor gets "-1", "-2", ... as on GitHub.
std::string Slug(const std::string& title);

// A relative path as a URL: every byte but unreserved characters and '/'
// percent-encoded.
std::string UrlPath(const std::string& path);

// index.html: one self-contained page with its stylesheet, contents and
// figures (inline SVG, or PNG data URIs); no scripts.
std::string RenderHtml(const Document& document);
// report.md: CommonMark with pipe tables, as forges render it.
std::string RenderMarkdown(const Document& document);

}  // namespace granasym::analysis::report
