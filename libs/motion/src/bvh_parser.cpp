// throng::motion BVH parser — Biovision Hierarchy text → MotionClip (see throng/motion/bvh.hpp for the
// grammar). A cursor walks the text keeping line:column (columns count Unicode code points, as in
// json_document); the hierarchy is read by recursive descent bounded by kMaxBvhDepth, the MOTION
// section one line per frame. Reads text or one file; writes the clip and diagnostics. No
// exception escapes: even an internal failure becomes a diagnostic.
#include "throng/motion/bvh.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace throng::motion {

namespace {

constexpr std::size_t kMaxRowDiagnostics = 50;  ///< frame row errors reported before giving up
constexpr std::size_t kMaxDiagnostics = 100;    ///< problems of any kind reported before giving up

constexpr std::array<std::string_view, 6> kChannelNames = {"Xposition", "Yposition", "Zposition",
                                                           "Xrotation", "Yrotation", "Zrotation"};

struct Pos {
  int line = 1;
  int column = 1;
};

struct Token {
  std::string_view text;  ///< empty at the end of the text
  Pos pos;
};

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

/// A token shown in a message: quoted, at most 40 characters, control and non-ASCII bytes as '?'.
std::string quote(std::string_view s) {
  if (s.empty()) return "the end of the file";
  std::string q = "\"";
  for (const char c : s.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    q += (u < 0x20 || u >= 0x7f) ? '?' : c;
  }
  if (s.size() > 40) q += "...";
  return q + "\"";
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// Walks the text byte by byte, tracking the 1-based line and column of the next byte.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  [[nodiscard]] Pos pos() const { return pos_; }
  [[nodiscard]] bool atEnd() const { return i_ >= text_.size(); }

  /// The next whitespace-separated token (crossing lines); empty at the end.
  Token next() {
    skip(true);
    return word();
  }

  /// The next token on the current line; empty at the end of the line (the newline stays).
  Token nextOnLine() {
    skip(false);
    return word();
  }

  /// Skips blank space up to and including the next newline; false if something else comes first.
  bool endLine() {
    skip(false);
    if (atEnd()) return true;
    if (text_[i_] != '\n') return false;
    advance();
    return true;
  }

  /// Skips whitespace (newlines included).
  void skipBlank() { skip(true); }

 private:
  void advance() {
    const char c = text_[i_++];
    if (c == '\n') {
      ++pos_.line;
      pos_.column = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      ++pos_.column;  // UTF-8 continuation bytes belong to the previous code point's column
    }
  }

  void skip(bool newlines) {
    while (!atEnd() && isSpace(text_[i_]) && (newlines || text_[i_] != '\n')) advance();
  }

  Token word() {
    Token t{{}, pos_};
    const std::size_t start = i_;
    while (!atEnd() && !isSpace(text_[i_])) advance();
    t.text = text_.substr(start, i_ - start);
    return t;
  }

  std::string_view text_;
  std::size_t i_ = 0;
  Pos pos_;
};

/// Thrown inside the parser to stop at a structural error (after recording its diagnostic);
/// caught in parseBvh, never escapes.
struct Stop {};

class BvhParser {
 public:
  BvhParser(std::string_view text, const std::string& source) : cur_(text), source_(source), text_(text) {}

  core::Result<MotionClip> run() {
    clip_.name = std::filesystem::path(source_).stem().string();
    try {
      if (text_.size() > kMaxBvhBytes) {
        error({1, 1}, "file is " + std::to_string(text_.size()) + " bytes",
              "at most " + std::to_string(kMaxBvhBytes) + " bytes (64 MiB)");
        throw Stop{};
      }
      readHierarchy();
      readMotion();
    } catch (const Stop&) {
      // diagnostics already recorded
    }
    if (!diags_.empty()) return std::move(diags_);
    return std::move(clip_);
  }

