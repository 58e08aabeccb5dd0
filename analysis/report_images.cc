#include "analysis/report_images.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <utility>
#include <vector>

#include "analysis/report.h"
#include "common/error.h"

namespace granasym::analysis::report {
namespace {

struct Attribute {
  std::string name, value;  // the value as written (entities not decoded)
};

// A start or end tag of the SVG.
struct Tag {
  std::string name;
  std::vector<Attribute> attributes;
  bool end = false, self_closing = false;
  size_t next = 0;  // the position after its '>'
};

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool StartsWith(const std::string& text, size_t at, const std::string& prefix) {
  return text.compare(at, prefix.size(), prefix) == 0;
}

class SvgError {
 public:
  SvgError(const std::string& text, std::string origin) : text_(text), origin_(std::move(origin)) {}
  [[noreturn]] void Throw(size_t at, const std::string& what) const {
    const int line = 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + at, '\n'));
    throw InputError(origin_ + ": line " + std::to_string(line) + ": " + what +
                     " (expected an SVG written by gnuplot's svg terminal)");
  }

 private:
  const std::string& text_;
  std::string origin_;
};

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// The tag that starts at text[at] == '<' (not a comment, declaration or
// processing instruction).
Tag ReadTag(const std::string& text, size_t at, const SvgError& error) {
  Tag tag;
  size_t k = at + 1;
  if (k < text.size() && text[k] == '/') {
    tag.end = true;
    ++k;
  }
  const size_t name_start = k;
  while (k < text.size() && !IsSpace(text[k]) && text[k] != '>' && text[k] != '/') ++k;
  tag.name = text.substr(name_start, k - name_start);
  if (tag.name.empty()) error.Throw(at, "a '<' that starts no tag");
  while (true) {
    while (k < text.size() && IsSpace(text[k])) ++k;
    if (k >= text.size()) error.Throw(at, "the tag <" + tag.name + "> is not closed");
    if (text[k] == '>') {
      tag.next = k + 1;
      return tag;
    }
    if (text[k] == '/' && k + 1 < text.size() && text[k + 1] == '>') {
      tag.self_closing = true;
      tag.next = k + 2;
      return tag;
    }
    Attribute attribute;
    const size_t attribute_start = k;
    while (k < text.size() && !IsSpace(text[k]) && text[k] != '=' && text[k] != '>' &&
           text[k] != '/') {
      ++k;
    }
    attribute.name = text.substr(attribute_start, k - attribute_start);
    if (attribute.name.empty()) error.Throw(k, "a stray '/' in the tag <" + tag.name + ">");
    while (k < text.size() && IsSpace(text[k])) ++k;
    if (k < text.size() && text[k] == '=') {
      ++k;
      while (k < text.size() && IsSpace(text[k])) ++k;
      if (k < text.size() && (text[k] == '"' || text[k] == '\'')) {
        const char quote = text[k];
        const size_t end = text.find(quote, k + 1);
        if (end == std::string::npos) {
          error.Throw(k, "the value of " + attribute.name + " in <" + tag.name + "> is not closed");
        }
        attribute.value = text.substr(k + 1, end - k - 1);
        k = end + 1;
      } else {
        const size_t value_start = k;
        while (k < text.size() && !IsSpace(text[k]) && text[k] != '>') ++k;
        attribute.value = text.substr(value_start, k - value_start);
      }
    }
    tag.attributes.push_back(std::move(attribute));
  }
}

// `code` as UTF-8.
std::string Utf8(uint32_t code) {
  std::string out;
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  return out;
}

// An attribute value as the XML parser reads it: its entities replaced.
std::string XmlDecoded(const std::string& value) {
  std::string out;
  for (size_t k = 0; k < value.size(); ++k) {
    const size_t end = value[k] == '&' ? value.find(';', k) : std::string::npos;
    if (end == std::string::npos || end - k > 10) {
      out += value[k];
      continue;
    }
    const std::string name = value.substr(k + 1, end - k - 1);
    std::string decoded;
    if (name == "amp") decoded = "&";
    if (name == "lt") decoded = "<";
    if (name == "gt") decoded = ">";
    if (name == "quot") decoded = "\"";
    if (name == "apos") decoded = "'";
    if (name.size() > 1 && name[0] == '#') {
      const bool hex = name[1] == 'x' || name[1] == 'X';
      const std::string digits = name.substr(hex ? 2 : 1);
      const bool valid = !digits.empty() && std::all_of(digits.begin(), digits.end(), [&](char c) {
        return hex ? std::isxdigit(static_cast<unsigned char>(c)) != 0
                   : std::isdigit(static_cast<unsigned char>(c)) != 0;
      });
      if (valid) {
        const unsigned long code = std::stoul(digits, nullptr, hex ? 16 : 10);
        if (code > 0 && code <= 0x10FFFF) decoded = Utf8(static_cast<uint32_t>(code));
      }
    }
    if (decoded.empty()) {
      out += value[k];
      continue;
    }
    out += decoded;
    k = end;
  }
  return out;
}

