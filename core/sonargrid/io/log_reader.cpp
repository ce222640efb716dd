// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/log_reader.h"

#include <array>
#include <vector>

#include "sonargrid/io/bag/bag.h"
#include "sonargrid/io/bag/bag_log.h"

#include "sonargrid/io/carmen.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/player.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/io/start_pose.h"
#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

// Message names written by CARMEN loggers (logger/logger_io); any one of them marks a CARMEN log.
constexpr std::array<std::string_view, 16> kCarmenMessages{
    "ODOM",        "TRUEPOS", "SONAR",   "PARAM",     "SYNC",      "FLASER",
    "RLASER",      "LASER3",  "LASER4",  "RAWLASER1", "RAWLASER2", "ROBOTLASER1",
    "ROBOTLASER2", "NMEAGGA", "NMEARMC", "BUMPER"};

bool isNumber(std::string_view s) {
  double v = 0.0;
  return text::parseFinite(s, v);
}

bool isWord(std::string_view s) {
  if (s.empty()) return false;
  for (const char c : s) {
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) {
      return false;
    }
  }
  return !(s[0] >= '0' && s[0] <= '9');
}

// The odometry placed at LogOptions::startPose. The .sglog reader does it itself, since its header
// may carry a start pose that the option overrides.
Dataset placed(Dataset log, const LogOptions& options) {
  if (options.startPose) placeOdometryAt(log, *options.startPose);
  return log;
}

Dataset dispatch(LogFormat format, text::ByteSource& source, const std::string& name,
                 const LogOptions& options, LoadReport& report) {
  switch (format) {
    case LogFormat::Sglog:
      return readSglog(source, name, options, report);
    case LogFormat::Carmen:
      return placed(readCarmen(source, name, options, report), options);
    case LogFormat::Player:
      return placed(readPlayer(source, name, options, report), options);
    case LogFormat::Csv:
    case LogFormat::Auto:
    case LogFormat::Bag:  // read before the text source is opened (readLog, parseLog)
      break;
  }
  return placed(readCsvLog(source, name, options, report), options);
}

LogFormat chooseFormat(std::string_view head, const std::string& name, const LogOptions& options) {
  if (options.format != LogFormat::Auto) return options.format;
  const LogFormat detected = detectLogFormat(head);
  if (detected != LogFormat::Auto) return detected;
  // Content that says nothing (an empty file, a cut header): the name decides, so that the
  // reader of that format explains what is missing.
  auto endsWith = [&name](std::string_view suffix) {
    return name.size() >= suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (endsWith(".sglog")) return LogFormat::Sglog;
  if (endsWith(".clf") || endsWith(".carmen")) return LogFormat::Carmen;
  if (options.csv) return LogFormat::Csv;
  throw LogError(name, 0, "format",
                 "expected an sglog header, CARMEN messages, Player writelog lines or CSV rows; "
                 "cannot tell the format from the content (give --format)");
}

Dataset load(text::ByteSource& source, std::string_view head, const std::string& name,
             const LogOptions& options, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report != nullptr ? *report : local;
  r = LoadReport{};
  // A head cut at kDetectBytes may end inside a line: judge whole lines only.
  if (head.size() >= kDetectBytes) head = head.substr(0, head.rfind('\n') + 1);
  return dispatch(chooseFormat(head, name, options), source, name, options, r);
}

}  // namespace

LogFormat detectLogFormat(std::string_view head) {
  if (bag::detectContainer(head) != bag::Container::Unknown) return LogFormat::Bag;
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (head.substr(0, kBom.size()) == kBom) head.remove_prefix(kBom.size());
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  bool csvLike = false;
  bool first = true;
  while (start < head.size()) {
    std::size_t stop = head.find('\n', start);
    if (stop == std::string_view::npos) stop = head.size();
    std::string_view line = head.substr(start, stop - start);
    start = stop + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.substr(0, 9) == "## Player") return LogFormat::Player;
    if (line.find("CARMEN") != std::string_view::npos && line.substr(0, 1) == "#") {
      return LogFormat::Carmen;
    }
    text::splitFields(line, fields);
    if (fields.empty()) continue;
    if (first && fields[0] == "sglog") return LogFormat::Sglog;
    first = false;
    for (const std::string_view m : kCarmenMessages) {
      if (fields[0] == m) return LogFormat::Carmen;
    }
    // time host robot interface index ...
    if (fields.size() >= 6 && isNumber(fields[0]) && isWord(fields[3]) && isNumber(fields[4])) {
      return LogFormat::Player;
    }
    // Rows of numbers split at commas, semicolons or blanks.
    if (!csvLike) {
      std::vector<std::string_view> cells;
      const char d = line.find(',') != std::string_view::npos   ? ','
                     : line.find(';') != std::string_view::npos ? ';'
                                                                : ' ';
      if (d == ' ') {
        cells = fields;
      } else {
        text::splitDelimited(line, d, cells);
      }
      std::size_t numbers = 0;
      for (const std::string_view c : cells) numbers += isNumber(c) ? 1 : 0;
      csvLike = cells.size() >= 2 && numbers == cells.size();
    }
  }
  return csvLike ? LogFormat::Csv : LogFormat::Auto;
}

namespace {

// A bag is binary (or a rosbag2 folder, or its metadata.yaml): it is read by bag_log.h, not
// through the text readers.
bool readsAsBag(const std::string& path, const LogOptions& options) {
  if (options.format == LogFormat::Bag) return true;
  if (options.format != LogFormat::Auto) return false;
  // A folder is a bag when it holds rosbag2's files; any other folder fails as a folder does.
  return bag::isBag(path);
}

}  // namespace

Dataset readLog(const std::string& path, const LogOptions& options, LoadReport* report) {
  if (readsAsBag(path, options)) {
    LoadReport local;
    LoadReport& r = report != nullptr ? *report : local;
    r = LoadReport{};
    return placed(bag::readBag(path, options, r), options);
  }
  text::FileSource source(path);
  std::string head;
  if (options.format == LogFormat::Auto) {
    head.resize(kDetectBytes);
    std::size_t got = 0;
    for (std::size_t n = 1; n != 0 && got < head.size(); got += n) {
      n = source.read(head.data() + got, head.size() - got);
    }
    head.resize(got);
    if (!source.rewind()) throw LogError(path, 0, "", "cannot read: the file cannot be rewound");
  }
  return load(source, head, path, options, report);
}

std::shared_ptr<ScanSource> openLog(const std::string& path, const LogOptions& options,
                                    LoadReport* report) {
  return std::make_shared<ScanSource>(
      std::make_shared<const Dataset>(readLog(path, options, report)));
}

Dataset parseLog(std::string_view bytes, const std::string& displayName, const LogOptions& options,
                 LoadReport* report) {
  if (options.format == LogFormat::Bag ||
      (options.format == LogFormat::Auto &&
       bag::detectContainer(bytes.substr(0, 16)) != bag::Container::Unknown)) {
    LoadReport local;
    LoadReport& r = report != nullptr ? *report : local;
    r = LoadReport{};
    return placed(bag::readBagBytes(bytes, displayName, options, r), options);
  }
  text::MemorySource source(bytes);
  return load(source, bytes.substr(0, kDetectBytes), displayName, options, report);
}

}  // namespace sg