 private:
  void error(Pos p, std::string what, std::string expected, std::string hint = {}) {
    if (diags_.size() >= kMaxDiagnostics) {
      diags_.push_back(core::Diagnostic{source_, p.line, p.column, "", "too many problems; stopped here",
                                        "at most " + std::to_string(kMaxDiagnostics) + " reported", ""});
      throw Stop{};
    }
    diags_.push_back(core::Diagnostic{source_, p.line, p.column, "", std::move(what), std::move(expected), std::move(hint)});
  }

  [[noreturn]] void fail(Pos p, std::string what, std::string expected, std::string hint = {}) {
    error(p, std::move(what), std::move(expected), std::move(hint));
    throw Stop{};
  }

  /// The next token, which must be `keyword`; `expected` describes what should follow it.
  Token expectKeyword(std::string_view keyword, const std::string& expected) {
    const Token t = cur_.next();
    if (t.text != keyword) fail(t.pos, "found " + quote(t.text), expected);
    return t;
  }

  /// Parses a number token; reports a bad one (not a number, not finite, too large) and returns false.
  bool parseNumber(const Token& t, const std::string& expected, double& out) {
    std::string_view s = t.text;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || end != s.data() + s.size() || (ec != std::errc() && ec != std::errc::result_out_of_range)) {
      error(t.pos, "found " + quote(t.text), expected);
      return false;
    }
    if (ec == std::errc::result_out_of_range || !std::isfinite(v)) {
      error(t.pos, "number " + quote(t.text) + " is not finite", expected);
      return false;
    }
    if (std::fabs(v) > kMaxBvhMagnitude) {
      error(t.pos, "number " + quote(t.text) + " is out of range",
            "a number with magnitude at most " + num(kMaxBvhMagnitude));
      return false;
    }
    out = v;
    return true;
  }

  /// "OFFSET x y z"; a misspelled keyword or a missing number stops the parse.
  std::array<float, 3> readOffset() {
    const std::string expected = "\"OFFSET\" followed by 3 numbers";
    const Token key = cur_.next();
    if (key.text != "OFFSET") {
      const std::string match = core::closestMatch(std::string(key.text), {"OFFSET"});
      fail(key.pos, "found " + quote(key.text), expected, match.empty() ? "" : "did you mean \"OFFSET\"?");
    }
    std::array<float, 3> out{};
    for (int k = 0; k < 3; ++k) {
      const Token t = cur_.next();
      double v = 0.0;
      if (t.text.empty() || t.text == "}" || t.text == "CHANNELS" || t.text == "JOINT" || t.text == "End") {
        fail(t.pos, "OFFSET has " + std::to_string(k) + " number" + (k == 1 ? "" : "s"), expected);
      }
      if (parseNumber(t, "a finite number (OFFSET x y z)", v)) out[static_cast<std::size_t>(k)] = static_cast<float>(v);
    }
    return out;
  }

  /// "CHANNELS n name…" (the keyword already read).
  void readChannels(MotionClip::Joint& joint) {
    const Token countTok = cur_.next();
    const std::string countExpected = "a channel count from 0 to 6 after \"CHANNELS\"";
    std::size_t count = 0;
    const auto [end, ec] = std::from_chars(countTok.text.data(), countTok.text.data() + countTok.text.size(), count);
    if (countTok.text.empty() || ec != std::errc() || end != countTok.text.data() + countTok.text.size()) {
      fail(countTok.pos, "found " + quote(countTok.text), countExpected);
    }
    if (count > 6) fail(countTok.pos, "channel count " + std::to_string(count) + " is out of range", countExpected);
    std::vector<std::string> names(kChannelNames.begin(), kChannelNames.end());
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    for (std::size_t k = 0; k < count; ++k) {
      const Token t = cur_.next();
      if (t.text.empty() || t.text == "JOINT" || t.text == "End" || t.text == "}" || t.text == "{") {
        fail(t.pos, "CHANNELS declares " + std::to_string(count) + " channels but lists " + std::to_string(k),
             std::to_string(count) + " channel names (" + list + ")");
      }
      const auto it = std::find(kChannelNames.begin(), kChannelNames.end(), t.text);
      if (it == kChannelNames.end()) {
        std::string match = core::closestMatch(std::string(t.text), names);
        for (std::size_t c = 0; match.empty() && t.text.size() >= 2 && c < names.size(); ++c) {
          if (names[c].compare(0, t.text.size(), t.text) == 0) match = names[c];  // "Xrot" → "Xrotation"
        }
        error(t.pos, "unknown channel " + quote(t.text), "one of: " + list,
              match.empty() ? "" : "did you mean \"" + match + "\"?");
        joint.channels.push_back(MotionChannel::Xposition);  // keeps the column count right
        continue;
      }
      const auto channel = static_cast<MotionChannel>(it - kChannelNames.begin());
      if (std::find(joint.channels.begin(), joint.channels.end(), channel) != joint.channels.end()) {
        error(t.pos, "channel " + quote(t.text) + " listed twice for joint " + quote(joint.name),
              "each channel at most once per joint");
      }
      joint.channels.push_back(channel);
    }
    joint.firstChannel = clip_.channelCount;
    clip_.channelCount += count;
  }

