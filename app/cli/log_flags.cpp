// SPDX-License-Identifier: GPL-3.0-or-later
// The log-reading flags every command that reads a log shares (docs/cli.md, "Reading logs"):
// --format, --lenient, --robot, --columns, --poses, --start-pose, and a bag's --sonar-topic,
// --odom-topic and --truth-topic.

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "map_options.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/start_pose.h"

namespace sg::cli {

LogOptions parseLogOptions(Arguments& args) {
  LogOptions o;
  if (const auto format = args.value("--format")) {
    if (!parseLogFormat(*format, o.format)) {
      throw UsageError("--format takes auto, sglog, carmen, player, csv or bag, got '" + *format +
                       "'");
    }
  }
  o.lenient = args.flag("--lenient");
  if (const auto robot = args.value("--robot")) {
    SonarRing ring;
    if (SonarRing::preset(*robot, ring)) {
      o.ring = ring;
    } else if (std::filesystem::is_regular_file(*robot)) {
      try {
        o.ring = readSonarGeometry(*robot);
      } catch (const LogError& e) {
        throw InputError(e.what());
      }
    } else {
      std::string names;
      for (const std::string& n : SonarRing::presetNames()) names += n + ", ";
      throw UsageError("--robot takes a preset (" + names + "or a sonar geometry file), got '" +
                       *robot + "'");
    }
  }
  if (const auto columns = args.value("--columns")) {
    try {
      o.csv = parseCsvLayout(*columns);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  if (const auto poses = args.value("--poses")) o.posesPath = *poses;
  if (const auto start = args.value("--start-pose")) {
    std::string why;
    o.startPose = parseStartPose(*start, &why);
    if (!o.startPose) throw UsageError("--start-pose: " + why);
  }
  // Repeated, or a comma-separated list: one topic per transducer, or one for them all.
  for (const std::string& v : args.values("--sonar-topic")) {
    std::size_t start = 0;
    while (start <= v.size()) {
      const std::size_t stop = std::min(v.find(',', start), v.size());
      if (stop > start) o.topics.sonar.push_back(v.substr(start, stop - start));
      start = stop + 1;
    }
  }
  if (const auto odom = args.value("--odom-topic")) o.topics.odometry = *odom;
  if (const auto truth = args.value("--truth-topic")) o.topics.truth = *truth;
  if (!o.topics.empty() && o.format != LogFormat::Auto && o.format != LogFormat::Bag) {
    throw UsageError(
        "--sonar-topic, --odom-topic and --truth-topic choose a bag's topics; they do "
        "not go with --format " +
        std::string(logFormatName(o.format)));
  }
  const bool csvOnly = o.csv || !o.posesPath.empty();
  if (csvOnly && o.format != LogFormat::Auto && o.format != LogFormat::Csv) {
    throw UsageError("--columns and --poses describe CSV logs; they do not go with --format " +
                     std::string(logFormatName(o.format)));
  }
  if (!o.posesPath.empty() && !o.csv) throw UsageError("--poses needs --columns");
  return o;
}

Dataset loadLog(const std::string& path, const LogOptions& options, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report != nullptr ? *report : local;
  Dataset data;
  try {
    data = readLog(path, options, &r);
  } catch (const LogError& e) {
    throw InputError(e.what());
  }
  for (const std::string& note : r.notes)
    std::cerr << "sonargrid-cli: " << path << ": " << note << "\n";
  if (r.skippedLines != 0) {
    std::cerr << "sonargrid-cli: " << path << ": --lenient skipped " << r.skippedLines
              << (r.skippedLines == 1 ? " bad line:\n" : " bad lines:\n");
    const std::string summary = r.summary();
    std::size_t start = 0;
    while (start < summary.size()) {
      const std::size_t stop = summary.find('\n', start);
      std::cerr << "  " << summary.substr(start, stop - start + 1);
      start = stop + 1;
    }
  }
  return data;
}

Dataset loadLog(const std::string& path) {
  return loadLog(path, LogOptions{});
}

}  // namespace sg::cli
