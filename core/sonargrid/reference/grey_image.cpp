// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/grey_image.h"

#include <charconv>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sonargrid/base/file_text.h"

namespace sg {
namespace {

using file_text::shown;

// Beyond this the "map" is a photograph or a unit mistake: 100 megapixels is a square
// kilometre at 10 cm.
constexpr std::size_t kMaxPixels = 100'000'000;
constexpr std::size_t kMaxImageBytes = 512u * 1024u * 1024u;

GreyImage decodeWithOpenCv(const std::string& bytes, const std::string& path) {
  cv::Mat image;
  try {
    const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
    image = cv::imdecode(raw, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw LogError(path, 0, "image", std::string("cannot decode the image: ") + e.what());
  }
  if (image.empty())
    throw LogError(path, 0, "image",
                   "cannot decode the image (not a PGM, PNG or other format OpenCV reads)");
  if (image.depth() != CV_8U)
    throw LogError(path, 0, "image", "only 8-bit images are read (map_server's convention)");
  if (static_cast<std::size_t>(image.total()) > kMaxPixels) {
    throw LogError(path, 0, "image", "more than " + std::to_string(kMaxPixels) + " pixels");
  }
  GreyImage out;
  out.width = image.cols;
  out.height = image.rows;
  out.pixels.resize(static_cast<std::size_t>(image.total()));
  const int channels = image.channels();
  // map_server averages the colour channels (integer division) and ignores alpha in trinary mode;
  // grey + alpha keeps the grey.
  const int colour = channels == 4 ? 3 : (channels == 2 ? 1 : channels);
  for (int r = 0; r < image.rows; ++r) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.cols; ++c) {
      int sum = 0;
      for (int k = 0; k < colour; ++k) sum += row[c * channels + k];
      out.pixels[static_cast<std::size_t>(r) * static_cast<std::size_t>(image.cols) +
                 static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(sum / colour);
    }
  }
  return out;
}

bool looksLikePgm(std::string_view bytes) {
  return bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '2');
}

}  // namespace

GreyImage parsePgm(std::string_view bytes, const std::string& displayName) {
  std::size_t pos = 0;
  std::size_t line = 1;
  auto skipSpaceAndComments = [&] {
    while (pos < bytes.size()) {
      const char c = bytes[pos];
      if (c == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
        if (c == '\n') ++line;
        ++pos;
      } else {
        break;
      }
    }
  };
  auto readUnsigned = [&](const char* field, unsigned long max) -> unsigned long {
    skipSpaceAndComments();
    if (pos >= bytes.size())
      throw LogError(displayName, line, field, "missing (the file ends early)");
    std::size_t start = pos;
    while (pos < bytes.size() && bytes[pos] >= '0' && bytes[pos] <= '9') ++pos;
    if (pos == start) {
      throw LogError(displayName, line, field,
                     "expected a whole number, got \"" + shown(bytes.substr(start, 8)) + "\"");
    }
    unsigned long v = 0;
    const auto [ptr, ec] = std::from_chars(bytes.data() + start, bytes.data() + pos, v);
    if (ec != std::errc() || v > max) {
      throw LogError(
          displayName, line, field,
          std::string(bytes.substr(start, pos - start)) + " is above " + std::to_string(max));
    }
    return v;
  };

  if (!looksLikePgm(bytes))
    throw LogError(displayName, 1, "magic", "expected a PGM image (P5 or P2)");
  const bool binary = bytes[1] == '5';
  pos = 2;
  GreyImage img;
  const unsigned long width = readUnsigned("width", 1'000'000);
  const unsigned long height = readUnsigned("height", 1'000'000);
  if (width == 0 || height == 0)
    throw LogError(displayName, line, width == 0 ? "width" : "height", "must be at least 1");
  if (width * height > kMaxPixels) {
    throw LogError(displayName, line, "width",
                   std::to_string(width) + " x " + std::to_string(height) + " is more than " +
                       std::to_string(kMaxPixels) + " pixels");
  }
  const unsigned long maxval = readUnsigned("maxval", 65535);
  if (maxval == 0) throw LogError(displayName, line, "maxval", "must be at least 1");
  if (maxval > 255)
    throw LogError(displayName, line, "maxval",
                   "16-bit PGM is not read; map_server images are 8-bit (maxval <= 255)");
  img.width = static_cast<int>(width);
  img.height = static_cast<int>(height);
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  img.pixels.resize(count);
  // Values with a maxval below 255 are stretched to 0..255 as image readers do.
  auto scaled = [&](unsigned long v) {
    return static_cast<std::uint8_t>(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
  };
  if (binary) {
    // Exactly one whitespace byte separates maxval from the pixels.
    if (pos >= bytes.size() ||
        !(bytes[pos] == ' ' || bytes[pos] == '\n' || bytes[pos] == '\r' || bytes[pos] == '\t')) {
      throw LogError(displayName, line, "maxval", "expected one whitespace byte before the pixels");
    }
    ++pos;
    if (bytes.size() - pos < count) {
      throw LogError(displayName, 0, "pixels",
                     "the file ends after " + std::to_string(bytes.size() - pos) + " of " +
                         std::to_string(count) + " pixels");
    }
    for (std::size_t i = 0; i < count; ++i) {
      const auto v = static_cast<unsigned char>(bytes[pos + i]);
      if (v > maxval) {
        throw LogError(displayName, 0, "pixels",
                       "pixel " + std::to_string(i) + " is " + std::to_string(v) +
                           ", above maxval " + std::to_string(maxval));
      }
      img.pixels[i] = scaled(v);
    }
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      skipSpaceAndComments();
      if (pos >= bytes.size()) {
        throw LogError(displayName, line, "pixels",
                       "the file ends after " + std::to_string(i) + " of " + std::to_string(count) +
                           " pixels");
      }
      const unsigned long v = readUnsigned("pixels", maxval);
      img.pixels[i] = scaled(v);
    }
  }
  return img;
}

GreyImage readGreyImage(const std::string& path) {
  const std::string bytes = file_text::readFileBytes(path, kMaxImageBytes);
  return looksLikePgm(bytes) ? parsePgm(bytes, path) : decodeWithOpenCv(bytes, path);
}

}  // namespace sg