// The text of gnuplot_svg.showHypertext(evt,'...') in `raw_value` (an
// attribute's value as written); false when the value is something else.
bool HypertextOf(const std::string& raw_value, std::string* text) {
  const std::string value = XmlDecoded(raw_value);
  const std::string call = "showHypertext(";
  const size_t at = value.find(call);
  if (at == std::string::npos) return false;
  const size_t open = value.find_first_of("'\"", at + call.size());
  const size_t close = value.find_last_of(")");
  if (open == std::string::npos || close == std::string::npos || close <= open) return false;
  const char quote = value[open];
  const size_t end = value.find_last_of(quote, close);
  if (end == std::string::npos || end <= open) return false;
  // The JavaScript string's escapes.
  text->clear();
  for (size_t k = open + 1; k < end; ++k) {
    if (value[k] != '\\' || k + 1 == end) {
      *text += value[k];
      continue;
    }
    const char next = value[++k];
    *text += next == 'n' ? '\n' : next == 't' ? '\t' : next;
  }
  return true;
}

std::string Prefixed(const std::string& value, const std::string& prefix) {
  std::string out;
  size_t at = 0;
  while (true) {
    const size_t found = value.find("url(", at);
    if (found == std::string::npos) break;
    size_t hash = found + 4;
    if (hash < value.size() && (value[hash] == '\'' || value[hash] == '"')) ++hash;
    out += value.substr(at, hash - at);
    at = hash;
    if (hash < value.size() && value[hash] == '#') {
      out += "#" + prefix;
      at = hash + 1;
    }
  }
  return out + value.substr(at);
}

std::string TrimmedLower(const std::string& value) {
  size_t start = 0;
  while (start < value.size() && IsSpace(value[start])) ++start;
  return Lower(value.substr(start));
}

// The start tag `tag` written back: handlers and script links dropped, ids
// and references prefixed, values double-quoted.
std::string Rewritten(const Tag& tag, const std::string& prefix,
                      const std::vector<Attribute>& extra) {
  std::string out = "<" + tag.name;
  std::vector<Attribute> attributes = tag.attributes;
  for (const Attribute& added : extra) {
    auto same = std::find_if(attributes.begin(), attributes.end(),
                             [&](const Attribute& a) { return Lower(a.name) == added.name; });
    if (same == attributes.end()) {
      attributes.push_back(added);
    } else {
      same->value = added.name == "class" ? same->value + " " + added.value : added.value;
    }
  }
  for (const Attribute& a : attributes) {
    const std::string name = Lower(a.name);
    if (name.size() > 2 && StartsWith(name, 0, "on")) continue;
    std::string value = a.value;
    const bool link = name == "href" || name == "xlink:href";
    if (link && StartsWith(TrimmedLower(XmlDecoded(value)), 0, "javascript:")) continue;
    if (name == "id") value = prefix + value;
    if (link && !value.empty() && value[0] == '#') value = "#" + prefix + value.substr(1);
    value = Prefixed(value, prefix);
    std::string quoted;
    for (char c : value) quoted += c == '"' ? std::string("&quot;") : std::string(1, c);
    out += " " + a.name + "=\"" + quoted + "\"";
  }
  return out + (tag.self_closing ? "/>" : ">");
}

// The position after the markup that is not an element at text[at] == '<'
// (comment, declaration, processing instruction), or npos for a tag.
size_t SkipNonElement(const std::string& text, size_t at, const SvgError& error) {
  auto after = [&](const std::string& close) {
    const size_t end = text.find(close, at);
    if (end == std::string::npos) error.Throw(at, "'" + close + "' is missing");
    return end + close.size();
  };
  if (StartsWith(text, at, "<!--")) return after("-->");
  if (StartsWith(text, at, "<?")) return after("?>");
  if (StartsWith(text, at, "<!") && !StartsWith(text, at, "<![CDATA[")) {
    // <!DOCTYPE ...>, perhaps with an internal subset in [...].
    const size_t bracket = text.find('[', at), close = text.find('>', at);
    if (bracket != std::string::npos && close != std::string::npos && bracket < close) {
      return after("]>");
    }
    return after(">");
  }
  return std::string::npos;
}

// An element that only gnuplot's script uses: the hidden boxes in which it
// shows coordinates and hover texts, and the button that toggles the grid.
bool ScriptOnly(const Tag& tag) {
  for (const Attribute& a : tag.attributes) {
    const std::string name = Lower(a.name);
    if (name == "id" && (a.value == "coord_text" || a.value == "hypertextbox" ||
                         a.value == "hypertext" || a.value == "hyperimage")) {
      return true;
    }
    if (name == "onclick" && a.value.find("gnuplot_svg.toggleGrid") != std::string::npos) {
      return true;
    }
  }
  return false;
}

}  // namespace

