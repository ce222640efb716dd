// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/base/file_text.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "sonargrid/base/log_error.h"

namespace sg::file_text {
namespace {

std::string osReason(int err) {
  return std::error_code(err, std::generic_category()).message();
}

}  // namespace

std::string readFileBytes(const std::string& path, std::size_t maxBytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    throw LogError(path, 0, "", "cannot open: " + (ec ? ec.message() : osReason(ENOENT)));
  }
  if (fs::is_directory(status)) throw LogError(path, 0, "", "cannot open: it is a directory");
  if (!fs::is_regular_file(status)) throw LogError(path, 0, "", "cannot open: not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw LogError(path, 0, "", "cannot open: " + ec.message());
  if (size > maxBytes) {
    throw LogError(path, 0, "",
                   "the file is " + std::to_string(size) + " bytes; a reference map is at most " +
                       std::to_string(maxBytes) + " bytes");
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LogError(path, 0, "", "cannot open: " + osReason(errno != 0 ? errno : EACCES));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  // A file that shrank while we read it is read as far as it goes.
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw LogError(path, 0, "", "read error");
  return bytes;
}

std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    const bool last = end == std::string_view::npos;
    if (last) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = last ? text.size() : end + 1;
  }
  return lines;
}

std::string shown(std::string_view s, std::size_t max) {
  std::string out;
  const std::size_t n = s.size() < max ? s.size() : max;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>(c));
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (s.size() > max) out += "...";
  return out;
}

}  // namespace sg::file_text
