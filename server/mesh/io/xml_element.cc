#include "mesh/io/xml_element.h"

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "mesh/io/text_scanner.h"

namespace kerf::mesh::internal {
namespace {

constexpr int kMaxDepth = 32;

bool IsNameChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c == ':';
}
bool IsXmlSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

class XmlParser {
 public:
  XmlParser(absl::string_view text, absl::string_view source)
      : text_(text), errors_(text, source) {}

  absl::StatusOr<XmlElement> ParseDocument() {
    if (auto st = SkipMisc(); !st.ok()) return st;
    if (pos_ >= text_.size() || text_[pos_] != '<') return Error("expected the root element");
    absl::StatusOr<XmlElement> root = ParseElement(0);
    if (!root.ok()) return root;
    if (auto st = SkipMisc(); !st.ok()) return st;
    if (pos_ < text_.size())
      return Error("expected the end of the document after the root element");
    return root;
  }

 private:
  absl::Status Error(absl::string_view message) const { return errors_.ErrorAt(pos_, message); }

  void SkipSpace() {
    while (pos_ < text_.size() && IsXmlSpace(text_[pos_])) ++pos_;
  }

  // Skips "<?...?>", "<!--...-->" and "<!DOCTYPE ...>" and white space.
  absl::Status SkipMisc() {
    while (true) {
      SkipSpace();
      const absl::string_view rest = text_.substr(pos_);
      absl::string_view end;
      if (absl::StartsWith(rest, "<?")) {
        end = "?>";
      } else if (absl::StartsWith(rest, "<!--")) {
        end = "-->";
      } else if (absl::StartsWith(rest, "<!")) {
        end = ">";
      } else {
        return absl::OkStatus();
      }
      const std::size_t close = text_.find(end, pos_ + 2);
      if (close == absl::string_view::npos)
        return Error(absl::StrCat("unterminated markup, expected '", end, "'"));
      pos_ = close + end.size();
    }
  }

  absl::string_view ReadName() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && IsNameChar(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  absl::StatusOr<XmlElement> ParseElement(int depth) {
    if (depth > kMaxDepth) return Error("XML nested too deeply");
    XmlElement element;
    element.offset = pos_;
    ++pos_;  // '<'
    element.name = ReadName();
    if (element.name.empty()) return Error("expected an element name after '<'");
    while (true) {
      SkipSpace();
      if (pos_ >= text_.size())
        return Error(absl::StrCat("unterminated start tag <", element.name, ">"));
      if (text_[pos_] == '/') {
        if (pos_ + 1 >= text_.size() || text_[pos_ + 1] != '>') return Error("expected '/>'");
        pos_ += 2;
        return element;
      }
      if (text_[pos_] == '>') {
        ++pos_;
        break;
      }
      const absl::string_view key = ReadName();
      if (key.empty())
        return Error(absl::StrCat("expected an attribute name in <", element.name, ">"));
      SkipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '=')
        return Error(absl::StrCat("expected '=' after attribute ", key));
      ++pos_;
      SkipSpace();
      if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) {
        return Error(absl::StrCat("expected a quoted value for attribute ", key));
      }
      const char quote = text_[pos_++];
      const std::size_t close = text_.find(quote, pos_);
      if (close == absl::string_view::npos)
        return Error(absl::StrCat("unterminated value of attribute ", key));
      element.attributes.emplace_back(key, text_.substr(pos_, close - pos_));
      pos_ = close + 1;
    }
    // Content: text and child elements up to the end tag.
    const std::size_t content_start = pos_;
    while (true) {
      const std::size_t lt = text_.find('<', pos_);
      if (lt == absl::string_view::npos) {
        pos_ = text_.size();
        return Error(absl::StrCat("expected </", element.name, ">"));
      }
      pos_ = lt;
      if (absl::StartsWith(text_.substr(pos_), "</")) {
        if (element.children.empty())
          element.text = text_.substr(content_start, pos_ - content_start);
        pos_ += 2;
        const absl::string_view name = ReadName();
        if (name != element.name)
          return Error(absl::StrCat("expected </", element.name, ">, found </", name, ">"));
        SkipSpace();
        if (pos_ >= text_.size() || text_[pos_] != '>') return Error("expected '>'");
        ++pos_;
        return element;
      }
      if (absl::StartsWith(text_.substr(pos_), "<!") ||
          absl::StartsWith(text_.substr(pos_), "<?")) {
        if (absl::StartsWith(text_.substr(pos_), "<![CDATA["))
          return Error("CDATA sections are not supported");
        if (auto st = SkipMisc(); !st.ok()) return st;
        continue;
      }
      absl::StatusOr<XmlElement> child = ParseElement(depth + 1);
      if (!child.ok()) return child.status();
      element.children.push_back(*std::move(child));
    }
  }

  absl::string_view text_;
  TextScanner errors_;  // only for locating errors
  std::size_t pos_ = 0;
};

}  // namespace

std::optional<absl::string_view> XmlElement::Attribute(absl::string_view key) const {
  for (const auto& [k, v] : attributes) {
    if (k == key) return v;
  }
  return std::nullopt;
}

const XmlElement* XmlElement::Child(absl::string_view child_name) const {
  for (const XmlElement& child : children) {
    if (child.name == child_name) return &child;
  }
  return nullptr;
}

absl::StatusOr<XmlElement> ParseXml(absl::string_view text, absl::string_view source) {
  return XmlParser(text, source).ParseDocument();
}

}  // namespace kerf::mesh::internal
