// throng::io WKT reader — OGC well-known text (Simple Features 1.2.1, §7) → plan shapes: POLYGON
// (the first ring walkable, inner rings obstacles), MULTIPOLYGON, LINESTRING and MULTILINESTRING
// (walls), GEOMETRYCOLLECTION (nested at most kMaxWktDepth deep); POINT and MULTIPOINT are read and
// skipped. Z, M and ZM coordinates keep x and y. Several geometries may follow one another
// (whitespace or ';' between them); an EWKT "SRID=n;" prefix is skipped. Errors name
// file:line:column. Linear in the text.
#include <cctype>
#include <charconv>
#include <cmath>

#include "plan_shapes.hpp"
#include "throng/core/text.hpp"

namespace throng::io::plan {

namespace {

const std::string kGeometries = "POLYGON, MULTIPOLYGON, LINESTRING, MULTILINESTRING, GEOMETRYCOLLECTION, POINT or MULTIPOINT";

class WktParser {
 public:
  WktParser(std::string_view text, Reporter& report) : text_(text), report_(report) {}

  Drawing run() {
    skipSpace();
    if (at_ >= text_.size()) {
      error("no geometry", kGeometries);
      return {};
    }
    while (!report_.failed()) {
      skipSrid();
      geometry(0);
      skipSpace();
      while (at_ < text_.size() && text_[at_] == ';') {
        advance();
        skipSpace();
      }
      if (at_ >= text_.size()) break;
    }
    return std::move(drawing_);
  }

 private:
  void error(std::string what, std::string expected) { report_.error(line_, column_, std::move(what), std::move(expected)); }

  void advance() {
    if (text_[at_] == '\n') {
      ++line_;
      column_ = 1;
    } else if ((static_cast<unsigned char>(text_[at_]) & 0xC0) != 0x80) {
      ++column_;  // columns count characters: UTF-8 continuation bytes do not move it
    }
    ++at_;
  }

  void skipSpace() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) advance();
  }

  /// The next token as text (a word, a number, or one punctuation character), without consuming it.
  std::string_view peekToken() {
    skipSpace();
    if (at_ >= text_.size()) return {};
    std::size_t end = at_;
    const auto wordy = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' || c == '_'; };
    while (end < text_.size() && wordy(text_[end])) ++end;
    return text_.substr(at_, std::max(end, at_ + 1) - at_);
  }

  void consume(std::string_view token) {
    for (std::size_t i = 0; i < token.size(); ++i) advance();
  }

  std::string describe(std::string_view token) {
    return token.empty() ? std::string("the end of the text") : "\"" + core::printable(std::string(token.substr(0, 40)), 40) + "\"";
  }

  bool expect(char c) {
    const std::string_view t = peekToken();
    if (t.size() == 1 && t[0] == c) {
      consume(t);
      return true;
    }
    error(describe(t) + " where '" + std::string(1, c) + "' belongs", std::string("'") + c + "'");
    return false;
  }

  /// True (consumed) when the next token is `c`.
  bool accept(char c) {
    const std::string_view t = peekToken();
    if (t.size() != 1 || t[0] != c) return false;
    consume(t);
    return true;
  }

  static std::string upper(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
  }

  void skipSrid() {
    const std::string_view t = peekToken();
    if (upper(t).rfind("SRID", 0) != 0) return;
    while (at_ < text_.size() && text_[at_] != ';' && text_[at_] != '\n') advance();
    if (!expect(';')) return;
  }

