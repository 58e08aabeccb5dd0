#include "analysis/report_document.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "analysis/report.h"

namespace granasym::analysis {

std::string HtmlEscaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace report {
namespace {

// ---------------------------------------------------------------------------
// HTML

constexpr const char* kStylesheet = R"(
*{box-sizing:border-box}
body{font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Noto Sans",sans-serif;
 color:#1b1b1b;background:#fff;margin:0 auto;max-width:84rem;padding:0 1rem 3rem}
h1{font-size:1.7em;margin:1em 0 .3em}
h2{font-size:1.35em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2.2em}
h3{font-size:1.1em;margin-top:1.6em}
p,li,figcaption,summary,h1,h2,h3{overflow-wrap:anywhere}
a{color:#0b57a4}
nav.toc{background:#f4f6f8;border:1px solid #dde;padding:.3em 1em;margin:1em 0}
nav.toc ol{margin:.3em 0;padding-left:1.5em}
.scroll{overflow-x:auto;max-width:100%;margin:.5em 0 1em}
table{border-collapse:collapse;font-size:13px}
th,td{border:1px solid #d0d4d8;padding:.2em .5em;text-align:left;vertical-align:top;
 white-space:nowrap}
th{background:#eef1f4}
td.num{text-align:right;font-variant-numeric:tabular-nums}
td.text{white-space:normal;min-width:18em;max-width:44em}
tr.total td{font-weight:600;background:#f6f6f6}
.status-detected,.status-fitted,.status-fixed,.status-completed,.status-joined{color:#176b2c}
.status-drifting,.status-not_reached,.status-at_bound,.status-not_joined,.status-no_overlap,
.status-interrupted,.status-running,.status-stale,.flagged{color:#8a5a00;font-weight:600}
.status-gas,.status-invalid,.status-no_result,.status-undetermined,.status-failed,.status-inadmissible,
.status-not_run{color:#b3261e;font-weight:600}
.verdict-reproduced{background:#e3f4e6;color:#176b2c;font-weight:600}
.verdict-partly{background:#fdf1dc;color:#8a5a00;font-weight:600}
.verdict-not_reproduced{background:#fbe3e1;color:#b3261e;font-weight:600}
.verdict-not_tested{background:#eee;color:#555;font-weight:600}
td.small{font-size:85%}
p.note{border-left:4px solid #d39e00;background:#fff8e1;padding:.4em .8em}
figure{margin:1em 0}
figure img,figure svg{display:block;max-width:100%;height:auto;border:1px solid #e0e0e0;
 background:#fff}
pre{overflow-x:auto;background:#f5f5f5;padding:.6em;font-size:13px;max-width:100%}
code{font-size:90%;overflow-wrap:anywhere}
details{margin:.5em 0}
summary{cursor:pointer}
)";

std::string HtmlInline(const Inline& content) {
  std::string html;
  for (const Span& span : content) {
    std::string text = HtmlEscaped(span.text);
    if (span.code) text = "<code>" + text + "</code>";
    if (!span.href.empty()) text = "<a href=\"" + HtmlEscaped(span.href) + "\">" + text + "</a>";
    html += text;
  }
  return html;
}

void HtmlBlock(const Block& block, std::string* html) {
  switch (block.type) {
    case Block::Type::kParagraph:
      *html += "<p>" + HtmlInline(block.text) + "</p>\n";
      break;
    case Block::Type::kNote:
      *html += "<p class=\"note\">" + HtmlInline(block.text) + "</p>\n";
      break;
    case Block::Type::kTable: {
      *html += "<div class=\"scroll\"><table>\n<thead><tr>";
      for (const std::string& name : block.header) *html += "<th>" + HtmlEscaped(name) + "</th>";
      *html += "</tr></thead>\n<tbody>\n";
      for (size_t r = 0; r < block.rows.size(); ++r) {
        const std::string css = r < block.row_css.size() ? block.row_css[r] : "";
        *html += css.empty() ? "<tr>" : "<tr class=\"" + HtmlEscaped(css) + "\">";
        for (const Cell& cell : block.rows[r]) {
          *html += cell.css.empty() ? "<td>" : "<td class=\"" + HtmlEscaped(cell.css) + "\">";
          *html += HtmlInline(cell.content) + "</td>";
        }
        *html += "</tr>\n";
      }
      *html += "</tbody></table></div>\n";
      break;
    }
    case Block::Type::kFigure:
      *html += "<figure>";
      if (!block.svg_markup.empty()) {
        *html += block.svg_markup;
      } else {
        *html += "<img src=\"" + HtmlEscaped(block.data_uri) + "\" alt=\"" +
                 HtmlEscaped(PlainText(block.text)) + "\">";
      }
      *html += "</figure>\n";
      break;
    case Block::Type::kDetails:
      *html += "<details><summary>" + HtmlInline(block.text) + "</summary>\n";
      if (!block.preformatted.empty()) {
        *html += "<pre>" + HtmlEscaped(block.preformatted) + "</pre>\n";
      }
      for (const Block& child : block.children) HtmlBlock(child, html);
      *html += "</details>\n";
      break;
    case Block::Type::kList:
      *html += "<ul>\n";
      for (const Inline& item : block.items) *html += "<li>" + HtmlInline(item) + "</li>\n";
      *html += "</ul>\n";
      break;
  }
}

// ---------------------------------------------------------------------------
// Markdown (CommonMark with pipe tables, as forges render it)

std::string MarkdownEscaped(const std::string& text) {
  std::string out;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (c == '\n' || c == '\r') {
      out += ' ';
      continue;
    }
    // '_' only emphasises at a word boundary (snake_case names stay readable).
    const bool boundary_underscore =
        c == '_' &&
        (k == 0 || k + 1 == text.size() || !std::isalnum(static_cast<unsigned char>(text[k - 1])) ||
         !std::isalnum(static_cast<unsigned char>(text[k + 1])));
    if (c == '\\' || c == '*' || c == '[' || c == ']' || c == '<' || c == '>' || c == '`' ||
        c == '|' || c == '#' || c == '&' || boundary_underscore) {
      out += '\\';
    }
    out += c;
  }
  return out;
}

std::string Fence(const std::string& text, char mark, size_t minimum) {
  size_t longest = 0, run = 0;
  for (char c : text) {
    run = c == mark ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return std::string(std::max(minimum, longest + 1), mark);
}

std::string MarkdownInline(const Inline& content) {
  std::string md;
  for (const Span& span : content) {
    std::string text;
    if (span.code) {
      std::string code = span.text;
      std::replace(code.begin(), code.end(), '\n', ' ');
      const std::string fence = Fence(code, '`', 1);
      const bool pad = !code.empty() && (code.front() == '`' || code.back() == '`');
      text = fence + (pad ? " " : "") + code + (pad ? " " : "") + fence;
      // Inside a pipe table a '|' ends the cell even in a code span.
      std::string escaped;
      for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
      text = escaped;
    } else {
      text = MarkdownEscaped(span.text);
    }
    if (!span.href.empty()) {
      std::string href;
      for (char c : span.href) {
        href += c == '(' ? std::string("%28") : c == ')' ? std::string("%29") : std::string(1, c);
      }
      text = "[" + text + "](" + href + ")";
    }
    md += text;
  }
  return md;
}

void MarkdownBlock(const Block& block, std::string* md) {
  switch (block.type) {
    case Block::Type::kParagraph:
      *md += MarkdownInline(block.text) + "\n\n";
      break;
    case Block::Type::kNote:
      *md += "> " + MarkdownInline(block.text) + "\n\n";
      break;
    case Block::Type::kTable: {
      std::string line = "|", rule = "|";
      for (const std::string& name : block.header) {
        line += " " + MarkdownEscaped(name) + " |";
        rule += " --- |";
      }
      *md += line + "\n" + rule + "\n";
      for (const std::vector<Cell>& row : block.rows) {
        line = "|";
        for (const Cell& cell : row) line += " " + MarkdownInline(cell.content) + " |";
        *md += line + "\n";
      }
      *md += "\n";
      break;
    }
    case Block::Type::kFigure:
      *md += "![" + MarkdownEscaped(PlainText(block.text)) + "](" + UrlPath(block.image) + ")\n\n";
      break;
    case Block::Type::kDetails:
      // Forges fold <details>; a terminal shows its content as it is.
      *md += "<details><summary>" + HtmlEscaped(PlainText(block.text)) + "</summary>\n\n";
      if (!block.preformatted.empty()) {
        const std::string fence = Fence(block.preformatted, '`', 3);
        *md += fence + "text\n" + block.preformatted +
               (block.preformatted.back() == '\n' ? "" : "\n") + fence + "\n\n";
      }
      for (const Block& child : block.children) MarkdownBlock(child, md);
      *md += "</details>\n\n";
      break;
    case Block::Type::kList:
      for (const Inline& item : block.items) *md += "- " + MarkdownInline(item) + "\n";
      *md += "\n";
      break;
  }
}

}  // namespace

std::string PlainText(const Inline& content) {
  std::string text;
  for (const Span& span : content) text += span.text;
  return text;
}

Block Paragraph(Inline text) {
  Block block;
  block.text = std::move(text);
  return block;
}
Block Note(Inline text) {
  Block block = Paragraph(std::move(text));
  block.type = Block::Type::kNote;
  return block;
}

std::string Slug(const std::string& title) {
  std::string slug;
  for (char c : title) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || u >= 0x80) {
      slug += static_cast<char>(std::tolower(u));
    } else if (c == ' ' || c == '-') {
      slug += '-';
    } else if (c == '_') {
      slug += '_';
    }
  }
  return slug;
}

std::string UrlPath(const std::string& path) {
  std::string url;
  for (char c : path) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '/' || c == '.' || c == '_' || c == '-' || c == '~') {
      url += c;
    } else {
      url += fmt::format("%{:02X}", u);
    }
  }
  return url;
}

std::string RenderHtml(const Document& document) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      HtmlEscaped(document.title) + "</title>\n<style>" + kStylesheet +
      "</style>\n</head>\n<body>\n";
  html += "<h1>" + HtmlEscaped(document.title) + "</h1>\n";
  html += "<p>" + HtmlInline(document.subtitle) + "</p>\n";
  html += "<nav class=\"toc\"><strong>Contents</strong>\n<ol>\n";
  bool open_item = false, nested = false;
  for (const Section& section : document.sections) {
    const std::string link =
        "<a href=\"#" + HtmlEscaped(section.id) + "\">" + HtmlEscaped(section.title) + "</a>";
    if (section.level > 2 && open_item) {
      if (!nested) html += "\n<ol>\n";
      nested = true;
      html += "<li>" + link + "</li>\n";
      continue;
    }
    if (nested) html += "</ol>";
    if (open_item) html += "</li>\n";
    html += "<li>" + link;
    open_item = true;
    nested = false;
  }
  if (nested) html += "</ol>";
  if (open_item) html += "</li>\n";
  html += "</ol></nav>\n";
  for (const Section& section : document.sections) {
    const std::string tag = "h" + std::to_string(section.level);
    html += "<" + tag + " id=\"" + HtmlEscaped(section.id) + "\">" + HtmlEscaped(section.title) +
            "</" + tag + ">\n";
    for (const Block& block : section.blocks) HtmlBlock(block, &html);
  }
  html += "</body>\n</html>\n";
  return html;
}

std::string RenderMarkdown(const Document& document) {
  std::string md = "# " + MarkdownEscaped(document.title) + "\n\n";
  md += MarkdownInline(document.subtitle) + "\n\n";
  md += "**Contents**\n\n";
  for (const Section& section : document.sections) {
    md += std::string(section.level > 2 ? "    " : "") + "- [" + MarkdownEscaped(section.title) +
          "](#" + section.id + ")\n";
  }
  md += "\n";
  for (const Section& section : document.sections) {
    md += std::string(section.level, '#') + " " + MarkdownEscaped(section.title) + "\n\n";
    for (const Block& block : section.blocks) MarkdownBlock(block, &md);
  }
  return md;
}

}  // namespace report
}  // namespace granasym::analysis