InlineSvg MakeInlineSvg(const std::string& svg, const std::string& prefix, const std::string& label,
                        const std::string& origin) {
  const SvgError error(svg, origin);
  InlineSvg result;
  std::string& out = result.markup;
  std::vector<std::string> open;  // the elements open, the root first
  bool done = false;
  size_t at = 0;
  while (at < svg.size() && !done) {
    if (svg[at] != '<') {
      const size_t next = std::min(svg.find('<', at), svg.size());
      if (!open.empty()) out.append(svg, at, next - at);
      at = next;
      continue;
    }
    if (StartsWith(svg, at, "<![CDATA[")) {
      const size_t end = svg.find("]]>", at);
      if (end == std::string::npos) error.Throw(at, "a CDATA section is not closed");
      if (!open.empty()) out.append(svg, at, end + 3 - at);
      at = end + 3;
      continue;
    }
    const size_t skipped = SkipNonElement(svg, at, error);
    if (skipped != std::string::npos) {
      at = skipped;
      continue;
    }
    const Tag tag = ReadTag(svg, at, error);
    const std::string name = Lower(tag.name);
    if (open.empty() && (tag.end || name != "svg")) {
      error.Throw(at, "the document starts with <" + std::string(tag.end ? "/" : "") + tag.name +
                          ">, not <svg>");
    }
    if (tag.end) {
      if (open.back() != name) {
        error.Throw(at, "</" + tag.name + "> closes <" + open.back() + ">");
      }
      out += "</" + tag.name + ">";
      open.pop_back();
      done = open.empty();
      at = tag.next;
      continue;
    }
    // Scripts go whole; so do the root's own <title> ("Gnuplot": the
    // figure's label replaces it) and what only the script used.
    const bool root_title = name == "title" && open.size() == 1;
    if (name == "script" || root_title || ScriptOnly(tag)) {
      at = tag.next;
      if (!tag.self_closing) {
        const std::string close = "</" + tag.name;
        const size_t end = svg.find(close, at);
        if (end == std::string::npos) error.Throw(at, "<" + tag.name + "> is not closed");
        at = svg.find('>', end);
        if (at == std::string::npos) error.Throw(end, close + " is not closed");
        ++at;
      }
      continue;
    }
    // A hypertext label: its text goes into the group's <title>, which
    // replaces gnuplot's blank one (or comes first where there is none).
    std::string hypertext;
    bool is_hypertext = false;
    for (const Attribute& a : tag.attributes) {
      if (Lower(a.name) == "onmousemove") is_hypertext = HypertextOf(a.value, &hypertext);
      if (is_hypertext) break;
    }
    std::vector<Attribute> extra;
    if (open.empty()) {
      extra = {{"class", "plot"}, {"role", "img"}, {"aria-label", HtmlEscaped(label)}};
    }
    // Marked, so that a reader (or a test) tells a state's label from a curve's title.
    if (is_hypertext && !tag.self_closing) extra = {{"class", "hover"}};
    out += Rewritten(tag, prefix, extra);
    at = tag.next;
    if (tag.self_closing) continue;
    open.push_back(name);
    if (!is_hypertext) continue;
    ++result.tooltips;
    size_t next = at;
    while (next < svg.size() && IsSpace(svg[next])) ++next;
    if (StartsWith(svg, next, "<title")) {
      const Tag title = ReadTag(svg, next, error);
      if (Lower(title.name) == "title" && !title.end) {
        at = title.next;
        if (!title.self_closing) {
          const size_t end = svg.find("</title>", at);
          if (end == std::string::npos) error.Throw(next, "<title> is not closed");
          at = end + std::string("</title>").size();
        }
      }
    }
    out += "<title>" + HtmlEscaped(hypertext) + "</title>";
  }
  if (open.empty() && !done) error.Throw(svg.size(), "no <svg> element");
  if (!done) error.Throw(svg.size(), "<" + open.back() + "> is not closed at the end");
  return result;
}

std::string DataUri(const std::string& mime, const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out = "data:" + mime + ";base64,";
  out.reserve(out.size() + (bytes.size() + 2) / 3 * 4);
  size_t k = 0;
  for (; k + 2 < bytes.size(); k += 3) {
    const uint32_t n = static_cast<uint32_t>(static_cast<unsigned char>(bytes[k])) << 16 |
                       static_cast<uint32_t>(static_cast<unsigned char>(bytes[k + 1])) << 8 |
                       static_cast<unsigned char>(bytes[k + 2]);
    out += kAlphabet[n >> 18];
    out += kAlphabet[(n >> 12) & 63];
    out += kAlphabet[(n >> 6) & 63];
    out += kAlphabet[n & 63];
  }
  if (k < bytes.size()) {
    uint32_t n = static_cast<uint32_t>(static_cast<unsigned char>(bytes[k])) << 16;
    if (k + 1 < bytes.size())
      n |= static_cast<uint32_t>(static_cast<unsigned char>(bytes[k + 1])) << 8;
    out += kAlphabet[n >> 18];
    out += kAlphabet[(n >> 12) & 63];
    out += k + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace granasym::analysis::report