  void geometry(int depth) {
    const int line = line_, column = column_;
    const std::string_view t = peekToken();
    const std::string tag = upper(t);
    consume(t);
    const bool known = tag == "POLYGON" || tag == "MULTIPOLYGON" || tag == "LINESTRING" || tag == "MULTILINESTRING" ||
                       tag == "GEOMETRYCOLLECTION" || tag == "POINT" || tag == "MULTIPOINT";
    if (!known) {
      report_.error(line, column, describe(t) + " is not a geometry this importer reads", kGeometries);
      return;
    }
    const std::string dims = upper(peekToken());
    if (dims == "Z" || dims == "M" || dims == "ZM") consume(peekToken());
    if (upper(peekToken()) == "EMPTY") {
      consume(peekToken());
      return;
    }
    if (tag == "POLYGON") polygon();
    else if (tag == "MULTIPOLYGON") list([&] { polygon(); });
    else if (tag == "LINESTRING") wall("LINESTRING");
    else if (tag == "MULTILINESTRING") list([&] { wall("MULTILINESTRING part"); });
    else if (tag == "POINT") points(nullptr);
    else if (tag == "MULTIPOINT") multipoint();
    else if (depth + 1 >= kMaxWktDepth) {
      report_.error(line, column, "GEOMETRYCOLLECTION nested more than " + std::to_string(kMaxWktDepth) + " deep",
                    "at most " + std::to_string(kMaxWktDepth) + " levels of GEOMETRYCOLLECTION");
    } else {
      list([&] { geometry(depth + 1); });
    }
  }

  /// '(' item (',' item)* ')'.
  template <class F>
  void list(F&& item) {
    if (!expect('(')) return;
    do {
      item();
      if (report_.failed()) return;
    } while (accept(','));
    expect(')');
  }

  /// '(' x y [z [m]] (',' ...)* ')' into `out` (nullptr: read and dropped).
  void points(std::vector<Point>* out) {
    list([&] {
      Point p;
      int n = 0;
      for (;;) {
        const std::string_view t = peekToken();
        double v = 0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (t.empty() || ec != std::errc() || end != t.data() + t.size()) break;
        if (!std::isfinite(v)) {
          error("coordinate " + describe(t) + " is not finite", "a finite number");
          return;
        }
        if (n == 0) p.x = v;
        if (n == 1) p.y = v;
        ++n;
        consume(t);
      }
      if (n < 2 || n > 4) {
        error(n < 2 ? describe(peekToken()) + " where a coordinate belongs" : std::to_string(n) + " coordinates in one point",
              "a point of 2 to 4 numbers (x y, x y z, x y m or x y z m)");
        return;
      }
      if (out != nullptr && report_.addVertices(1, line_, column_)) out->push_back(p);
    });
  }

  /// MULTIPOINT (1 2, 3 4) or MULTIPOINT ((1 2), (3 4)).
  void multipoint() {
    const std::size_t save = at_;
    const int line = line_, column = column_;
    if (!expect('(')) return;
    const bool nested = peekToken() == "(";
    at_ = save;
    line_ = line;
    column_ = column;
    if (nested) list([&] { points(nullptr); });
    else points(nullptr);
  }

  Shape shape(std::string what, PlanRole role, int line, int column, bool closed) {
    Shape s;
    s.role = role;
    s.closed = closed;
    s.line = line;
    s.column = column;
    s.what = std::move(what);
    return s;
  }

  bool push(Shape s) {
    if (drawing_.shapes.size() >= kMaxPlanShapes) {
      report_.error(s.line, s.column, "more than " + std::to_string(kMaxPlanShapes) + " rings and lines",
                    "a plan of at most " + std::to_string(kMaxPlanShapes) + " rings and lines");
      return false;
    }
    drawing_.shapes.push_back(std::move(s));
    return true;
  }

  void polygon() {
    int ring = 0;
    list([&] {
      skipSpace();
      Shape s = shape(ring == 0 ? "POLYGON" : "POLYGON hole " + std::to_string(ring), ring == 0 ? PlanRole::Walkable : PlanRole::Obstacle,
                      line_, column_, true);
      ++ring;
      points(&s.points);
      if (!report_.failed()) push(std::move(s));
    });
  }

  void wall(const std::string& what) {
    skipSpace();
    Shape s = shape(what, PlanRole::Wall, line_, column_, false);
    points(&s.points);
    if (!report_.failed()) push(std::move(s));
  }

  std::string_view text_;
  Reporter& report_;
  std::size_t at_ = 0;
  int line_ = 1, column_ = 1;
  Drawing drawing_;
};

}  // namespace

Drawing readWkt(std::string_view text, const PlanImportOptions&, Reporter& report) { return WktParser(text, report).run(); }

}  // namespace throng::io::plan
