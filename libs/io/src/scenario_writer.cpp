// throng::io scenario writer — formatJsonForDiffs (a recursive printer: scalars through
// nlohmann's dump, flat arrays on one line) and writeFileAtomically (mkstemp beside the target,
// write, fsync, then rename or link). Reads JSON values; writes one file.
#include "throng/io/scenario_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace throng::io {

namespace {

using Json = nlohmann::ordered_json;

std::string scalar(const Json& v) { return v.dump(-1, ' ', false, Json::error_handler_t::replace); }

bool flat(const Json& v) {
  return v.is_array() && std::none_of(v.begin(), v.end(), [](const Json& x) { return x.is_structured(); });
}

void print(const Json& v, int depth, std::string& out) {
  const std::string pad(std::size_t(2 * (depth + 1)), ' ');
  if (v.is_object() && !v.empty()) {
    out += "{\n";
    std::size_t i = 0;
    for (const auto& [key, member] : v.items()) {
      out += pad + scalar(Json(key)) + ": ";
      print(member, depth + 1, out);
      out += ++i < v.size() ? ",\n" : "\n";
    }
    out += std::string(std::size_t(2 * depth), ' ') + "}";
  } else if (v.is_array() && !v.empty() && !flat(v)) {
    out += "[\n";
    for (std::size_t i = 0; i < v.size(); ++i) {
      out += pad;
      print(v[i], depth + 1, out);
      out += i + 1 < v.size() ? ",\n" : "\n";
    }
    out += std::string(std::size_t(2 * depth), ' ') + "]";
  } else if (v.is_array()) {
    out += "[";
    for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + scalar(v[i]);
    out += "]";
  } else {
    out += scalar(v);
  }
}

core::Diagnostic problem(const std::string& path, std::string what, std::string expected) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

}  // namespace

std::string formatJsonForDiffs(const nlohmann::ordered_json& value) {
  std::string out;
  print(value, 0, out);
  return out + "\n";
}

core::Status writeFileAtomically(const std::string& path, std::string_view text, bool overwrite) {
  const std::string expected = "a writable directory";
  if (!overwrite && std::filesystem::exists(path)) {
    return problem(path, "file exists", "a new file name, or --force to overwrite it");
  }
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::string tmp = ((dir.empty() ? std::filesystem::path(".") : dir) / ".throng-XXXXXX").string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) return problem(path, std::string("cannot create a temporary file beside it: ") + std::strerror(errno), expected);
  const auto fail = [&](const std::string& step, int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    return problem(path, "cannot write file: " + step + ": " + std::strerror(err), expected);
  };
  // mkstemp creates the file 0600; a scenario is an ordinary readable file.
  if (::fchmod(fd, S_IRUSR | S_IWUSR | S_IRGRP | S_IROTH) != 0) return fail("cannot set permissions", errno);
  for (std::size_t written = 0; written < text.size();) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return fail("write failed", errno);
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) return fail("fsync failed", errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return problem(path, std::string("cannot write file: close failed: ") + std::strerror(err), expected);
  }
  // Without overwrite, link() fails if the name was taken meanwhile; rename() would replace it.
  const int rc = overwrite ? ::rename(tmp.c_str(), path.c_str()) : ::link(tmp.c_str(), path.c_str());
  const int err = errno;
  if (!overwrite || rc != 0) ::unlink(tmp.c_str());
  if (rc == 0) return core::Ok{};
  if (err == EEXIST) return problem(path, "file exists", "a new file name, or --force to overwrite it");
  return problem(path, std::string("cannot write file: cannot move the temporary file into place: ") + std::strerror(err), expected);
}

}  // namespace throng::io
