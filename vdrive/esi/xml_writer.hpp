#pragma once
// A thin, well-escaping XML writer for the ESI export (tinyxml2's streaming printer: text and
// attribute values are escaped by it). Element and attribute names must be string literals: the
// printer keeps the pointer until the element is closed.
#include <string>

#include <tinyxml2.h>

namespace vdrive::esi {

class XmlWriter {
public:
  XmlWriter() : printer_(nullptr, /*compact=*/false) {
    printer_.PushDeclaration("xml version=\"1.0\" encoding=\"UTF-8\"");
  }

  void open(const char* name) { printer_.OpenElement(name); }
  void attr(const char* name, const std::string& value) { printer_.PushAttribute(name, value.c_str()); }
  void close() { printer_.CloseElement(); }
  // <name>text</name>
  void element(const char* name, const std::string& text) {
    printer_.OpenElement(name);
    printer_.PushText(text.c_str());
    printer_.CloseElement();
  }
  // Text then close: for an element that has attributes, <name a="..">text</name>.
  void close_with_text(const std::string& text) {
    printer_.PushText(text.c_str());
    printer_.CloseElement();
  }
  // A comment; "--" is not allowed inside one, so it is replaced.
  void comment(std::string text);
  std::string str() const { return printer_.CStr(); }

private:
  tinyxml2::XMLPrinter printer_;
};

inline void XmlWriter::comment(std::string text) {
  for (std::size_t p = text.find("--"); p != std::string::npos; p = text.find("--", p)) text.replace(p, 2, "- ");
  if (!text.empty() && text.back() == '-') text += ' ';
  printer_.PushComment((" " + text + " ").c_str());
}

}  // namespace vdrive::esi
