// throng::io::JsonDocument — a position-keeping JSON reader (RFC 8259). Reads the text once,
// byte by byte, tracking line and column; writes nlohmann::ordered_json values and a
// pointer → position map used to locate every diagnostic. Never throws: a syntax error becomes one
// diagnostic ("unexpected X; expected Y") at the offending line:column.
#include "json_document.hpp"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstdint>

namespace throng::io {

std::string escapePointerToken(std::string_view token) {
  std::string out;
  out.reserve(token.size());
  for (const char c : token) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string describeType(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::string: return "a string";
    case Json::value_t::array: return "an array";
    case Json::value_t::object: return "an object";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned: return "an integer";
    case Json::value_t::number_float: return "a number";
    default: return "an unsupported value";
  }
}

namespace {
std::string parentPointer(const std::string& pointer) {
  const auto slash = pointer.rfind('/');
  return slash == std::string::npos ? std::string{} : pointer.substr(0, slash);
}
}  // namespace

SourcePos JsonDocument::position(const std::string& pointer) const {
  std::string p = pointer;
  for (;;) {
    if (auto it = values_.find(p); it != values_.end()) return it->second;
    if (p.empty()) return {};
    p = parentPointer(p);
  }
}

SourcePos JsonDocument::keyPosition(const std::string& pointer) const {
  if (auto it = keys_.find(pointer); it != keys_.end()) return it->second;
  return position(pointer);
}

core::Diagnostic JsonDocument::diagnostic(const std::string& pointer, std::string what, std::string expected,
                                          std::string hint, bool atKey) const {
  const SourcePos pos = atKey ? keyPosition(pointer) : position(pointer);
  return core::Diagnostic{source_, pos.line, pos.column, pointer, std::move(what), std::move(expected), std::move(hint)};
}

/// The recursive-descent reader; one instance per parse.
class JsonReader {
 public:
  JsonReader(std::string_view text, JsonDocument& doc) : text_(text), doc_(doc) {}

  bool run() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte order mark
    skipWhitespace();
    if (atEnd()) return fail("empty document", "a JSON object");
    if (!parseValue(doc_.root_, "", 0)) return false;
    skipWhitespace();
    if (!atEnd()) return fail("unexpected " + describeHere() + " after the document", "end of file");
    return true;
  }

  core::Diagnostic error() const { return error_; }

 private:
  bool atEnd() const { return pos_ >= text_.size(); }
  char peek() const { return atEnd() ? '\0' : text_[pos_]; }

  void advance() {
    const auto c = static_cast<unsigned char>(text_[pos_++]);
    if (c == '\n') {
      ++line_;
      column_ = 1;
    } else if ((c & 0xC0u) != 0x80u) {  // count code points, not UTF-8 continuation bytes
      ++column_;
    }
  }

  void skipWhitespace() {
    while (!atEnd()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') advance();
      else break;
    }
  }