  /// A ROOT or JOINT block after its keyword: name { OFFSET [CHANNELS] children }.
  void readJoint(int parent, std::size_t depth, Pos keywordPos) {
    if (depth > kMaxBvhDepth) {
      fail(keywordPos, "hierarchy nested deeper than " + std::to_string(kMaxBvhDepth) + " joints",
           "at most " + std::to_string(kMaxBvhDepth) + " levels of JOINT below ROOT");
    }
    if (clip_.joints.size() >= kMaxBvhJoints) {
      fail(keywordPos, "more than " + std::to_string(kMaxBvhJoints) + " joints",
           "at most " + std::to_string(kMaxBvhJoints) + " joints");
    }
    const Token name = cur_.next();
    if (name.text.empty() || name.text == "{" || name.text == "}") {
      fail(name.pos, "found " + quote(name.text), "a joint name");
    }
    MotionClip::Joint joint;
    joint.name = std::string(name.text);
    joint.parent = parent;
    if (!names_.insert(joint.name).second) {
      error(name.pos, "duplicate joint name " + quote(name.text), "joint names unique within the file");
    }
    expectKeyword("{", "\"{\" after the joint name " + quote(name.text) + " (joint names contain no spaces)");
    joint.offset = readOffset();
    const int index = static_cast<int>(clip_.joints.size());
    clip_.joints.push_back(std::move(joint));
    // Channels, then children, then "}". Reading into clip_.joints[index] (not `joint`): the
    // vector grows while the children are read.
    Token t = cur_.next();
    if (t.text == "CHANNELS") {
      MotionClip::Joint& self = clip_.joints[static_cast<std::size_t>(index)];
      readChannels(self);
      t = cur_.next();
    }
    const std::vector<std::string> keywords = {"CHANNELS", "JOINT", "End", "}"};
    for (;;) {
      if (t.text == "}") return;
      if (t.text == "JOINT") {
        readJoint(index, depth + 1, t.pos);
      } else if (t.text == "End") {
        readEndSite(index);
      } else {
        const std::string match = core::closestMatch(std::string(t.text), keywords);
        const bool channels = t.text == "CHANNELS";
        fail(t.pos, channels ? "\"CHANNELS\" after a child joint" : "found " + quote(t.text),
             channels ? "\"CHANNELS\" right after the joint's OFFSET"
                      : "\"JOINT\", \"End Site\" or \"}\" closing joint " + quote(clip_.joints[std::size_t(index)].name),
             match.empty() || channels ? "" : "did you mean \"" + (match == "End" ? std::string("End Site") : match) + "\"?");
      }
      t = cur_.next();
    }
  }

