// A temporary directory for tests (recordings, damaged databases, files to load), removed with everything
// in it when the test ends, even where a test made it read-only.
#pragma once
#include <stdlib.h>

#include <filesystem>
#include <string>

namespace throng::test {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "throng-test") {
    std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    path_ = ::mkdtemp(tmpl.data()) ? tmpl : std::string();
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ec);
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return path_ + "/" + name; }
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace throng::test