  std::string describeHere() const {
    if (atEnd()) return "end of file";
    const auto c = static_cast<unsigned char>(text_[pos_]);
    if (c < 0x20 || c >= 0x7f) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "byte 0x%02X", c);
      return buf;
    }
    if (c == '\'') return "character \"'\" (JSON strings use double quotes)";
    return std::string("character '") + static_cast<char>(c) + "'";
  }

  bool fail(std::string what, std::string expected, std::string hint = {}) {
    error_ = core::Diagnostic{doc_.source_, line_, column_, "", "JSON syntax error: " + std::move(what),
                              std::move(expected), std::move(hint)};
    return false;
  }

  bool parseValue(Json& out, const std::string& pointer, int depth) {
    doc_.values_[pointer] = SourcePos{line_, column_};
    if (depth > JsonDocument::kMaxDepth) {
      return fail("nesting deeper than " + std::to_string(JsonDocument::kMaxDepth) + " levels", "a shallower document");
    }
    switch (peek()) {
      case '{': return parseObject(out, pointer, depth);
      case '[': return parseArray(out, pointer, depth);
      case '"': {
        std::string s;
        if (!parseString(s)) return false;
        out = std::move(s);
        return true;
      }
      case 't': return parseLiteral("true", out, Json(true));
      case 'f': return parseLiteral("false", out, Json(false));
      case 'n': return parseLiteral("null", out, Json(nullptr));
      default:
        if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return parseNumber(out);
        return fail("unexpected " + describeHere(), "a value (object, array, string, number, true, false or null)");
    }
  }

  bool parseLiteral(std::string_view word, Json& out, Json value) {
    for (const char c : word) {
      if (peek() != c) return fail("unexpected " + describeHere(), "a value (object, array, string, number, true, false or null)");
      advance();
    }
    out = std::move(value);
    return true;
  }

  bool parseObject(Json& out, const std::string& pointer, int depth) {
    out = Json::object();
    advance();  // '{'
    skipWhitespace();
    if (peek() == '}') {
      advance();
      return true;
    }
    for (;;) {
      skipWhitespace();
      if (peek() != '"') {
        return fail("unexpected " + describeHere() + " in an object", "a key in double quotes",
                    peek() == '}' ? "JSON allows no trailing comma" : "");
      }
      const SourcePos keyPos{line_, column_};
      std::string key;
      if (!parseString(key)) return false;
      const std::string child = pointer + "/" + escapePointerToken(key);
      if (out.contains(key)) {
        error_ = core::Diagnostic{doc_.source_, keyPos.line, keyPos.column, child, "duplicate key \"" + key + "\"",
                                  "each key once per object", ""};
        return false;
      }
      doc_.keys_[child] = keyPos;
      skipWhitespace();
      if (peek() != ':') return fail("unexpected " + describeHere() + " after key \"" + key + "\"", "':'");
      advance();
      skipWhitespace();
      Json value;
      if (!parseValue(value, child, depth + 1)) return false;
      out[key] = std::move(value);
      skipWhitespace();
      if (peek() == ',') {
        advance();
        continue;
      }
      if (peek() == '}') {
        advance();
        return true;
      }
      return fail("unexpected " + describeHere() + " in an object", "',' or '}'");
    }
  }

  bool parseArray(Json& out, const std::string& pointer, int depth) {
    out = Json::array();
    advance();  // '['
    skipWhitespace();
    if (peek() == ']') {
      advance();
      return true;
    }
    for (std::size_t index = 0;; ++index) {
      skipWhitespace();
      if (peek() == ']') return fail("unexpected ']'", "a value", "JSON allows no trailing comma");
      Json value;
      if (!parseValue(value, pointer + "/" + std::to_string(index), depth + 1)) return false;
      out.push_back(std::move(value));
      skipWhitespace();
      if (peek() == ',') {
        advance();
        continue;
      }
      if (peek() == ']') {
        advance();
        return true;
      }
      return fail("unexpected " + describeHere() + " in an array", "',' or ']'");
    }
  }

  static void appendUtf8(std::string& s, std::uint32_t cp) {
    if (cp < 0x80) {
      s += static_cast<char>(cp);
    } else if (cp < 0x800) {
      s += static_cast<char>(0xC0 | (cp >> 6));
      s += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      s += static_cast<char>(0xE0 | (cp >> 12));
      s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      s += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      s += static_cast<char>(0xF0 | (cp >> 18));
      s += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      s += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  bool parseHex4(std::uint32_t& cp) {
    cp = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = peek();
      std::uint32_t d;
      if (c >= '0' && c <= '9') d = static_cast<std::uint32_t>(c - '0');
      else if (c >= 'a' && c <= 'f') d = static_cast<std::uint32_t>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') d = static_cast<std::uint32_t>(c - 'A' + 10);
      else return fail("bad \\u escape: unexpected " + describeHere(), "4 hexadecimal digits");
      cp = cp * 16 + d;
      advance();
    }
    return true;
  }

  bool parseString(std::string& out) {
    advance();  // opening quote
    for (;;) {
      if (atEnd()) return fail("unterminated string", "a closing '\"'");
      const auto c = static_cast<unsigned char>(peek());
      if (c == '"') {
        advance();
        return true;
      }
      if (c < 0x20) {
        return fail("unexpected " + describeHere() + " in a string", "no raw control characters (write \\n, \\t)",
                    c == '\n' ? "a string cannot span lines" : "");
      }
      if (c != '\\') {
        out += static_cast<char>(c);
        advance();
        continue;
      }
      advance();  // backslash
      const char e = peek();
      if (atEnd()) return fail("unterminated string", "a closing '\"'");
      advance();
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp;
          if (!parseHex4(cp)) return false;
          if (cp >= 0xD800 && cp <= 0xDBFF) {
            if (peek() != '\\') return fail("lone UTF-16 high surrogate", "a following \\uDC00..\\uDFFF");
            advance();
            if (peek() != 'u') return fail("lone UTF-16 high surrogate", "a following \\uDC00..\\uDFFF");
            advance();
            std::uint32_t low;
            if (!parseHex4(low)) return false;
            if (low < 0xDC00 || low > 0xDFFF) return fail("bad UTF-16 low surrogate", "\\uDC00..\\uDFFF");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
          } else if (cp >= 0xDC00 && cp <= 0xDFFF) {
            return fail("lone UTF-16 low surrogate", "a high surrogate \\uD800..\\uDBFF before it");
          }
          appendUtf8(out, cp);
          break;
        }
        default:
          return fail(std::string("unknown escape \\") + (static_cast<unsigned char>(e) >= 0x20 && e != 0x7f ? std::string(1, e) : "?"),
                      "one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX");
      }
    }
  }

  bool parseNumber(Json& out) {
    const std::size_t start = pos_;
    const int startLine = line_;
    const int startColumn = column_;
    bool integral = true;
    if (peek() == '-') advance();
    if (peek() == '0') {
      advance();
      if (peek() >= '0' && peek() <= '9') return fail("leading zero in a number", "a number without leading zeros");
    } else if (peek() >= '1' && peek() <= '9') {
      while (peek() >= '0' && peek() <= '9') advance();
    } else {
      return fail("unexpected " + describeHere() + " in a number", "a digit");
    }
    if (peek() == '.') {
      integral = false;
      advance();
      if (!(peek() >= '0' && peek() <= '9')) return fail("unexpected " + describeHere() + " after '.'", "a digit");
      while (peek() >= '0' && peek() <= '9') advance();
    }
    if (peek() == 'e' || peek() == 'E') {
      integral = false;
      advance();
      if (peek() == '+' || peek() == '-') advance();
      if (!(peek() >= '0' && peek() <= '9')) return fail("unexpected " + describeHere() + " in an exponent", "a digit");
      while (peek() >= '0' && peek() <= '9') advance();
    }
    const std::string_view token = text_.substr(start, pos_ - start);
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (integral) {
      if (token[0] == '-') {
        std::int64_t v = 0;
        if (auto r = std::from_chars(first, last, v); r.ec == std::errc{} && r.ptr == last) {
          out = v;
          return true;
        }
      } else {
        std::uint64_t v = 0;
        if (auto r = std::from_chars(first, last, v); r.ec == std::errc{} && r.ptr == last) {
          out = v;
          return true;
        }
      }
    }
    double d = 0.0;
    const auto r = std::from_chars(first, last, d);
    if (r.ec != std::errc{} || !std::isfinite(d)) {
      line_ = startLine;
      column_ = startColumn;
      return fail("number " + std::string(token.substr(0, 40)) + " is out of range", "a finite double-precision number");
    }
    out = d;
    return true;
  }

  std::string_view text_;
  JsonDocument& doc_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
  core::Diagnostic error_;
};

core::Result<JsonDocument> JsonDocument::parse(std::string_view text, const std::string& source) {
  JsonDocument doc;
  doc.source_ = source;
  if (text.size() > kMaxBytes) {
    return core::Diagnostic{source, 0, 0, "", "document is " + std::to_string(text.size()) + " bytes",
                            "at most " + std::to_string(kMaxBytes) + " bytes", ""};
  }
  try {
    JsonReader reader(text, doc);
    if (!reader.run()) return reader.error();
  } catch (const std::exception& e) {  // allocation failure: never let it escape
    return core::Diagnostic{source, 0, 0, "", std::string("cannot parse document: ") + e.what(), "", ""};
  }
  return doc;
}

}  // namespace throng::io