  /// "End Site { OFFSET x y z }" after "End".
  void readEndSite(int owner) {
    expectKeyword("Site", "\"Site\" after \"End\"");
    MotionClip::Joint& joint = clip_.joints[static_cast<std::size_t>(owner)];
    const Token open = expectKeyword("{", "\"{\" after \"End Site\"");
    if (joint.hasEndSite) error(open.pos, "second End Site in joint " + quote(joint.name), "at most one End Site per joint");
    const std::array<float, 3> offset = readOffset();
    clip_.joints[static_cast<std::size_t>(owner)].hasEndSite = true;
    clip_.joints[static_cast<std::size_t>(owner)].endSite = offset;
    expectKeyword("}", "\"}\" closing the End Site (it holds only an OFFSET)");
  }

  void readHierarchy() {
    const Token head = cur_.next();
    if (head.text != "HIERARCHY") {
      fail(head.pos, "found " + quote(head.text), "\"HIERARCHY\" at the start of a BVH file");
    }
    const Token root = cur_.next();
    if (root.text != "ROOT") {
      const std::string match = core::closestMatch(std::string(root.text), {"ROOT"});
      fail(root.pos, "found " + quote(root.text), "\"ROOT\" followed by the root joint's name",
           match.empty() ? "" : "did you mean \"ROOT\"?");
    }
    readJoint(-1, 0, root.pos);
    if (clip_.channelCount == 0) {
      fail(root.pos, "the hierarchy declares no channels", "at least one joint with CHANNELS");
    }
  }

  void readMotion() {
    const Token motion = cur_.next();
    if (motion.text != "MOTION") {
      const bool root = motion.text == "ROOT";
      fail(motion.pos, root ? "a second ROOT" : "found " + quote(motion.text),
           "\"MOTION\" after the hierarchy" + std::string(root ? " (one skeleton per file)" : ""));
    }
    expectKeyword("Frames:", "\"Frames:\" followed by the number of frames");
    const Token framesTok = cur_.next();
    const std::string framesExpected = "a whole number of frames from 1 to " + std::to_string(kMaxBvhFrames);
    std::size_t frames = 0;
    const auto [fend, fec] = std::from_chars(framesTok.text.data(), framesTok.text.data() + framesTok.text.size(), frames);
    if (framesTok.text.empty() || fend != framesTok.text.data() + framesTok.text.size() ||
        (fec != std::errc() && fec != std::errc::result_out_of_range)) {
      fail(framesTok.pos, "found " + quote(framesTok.text), framesExpected);
    }
    if (fec == std::errc::result_out_of_range || frames < 1 || frames > kMaxBvhFrames) {
      fail(framesTok.pos, "frame count " + quote(framesTok.text) + " is out of range", framesExpected);
    }
    expectKeyword("Frame", "\"Frame Time:\" followed by the seconds per frame");
    expectKeyword("Time:", "\"Frame Time:\" followed by the seconds per frame");
    const Token timeTok = cur_.next();
    const std::string timeExpected = "a frame time > 0 and <= " + num(kMaxBvhFrameTime) + " s";
    double frameTime = 0.0;
    if (!parseNumber(timeTok, timeExpected, frameTime)) throw Stop{};
    if (!(frameTime > 0.0 && frameTime <= kMaxBvhFrameTime)) {
      fail(timeTok.pos, "frame time " + num(frameTime) + " s is out of range", timeExpected);
    }
    if (!cur_.endLine()) {
      const Token extra = cur_.nextOnLine();
      fail(extra.pos, "found " + quote(extra.text) + " after the frame time", "the first frame on the next line");
    }
    clip_.frameCount = frames;
    clip_.frameTime = frameTime;
    readFrames(frames, framesTok.pos);
  }

  /// One row of channelCount numbers per line; blank lines are skipped.
  void readFrames(std::size_t frames, Pos framesPos) {
    const std::size_t channels = clip_.channelCount;
    // Never reserve from the header alone: "Frames: 1000000" costs nothing to write.
    clip_.values.reserve(std::min(frames * channels, text_.size() / 2 + 1));
    std::size_t row = 0;
    std::size_t rowErrors = 0;
    const auto rowError = [&](Pos p, std::string what, std::string expected) {
      if (++rowErrors > kMaxRowDiagnostics) {
        fail(p, "too many bad frame rows; stopped after " + std::to_string(kMaxRowDiagnostics), "");
      }
      error(p, std::move(what), std::move(expected));
    };
    const std::string rowExpected = std::to_string(channels) + " numbers (one per channel)";
    for (;;) {
      cur_.skipBlank();
      if (cur_.atEnd()) break;
      const Pos rowPos = cur_.pos();
      if (row == frames) {
        fail(rowPos, "more frame rows than \"Frames: " + std::to_string(frames) + "\"",
             "exactly " + std::to_string(frames) + " rows (fix the Frames: count or remove the extra rows)");
      }
      std::size_t count = 0;
      bool reportedTooMany = false;
      for (Token t = cur_.nextOnLine(); !t.text.empty(); t = cur_.nextOnLine()) {
        if (count == channels && !reportedTooMany) {
          reportedTooMany = true;
          rowError(t.pos, "frame " + std::to_string(row + 1) + " has more than " + std::to_string(channels) + " values",
                   rowExpected);
        }
        double v = 0.0;
        if (!parseNumber(t, "a finite number (frame " + std::to_string(row + 1) + ", channel " +
                                std::to_string(count + 1) + ")", v)) {
          if (++rowErrors > kMaxRowDiagnostics) fail(t.pos, "too many bad values; stopped", "");
        }
        if (count < channels) clip_.values.push_back(static_cast<float>(v));
        ++count;
      }
      if (count < channels) {
        rowError(cur_.pos(), "frame " + std::to_string(row + 1) + " has " + std::to_string(count) + " value" +
                                 (count == 1 ? "" : "s"),
                 rowExpected);
        clip_.values.resize(clip_.values.size() + (channels - count), 0.0f);
      }
      cur_.endLine();
      ++row;
    }
    if (row < frames) {
      fail(framesPos, "\"Frames: " + std::to_string(frames) + "\" but the file has " + std::to_string(row) +
                          " frame row" + (row == 1 ? "" : "s"),
           std::to_string(frames) + " rows of " + std::to_string(channels) + " numbers (fix the Frames: count)");
    }
  }

  Cursor cur_;
  const std::string& source_;
  std::string_view text_;
  MotionClip clip_;
  std::set<std::string> names_;
  core::Diagnostics diags_;
};

}  // namespace

std::string_view channelName(MotionChannel channel) {
  const auto i = static_cast<std::size_t>(channel);
  return i < kChannelNames.size() ? kChannelNames[i] : std::string_view("unknown");
}

int MotionClip::findJoint(std::string_view jointName) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == jointName) return static_cast<int>(i);
  }
  return -1;
}

core::Result<MotionClip> parseBvh(std::string_view text, const std::string& source) {
  try {
    return BvhParser(text, source).run();
  } catch (const std::exception& e) {
    return core::Diagnostic{source, 0, 0, "", std::string("internal error while reading the BVH file: ") + e.what(), "", ""};
  }
}

core::Result<MotionClip> loadBvhFile(const std::string& path) {
  const std::string expected = "a readable BVH file of at most 64 MiB";
  try {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec || !fs::exists(status)) {
      return core::Diagnostic{path, 0, 0, "", "cannot open file: " + (ec ? ec.message() : std::string("not found")),
                              expected, ""};
    }
    if (!fs::is_regular_file(status)) {
      return core::Diagnostic{path, 0, 0, "", "cannot read: not a regular file", expected, ""};
    }
    const auto size = fs::file_size(path, ec);
    if (!ec && size > kMaxBvhBytes) {
      return core::Diagnostic{path, 0, 0, "", "file is " + std::to_string(size) + " bytes", expected, ""};
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) return core::Diagnostic{path, 0, 0, "", std::string("cannot open file: ") + std::strerror(errno), expected, ""};
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return core::Diagnostic{path, 0, 0, "", "cannot read file", expected, ""};
    return parseBvh(text.str(), path);
  } catch (const std::exception& e) {
    return core::Diagnostic{path, 0, 0, "", std::string("cannot read file: ") + e.what(), expected, ""};
  }
}

}  // namespace throng::motion
